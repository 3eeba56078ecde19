// The command interpreter: walks a command buffer's list and runs each command. Render-pass load/clear and
// resolve run here; draws and their state go to execute_draw.cpp.
#include "execute.h"

#include "execute_blit.h"

#include "buffer.h"
#include "framebuffer.h"
#include "image.h"
#include "rast/render/stage_timer.h"
#include "render_pass.h"
#include "sync.h"
#include "vk_names.h"
#include "workers.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <utility>
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
    const rast::render::StageScope timed(rast::render::Stage::kAttach);
    const RenderPass& rp = *st.render_pass;
    // Reused from pass to pass on the submitting thread (a steady frame allocates nothing). The worker tasks below
    // read them through these references, not by name (a thread_local names each thread's own).
    static thread_local std::vector<LoadClear> clears_storage;
    static thread_local std::vector<size_t> first_task_storage;
    std::vector<LoadClear>& clears = clears_storage;
    std::vector<size_t>& first_task = first_task_storage;
    clears.clear();
    for (uint32_t a = 0; a < rp.attachments.size(); ++a) {
        const ImageView* view = attachment_view(st, a);
        // Multiview: the views first rendered here (render_pass.cpp plan_view_loads), one layer each.
        const uint32_t views = rp.multiview ? rp.subpasses[sp].load_views[a] : 0;
        if (view == nullptr || (rp.multiview ? views == 0 : rp.first_use[a] != sp)) continue;
        const VkAttachmentDescription& d = rp.attachments[a];
        const ImageView& v = *view;
        VkImageAspectFlags aspects = 0;
        if (v.format->aspects & VK_IMAGE_ASPECT_COLOR_BIT) {
            if (d.loadOp == VK_ATTACHMENT_LOAD_OP_CLEAR) aspects = VK_IMAGE_ASPECT_COLOR_BIT;
        } else {
            if (d.loadOp == VK_ATTACHMENT_LOAD_OP_CLEAR) aspects |= VK_IMAGE_ASPECT_DEPTH_BIT;
            if (d.stencilLoadOp == VK_ATTACHMENT_LOAD_OP_CLEAR) aspects |= VK_IMAGE_ASPECT_STENCIL_BIT;
        }
        if (aspects == 0) continue;
        const VkRect2D rect = clip_to_view(st.area, v);
        if (rp.multiview) {
            for (uint32_t m = views; m != 0; m &= m - 1)
                clears.push_back(
                    {&v, v.range.baseArrayLayer + uint32_t(std::countr_zero(m)), rect, aspects, st.clears[a]});
            continue;
        }
        const uint32_t layers = std::min(v.range.layerCount, st.framebuffer->layers);
        for (uint32_t l = 0; l < layers; ++l)
            clears.push_back({&v, v.range.baseArrayLayer + l, rect, aspects, st.clears[a]});
    }
    // Tasks: the bands of every clear, in order.
    first_task.assign(clears.size() + 1, 0);
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
            clear_color_rect(img, *c.view->format, level, c.layer, 1, rect, c.value.color);
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

// Runs `resolve(layer, offset, extent)` over `rect` of every layer the subpass resolves (the framebuffer's, or in a
// multiview subpass the views of its mask), in bands of rows on the workers: each pixel's resolve reads only its own
// samples, so the bands are independent.
template <class Resolve>
void resolve_in_bands(ExecState& st, const Subpass& s, const ImageView& src, const VkRect2D& rect, Resolve&& resolve) {
    const uint32_t layers = std::min(src.range.layerCount, st.framebuffer->layers);
    const uint32_t layer_mask = s.view_mask != 0 ? s.view_mask : (layers >= 32 ? ~0u : (1u << layers) - 1);
    constexpr uint32_t kBandRows = 32;
    const size_t bands = (rect.extent.height + kBandRows - 1) / kBandRows;
    for (uint32_t m = layer_mask; m != 0; m &= m - 1) {
        const uint32_t l = uint32_t(std::countr_zero(m));
        run_on_workers(st, bands, [&](size_t band) {
            const uint32_t y0 = uint32_t(band) * kBandRows;
            const VkOffset2D offset{rect.offset.x, rect.offset.y + int32_t(y0)};
            const VkExtent2D extent{rect.extent.width, std::min(kBandRows, rect.extent.height - y0)};
            resolve(l, offset, extent);
        });
    }
}

// The subpass's colour resolves as the renderer's last scene can run them, tile by tile while each tile is in cache
// (rast/render/targets.h TileResolve): a 4x attachment the renderer draws into in place (every colour format is),
// one layer, no multiview (each view is a pass of its own). Any other resolve stays whole-image, after rendering.
void plan_tile_resolves(const ExecState& st, uint32_t sp, rast::render::TileResolves& out) {
    out.count = 0;
    const Subpass& s = st.render_pass->subpasses[sp];
    if (s.view_mask != 0) return;
    for (size_t i = 0; i < s.resolves.size() && i < size_t(rast::render::kMaxColorTargets); ++i) {
        const ImageView* src = attachment_view(st, s.colors[i].attachment);
        const ImageView* dst = attachment_view(st, s.resolves[i].attachment);
        if (src == nullptr || dst == nullptr || dst->image->memory == nullptr) continue;
        if (!can_resolve(*src->format) || !(image_features(*src->format) & format::kColorAttachment) ||
            src->image->samples != uint32_t(rast::fragment::kMaxSamples) || dst->image->samples != 1 ||
            dst->format->bytes != src->format->bytes || std::min(src->range.layerCount, st.framebuffer->layers) != 1)
            continue;
        const VkRect2D rect = clip_to_view(clip_to_view(st.area, *src), *dst);
        const uint32_t level = dst->range.baseMipLevel;
        rast::render::TileResolve& r = out.items[out.count++];
        r.target = uint32_t(i);
        r.dst = dst->image->texel(level, dst->range.baseArrayLayer, 0, 0);
        r.dst_pitch = size_t(dst->image->layout.row_pitch[level]);
        r.x0 = rect.offset.x;
        r.y0 = rect.offset.y;
        r.x1 = rect.offset.x + int32_t(rect.extent.width);
        r.y1 = rect.offset.y + int32_t(rect.extent.height);
    }
}

// Renders the subpass's last scene; with `resolve` its colour resolves are planned for the renderer's tiles.
// Returns whether they ran there.
bool finish_subpass(ExecState& st, bool resolve) {
    static thread_local rast::render::TileResolves plan;  // the submitting thread's, reused
    if (!resolve) {
        finish_rendering(st);
        return false;
    }
    plan_tile_resolves(st, st.subpass, plan);
    return finish_rendering(st, plan.count != 0 ? &plan : nullptr);
}

// Resolves the subpass's colour attachments into its resolve attachments over the render area, then its
// depth/stencil attachment into its depth/stencil resolve attachment (lavapipe's lvp_execute.c render_resolve runs
// them in the other order; they write different attachments).
// `tiled`: the resolves plan_tile_resolves chose were done by the renderer's tiles.
void resolve_attachments(ExecState& st, uint32_t sp, bool tiled) {
    const rast::render::StageScope timed(rast::render::Stage::kResolve);
    const Subpass& s = st.render_pass->subpasses[sp];
    rast::render::TileResolves done;
    if (tiled) plan_tile_resolves(st, sp, done);
    for (size_t i = 0, next = 0; i < s.resolves.size(); ++i) {
        if (next < done.count && done.items[next].target == i) {
            ++next;
            continue;
        }
        uint32_t src_a = s.colors[i].attachment, dst_a = s.resolves[i].attachment;
        const ImageView* src_view = attachment_view(st, src_a);
        const ImageView* dst_view = attachment_view(st, dst_a);
        if (src_view == nullptr || dst_view == nullptr) continue;
        const ImageView& src = *src_view;
        const ImageView& dst = *dst_view;
        if (!can_resolve(*src.format)) {
            log_error("render pass resolve: resolving %s is not implemented; attachment %u not resolved",
                      vk_enum_name(vk_format(*src.format)), dst_a);
            continue;
        }
        const VkRect2D rect = clip_to_view(clip_to_view(st.area, src), dst);
        resolve_in_bands(st, s, src, rect, [&](uint32_t l, VkOffset2D offset, VkExtent2D extent) {
            resolve_rect(*src.image, src.range.baseMipLevel, src.range.baseArrayLayer + l, offset, *dst.image,
                         dst.range.baseMipLevel, dst.range.baseArrayLayer + l, offset, extent);
        });
    }
    const ImageView* ds_src = attachment_view(st, s.depth_stencil.attachment);
    const ImageView* ds_dst = attachment_view(st, s.ds_resolve.attachment);
    if (ds_src == nullptr || ds_dst == nullptr) return;
    if (s.depth_resolve == VK_RESOLVE_MODE_NONE && s.stencil_resolve == VK_RESOLVE_MODE_NONE) return;
    const ImageView& src = *ds_src;
    const ImageView& dst = *ds_dst;
    const VkRect2D rect = clip_to_view(clip_to_view(st.area, src), dst);
    resolve_in_bands(st, s, src, rect, [&](uint32_t l, VkOffset2D offset, VkExtent2D extent) {
        resolve_depth_stencil_rect(*src.image, src.range.baseMipLevel, src.range.baseArrayLayer + l, *dst.image,
                                   dst.range.baseMipLevel, dst.range.baseArrayLayer + l, offset, extent);
    });
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
        const ImageView* view = attachment_view(st, a);
        if (view == nullptr) continue;
        const ImageView& v = *view;
        for (uint32_t r = 0; r < c.rect_count; ++r) {
            const VkClearRect& cr = c.rects[r];
            const VkRect2D rect = clip_to_view(cr.rect, v);
            // In a multiview subpass the rect names layer 0 of one layer (VUID-vkCmdClearAttachments-baseArrayLayer-
            // 00018) and the clear applies to the view being rendered (each view runs the command on its own).
            uint32_t base = v.range.baseArrayLayer + cr.baseArrayLayer, count = cr.layerCount;
            if (st.view_mask != 0) {
                base = v.range.baseArrayLayer + st.view;
                count = 1;
            }
            if (ca.aspectMask & VK_IMAGE_ASPECT_COLOR_BIT) {
                clear_color_rect(*v.image, *v.format, v.range.baseMipLevel, base, count, rect, ca.clearValue.color);
            } else {
                clear_depth_stencil_rect(*v.image, v.range.baseMipLevel, base, count, rect, ca.aspectMask,
                                         ca.clearValue.depthStencil);
            }
        }
    }
}

// Whether the draw, dispatch or vkCmdClearAttachments being executed runs: outside conditional rendering always;
// inside, when the 32-bit predicate read now is non-zero (zero with INVERTED). lavapipe reads it the same way when
// each command executes (llvmpipe lp_query.c llvmpipe_check_render_cond: `(!data) == inverted` skips it), and skips
// those commands alone: load-op clears, resolves, copies and blits run (docs/lavapipe-rules.md "Conditional
// rendering").
bool condition_passes(const ExecState& st) {
    const Buffer* b = st.condition_buffer;
    if (b == nullptr) return true;
    uint32_t predicate = 0;
    if (b->memory == nullptr || st.condition_offset > b->size || b->size - st.condition_offset < sizeof predicate) {
        log_error(
            "vkCmdBeginConditionalRenderingEXT: offset %llu + 4 bytes lies outside the buffer; the predicate "
            "reads as 0",
            static_cast<unsigned long long>(st.condition_offset));
    } else {
        std::memcpy(&predicate, b->data() + st.condition_offset, sizeof predicate);
    }
    return (predicate != 0) != st.condition_inverted;
}

// A subpass begins (after its load ops): a multiview subpass starts with its lowest view and remembers where it began.
void begin_subpass_views(ExecState& st) {
    st.view_mask = st.render_pass->subpasses[st.subpass].view_mask;
    st.view = st.view_mask != 0 ? uint32_t(std::countr_zero(st.view_mask)) : 0;
    st.view_ordinal = 0;
    if (st.view_mask == 0) return;
    st.subpass_command = st.current_command;
    st.subpass_bound = st.bound;
}

// A subpass ends (at vkCmdNextSubpass / vkCmdEndRenderPass): in a multiview subpass with views left, the next view
// runs the subpass's commands again from its beginning, with the state bound then. Returns true if it does.
bool next_view(ExecState& st) {
    const uint32_t rest = st.view_mask & ~((2u << st.view) - 1);
    if (rest == 0 || st.subpass_command == nullptr) return false;
    st.view = uint32_t(std::countr_zero(rest));
    ++st.view_ordinal;
    st.bound = st.subpass_bound;
    st.bound.dirty = ~DynamicMask(0);  // the renderer's translated states ended with its pass
    st.jump_after = st.subpass_command;
    return true;
}

// Runs each command as its own type (commands.h visit_command).
struct CommandRunner {
    ExecState& st;

    void operator()(const CmdCopyBuffer& c) { exec_copy_buffer(c); }
    void operator()(const CmdCopyImage& c) { exec_copy_image(c); }
    void operator()(const CmdCopyBufferToImage& c) { exec_copy_buffer_to_image(c); }
    void operator()(const CmdCopyImageToBuffer& c) { exec_copy_image_to_buffer(c); }
    void operator()(const CmdUpdateBuffer& c) { exec_update_buffer(c); }
    void operator()(const CmdFillBuffer& c) { exec_fill_buffer(c); }
    void operator()(const CmdClearColorImage& c) { exec_clear_color_image(c); }
    void operator()(const CmdClearDepthStencilImage& c) { exec_clear_depth_stencil_image(c); }
    void operator()(const CmdResolveImage& c) { exec_resolve_image(c); }
    void operator()(const CmdBlitImage& c) { exec_blit_image(st, c); }
    // Execution is serial and in order, so barriers have nothing left to order.
    void operator()(const CmdPipelineBarrier&) {}
    void operator()(const CmdSetEvent& c) { c.event->set.store(true); }
    void operator()(const CmdResetEvent& c) { c.event->set.store(false); }
    // Device-side sets happened earlier in this serial stream; host sets must precede the submission.
    void operator()(const CmdWaitEvents&) {}

    void operator()(const CmdBeginRenderPass& c) {
        st.render_pass = c.render_pass;
        st.framebuffer = c.framebuffer;
        st.view_count = c.view_count;
        st.views = c.views;
        st.area = c.area;
        st.clears = c.clears;
        st.subpass = 0;
        st.suspending = c.suspending;
        if (!c.resuming) load_attachments(st, 0);
        begin_subpass_views(st);
    }
    void operator()(const CmdNextSubpass&) {
        if (st.render_pass == nullptr) return;
        const bool tiled = finish_subpass(st, st.view_mask == 0);
        st.query_command_pending = false;  // it belonged to the subpass that ended
        if (next_view(st)) return;
        resolve_attachments(st, st.subpass, tiled);
        ++st.subpass;
        load_attachments(st, st.subpass);
        begin_subpass_views(st);
    }
    void operator()(const CmdEndRenderPass&) {
        if (st.render_pass == nullptr) return;
        const bool tiled = finish_subpass(st, st.view_mask == 0 && !st.suspending);
        st.query_command_pending = false;
        if (next_view(st)) return;
        if (!st.suspending) resolve_attachments(st, st.subpass, tiled);
        st.view_mask = 0;
        st.subpass_command = nullptr;
        st.render_pass = nullptr;
        st.framebuffer = nullptr;
        st.view_count = 0;
        st.views = nullptr;
    }
    void operator()(const CmdClearAttachments& c) {
        if (!condition_passes(st)) return;
        // Binned draws render first, so the clear lands after them in API order.
        finish_rendering(st);
        clear_attachments(st, c);
    }
    void operator()(const CmdExecuteCommands& c) {
        for (uint32_t i = 0; i < c.count; ++i) execute_command_buffer(c.buffers[i], st);
    }

    void operator()(const CmdBindPipeline& c) { exec_state(st, c); }
    void operator()(const CmdBindDescriptorSets& c) { exec_state(st, c); }
    void operator()(const CmdBindVertexBuffers& c) { exec_state(st, c); }
    void operator()(const CmdBindIndexBuffer& c) { exec_state(st, c); }
    void operator()(const CmdPushConstants& c) { exec_state(st, c); }
    void operator()(const CmdSetViewport& c) { exec_state(st, c); }
    void operator()(const CmdSetScissor& c) { exec_state(st, c); }
    void operator()(const CmdSetLineWidth& c) { exec_state(st, c); }
    void operator()(const CmdSetDepthBias& c) { exec_state(st, c); }
    void operator()(const CmdSetBlendConstants& c) { exec_state(st, c); }
    // Depth bounds are not reported (the feature is VK_FALSE), so nothing reads them.
    void operator()(const CmdSetDepthBounds&) {}
    void operator()(const CmdSetStencilCompareMask& c) { exec_state(st, c); }
    void operator()(const CmdSetStencilWriteMask& c) { exec_state(st, c); }
    void operator()(const CmdSetStencilReference& c) { exec_state(st, c); }
    void operator()(const CmdSetDynamic& c) { exec_state(st, c); }
    void operator()(const CmdSetStencilOp& c) { exec_state(st, c); }
    void operator()(const CmdSetVertexInput& c) { exec_state(st, c); }
    void operator()(const CmdSetAttachmentDynamic& c) { exec_state(st, c); }
    // A draw or dispatch that conditional rendering discards does nothing at all: no fetch of its indirect
    // parameters, no query counts (llvmpipe's draw_vbo and launch_grid return first thing).
    void operator()(const CmdDraw& c) { run_if_condition(c); }
    void operator()(const CmdDrawIndexed& c) { run_if_condition(c); }
    void operator()(const CmdDrawIndirect& c) { run_if_condition(c); }
    void operator()(const CmdDrawIndexedIndirect& c) { run_if_condition(c); }
    void operator()(const CmdDrawMulti& c) { run_if_condition(c); }
    void operator()(const CmdDispatch& c) { run_if_condition(c); }
    void operator()(const CmdDispatchIndirect& c) { run_if_condition(c); }
    void operator()(const CmdBeginConditionalRendering& c) {
        st.condition_buffer = c.buffer;
        st.condition_offset = c.offset;
        st.condition_inverted = c.inverted;
    }
    void operator()(const CmdEndConditionalRendering&) { st.condition_buffer = nullptr; }
    template <class C>
    void run_if_condition(const C& c) {
        if (!condition_passes(st)) return;
        if constexpr (requires { exec_draw(st, c); })
            exec_draw(st, c);
        else
            exec_dispatch(st, c);
    }

    void operator()(const CmdBeginQuery& c) { exec_query(st, c); }
    void operator()(const CmdEndQuery& c) { exec_query(st, c); }
    void operator()(const CmdResetQueryPool& c) { exec_query(st, c); }
    void operator()(const CmdWriteTimestamp& c) { exec_query(st, c); }
    void operator()(const CmdCopyQueryPoolResults& c) { exec_query(st, c); }
};

}  // namespace

void execute_command_buffer(CommandBuffer* cb, ExecState& st) {
    CommandRunner run{st};
    for (const Cmd* cmd = cb->first; cmd != nullptr; cmd = cmd->next) {
        if (st.stop != nullptr && st.stop->load(std::memory_order_relaxed)) return;  // past the time limit
        st.current_command = cmd;
        visit_command(*cmd, run);
        // A multiview subpass's next view: back to its Begin/Next command (in this, the primary, command buffer).
        if (st.jump_after != nullptr) cmd = std::exchange(st.jump_after, nullptr);
    }
}

}  // namespace tilevk::icd
