// VkRenderPass: attachments and subpasses, copied into plain vectors.
#pragma once
#include <vector>

#include "object.h"

namespace tilevk::icd {

struct Subpass {
    std::vector<VkAttachmentReference> inputs;
    std::vector<VkAttachmentReference> colors;
    std::vector<VkAttachmentReference> resolves;  // empty or one per colour attachment
    VkAttachmentReference depth_stencil{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_UNDEFINED};
    std::vector<uint32_t> preserves;
};

struct RenderPass : NonDispatchableObject {
    using Handle = VkRenderPass;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_RENDER_PASS;
    RenderPass() : NonDispatchableObject(kType) {}
    std::vector<VkAttachmentDescription> attachments;
    std::vector<Subpass> subpasses;
    std::vector<VkSubpassDependency> dependencies;
    // For each attachment, the first subpass that uses it (its load op applies there), or ~0u if unused.
    std::vector<uint32_t> first_use;
};

}  // namespace tilevk::icd
