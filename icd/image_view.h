// VkImageView: an image, a format, and a subresource range.
#pragma once
#include "image.h"
#include "shader/program.h"

namespace tilevk::icd {

struct ImageView : NonDispatchableObject {
    using Handle = VkImageView;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_IMAGE_VIEW;
    ImageView() : NonDispatchableObject(kType) {}
    Image* image = nullptr;
    const FormatInfo* format = nullptr;
    VkImageViewType view_type = VK_IMAGE_VIEW_TYPE_2D;
    VkComponentMapping components{};
    VkImageSubresourceRange range{};  // VK_REMAINING_* resolved to real counts
    // The view as shader/ samples it (render_state.h shader_view_of), translated at vkCreateImageView instead of
    // at every draw; `sampled_memory` is the image memory it was made for (null: the image had none yet).
    shader::ImageView sampled{};
    bool sampled_ok = false;
    const void* sampled_memory = nullptr;
};

}  // namespace tilevk::icd
