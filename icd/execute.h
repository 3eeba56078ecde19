// Executing recorded command buffers at vkQueueSubmit (on the submitting thread, in submission order).
#pragma once
#include "command_buffer.h"
#include "formats.h"

#include <utility>
#include <vector>

namespace tilevk::icd {

struct Image;
struct ImageView;
struct RenderPass;
struct Framebuffer;
struct Pipeline;
struct DescriptorSet;
struct Buffer;
struct QueryPool;
struct DrawContext;  // execute_draw.cpp: one renderer per queue

// Bound draw state (vkCmdBind*, vkCmdSet*): lives for one command buffer.
struct BoundState {
    static constexpr uint32_t kMaxSets = 4, kMaxVertexBuffers = 16, kMaxDynamicOffsets = 64;
    Pipeline* pipeline = nullptr;
    DescriptorSet* sets[kMaxSets] = {};
    uint32_t dynamic_offsets[kMaxSets][kMaxDynamicOffsets] = {};  // per set, in binding/element order
    Buffer* vertex_buffers[kMaxVertexBuffers] = {};
    VkDeviceSize vertex_offsets[kMaxVertexBuffers] = {};
    Buffer* index_buffer = nullptr;
    VkDeviceSize index_offset = 0;
    VkIndexType index_type = VK_INDEX_TYPE_UINT16;
    alignas(16) uint8_t push_constants[128] = {};
    VkViewport viewport{};
    VkRect2D scissor{};
    float line_width = 1.0f;
    float depth_bias[3] = {0, 0, 0};  // constant, clamp, slope
    float blend_constants[4] = {0, 0, 0, 0};
    uint32_t stencil_compare[2] = {0xff, 0xff}, stencil_write[2] = {0xff, 0xff}, stencil_ref[2] = {0, 0};
};

// State that lives across commands while a queue runs one command buffer.
struct ExecState {
    DrawContext* draw = nullptr;  // the queue's renderer (never null when a queue executes)
    BoundState bound;
    RenderPass* render_pass = nullptr;
    Framebuffer* framebuffer = nullptr;
    uint32_t subpass = 0;
    VkRect2D area{};
    const VkClearValue* clears = nullptr;
    bool draw_warned = false;
    // The active occlusion query (at most one per command buffer): draws add their passing samples to it.
    QueryPool* occlusion_pool = nullptr;
    uint32_t occlusion_query = 0;
    // Queries ended inside a render pass: their last draws may still be binned; they become available when the
    // renderer's pass ends (finish_rendering).
    std::vector<std::pair<QueryPool*, uint32_t>> ended_in_pass;
    // A query command inside the render pass before the renderer's next scene began: that scene is not linear
    // (note_query_command_in_pass).
    bool query_command_pending = false;
};

void execute_command_buffer(CommandBuffer* cb, ExecState& st);

// A query command (begin/end occlusion, timestamp) executed inside a render pass. lavapipe bins it into every tile
// of its current scene, which keeps that scene off its linear rasterizer; tilevk's current (or next) scene of the
// subpass follows it (rast::render::Renderer::mark_scene_not_linear).
void note_query_command_in_pass(ExecState& st);

// ---- draws (execute_draw.cpp) ----
DrawContext* create_draw_context();
void destroy_draw_context(DrawContext* ctx);
// Shader runs the loop watchdog has cut short on this context so far (shader::Scratch::loop_limit_hits).
uint64_t shader_watchdog_hits(const DrawContext& ctx);
// vkCmdBind* / vkCmdSet*: updates st.bound.
void exec_state_command(ExecState& st, const Cmd& cmd);
// vkCmdDraw*: renders into the current subpass (the renderer starts lazily at the subpass's first draw).
void exec_draw_command(ExecState& st, const Cmd& cmd);
// Ends the renderer's pass if one is running: renders what is binned and writes the targets back.
void finish_rendering(ExecState& st);

// ---- queries (execute_query.cpp) ----
void exec_query_command(ExecState& st, const Cmd& cmd);
// Makes the queries ended while draws were binned available (called once the binned draws are rendered).
void publish_ended_queries(ExecState& st);
// After a primary command buffer: a query left active (never ended: invalid usage) is ended with a message, so
// that no host waits for it forever.
void finish_queries(ExecState& st);
// The sample counter of the active occlusion query, or null.
uint64_t* active_occlusion_counter(const ExecState& st);

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
// Packs and writes a colour clear into rect of `layer_count` layers from `base_layer`.
void clear_color_rect(const Image& img, uint32_t level, uint32_t base_layer, uint32_t layer_count, const VkRect2D& rect,
                      const VkClearColorValue& color);
// Clears the given aspects of a depth/stencil image in rect.
void clear_depth_stencil_rect(const Image& img, uint32_t level, uint32_t base_layer, uint32_t layer_count,
                              const VkRect2D& rect, VkImageAspectFlags aspects, const VkClearDepthStencilValue& v);
// Resolves a 4x region into a 1x one, as lavapipe's blitter does (see execute_transfer.cpp).
void resolve_rect(const Image& src, uint32_t src_level, uint32_t src_layer, VkOffset2D src_offset, const Image& dst,
                  uint32_t dst_level, uint32_t dst_layer, VkOffset2D dst_offset, VkExtent2D extent);
// True if resolve_rect implements the format.
bool can_resolve(const FormatInfo& f);

}  // namespace tilevk::icd
