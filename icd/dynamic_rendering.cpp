// vkCmdBeginRendering / vkCmdEndRendering (VK_KHR_dynamic_rendering, Vulkan 1.3). A VkRenderingInfo is translated at
// record time into a one-subpass RenderPass, a Framebuffer and the views and clear values of a CmdBeginRenderPass
// (vkCmdEndRendering records a CmdEndRenderPass), so a dynamic render pass instance runs through the code that runs
// vkCmdBeginRenderPass (execute.cpp: load ops, draws, vkCmdClearAttachments, multiview, colour and depth/stencil
// resolves): there is no second copy of any of it. Attachment numbering of the translated pass: colour attachment i
// is attachment i, then the colour resolve attachments, the depth/stencil attachment and its resolve attachment.
#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <vector>

#include "command_buffer.h"
#include "device.h"
#include "device_group.h"
#include "entrypoints.h"
#include "image_view.h"
#include "physical_device.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

// The attachments, views and clear values of the translated pass, built in attachment order.
struct Translation {
    RenderPass& pass;
    std::vector<ImageView*> views;
    std::vector<VkClearValue> clears;

    uint32_t add(ImageView* v, VkAttachmentLoadOp load, VkAttachmentLoadOp stencil_load, const VkClearValue& clear) {
        VkAttachmentDescription d{};
        d.format = vk_format(*v->format);
        d.samples = VkSampleCountFlagBits(v->image->samples);
        d.loadOp = load;
        d.storeOp = VK_ATTACHMENT_STORE_OP_STORE;  // tilevk renders into the image: every store op keeps the bytes
        d.stencilLoadOp = stencil_load;
        d.stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
        pass.attachments.push_back(d);
        views.push_back(v);
        clears.push_back(clear);
        return uint32_t(pass.attachments.size() - 1);
    }
};

// Logs why a VkRenderingInfo is not rendered (invalid usage, or valid but not implemented: commands return nothing,
// so the render pass instance then renders into nothing).
__attribute__((format(printf, 1, 2))) bool refuse(const char* fmt, ...) {
    char msg[512];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(msg, sizeof msg, fmt, args);
    va_end(args);
    log_error("vkCmdBeginRendering: %s; the render pass instance renders nothing", msg);
    return false;
}

// The pNext structs of VkRenderingInfo that would change what is rendered; all come from extensions tilevk does not
// offer (VkDeviceGroupRenderPassBeginInfo is taken by render_area_of).
bool check_chain(const VkRenderingInfo& ri) {
    for (auto* s = static_cast<const VkBaseInStructure*>(ri.pNext); s != nullptr; s = s->pNext) {
        switch (s->sType) {
            case VK_STRUCTURE_TYPE_RENDERING_FRAGMENT_SHADING_RATE_ATTACHMENT_INFO_KHR:
            case VK_STRUCTURE_TYPE_RENDERING_FRAGMENT_DENSITY_MAP_ATTACHMENT_INFO_EXT:
            case VK_STRUCTURE_TYPE_MULTISAMPLED_RENDER_TO_SINGLE_SAMPLED_INFO_EXT:
            case VK_STRUCTURE_TYPE_MULTIVIEW_PER_VIEW_ATTRIBUTES_INFO_NVX:
                return refuse("pRenderingInfo chains %s, which tilevk does not implement", vk_enum_name(s->sType));
            default:
                break;
        }
    }
    return true;
}

// Colour attachment i of `ri` and, when it resolves, its resolve attachment. A resolve needs
// VK_RESOLVE_MODE_AVERAGE_BIT (VUID-VkRenderingAttachmentInfo-imageView-06129: tilevk's multisampled colour formats are
// float or normalized).
bool add_colors(const VkRenderingInfo& ri, Translation& t, Subpass& sub) {
    for (uint32_t i = 0; i < ri.colorAttachmentCount; ++i) {
        const VkRenderingAttachmentInfo& a = ri.pColorAttachments[i];
        ImageView* v = from_handle<ImageView>(a.imageView);
        const uint32_t index =
            v != nullptr ? t.add(v, a.loadOp, VK_ATTACHMENT_LOAD_OP_DONT_CARE, a.clearValue) : VK_ATTACHMENT_UNUSED;
        sub.colors.push_back({index, a.imageLayout});
    }
    for (uint32_t i = 0; i < ri.colorAttachmentCount; ++i) {
        const VkRenderingAttachmentInfo& a = ri.pColorAttachments[i];
        ImageView* rv = from_handle<ImageView>(a.resolveImageView);
        if (a.imageView == VK_NULL_HANDLE || a.resolveMode == VK_RESOLVE_MODE_NONE || rv == nullptr) continue;
        if (a.resolveMode != VK_RESOLVE_MODE_AVERAGE_BIT)
            return refuse("pColorAttachments[%u].resolveMode = %s is not supported (VK_RESOLVE_MODE_AVERAGE_BIT)", i,
                          vk_flags_name<VkResolveModeFlagBits>(a.resolveMode).c_str());
        sub.resolves.resize(ri.colorAttachmentCount, {VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_UNDEFINED});
        sub.resolves[i] = {t.add(rv, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_LOAD_OP_DONT_CARE, {}),
                           a.resolveImageLayout};
    }
    return true;
}

// The depth/stencil resolve of `ri`, checked as vkCreateRenderPass2's check_ds_resolve checks
// VkSubpassDescriptionDepthStencilResolve: modes among kDepthResolveModes / kStencilResolveModes, one mode for both
// aspects of a format that has both (independentResolve and independentResolveNone are VK_FALSE; tilevk's resolve
// copies whole texels, so a format with both aspects resolves only when both attachments resolve alike).
bool add_ds_resolve(const VkRenderingAttachmentInfo* d, const VkRenderingAttachmentInfo* s, const ImageView& src,
                    Translation& t, Subpass& sub) {
    const VkResolveModeFlagBits dm =
        d != nullptr && d->resolveImageView != VK_NULL_HANDLE ? d->resolveMode : VK_RESOLVE_MODE_NONE;
    const VkResolveModeFlagBits sm =
        s != nullptr && s->resolveImageView != VK_NULL_HANDLE ? s->resolveMode : VK_RESOLVE_MODE_NONE;
    if (dm == VK_RESOLVE_MODE_NONE && sm == VK_RESOLVE_MODE_NONE) return true;
    if ((dm & ~kDepthResolveModes) != 0)
        return refuse("pDepthAttachment->resolveMode = %s is not one of supportedDepthResolveModes",
                      vk_flags_name<VkResolveModeFlagBits>(dm).c_str());
    if ((sm & ~kStencilResolveModes) != 0)
        return refuse("pStencilAttachment->resolveMode = %s is not one of supportedStencilResolveModes",
                      vk_flags_name<VkResolveModeFlagBits>(sm).c_str());
    const bool depth = (src.format->aspects & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
    const bool stencil = (src.format->aspects & VK_IMAGE_ASPECT_STENCIL_BIT) != 0;
    if (depth && stencil && dm != sm)
        return refuse(
            "pDepthAttachment->resolveMode and pStencilAttachment->resolveMode differ for %s, which has "
            "depth and stencil: tilevk resolves both aspects together (independentResolve VK_FALSE)",
            vk_enum_name(vk_format(*src.format)));
    ImageView* rv = from_handle<ImageView>(dm != VK_RESOLVE_MODE_NONE ? d->resolveImageView : s->resolveImageView);
    const VkImageLayout layout = dm != VK_RESOLVE_MODE_NONE ? d->resolveImageLayout : s->resolveImageLayout;
    sub.ds_resolve = {t.add(rv, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_LOAD_OP_DONT_CARE, {}), layout};
    sub.depth_resolve = depth ? (dm != VK_RESOLVE_MODE_NONE ? dm : sm) : VK_RESOLVE_MODE_NONE;
    sub.stencil_resolve = stencil ? (sm != VK_RESOLVE_MODE_NONE ? sm : dm) : VK_RESOLVE_MODE_NONE;
    return true;
}

// The depth/stencil attachment: one view for both aspects (VUID-VkRenderingInfo-pDepthAttachment-06085), the load op
// and clear value of each aspect from its own VkRenderingAttachmentInfo; an aspect without one is loaded (kept).
bool add_depth_stencil(const VkRenderingInfo& ri, Translation& t, Subpass& sub) {
    const VkRenderingAttachmentInfo* d =
        ri.pDepthAttachment != nullptr && ri.pDepthAttachment->imageView != VK_NULL_HANDLE ? ri.pDepthAttachment
                                                                                           : nullptr;
    const VkRenderingAttachmentInfo* s =
        ri.pStencilAttachment != nullptr && ri.pStencilAttachment->imageView != VK_NULL_HANDLE ? ri.pStencilAttachment
                                                                                               : nullptr;
    if (d == nullptr && s == nullptr) return true;
    if (d != nullptr && s != nullptr && d->imageView != s->imageView)
        return refuse(
            "pDepthAttachment->imageView and pStencilAttachment->imageView differ "
            "(VUID-VkRenderingInfo-pDepthAttachment-06085)");
    ImageView* v = from_handle<ImageView>(d != nullptr ? d->imageView : s->imageView);
    VkClearValue clear{};
    clear.depthStencil.depth = d != nullptr ? d->clearValue.depthStencil.depth : 0.0f;
    clear.depthStencil.stencil = s != nullptr ? s->clearValue.depthStencil.stencil : 0;
    const uint32_t index = t.add(v, d != nullptr ? d->loadOp : VK_ATTACHMENT_LOAD_OP_LOAD,
                                 s != nullptr ? s->loadOp : VK_ATTACHMENT_LOAD_OP_LOAD, clear);
    sub.depth_stencil = {index, d != nullptr ? d->imageLayout : s->imageLayout};
    return add_ds_resolve(d, s, *v, t, sub);
}

// The framebuffer of the instance: lavapipe's (lvp_execute.c handle_begin_rendering: renderArea.offset + extent wide
// and high, layerCount layers), within every attachment view and the framebuffer limits so that no bad render area
// reaches past an image.
void size_framebuffer(const VkRect2D& area, uint32_t layers, const std::vector<ImageView*>& views, Framebuffer& fb) {
    // At most maxFramebufferWidth/Height (= kMaxImageDimension), also for an instance without attachments.
    fb.width =
        uint32_t(std::min<uint64_t>(uint64_t(std::max(area.offset.x, 0)) + area.extent.width, kMaxImageDimension));
    fb.height =
        uint32_t(std::min<uint64_t>(uint64_t(std::max(area.offset.y, 0)) + area.extent.height, kMaxImageDimension));
    fb.layers = std::max(layers, 1u);
    for (const ImageView* v : views) {
        fb.width = std::min(fb.width, v->image->level_width(v->range.baseMipLevel));
        fb.height = std::min(fb.height, v->image->level_height(v->range.baseMipLevel));
    }
}

// Translates `ri` into `out` and the views and clears of `t`; false (logged) if it is not rendered.
bool translate(const Device& dev, const VkRenderingInfo& ri, Translation& t, Subpass& sub) {
    if (!dev.enabled_features.core.v13.dynamicRendering)
        return refuse(
            "the dynamicRendering feature (VkPhysicalDeviceDynamicRenderingFeatures::dynamicRendering) "
            "is not enabled");
    if (!check_chain(ri)) return false;
    if (ri.viewMask != 0 && !dev.enabled_features.core.v11.multiview)
        return refuse(
            "VkRenderingInfo::viewMask = 0x%x needs the multiview feature "
            "(VkPhysicalDeviceMultiviewFeatures::multiview), which is not enabled",
            ri.viewMask);
    if (ri.viewMask >> kMaxMultiviewViews)
        return refuse("VkRenderingInfo::viewMask = 0x%x names a view at or past maxMultiviewViewCount (%u)",
                      ri.viewMask, kMaxMultiviewViews);
    if (ri.colorAttachmentCount > uint32_t(kMaxColorAttachments))
        return refuse("VkRenderingInfo::colorAttachmentCount = %u is more than maxColorAttachments (%u)",
                      ri.colorAttachmentCount, kMaxColorAttachments);
    sub.view_mask = ri.viewMask;
    return add_colors(ri, t, sub) && add_depth_stencil(ri, t, sub);
}

// An uninitialised array of `n` object pointers in the command buffer's arena (null when out of memory), as
// command_buffer.cpp copies handle arrays.
template <class T>
T** pointer_array(CommandBuffer& cb, size_t n) {
    return static_cast<T**>(cb.arena.allocate(sizeof(T*) * n, alignof(T*)));
}

}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_CmdBeginRendering(VkCommandBuffer commandBuffer, const VkRenderingInfo* pRenderingInfo) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    const VkRenderingInfo& ri = *pRenderingInfo;
    RenderingInstance* inst = nullptr;
    try {
        inst = cb->rendering.emplace_back(std::make_unique<RenderingInstance>()).get();
        Translation t{inst->pass, {}, {}};
        inst->pass.subpasses.resize(1);
        Subpass& sub = inst->pass.subpasses[0];
        if (!translate(*cb->pool->device, ri, t, sub)) {  // renders into nothing: no attachments, no views
            inst->pass.attachments.clear();
            sub = Subpass{};
            t.views.clear();
            t.clears.clear();
        }
        plan_attachment_loads(inst->pass);
        const VkRect2D area = render_area_of(ri.renderArea, ri.pNext, "vkCmdBeginRendering");
        size_framebuffer(area, ri.viewMask != 0 ? 1 : ri.layerCount, t.views, inst->framebuffer);
        auto* c = cb->append<CmdBeginRenderPass>();
        if (c == nullptr) return;
        c->render_pass = &inst->pass;
        c->framebuffer = &inst->framebuffer;
        c->view_count = uint32_t(t.views.size());
        if (!t.views.empty()) {
            ImageView** views = pointer_array<ImageView>(*cb, t.views.size());
            if (views == nullptr) {
                cb->out_of_memory();
                c->view_count = 0;
            } else {
                std::copy(t.views.begin(), t.views.end(), views);
                c->views = views;
            }
        }
        c->area = area;
        c->clear_count = uint32_t(t.clears.size());
        c->clears = cb->copy(t.clears.data(), t.clears.size());
        c->resuming = (ri.flags & VK_RENDERING_RESUMING_BIT) != 0;
        c->suspending = (ri.flags & VK_RENDERING_SUSPENDING_BIT) != 0;
    } catch (const std::bad_alloc&) {
        cb->out_of_memory();
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdEndRendering(VkCommandBuffer commandBuffer) {
    from_handle<CommandBuffer>(commandBuffer)->append<CmdEndRenderPass>();
}

}  // namespace tilevk::icd
