// VkFramebuffer: attachment views and size.
#pragma once
#include <vector>

#include "image_view.h"

namespace tilevk::icd {

struct Framebuffer : NonDispatchableObject {
    using Handle = VkFramebuffer;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_FRAMEBUFFER;
    Framebuffer() : NonDispatchableObject(kType) {}
    std::vector<ImageView*> attachments;  // empty when imageless
    uint32_t width = 0, height = 0, layers = 0;
    // VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT: the views come with each vkCmdBeginRenderPass
    // (VkRenderPassAttachmentBeginInfo), `imageless_count` of them.
    bool imageless = false;
    uint32_t imageless_count = 0;
};

}  // namespace tilevk::icd
