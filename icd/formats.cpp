#include "formats.h"

namespace tilevk::icd {

const FormatInfo* find_format(VkFormat format) {
    const format::Format f = to_format(format);
    return f == format::Format::UNDEFINED ? nullptr : &format::format_info(f);
}

uint32_t buffer_texel_bytes(const FormatInfo& f, VkImageAspectFlags aspect) {
    if (!has_depth_and_stencil(f)) return f.bytes;
    return aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? 1 : 4;
}

uint32_t aspect_offset(const FormatInfo& f, VkImageAspectFlags aspect) {
    if (aspect != VK_IMAGE_ASPECT_STENCIL_BIT || !has_depth_and_stencil(f)) return 0;
    return format::find_channel(f, format::Component::kS)->shift / 8;
}

}  // namespace tilevk::icd
