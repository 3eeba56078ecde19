#include "render_pass.h"

#include "device.h"
#include "entrypoints.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

void note_use(RenderPass* rp, uint32_t subpass, uint32_t attachment) {
    if (attachment == VK_ATTACHMENT_UNUSED) return;
    if (rp->first_use[attachment] == ~0u) rp->first_use[attachment] = subpass;
}

// What tilevk cannot render: subpass flags all belong to extensions tilevk does not offer (per-view attributes, shader
// resolve, rasterization order access...), and multiview has no renderer. VkRenderPassMultiviewCreateInfo comes with
// VK_KHR_multiview, which tilevk does not expose (an application chaining it is invalid); a view mask would otherwise
// render one view silently, so it is refused by name.
VkResult refuse_unsupported(const VkRenderPassCreateInfo& ci) {
    for (uint32_t i = 0; i < ci.subpassCount; ++i) {
        if (ci.pSubpasses[i].flags != 0) {
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkCreateRenderPass: pSubpasses[%u].flags = %s is not supported by tilevk", i,
                        vk_flags_name<VkSubpassDescriptionFlagBits>(ci.pSubpasses[i].flags).c_str());
        }
    }
    const auto* mv =
        find_in_chain<VkRenderPassMultiviewCreateInfo>(ci.pNext, VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO);
    if (mv != nullptr) {
        for (uint32_t i = 0; i < mv->subpassCount; ++i) {
            if (mv->pViewMasks[i] != 0) {
                return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                            "vkCreateRenderPass: VkRenderPassMultiviewCreateInfo::pViewMasks[%u] = 0x%x: multiview is "
                            "not supported by tilevk (VK_KHR_multiview is not exposed)",
                            i, mv->pViewMasks[i]);
            }
        }
    }
    return VK_SUCCESS;
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateRenderPass(VkDevice device, const VkRenderPassCreateInfo* ci,
                                                    const VkAllocationCallbacks* pAllocator,
                                                    VkRenderPass* pRenderPass) {
    Device* dev = from_handle<Device>(device);
    if (VkResult r = refuse_unsupported(*ci); r != VK_SUCCESS) return r;
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
            for (auto& r : s.inputs) note_use(rp, i, r.attachment);
            for (auto& r : s.colors) note_use(rp, i, r.attachment);
            for (auto& r : s.resolves) note_use(rp, i, r.attachment);
            note_use(rp, i, s.depth_stencil.attachment);
        }
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
