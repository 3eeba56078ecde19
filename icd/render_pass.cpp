#include "render_pass.h"

#include <cstdio>
#include <vector>

#include "device.h"
#include "entrypoints.h"
#include "formats.h"
#include "physical_device.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

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
        // Input attachments of a multiview subpass read layer ViewIndex of their view; the fetch reads layer 0.
        if (m != 0 && i < ci.subpassCount && ci.pSubpasses[i].inputAttachmentCount != 0) {
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkCreateRenderPass: pSubpasses[%u] has input attachments and view mask 0x%x: input "
                        "attachments in a multiview subpass are not supported by tilevk",
                        i, m);
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

// One subpass's depth/stencil resolve (VkSubpassDescriptionDepthStencilResolve, render-pass-2 only), checked.
struct DsResolve {
    VkAttachmentReference ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_UNDEFINED};
    VkResolveModeFlagBits depth = VK_RESOLVE_MODE_NONE, stencil = VK_RESOLVE_MODE_NONE;
};

// vkCreateRenderPass, and vkCreateRenderPass2 through it: `ds` is null or holds one depth/stencil resolve per subpass.
VkResult create_render_pass(Device* dev, const VkRenderPassCreateInfo* ci, const std::vector<DsResolve>* ds,
                            const VkAllocationCallbacks* pAllocator, VkRenderPass* pRenderPass) {
    if (VkResult r = refuse_unsupported(*ci); r != VK_SUCCESS) return r;
    std::vector<uint32_t> view_masks;
    if (VkResult r = check_view_masks(*dev, *ci, view_masks); r != VK_SUCCESS) return r;
    RenderPass* rp =
        create_object<RenderPass>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (rp == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateRenderPass: out of host memory");
    try {
        rp->attachments.assign(ci->pAttachments, ci->pAttachments + ci->attachmentCount);
        rp->dependencies.assign(ci->pDependencies, ci->pDependencies + ci->dependencyCount);
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
            if (ds != nullptr) {
                s.ds_resolve = (*ds)[i].ref;
                s.depth_resolve = (*ds)[i].depth;
                s.stencil_resolve = (*ds)[i].stencil;
            }
        }
        plan_attachment_loads(*rp);
    } catch (const std::bad_alloc&) {
        destroy_object(rp);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateRenderPass: out of host memory");
    }
    *pRenderPass = to_handle(rp);
    return VK_SUCCESS;
}

}  // namespace

// Where each attachment's load op applies: its first use (the spec's "Load operations"); in a multiview render pass
// per view, in the first subpass that uses the attachment and renders that view.
void plan_attachment_loads(RenderPass& rp) {
    const size_t n = rp.attachments.size();
    rp.first_use.assign(n, ~0u);
    rp.multiview = !rp.subpasses.empty() && rp.subpasses[0].view_mask != 0;
    std::vector<uint32_t> seen(n, 0);
    for (uint32_t i = 0; i < rp.subpasses.size(); ++i) {
        Subpass& s = rp.subpasses[i];
        if (rp.multiview) s.load_views.assign(n, 0);
        const auto use = [&](uint32_t a) {
            if (a == VK_ATTACHMENT_UNUSED || a >= n) return;
            if (rp.first_use[a] == ~0u) rp.first_use[a] = i;
            if (rp.multiview) s.load_views[a] |= s.view_mask & ~seen[a];
        };
        for (auto& r : s.inputs) use(r.attachment);
        for (auto& r : s.colors) use(r.attachment);
        for (auto& r : s.resolves) use(r.attachment);
        use(s.depth_stencil.attachment);
        use(s.ds_resolve.attachment);
        if (rp.multiview)
            for (size_t a = 0; a < n; ++a) seen[a] |= s.load_views[a];
    }
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateRenderPass(VkDevice device, const VkRenderPassCreateInfo* ci,
                                                    const VkAllocationCallbacks* pAllocator,
                                                    VkRenderPass* pRenderPass) {
    return create_render_pass(from_handle<Device>(device), ci, nullptr, pAllocator, pRenderPass);
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyRenderPass(VkDevice, VkRenderPass renderPass, const VkAllocationCallbacks*) {
    destroy_object(from_handle<RenderPass>(renderPass));
}

VKAPI_ATTR void VKAPI_CALL tvk_GetRenderAreaGranularity(VkDevice, VkRenderPass, VkExtent2D* pGranularity) {
    *pGranularity = {1, 1};
}

// ---- VK_KHR_create_renderpass2 ------------------------------------------------------------------------------
// The 2-structs say what the 1.0 structs say plus: per-subpass view masks, correlated view masks and view offsets
// (multiview: given to the 1.0 constructor as the VkRenderPassMultiviewCreateInfo they stand for, so they take the
// same checks and the same execution), an aspect mask per attachment reference, and pNext structs. The aspect mask of
// an input attachment is what VkRenderPassInputAttachmentAspectCreateInfo (VK_KHR_maintenance2) says for 1.0 passes:
// which aspects the shader may read. tilevk reads input attachments through the view bound to the descriptor, whose
// single aspect decides (VUID-VkDescriptorImageInfo-imageView-01976), and has one image layout, so neither form needs
// keeping; the layouts of VkAttachmentDescriptionStencilLayout / VkAttachmentReferenceStencilLayout likewise.
namespace {

// The pNext structs of the 2-structs that would change what is rendered: refused by name.
VkResult refuse_chain(const char* where, uint32_t index, const void* chain) {
    for (auto* s = static_cast<const VkBaseInStructure*>(chain); s != nullptr; s = s->pNext) {
        switch (s->sType) {
            case VK_STRUCTURE_TYPE_FRAGMENT_SHADING_RATE_ATTACHMENT_INFO_KHR:
            case VK_STRUCTURE_TYPE_MULTISAMPLED_RENDER_TO_SINGLE_SAMPLED_INFO_EXT:
            case VK_STRUCTURE_TYPE_RENDER_PASS_FRAGMENT_DENSITY_MAP_CREATE_INFO_EXT:
                return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                            "vkCreateRenderPass2: %s[%u] chains %s, which tilevk does not implement", where, index,
                            vk_enum_name(s->sType));
            default:
                break;  // depth/stencil resolves are read by check_ds_resolve; the other structs (stencil layouts,
                        // creation feedback) change nothing tilevk renders
        }
    }
    return VK_SUCCESS;
}

VkAttachmentReference ref1(const VkAttachmentReference2& r) {
    return {r.attachment, r.layout};
}

// Writes the 1.0 form of the subpass into `out`, its references into `refs` (which must not reallocate while the
// pointers are in use: the caller reserves).
void subpass1(const VkSubpassDescription2& d, std::vector<VkAttachmentReference>& refs, VkSubpassDescription* out) {
    const auto append = [&](const VkAttachmentReference2* r, uint32_t n) -> const VkAttachmentReference* {
        if (r == nullptr) return nullptr;
        const size_t first = refs.size();
        for (uint32_t i = 0; i < n; ++i) refs.push_back(ref1(r[i]));
        return refs.data() + first;
    };
    *out = {};
    out->flags = d.flags;
    out->pipelineBindPoint = d.pipelineBindPoint;
    out->inputAttachmentCount = d.inputAttachmentCount;
    out->pInputAttachments = append(d.pInputAttachments, d.inputAttachmentCount);
    out->colorAttachmentCount = d.colorAttachmentCount;
    out->pColorAttachments = append(d.pColorAttachments, d.colorAttachmentCount);
    out->pResolveAttachments = append(d.pResolveAttachments, d.colorAttachmentCount);
    out->pDepthStencilAttachment = append(d.pDepthStencilAttachment, 1);
    out->preserveAttachmentCount = d.preserveAttachmentCount;
    out->pPreserveAttachments = d.pPreserveAttachments;
}

// A dependency's 1.0 form; with a VkMemoryBarrier2 (synchronization2) its masks replace the 1.0 ones, the stages past
// bit 31 dropped as command_buffer2.cpp does for barriers (execution is serial: dependencies order nothing more).
VkSubpassDependency dependency1(const VkSubpassDependency2& d) {
    VkSubpassDependency out{d.srcSubpass,    d.dstSubpass,    d.srcStageMask,   d.dstStageMask,
                            d.srcAccessMask, d.dstAccessMask, d.dependencyFlags};
    if (const auto* b = find_in_chain<VkMemoryBarrier2>(d.pNext, VK_STRUCTURE_TYPE_MEMORY_BARRIER_2)) {
        out.srcStageMask = VkPipelineStageFlags(b->srcStageMask & 0x7fffffffull);
        out.dstStageMask = VkPipelineStageFlags(b->dstStageMask & 0x7fffffffull);
        out.srcAccessMask = VkAccessFlags(b->srcAccessMask & 0x7fffffffull);
        out.dstAccessMask = VkAccessFlags(b->dstAccessMask & 0x7fffffffull);
    }
    return out;
}

VkResult refuse_2(const VkRenderPassCreateInfo2& ci) {
    if (VkResult r = refuse_chain("pCreateInfo", 0, ci.pNext); r != VK_SUCCESS) return r;
    for (uint32_t i = 0; i < ci.attachmentCount; ++i)
        if (VkResult r = refuse_chain("pAttachments", i, ci.pAttachments[i].pNext); r != VK_SUCCESS) return r;
    for (uint32_t i = 0; i < ci.subpassCount; ++i)
        if (VkResult r = refuse_chain("pSubpasses", i, ci.pSubpasses[i].pNext); r != VK_SUCCESS) return r;
    return VK_SUCCESS;
}

// A refusal of subpass `subpass`'s VkSubpassDescriptionDepthStencilResolve, `what` naming the member.
VkResult refuse_ds_resolve(uint32_t subpass, const char* what) {
    return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                "vkCreateRenderPass2: pSubpasses[%u] VkSubpassDescriptionDepthStencilResolve::%s", subpass, what);
}

bool one_mode_of(VkResolveModeFlagBits mode, VkResolveModeFlags supported) {
    return (mode & (mode - 1)) == 0 && (mode & supported) == mode;
}

// Subpass `i`'s VkSubpassDescriptionDepthStencilResolve, checked into `out` (no struct, no attachment: no resolve).
// Refused by name: the spec's invalid usage (VUID-VkSubpassDescriptionDepthStencilResolve-*), modes outside
// kDepthResolveModes / kStencilResolveModes, different modes for the two aspects of a combined format (neither
// independentResolve nor independentResolveNone), and a resolve attachment of another format than the depth/stencil
// attachment's (valid when the aspects match, e.g. D24_UNORM_S8_UINT into X8_D24_UNORM_PACK32; lavapipe converts
// through float there, which tilevk does not model). A mode is ignored for an aspect the resolve format lacks.
VkResult check_ds_resolve(const VkRenderPassCreateInfo2& ci, uint32_t i, DsResolve& out) {
    const VkSubpassDescription2& sub = ci.pSubpasses[i];
    const auto* r = find_in_chain<VkSubpassDescriptionDepthStencilResolve>(
        sub.pNext, VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_DEPTH_STENCIL_RESOLVE);
    out = {};
    if (r == nullptr || r->pDepthStencilResolveAttachment == nullptr ||
        r->pDepthStencilResolveAttachment->attachment == VK_ATTACHMENT_UNUSED) {
        return VK_SUCCESS;
    }
    char what[320];
    const uint32_t dst = r->pDepthStencilResolveAttachment->attachment;
    const uint32_t src =
        sub.pDepthStencilAttachment != nullptr ? sub.pDepthStencilAttachment->attachment : VK_ATTACHMENT_UNUSED;
    if (dst >= ci.attachmentCount) {
        std::snprintf(what, sizeof what, "pDepthStencilResolveAttachment->attachment = %u is past attachmentCount (%u)",
                      dst, ci.attachmentCount);
        return refuse_ds_resolve(i, what);
    }
    if (src >= ci.attachmentCount)
        return refuse_ds_resolve(i,
                                 "pDepthStencilResolveAttachment is set but the subpass has no depth/stencil "
                                 "attachment (VUID-VkSubpassDescriptionDepthStencilResolve-"
                                 "pDepthStencilResolveAttachment-03177)");
    const VkAttachmentDescription2& sa = ci.pAttachments[src];
    const VkAttachmentDescription2& da = ci.pAttachments[dst];
    if (sa.samples == VK_SAMPLE_COUNT_1_BIT || da.samples != VK_SAMPLE_COUNT_1_BIT)
        return refuse_ds_resolve(i,
                                 "pDepthStencilResolveAttachment: the depth/stencil attachment must have more "
                                 "than one sample and the resolve attachment one (VUID-03179, VUID-03180)");
    const FormatInfo* f = find_format(da.format);
    if (f == nullptr || (f->aspects & (VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT)) == 0) {
        std::snprintf(what, sizeof what, "pDepthStencilResolveAttachment: format %s is not a depth/stencil format",
                      vk_enum_name(da.format));
        return refuse_ds_resolve(i, what);
    }
    if (da.format != sa.format) {
        std::snprintf(what, sizeof what,
                      "pDepthStencilResolveAttachment: format %s differs from the depth/stencil attachment's %s; "
                      "tilevk resolves depth/stencil only between attachments of one format",
                      vk_enum_name(da.format), vk_enum_name(sa.format));
        return refuse_ds_resolve(i, what);
    }
    if (r->depthResolveMode == VK_RESOLVE_MODE_NONE && r->stencilResolveMode == VK_RESOLVE_MODE_NONE)
        return refuse_ds_resolve(i,
                                 "depthResolveMode and stencilResolveMode are both VK_RESOLVE_MODE_NONE "
                                 "(VUID-VkSubpassDescriptionDepthStencilResolve-pDepthStencilResolveAttachment-03178)");
    const bool depth = (f->aspects & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
    const bool stencil = (f->aspects & VK_IMAGE_ASPECT_STENCIL_BIT) != 0;
    if (depth && !one_mode_of(r->depthResolveMode, kDepthResolveModes | VK_RESOLVE_MODE_NONE)) {
        std::snprintf(what, sizeof what, "depthResolveMode = %s is not one of supportedDepthResolveModes (%s)",
                      vk_flags_name<VkResolveModeFlagBits>(r->depthResolveMode).c_str(),
                      vk_flags_name<VkResolveModeFlagBits>(kDepthResolveModes).c_str());
        return refuse_ds_resolve(i, what);
    }
    if (stencil && !one_mode_of(r->stencilResolveMode, kStencilResolveModes | VK_RESOLVE_MODE_NONE)) {
        std::snprintf(what, sizeof what, "stencilResolveMode = %s is not one of supportedStencilResolveModes (%s)",
                      vk_flags_name<VkResolveModeFlagBits>(r->stencilResolveMode).c_str(),
                      vk_flags_name<VkResolveModeFlagBits>(kStencilResolveModes).c_str());
        return refuse_ds_resolve(i, what);
    }
    if (depth && stencil && r->depthResolveMode != r->stencilResolveMode) {
        std::snprintf(what, sizeof what,
                      "depthResolveMode = %s and stencilResolveMode = %s differ for %s, which has depth and stencil: "
                      "independentResolve and independentResolveNone are VK_FALSE (VUID-03185)",
                      vk_flags_name<VkResolveModeFlagBits>(r->depthResolveMode).c_str(),
                      vk_flags_name<VkResolveModeFlagBits>(r->stencilResolveMode).c_str(), vk_enum_name(da.format));
        return refuse_ds_resolve(i, what);
    }
    out.ref = {dst, r->pDepthStencilResolveAttachment->layout};
    out.depth = depth ? r->depthResolveMode : VK_RESOLVE_MODE_NONE;
    out.stencil = stencil ? r->stencilResolveMode : VK_RESOLVE_MODE_NONE;
    return VK_SUCCESS;
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateRenderPass2(VkDevice device, const VkRenderPassCreateInfo2* ci,
                                                     const VkAllocationCallbacks* pAllocator,
                                                     VkRenderPass* pRenderPass) {
    if (VkResult r = refuse_2(*ci); r != VK_SUCCESS) return r;
    try {
        std::vector<DsResolve> ds(ci->subpassCount);
        for (uint32_t i = 0; i < ci->subpassCount; ++i)
            if (VkResult r = check_ds_resolve(*ci, i, ds[i]); r != VK_SUCCESS) return r;
        std::vector<VkAttachmentDescription> atts;
        atts.reserve(ci->attachmentCount);
        for (uint32_t i = 0; i < ci->attachmentCount; ++i) {
            const VkAttachmentDescription2& a = ci->pAttachments[i];
            atts.push_back({a.flags, a.format, a.samples, a.loadOp, a.storeOp, a.stencilLoadOp, a.stencilStoreOp,
                            a.initialLayout, a.finalLayout});
        }
        size_t ref_count = 0;
        for (uint32_t i = 0; i < ci->subpassCount; ++i) {
            const VkSubpassDescription2& d = ci->pSubpasses[i];
            ref_count += d.inputAttachmentCount + 2 * size_t(d.colorAttachmentCount) + 1;
        }
        std::vector<VkAttachmentReference> refs;
        refs.reserve(ref_count);
        std::vector<VkSubpassDescription> subs(ci->subpassCount);
        for (uint32_t i = 0; i < ci->subpassCount; ++i) subpass1(ci->pSubpasses[i], refs, &subs[i]);
        std::vector<VkSubpassDependency> deps;
        deps.reserve(ci->dependencyCount);
        for (uint32_t i = 0; i < ci->dependencyCount; ++i) deps.push_back(dependency1(ci->pDependencies[i]));
        // Multiview: VkSubpassDescription2::viewMask, VkSubpassDependency2::viewOffset and the correlated masks,
        // as VkRenderPassMultiviewCreateInfo says them for 1.0 passes.
        std::vector<uint32_t> masks(ci->subpassCount);
        bool any_mask = false;
        for (uint32_t i = 0; i < ci->subpassCount; ++i) {
            masks[i] = ci->pSubpasses[i].viewMask;
            any_mask = any_mask || masks[i] != 0;
        }
        std::vector<int32_t> offsets(ci->dependencyCount);
        for (uint32_t i = 0; i < ci->dependencyCount; ++i) offsets[i] = ci->pDependencies[i].viewOffset;
        VkRenderPassMultiviewCreateInfo mv{};
        mv.sType = VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO;
        mv.subpassCount = ci->subpassCount;
        mv.pViewMasks = masks.data();
        mv.dependencyCount = ci->dependencyCount;
        mv.pViewOffsets = offsets.data();
        mv.correlationMaskCount = ci->correlatedViewMaskCount;
        mv.pCorrelationMasks = ci->pCorrelatedViewMasks;
        VkRenderPassCreateInfo ci1{};
        ci1.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
        ci1.pNext = any_mask ? &mv : nullptr;
        ci1.flags = ci->flags;
        ci1.attachmentCount = uint32_t(atts.size());
        ci1.pAttachments = atts.data();
        ci1.subpassCount = uint32_t(subs.size());
        ci1.pSubpasses = subs.data();
        ci1.dependencyCount = uint32_t(deps.size());
        ci1.pDependencies = deps.data();
        return create_render_pass(from_handle<Device>(device), &ci1, &ds, pAllocator, pRenderPass);
    } catch (const std::bad_alloc&) {
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateRenderPass2: out of host memory");
    }
}

}  // namespace tilevk::icd
