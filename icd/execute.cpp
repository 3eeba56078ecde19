// The command interpreter: walks a command buffer's list and runs each command. Render-pass load/clear and
// resolve run here; draws and their state go to execute_draw.cpp.
#include "execute.h"

#include "execute_blit.h"

#include "framebuffer.h"
#include "image.h"
#include "render_pass.h"
#include "sync.h"
#include "workers.h"

#include <algorithm>
#include <vector>

namespace tilevk::icd {
namespace {

VkRect2D clip_to_view(const VkRect2D& area, const ImageView& v) {
    // The render area lies inside the framebuffer, which lies inside every attachment: no clipping needed beyond
    // the view's level size, which guards against invalid input.
    const uint32_t w = v.image->level_width(v.range.baseMipLevel), h = v.image->level_height(v.range.baseMipLevel);
    VkRect2D r = area;
    if (r.offset.x < 0 || r.offset.y < 0 || uint32_t(r.offset.x) >= w || uint32_t(r.offset.y) >= h) return {};
    r.extent.width = std::min(r.extent.width, w - uint32_t(r.offset.x));
    r.extent.height = std::min(r.extent.height, h - uint32_t(r.offset.y));
    return r;
}

// One load-op clear of one layer of one attachment.
struct LoadClear {
    const ImageView* view;
    uint32_t layer;
    VkRect2D rect;
    VkImageAspectFlags aspects;  // COLOR, or DEPTH and/or STENCIL
    VkClearValue value;
};

// Rows per clear task: a band of 64-row tiles (the renderer's tile height), small enough to spread 1024 rows over
// the workers and large enough that a task is not dominated by the pool's hand-off.
constexpr uint32_t kClearBandRows = 64;

// Applies the load ops of attachments first used in subpass `sp`. The clears run on the renderer's workers in
// bands of rows; every band writes the same value to disjoint rows, so the result does not depend on the thread
// count or the order the bands run in.
void load_attachments(ExecState& st, uint32_t sp) {
    const RenderPass& rp = *st.render_pass;
    std::vector<LoadClear> clears;
    for (uint32_t a = 0; a < rp.attachments.size(); ++a) {
        if (rp.first_use[a] != sp || a >= st.framebuffer->attachments.size()) continue;
        const VkAttachmentDescription& d = rp.attachments[a];
        const ImageView& v = *st.framebuffer->attachments[a];
        VkImageAspectFlags aspects = 0;
        if (v.format->aspects & VK_IMAGE_ASPECT_COLOR_BIT) {
            if (d.loadOp == VK_ATTACHMENT_LOAD_OP_CLEAR) aspects = VK_IMAGE_ASPECT_COLOR_BIT;
        } else {
            if (d.loadOp == VK_ATTACHMENT_LOAD_OP_CLEAR) aspects |= VK_IMAGE_ASPECT_DEPTH_BIT;
            if (d.stencilLoadOp == VK_ATTACHMENT_LOAD_OP_CLEAR) aspects |= VK_IMAGE_ASPECT_STENCIL_BIT;
        }
        if (aspects == 0) continue;
        const VkRect2D rect = clip_to_view(st.area, v);
        const uint32_t layers = std::min(v.range.layerCount, st.framebuffer->layers);
        for (uint32_t l = 0; l < layers; ++l)
            clears.push_back({&v, v.range.baseArrayLayer + l, rect, aspects, st.clears[a]});
    }
    // Tasks: the bands of every clear, in order.
    std::vector<size_t> first_task(clears.size() + 1, 0);
    for (size_t i = 0; i < clears.size(); ++i) {
        const uint32_t bands = (clears[i].rect.extent.height + kClearBandRows - 1) / kClearBandRows;
        first_task[i + 1] = first_task[i] + bands;
    }
    const auto clear_band = [&](size_t task) {
        const size_t i = size_t(std::upper_bound(first_task.begin(), first_task.end(), task) - first_task.begin()) - 1;
        const LoadClear& c = clears[i];
        const uint32_t band = uint32_t(task - first_task[i]);
        VkRect2D rect = c.rect;
        rect.offset.y += int32_t(band * kClearBandRows);
        rect.extent.height = std::min(kClearBandRows, c.rect.extent.height - band * kClearBandRows);
        const Image& img = *c.view->image;
        const uint32_t level = c.view->range.baseMipLevel;
        if (c.aspects & VK_IMAGE_ASPECT_COLOR_BIT)
            clear_color_rect(img, level, c.layer, 1, rect, c.value.color);
        else
            clear_depth_stencil_rect(img, level, c.layer, 1, rect, c.aspects, c.value.depthStencil);
    };
    // Attachments that alias one image layer (VK_ATTACHMENT_DESCRIPTION_MAY_ALIAS_BIT) clear one after the other in
    // attachment order, so the last one wins whatever the thread count; otherwise every task owns its rows.
    bool aliased = false;
    for (size_t i = 0; i < clears.size() && !aliased; ++i)
        for (size_t j = i + 1; j < clears.size() && !aliased; ++j)
            aliased = clears[i].view->image == clears[j].view->image && clears[i].layer == clears[j].layer;
    if (aliased) {
        for (size_t task = 0; task < first_task.back(); ++task) clear_band(task);
    } else {
        run_on_workers(st, first_task.back(), clear_band);
    }
}

// Resolves the subpass's colour attachments into its resolve attachments over the render area.
void resolve_attachments(ExecState& st, uint32_t sp) {
    const Subpass& s = st.render_pass->subpasses[sp];
    for (size_t i = 0; i < s.resolves.size(); ++i) {
        uint32_t src_a = s.colors[i].attachment, dst_a = s.resolves[i].attachment;
        if (src_a == VK_ATTACHMENT_UNUSED || dst_a == VK_ATTACHMENT_UNUSED) continue;
        const ImageView& src = *st.framebuffer->attachments[src_a];
        const ImageView& dst = *st.framebuffer->attachments[dst_a];
        if (!can_resolve(*src.format)) {
            log_error("render pass resolve: format %d is not implemented; attachment %u not resolved",
                      int(src.format->format), dst_a);
            continue;
        }
        const VkRect2D rect = clip_to_view(clip_to_view(st.area, src), dst);
        const uint32_t layers = std::min(src.range.layerCount, st.framebuffer->layers);
        for (uint32_t l = 0; l < layers; ++l) {
            resolve_rect(*src.image, src.range.baseMipLevel, src.range.baseArrayLayer + l, rect.offset, *dst.image,
                         dst.range.baseMipLevel, dst.range.baseArrayLayer + l, rect.offset, rect.extent);
        }
    }
}

void clear_attachments(ExecState& st, const CmdClearAttachments& c) {
    if (st.render_pass == nullptr) return;
    const Subpass& s = st.render_pass->subpasses[st.subpass];
    for (uint32_t i = 0; i < c.attachment_count; ++i) {
        const VkClearAttachment& ca = c.attachments[i];
        uint32_t a = VK_ATTACHMENT_UNUSED;
        if (ca.aspectMask & VK_IMAGE_ASPECT_COLOR_BIT) {
            if (ca.colorAttachment < s.colors.size()) a = s.colors[ca.colorAttachment].attachment;
        } else {
            a = s.depth_stencil.attachment;
        }
        if (a == VK_ATTACHMENT_UNUSED) continue;
        const ImageView& v = *st.framebuffer->attachments[a];
        for (uint32_t r = 0; r < c.rect_count; ++r) {
            const VkClearRect& cr = c.rects[r];
            const VkRect2D rect = clip_to_view(cr.rect, v);
            const uint32_t base = v.range.baseArrayLayer + cr.baseArrayLayer;
            if (ca.aspectMask & VK_IMAGE_ASPECT_COLOR_BIT) {
                clear_color_rect(*v.image, v.range.baseMipLevel, base, cr.layerCount, rect, ca.clearValue.color);
            } else {
                clear_depth_stencil_rect(*v.image, v.range.baseMipLevel, base, cr.layerCount, rect, ca.aspectMask,
                                         ca.clearValue.depthStencil);
            }
        }
    }
}

}  // namespace

void execute_command_buffer(CommandBuffer* cb, ExecState& st) {
    for (Cmd* cmd = cb->first; cmd != nullptr; cmd = cmd->next) {
        switch (cmd->type) {
            case CmdType::kCopyBuffer:
                exec_copy_buffer(*static_cast<CmdCopyBuffer*>(cmd));
                break;
            case CmdType::kCopyImage:
                exec_copy_image(*static_cast<CmdCopyImage*>(cmd));
                break;
            case CmdType::kCopyBufferToImage:
                exec_copy_buffer_to_image(*static_cast<CmdCopyBufferToImage*>(cmd));
                break;
            case CmdType::kCopyImageToBuffer:
                exec_copy_image_to_buffer(*static_cast<CmdCopyImageToBuffer*>(cmd));
                break;
            case CmdType::kUpdateBuffer:
                exec_update_buffer(*static_cast<CmdUpdateBuffer*>(cmd));
                break;
            case CmdType::kFillBuffer:
                exec_fill_buffer(*static_cast<CmdFillBuffer*>(cmd));
                break;
            case CmdType::kClearColorImage:
                exec_clear_color_image(*static_cast<CmdClearColorImage*>(cmd));
                break;
            case CmdType::kClearDepthStencilImage:
                exec_clear_depth_stencil_image(*static_cast<CmdClearDepthStencilImage*>(cmd));
                break;
            case CmdType::kResolveImage:
                exec_resolve_image(*static_cast<CmdResolveImage*>(cmd));
                break;
            case CmdType::kBlitImage:
                exec_blit_image(*static_cast<CmdBlitImage*>(cmd));
                break;
            // Execution is serial and in order, so barriers have nothing left to order.
            case CmdType::kPipelineBarrier:
                break;
            case CmdType::kSetEvent:
                static_cast<CmdSetEvent*>(cmd)->event->set.store(true);
                break;
            case CmdType::kResetEvent:
                static_cast<CmdResetEvent*>(cmd)->event->set.store(false);
                break;
            // Device-side sets happened earlier in this serial stream; host sets must precede the submission.
            case CmdType::kWaitEvents:
                break;
            case CmdType::kBeginRenderPass: {
                auto* c = static_cast<CmdBeginRenderPass*>(cmd);
                st.render_pass = c->render_pass;
                st.framebuffer = c->framebuffer;
                st.area = c->area;
                st.clears = c->clears;
                st.subpass = 0;
                load_attachments(st, 0);
                break;
            }
            case CmdType::kNextSubpass:
                if (st.render_pass == nullptr) break;
                finish_rendering(st);
                st.query_command_pending = false;  // it belonged to the subpass that ended
                resolve_attachments(st, st.subpass);
                ++st.subpass;
                load_attachments(st, st.subpass);
                break;
            case CmdType::kEndRenderPass:
                if (st.render_pass == nullptr) break;
                finish_rendering(st);
                st.query_command_pending = false;
                resolve_attachments(st, st.subpass);
                st.render_pass = nullptr;
                st.framebuffer = nullptr;
                break;
            case CmdType::kClearAttachments:
                // Binned draws render first, so the clear lands after them in API order.
                finish_rendering(st);
                clear_attachments(st, *static_cast<CmdClearAttachments*>(cmd));
                break;
            case CmdType::kExecuteCommands: {
                auto* c = static_cast<CmdExecuteCommands*>(cmd);
                for (uint32_t i = 0; i < c->count; ++i) execute_command_buffer(c->buffers[i], st);
                break;
            }
            case CmdType::kBeginQuery:
            case CmdType::kEndQuery:
            case CmdType::kResetQueryPool:
            case CmdType::kWriteTimestamp:
            case CmdType::kCopyQueryPoolResults:
                exec_query_command(st, *cmd);
                break;
            case CmdType::kDraw:
            case CmdType::kDrawIndexed:
            case CmdType::kDrawIndirect:
            case CmdType::kDrawIndexedIndirect:
                exec_draw_command(st, *cmd);
                break;
            default:  // vkCmdBind* / vkCmdSet*
                exec_state_command(st, *cmd);
                break;
        }
    }
}

}  // namespace tilevk::icd
