// VkImageView: an image, a format, and a subresource range.
#pragma once
#include "image.h"

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
};

}  // namespace tilevk::icd
