// Executing recorded command buffers at vkQueueSubmit (on the submitting thread, in submission order).
#pragma once
#include "command_buffer.h"
#include "formats.h"
#include "query_pool.h"
#include "rast/render/raster_statistics.h"
#include "rast/render/targets.h"

#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace tilevk::shader {
class Program;
class Bindings;
}  // namespace tilevk::shader
namespace tilevk::rast::render {
struct DrawCall;
struct PipelineState;
}  // namespace tilevk::rast::render

namespace tilevk::icd {

struct Image;
struct RenderPass;
struct Framebuffer;
struct ImageView;
struct Pipeline;
struct DescriptorSet;
struct Buffer;
struct QueryPool;
struct DrawContext;  // execute_draw.cpp: one renderer per queue

// The descriptor sets bound at one bind point (graphics or compute) and their dynamic offsets.
struct BoundSets {
    static constexpr uint32_t kMaxSets = 8, kMaxDynamicOffsets = 64;
    DescriptorSet* sets[kMaxSets] = {};
    uint32_t dynamic_offsets[kMaxSets][kMaxDynamicOffsets] = {};  // per set, in binding/element order
};

// Bound draw and dispatch state (vkCmdBind*, vkCmdSet*): lives for one command buffer. The graphics and compute
// bind points have their own pipeline and sets; push constants are shared (they belong to the layout, not the
// bind point).
struct BoundState {
    static constexpr uint32_t kMaxSets = BoundSets::kMaxSets, kMaxVertexBuffers = kMaxVertexInputs,
                              kMaxDynamicOffsets = BoundSets::kMaxDynamicOffsets;
    Pipeline* pipeline = nullptr;  // graphics
    BoundSets graphics;
    Pipeline* compute_pipeline = nullptr;
    BoundSets compute;
    Buffer* vertex_buffers[kMaxVertexBuffers] = {};
    VkDeviceSize vertex_offsets[kMaxVertexBuffers] = {};
    Buffer* index_buffer = nullptr;
    VkDeviceSize index_offset = 0;
    VkIndexType index_type = VK_INDEX_TYPE_UINT16;
    VkDeviceSize vertex_sizes[kMaxVertexBuffers] = {};  // bytes bound from the offset (VK_WHOLE_SIZE: to the end)
    alignas(16) uint8_t push_constants[128] = {};
    DynamicValues dyn;  // vkCmdSet*: applied where the pipeline's state is dynamic (dynamic_state.cpp)
    // What changed since the draw state was last translated (execute_draw.cpp draw_state): dynamic_bit(state) per
    // vkCmdSet*, kDirtyPipeline for vkCmdBindPipeline. A draw translates the pipeline's state again only when the
    // pipeline or one of the states it takes dynamically changed.
    static constexpr DynamicMask kDirtyPipeline = DynamicMask(1) << 63;
    DynamicMask dirty = ~DynamicMask(0);
};

// State that lives across commands while a queue runs one command buffer.
struct ExecState {
    DrawContext* draw = nullptr;  // the queue's renderer (never null when a queue executes)
    BoundState bound;
    RenderPass* render_pass = nullptr;
    Framebuffer* framebuffer = nullptr;
    // The views of the render pass instance (CmdBeginRenderPass::views); attachment(a) reads them.
    uint32_t view_count = 0;
    ImageView* const* views = nullptr;
    uint32_t subpass = 0;
    VkRect2D area{};
    const VkClearValue* clears = nullptr;
    bool suspending = false;  // CmdBeginRenderPass::suspending of the current render pass instance
    // Multiview: the current subpass's view mask (0: not multiview), the view being rendered (ViewIndex, and the
    // layer of every attachment view it renders into: baseArrayLayer + view) and how many views of the mask came
    // before it (its query offset). Each view runs the subpass's commands on its own: the subpass's Begin/Next
    // command (`subpass_command`) is where the next view starts again, with the bound state the subpass began with.
    uint32_t view_mask = 0, view = 0, view_ordinal = 0;
    const Cmd* current_command = nullptr;  // the command being run (execute_command_buffer)
    const Cmd* subpass_command = nullptr;
    const Cmd* jump_after = nullptr;  // set: execution continues after this command instead of the current one
    BoundState subpass_bound;
    // The active occlusion query (at most one per command buffer): draws add their passing samples to it.
    QueryPool* occlusion_pool = nullptr;
    uint32_t occlusion_query = 0;
    // Queries ended inside a render pass: their last draws may still be binned; they become available when the
    // renderer's pass ends (finish_rendering).
    std::vector<std::pair<QueryPool*, uint32_t>> ended_in_pass;
    // Pipeline statistics, kept as llvmpipe keeps them: running totals (zeroed when a query begins while none is
    // active) and, per active query, its totals at begin (QueryPool::Slot::stats); a query's counts are the
    // difference at its end.
    StatisticCounters statistics_totals{};
    struct ActiveStatistics {
        QueryPool* pool;
        uint32_t query;
        size_t first_epoch;  // its first raster_epochs entry
    };
    std::vector<ActiveStatistics> statistics_queries;  // the active ones
    // The renderer's counts (CLIPPING_PRIMITIVES, fragment-shader blocks) come per draw, the fragment blocks only
    // once its tiles are rendered; lavapipe bins begin/end commands so a query counts exactly the draws between
    // them. Each change of the active set starts an epoch (draws point at raster_epochs.back()), so a query's
    // counts are the sum of the epochs it was active in, read when its draws are rendered. (Boxed, so that draws keep
    // their address; not a std::deque, whose construction allocates in every submission.)
    std::vector<std::unique_ptr<rast::render::RasterStatistics>> raster_epochs;
    struct EndedStatistics {
        QueryPool* pool;
        uint32_t query;
        size_t first_epoch, end_epoch;
        StatisticCounters totals;  // statistics_totals at its end
    };
    std::vector<EndedStatistics> statistics_ended;  // ended, made available once their draws are rendered
    // A query command inside the render pass before the renderer's next scene began: that scene is not linear
    // (note_query_command_in_pass).
    bool query_command_pending = false;
    // The submission's time limit (device_timeout.h): once true, the remaining commands are skipped.
    const std::atomic<bool>* stop = nullptr;
    // Where the running draw comes from, for the device-loss report: pSubmits[submit_index].pCommandBuffers[
    // command_buffer_index], its draw_number-th draw so far (vkCmdDraw* of it and its secondaries, each draw of an
    // indirect command counted).
    uint32_t submit_index = 0, command_buffer_index = 0, draw_number = 0;
    // The active vkCmdBeginConditionalRenderingEXT (null: none): its buffer, the predicate's offset, INVERTED.
    const Buffer* condition_buffer = nullptr;
    VkDeviceSize condition_offset = 0;
    bool condition_inverted = false;
};

void execute_command_buffer(CommandBuffer* cb, ExecState& st);

// The view of attachment `a` of the current render pass instance, or null (VK_ATTACHMENT_UNUSED, or past the views
// given: invalid usage, which renders nothing into it).
inline const ImageView* attachment_view(const ExecState& st, uint32_t a) {
    return a < st.view_count ? st.views[a] : nullptr;
}

// The layer offset the renderer writes into each attachment view: the current view in a multiview subpass, else 0.
inline uint32_t view_layer_offset(const ExecState& st) {
    return st.view_mask != 0 ? st.view : 0;
}

// A query command (begin/end occlusion, timestamp) executed inside a render pass. lavapipe bins it into every tile
// of its current scene, which keeps that scene off its linear rasterizer; tilevk's current (or next) scene of the
// subpass follows it (rast::render::Renderer::mark_scene_not_linear).
void note_query_command_in_pass(ExecState& st);

// ---- draws (execute_draw.cpp) ----
// `stop`: the queue's time-limit flag, which the renderer and its shaders watch (outlives the context).
DrawContext* create_draw_context(const std::atomic<bool>* stop);
void destroy_draw_context(DrawContext* ctx);
// A draw of the current submission, as the device-loss report names it.
struct DrawOrigin {
    VkPipeline pipeline;
    uint32_t submit, command_buffer, draw;
};
// Forgets the previous submission's draws.
void begin_submission(DrawContext& ctx);
// The draw the time limit interrupted in this submission, if the renderer was working on one.
std::optional<DrawOrigin> interrupted_draw(const DrawContext& ctx);
// vkCmdBind* / vkCmdSet*: update st.bound.
void exec_state(ExecState& st, const CmdBindPipeline& c);
void exec_state(ExecState& st, const CmdBindDescriptorSets& c);
void exec_state(ExecState& st, const CmdBindVertexBuffers& c);
void exec_state(ExecState& st, const CmdBindIndexBuffer& c);
void exec_state(ExecState& st, const CmdPushConstants& c);
void exec_state(ExecState& st, const CmdSetViewport& c);
void exec_state(ExecState& st, const CmdSetScissor& c);
void exec_state(ExecState& st, const CmdSetLineWidth& c);
void exec_state(ExecState& st, const CmdSetDepthBias& c);
void exec_state(ExecState& st, const CmdSetBlendConstants& c);
void exec_state(ExecState& st, const CmdSetStencilCompareMask& c);
void exec_state(ExecState& st, const CmdSetStencilWriteMask& c);
void exec_state(ExecState& st, const CmdSetStencilReference& c);
void exec_state(ExecState& st, const CmdSetDynamic& c);
void exec_state(ExecState& st, const CmdSetVertexInput& c);
void exec_state(ExecState& st, const CmdSetAttachmentDynamic& c);
void exec_state(ExecState& st, const CmdSetStencilOp& c);
// vkCmdDraw*: render into the current subpass (the renderer starts lazily at the subpass's first draw).
void exec_draw(ExecState& st, const CmdDraw& c);
void exec_draw(ExecState& st, const CmdDrawIndexed& c);
void exec_draw(ExecState& st, const CmdDrawIndirect& c);
void exec_draw(ExecState& st, const CmdDrawIndexedIndirect& c);
void exec_draw(ExecState& st, const CmdDrawMulti& c);
// Ends the renderer's pass if one is running: renders what is binned and writes the targets back. `resolves`: the
// subpass's colour resolves, done tile by tile as its last scene renders (rast/render/targets.h TileResolve); returns
// true if they were (else the caller resolves).
bool finish_rendering(ExecState& st, const rast::render::TileResolves* resolves = nullptr);
// The descriptors and push constants `program` reads, from the sets bound at the compute bind point (the graphics
// path's translation, execute_draw.cpp). Outside render passes only.
void build_compute_bindings(ExecState& st, const shader::Program& program, shader::Bindings& b);

// ---- dispatches (execute_compute.cpp) ----
void exec_dispatch(ExecState& st, const CmdDispatch& c);
void exec_dispatch(ExecState& st, const CmdDispatchIndirect& c);

// ---- queries (execute_query.cpp) ----
void exec_query(ExecState& st, const CmdBeginQuery& c);
void exec_query(ExecState& st, const CmdEndQuery& c);
void exec_query(ExecState& st, const CmdResetQueryPool& c);
void exec_query(ExecState& st, const CmdWriteTimestamp& c);
void exec_query(ExecState& st, const CmdCopyQueryPoolResults& c);
// Makes the queries ended while draws were binned available (called once the binned draws are rendered).
void publish_ended_queries(ExecState& st);
// After a primary command buffer: a query left active (never ended: invalid usage) is ended with a message, so
// that no host waits for it forever.
void finish_queries(ExecState& st);
// The sample counter of the active occlusion query, or null.
uint64_t* active_occlusion_counter(const ExecState& st);

// ---- pipeline statistics (execute_statistics.cpp) ----
// A draw that lavapipe's draw module would run (render pass, pipeline, index buffer when indexed), while a
// pipeline-statistics query is active: adds its vertex-side counts to st.statistics_totals. `s`: the draw's state;
// `rasterizer_discard`: rasterizerDiscardEnable (the draw is not rendered, but draw still runs its vertices).
void count_draw_statistics(ExecState& st, const rast::render::DrawCall& call, const rast::render::PipelineState& s,
                           bool rasterizer_discard);
// Where the renderer counts a draw's CLIPPING_PRIMITIVES and fragment-shader blocks (DrawCall::statistics):
// the current epoch while a statistics query is active, else null.
rast::render::RasterStatistics* active_raster_statistics(ExecState& st);
// Statistics queries: begin (totals so far, a new epoch) and end (false if it was not active). An ended query is
// made available by publish_statistics once its draws are rendered (at once outside a render pass).
void begin_statistics(ExecState& st, QueryPool& pool, uint32_t query);
bool end_statistics(ExecState& st, QueryPool& pool, uint32_t query);
void publish_statistics(ExecState& st);
// A dispatch of `workgroups` groups of `local_size` invocations each.
void count_dispatch_statistics(ExecState& st, uint64_t workgroups, const std::array<uint32_t, 3>& local_size);

// ---- transfer operations (execute_transfer.cpp) ----
void exec_copy_buffer(const CmdCopyBuffer& c);
void exec_copy_image(const CmdCopyImage& c);
void exec_copy_buffer_to_image(const CmdCopyBufferToImage& c);
void exec_copy_image_to_buffer(const CmdCopyImageToBuffer& c);
void exec_update_buffer(const CmdUpdateBuffer& c);
void exec_fill_buffer(const CmdFillBuffer& c);
void exec_clear_color_image(const CmdClearColorImage& c);
void exec_clear_depth_stencil_image(const CmdClearDepthStencilImage& c);
void exec_resolve_image(const CmdResolveImage& c);

// ---- building blocks shared with render passes ----
// Writes bytes [byte_offset, byte_offset + byte_count) of `texel` into every sample of every texel of `rect`.
void fill_rect(const Image& img, uint32_t level, uint32_t layer, const VkRect2D& rect, const uint8_t* texel,
               uint32_t byte_offset, uint32_t byte_count);
// Packs a colour clear as `as` (the image's format for vkCmdClearColorImage, an attachment view's for load-op clears
// and vkCmdClearAttachments: a MUTABLE_FORMAT image's sRGB view clears with the sRGB encoding, as lavapipe's surface
// of the view's format does) and writes it into rect of `layer_count` layers from `base_layer`.
void clear_color_rect(const Image& img, const FormatInfo& as, uint32_t level, uint32_t base_layer, uint32_t layer_count,
                      const VkRect2D& rect, const VkClearColorValue& color);
// Clears the given aspects of a depth/stencil image in rect.
void clear_depth_stencil_rect(const Image& img, uint32_t level, uint32_t base_layer, uint32_t layer_count,
                              const VkRect2D& rect, VkImageAspectFlags aspects, const VkClearDepthStencilValue& v);
// Resolves a 4x region into a 1x one, as lavapipe's blitter does (see execute_transfer.cpp).
void resolve_rect(const Image& src, uint32_t src_level, uint32_t src_layer, VkOffset2D src_offset, const Image& dst,
                  uint32_t dst_level, uint32_t dst_layer, VkOffset2D dst_offset, VkExtent2D extent);
// True if resolve_rect implements the format.
bool can_resolve(const FormatInfo& f);
// Resolves a 4x depth/stencil region into a 1x one of the same format and place: VK_KHR_depth_stencil_resolve's
// SAMPLE_ZERO, as lavapipe does it (see execute_transfer.cpp).
void resolve_depth_stencil_rect(const Image& src, uint32_t src_level, uint32_t src_layer, const Image& dst,
                                uint32_t dst_level, uint32_t dst_layer, VkOffset2D offset, VkExtent2D extent);

}  // namespace tilevk::icd
