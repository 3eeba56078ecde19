#include "render_pass.h"

#include "device.h"
#include "entrypoints.h"
#include "physical_device.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

void note_use(RenderPass* rp, uint32_t subpass, uint32_t attachment) {
    if (attachment == VK_ATTACHMENT_UNUSED) return;
    if (rp->first_use[attachment] == ~0u) rp->first_use[attachment] = subpass;
}

// What tilevk cannot render: subpass flags all belong to extensions tilevk does not offer (per-view attributes, shader
// resolve, rasterization order access...).
VkResult refuse_unsupported(const VkRenderPassCreateInfo& ci) {
    for (uint32_t i = 0; i < ci.subpassCount; ++i) {
        if (ci.pSubpasses[i].flags != 0) {
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkCreateRenderPass: pSubpasses[%u].flags = %s is not supported by tilevk", i,
                        vk_flags_name<VkSubpassDescriptionFlagBits>(ci.pSubpasses[i].flags).c_str());
        }
    }
    return VK_SUCCESS;
}

// VkRenderPassMultiviewCreateInfo's view masks, checked: they need the multiview feature, are one per subpass, all
// zero or all non-zero, and name views below maxMultiviewViewCount (each else invalid usage, refused by name).
// Correlation masks are a hint and view offsets order nothing in a serial executor, so both are accepted as they are.
// `masks` gets one mask per subpass (zeros when the pass is not multiview).
VkResult check_view_masks(const Device& dev, const VkRenderPassCreateInfo& ci, std::vector<uint32_t>& masks) {
    masks.assign(ci.subpassCount, 0);
    const auto* mv =
        find_in_chain<VkRenderPassMultiviewCreateInfo>(ci.pNext, VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO);
    if (mv == nullptr || mv->subpassCount == 0) return VK_SUCCESS;
    if (mv->subpassCount != ci.subpassCount) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateRenderPass: VkRenderPassMultiviewCreateInfo::subpassCount = %u, but the pass has %u "
                    "subpasses; invalid usage",
                    mv->subpassCount, ci.subpassCount);
    }
    uint32_t nonzero = 0;
    for (uint32_t i = 0; i < mv->subpassCount; ++i) {
        const uint32_t m = mv->pViewMasks[i];
        if (m != 0) ++nonzero;
        if (m >> kMaxMultiviewViews) {
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkCreateRenderPass: VkRenderPassMultiviewCreateInfo::pViewMasks[%u] = 0x%x names a view at or "
                        "past maxMultiviewViewCount (%u)",
                        i, m, kMaxMultiviewViews);
        }
        masks[i] = m;
    }
    if (nonzero == 0) return VK_SUCCESS;
    if (!dev.enabled_features.core.v11.multiview) {
        uint32_t first = 0;
        while (masks[first] == 0) ++first;
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateRenderPass: VkRenderPassMultiviewCreateInfo::pViewMasks[%u] = 0x%x needs the multiview "
                    "feature (VkPhysicalDeviceMultiviewFeatures::multiview), which is not enabled",
                    first, masks[first]);
    }
    if (nonzero != mv->subpassCount) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateRenderPass: VkRenderPassMultiviewCreateInfo::pViewMasks mixes zero and non-zero masks "
                    "(invalid usage)");
    }
    return VK_SUCCESS;
}

// Multiview load ops: an attachment's load op applies, per view, in the first subpass that uses the attachment and
// renders that view (the spec's "Load operations": in a multiview render pass the first use is per view).
void plan_view_loads(RenderPass* rp) {
    const size_t n = rp->attachments.size();
    std::vector<uint32_t> seen(n, 0);
    for (Subpass& s : rp->subpasses) {
        s.load_views.assign(n, 0);
        const auto use = [&](uint32_t a) {
            if (a == VK_ATTACHMENT_UNUSED || a >= n) return;
            s.load_views[a] |= s.view_mask & ~seen[a];
        };
        for (auto& r : s.inputs) use(r.attachment);
        for (auto& r : s.colors) use(r.attachment);
        for (auto& r : s.resolves) use(r.attachment);
        use(s.depth_stencil.attachment);
        for (size_t a = 0; a < n; ++a) seen[a] |= s.load_views[a];
    }
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateRenderPass(VkDevice device, const VkRenderPassCreateInfo* ci,
                                                    const VkAllocationCallbacks* pAllocator,
                                                    VkRenderPass* pRenderPass) {
    Device* dev = from_handle<Device>(device);
    if (VkResult r = refuse_unsupported(*ci); r != VK_SUCCESS) return r;
    std::vector<uint32_t> view_masks;
    if (VkResult r = check_view_masks(*dev, *ci, view_masks); r != VK_SUCCESS) return r;
    RenderPass* rp =
        create_object<RenderPass>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (rp == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateRenderPass: out of host memory");
    try {
        rp->attachments.assign(ci->pAttachments, ci->pAttachments + ci->attachmentCount);
        rp->dependencies.assign(ci->pDependencies, ci->pDependencies + ci->dependencyCount);
        rp->first_use.assign(ci->attachmentCount, ~0u);
        rp->subpasses.resize(ci->subpassCount);
        for (uint32_t i = 0; i < ci->subpassCount; ++i) {
            const VkSubpassDescription& d = ci->pSubpasses[i];
            Subpass& s = rp->subpasses[i];
            s.inputs.assign(d.pInputAttachments, d.pInputAttachments + d.inputAttachmentCount);
            s.colors.assign(d.pColorAttachments, d.pColorAttachments + d.colorAttachmentCount);
            if (d.pResolveAttachments != nullptr) {
                s.resolves.assign(d.pResolveAttachments, d.pResolveAttachments + d.colorAttachmentCount);
            }
            if (d.pDepthStencilAttachment != nullptr) s.depth_stencil = *d.pDepthStencilAttachment;
            s.preserves.assign(d.pPreserveAttachments, d.pPreserveAttachments + d.preserveAttachmentCount);
            s.view_mask = view_masks[i];
            for (auto& r : s.inputs) note_use(rp, i, r.attachment);
            for (auto& r : s.colors) note_use(rp, i, r.attachment);
            for (auto& r : s.resolves) note_use(rp, i, r.attachment);
            note_use(rp, i, s.depth_stencil.attachment);
        }
        rp->multiview = ci->subpassCount > 0 && view_masks[0] != 0;
        if (rp->multiview) plan_view_loads(rp);
    } catch (const std::bad_alloc&) {
        destroy_object(rp);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateRenderPass: out of host memory");
    }
    *pRenderPass = to_handle(rp);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyRenderPass(VkDevice, VkRenderPass renderPass, const VkAllocationCallbacks*) {
    destroy_object(from_handle<RenderPass>(renderPass));
}

VKAPI_ATTR void VKAPI_CALL tvk_GetRenderAreaGranularity(VkDevice, VkRenderPass, VkExtent2D* pGranularity) {
    *pGranularity = {1, 1};
}

}  // namespace tilevk::icd
