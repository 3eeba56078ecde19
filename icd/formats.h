// The formats as icd/ sees them: rows of the format table (format/format.h), found from a VkFormat through the
// generated mapping (format_map.h). What a row reports is decided in format/support.txt, nowhere else.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

#include "format/format.h"
#include "format_map.h"

namespace tilevk::icd {

using format::FormatInfo;

// The table row of `format`, or nullptr for VK_FORMAT_UNDEFINED and values that are not registry formats.
const FormatInfo* find_format(VkFormat format);

// A row's features convert to VkFormatFeatureFlags as they are: the table numbers its Feature bits as Vulkan does.
inline VkFormat vk_format(const FormatInfo& f) {
    return to_vk_format(f.id);
}
// True if images of the format can be created with some tiling.
inline bool has_image_support(const FormatInfo& f) {
    return format::image_features(f) != 0;
}
// True if optimal-tiling attachments of the format may have 4 samples (support.txt: only where the resolve is
// implemented, and depth formats, which Vulkan 1.0 never resolves).
inline bool format_supports_msaa(const FormatInfo& f) {
    return (f.sample_counts & VK_SAMPLE_COUNT_4_BIT) != 0;
}
// Depth and stencil interleaved in one texel (D24_UNORM_S8_UINT, D32_SFLOAT_S8_UINT).
inline bool has_depth_and_stencil(const FormatInfo& f) {
    return (f.aspects & VK_IMAGE_ASPECT_DEPTH_BIT) && (f.aspects & VK_IMAGE_ASPECT_STENCIL_BIT);
}

// Bytes of one aspect of a texel as laid out in a buffer for vkCmdCopyBufferToImage/ImageToBuffer (the spec's
// "Depth/stencil formats" copy rules: D24 depth in a 32-bit word, stencil one byte).
uint32_t buffer_texel_bytes(const FormatInfo& f, VkImageAspectFlags aspect);
// Byte offset of `aspect` inside one tilevk texel.
uint32_t aspect_offset(const FormatInfo& f, VkImageAspectFlags aspect);

}  // namespace tilevk::icd
