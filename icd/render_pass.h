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
    // VK_KHR_depth_stencil_resolve (VkSubpassDescriptionDepthStencilResolve): the attachment the depth/stencil
    // attachment resolves into at the end of the subpass (UNUSED: none), and the mode of each aspect, NONE for an
    // aspect the resolve attachment's format lacks (the spec ignores the mode then).
    VkAttachmentReference ds_resolve{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_UNDEFINED};
    VkResolveModeFlagBits depth_resolve = VK_RESOLVE_MODE_NONE;
    VkResolveModeFlagBits stencil_resolve = VK_RESOLVE_MODE_NONE;
    // Multiview (VkRenderPassMultiviewCreateInfo::pViewMasks, VkSubpassDescription2::viewMask): the views this
    // subpass renders, each into layer baseArrayLayer + view of every attachment; 0 when the pass is not multiview.
    uint32_t view_mask = 0;
    // Multiview: per attachment, the views whose load op applies at this subpass (the first subpass that uses the
    // attachment with that view); empty when the pass is not multiview (first_use decides then).
    std::vector<uint32_t> load_views;
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
    bool multiview = false;  // the subpasses have view masks (all non-zero)
};

// Fills first_use, multiview and each subpass's load_views from the subpasses (vkCreateRenderPass, and the one-subpass
// pass a vkCmdBeginRendering is translated into: dynamic_rendering.cpp).
void plan_attachment_loads(RenderPass& rp);

}  // namespace tilevk::icd
