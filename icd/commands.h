// Recorded commands: plain structs in a command buffer's arena, linked in recording order. Nothing runs at
// record time; vkQueueSubmit walks the list (queue.cpp, execute_*.cpp). Draw-path commands are recorded in full
// so that the render path only has to execute them.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

#include "dynamic_state.h"

namespace tilevk::icd {

struct Buffer;
struct Image;
struct Event;
struct Pipeline;
struct DescriptorSet;
struct ImageView;
struct RenderPass;
struct Framebuffer;
struct CommandBuffer;
struct QueryPool;

// Every recorded command, in one list. Adding a command: a line here, its struct below
// (`struct CmdName : CmdOf<CmdType::kName> { ... };`), and an overload `void operator()(const CmdName&)` in
// execute.cpp's CommandRunner (the build fails until every command has one).
// One line per command (not aligned), so that adding one touches one line.
// clang-format off
#define TILEVK_COMMANDS(X) \
    X(CopyBuffer) \
    X(CopyImage) \
    X(CopyBufferToImage) \
    X(CopyImageToBuffer) \
    X(UpdateBuffer) \
    X(FillBuffer) \
    X(ClearColorImage) \
    X(ClearDepthStencilImage) \
    X(ResolveImage) \
    X(BlitImage) \
    X(PipelineBarrier) \
    X(SetEvent) \
    X(ResetEvent) \
    X(WaitEvents) \
    X(BeginRenderPass) \
    X(NextSubpass) \
    X(EndRenderPass) \
    X(ClearAttachments) \
    X(BindPipeline) \
    X(BindDescriptorSets) \
    X(BindVertexBuffers) \
    X(BindIndexBuffer) \
    X(PushConstants) \
    X(SetViewport) \
    X(SetScissor) \
    X(SetLineWidth) \
    X(SetDepthBias) \
    X(SetBlendConstants) \
    X(SetDepthBounds) \
    X(SetStencilCompareMask) \
    X(SetStencilWriteMask) \
    X(SetStencilReference) \
    X(SetDynamic) \
    X(SetStencilOp) \
    X(SetVertexInput) \
    X(SetAttachmentDynamic) \
    X(Draw) \
    X(DrawIndexed) \
    X(DrawIndirect) \
    X(DrawIndexedIndirect) \
    X(DrawMulti) \
    X(Dispatch) \
    X(DispatchIndirect) \
    X(BeginConditionalRendering) \
    X(EndConditionalRendering) \
    X(ExecuteCommands) \
    X(BeginQuery) \
    X(EndQuery) \
    X(ResetQueryPool) \
    X(WriteTimestamp) \
    X(CopyQueryPoolResults)
// clang-format on

enum class CmdType : uint8_t {
#define TILEVK_COMMAND_ENUM(name) k##name,
    TILEVK_COMMANDS(TILEVK_COMMAND_ENUM)
#undef TILEVK_COMMAND_ENUM
};

// The header of every recorded command: its type and the next command in recording order.
struct Cmd {
    CmdType type;
    Cmd* next;
};

// Base of each command struct. The header is a private base, so code cannot cast a Cmd to a command struct:
// the only way from a Cmd to its struct is visit_command below, which casts by the recorded type, so a command
// can never be read through another command's layout.
template <CmdType T>
class CmdOf : private Cmd {
  public:
    static constexpr CmdType kType = T;
    CmdOf() : Cmd{T, nullptr} {}
    Cmd& header() { return *this; }

  private:
    friend struct CommandCast;
};

struct CmdCopyBuffer : CmdOf<CmdType::kCopyBuffer> {
    Buffer *src, *dst;
    uint32_t count;
    const VkBufferCopy* regions;
};
struct CmdCopyImage : CmdOf<CmdType::kCopyImage> {
    Image *src, *dst;
    uint32_t count;
    const VkImageCopy* regions;
};
struct CmdCopyBufferToImage : CmdOf<CmdType::kCopyBufferToImage> {
    Buffer* src;
    Image* dst;
    uint32_t count;
    const VkBufferImageCopy* regions;
};
struct CmdCopyImageToBuffer : CmdOf<CmdType::kCopyImageToBuffer> {
    Image* src;
    Buffer* dst;
    uint32_t count;
    const VkBufferImageCopy* regions;
};
struct CmdUpdateBuffer : CmdOf<CmdType::kUpdateBuffer> {
    Buffer* dst;
    VkDeviceSize offset, size;
    const uint8_t* data;
};
struct CmdFillBuffer : CmdOf<CmdType::kFillBuffer> {
    Buffer* dst;
    VkDeviceSize offset, size;  // size already resolved from VK_WHOLE_SIZE at execution
    uint32_t data;
};
struct CmdClearColorImage : CmdOf<CmdType::kClearColorImage> {
    Image* image;
    VkClearColorValue color;
    uint32_t count;
    const VkImageSubresourceRange* ranges;
};
struct CmdClearDepthStencilImage : CmdOf<CmdType::kClearDepthStencilImage> {
    Image* image;
    VkClearDepthStencilValue value;
    uint32_t count;
    const VkImageSubresourceRange* ranges;
};
struct CmdResolveImage : CmdOf<CmdType::kResolveImage> {
    Image *src, *dst;
    uint32_t count;
    const VkImageResolve* regions;
};
struct CmdBlitImage : CmdOf<CmdType::kBlitImage> {
    Image *src, *dst;
    uint32_t count;
    const VkImageBlit* regions;
    VkFilter filter;
};
struct CmdPipelineBarrier : CmdOf<CmdType::kPipelineBarrier> {
    VkPipelineStageFlags src_stages, dst_stages;
};
struct CmdSetEvent : CmdOf<CmdType::kSetEvent> {
    Event* event;
};
struct CmdResetEvent : CmdOf<CmdType::kResetEvent> {
    Event* event;
};
struct CmdWaitEvents : CmdOf<CmdType::kWaitEvents> {
    uint32_t count;
    Event* const* events;
};
struct CmdBeginRenderPass : CmdOf<CmdType::kBeginRenderPass> {
    RenderPass* render_pass;
    Framebuffer* framebuffer;
    // The views rendered into: the framebuffer's, or an imageless framebuffer's from VkRenderPassAttachmentBeginInfo.
    uint32_t view_count;
    ImageView* const* views;
    VkRect2D area;
    uint32_t clear_count;
    const VkClearValue* clears;
    // vkCmdBeginRendering (dynamic_rendering.cpp records it as this command, render_pass and framebuffer owned by the
    // command buffer): VK_RENDERING_RESUMING_BIT skips the load ops (a suspended instance goes on), and
    // VK_RENDERING_SUSPENDING_BIT makes its vkCmdEndRendering skip the resolves (the instance goes on later).
    bool resuming = false;
    bool suspending = false;
};
struct CmdNextSubpass : CmdOf<CmdType::kNextSubpass> {};
struct CmdEndRenderPass : CmdOf<CmdType::kEndRenderPass> {};
struct CmdClearAttachments : CmdOf<CmdType::kClearAttachments> {
    uint32_t attachment_count;
    const VkClearAttachment* attachments;
    uint32_t rect_count;
    const VkClearRect* rects;
};
struct CmdBindPipeline : CmdOf<CmdType::kBindPipeline> {
    VkPipelineBindPoint bind_point;
    Pipeline* pipeline;
};
// The pipeline layouts of vkCmdBindDescriptorSets and vkCmdPushConstants are not kept: they may be destroyed once
// recording has ended (VUID-vkDestroyPipelineLayout-pipelineLayout-02004 forbids it only while recording).
struct CmdBindDescriptorSets : CmdOf<CmdType::kBindDescriptorSets> {
    VkPipelineBindPoint bind_point;
    uint32_t first_set, set_count;
    DescriptorSet* const* sets;
    uint32_t dynamic_offset_count;
    const uint32_t* dynamic_offsets;
};
struct CmdBindVertexBuffers : CmdOf<CmdType::kBindVertexBuffers> {
    uint32_t first_binding, count;
    Buffer* const* buffers;
    const VkDeviceSize* offsets;
    const VkDeviceSize* sizes = nullptr;    // vkCmdBindVertexBuffers2: the bound ranges (VK_WHOLE_SIZE: to the end)
    const VkDeviceSize* strides = nullptr;  // vkCmdBindVertexBuffers2: VERTEX_INPUT_BINDING_STRIDE values
};
struct CmdBindIndexBuffer : CmdOf<CmdType::kBindIndexBuffer> {
    Buffer* buffer;
    VkDeviceSize offset;
    VkIndexType index_type;
};
struct CmdPushConstants : CmdOf<CmdType::kPushConstants> {
    VkShaderStageFlags stages;
    uint32_t offset, size;
    const uint8_t* values;
};
struct CmdSetViewport : CmdOf<CmdType::kSetViewport> {
    uint32_t first, count;
    const VkViewport* viewports;
};
struct CmdSetScissor : CmdOf<CmdType::kSetScissor> {
    uint32_t first, count;
    const VkRect2D* scissors;
};
struct CmdSetLineWidth : CmdOf<CmdType::kSetLineWidth> {
    float width;
};
struct CmdSetDepthBias : CmdOf<CmdType::kSetDepthBias> {
    float constant_factor, clamp, slope_factor;
};
struct CmdSetBlendConstants : CmdOf<CmdType::kSetBlendConstants> {
    float constants[4];
};
struct CmdSetDepthBounds : CmdOf<CmdType::kSetDepthBounds> {
    float min, max;
};
struct CmdSetStencilCompareMask : CmdOf<CmdType::kSetStencilCompareMask> {
    VkStencilFaceFlags faces;
    uint32_t value;
};
struct CmdSetStencilWriteMask : CmdOf<CmdType::kSetStencilWriteMask> {
    VkStencilFaceFlags faces;
    uint32_t value;
};
struct CmdSetStencilReference : CmdOf<CmdType::kSetStencilReference> {
    VkStencilFaceFlags faces;
    uint32_t value;
};
// One 32-bit dynamic state of extended dynamic state 1/2 (cull mode, front face, topology, depth/stencil/raster
// enables, depth compare op, logic op): `value` is the VkCullModeFlags / VkFrontFace / VkBool32 / ... the command set.
struct CmdSetDynamic : CmdOf<CmdType::kSetDynamic> {
    DynamicState state;
    uint32_t value;
};
struct CmdSetStencilOp : CmdOf<CmdType::kSetStencilOp> {
    VkStencilFaceFlags faces;
    VkStencilOpState ops;  // failOp, passOp, depthFailOp, compareOp (the masks and reference are not set)
};
// vkCmdSetVertexInputEXT, translated when recorded (command_buffer_dynamic3.cpp).
struct CmdSetVertexInput : CmdOf<CmdType::kSetVertexInput> {
    const VertexInputValues* values;
};
// The per-attachment states of extended dynamic state 3 (kColorBlendEnable, kColorBlendEquation, kColorWriteMask):
// attachments first .. first + count - 1 take values[i] (enables and masks) or equations[i].
struct CmdSetAttachmentDynamic : CmdOf<CmdType::kSetAttachmentDynamic> {
    DynamicState state;
    uint32_t first, count;
    const uint32_t* values;
    const VkColorBlendEquationEXT* equations;
};
struct CmdDraw : CmdOf<CmdType::kDraw> {
    uint32_t vertex_count, instance_count, first_vertex, first_instance;
};
struct CmdDrawIndexed : CmdOf<CmdType::kDrawIndexed> {
    uint32_t index_count, instance_count, first_index;
    int32_t vertex_offset;
    uint32_t first_instance;
};
// vkCmdDraw[Indexed]Indirect, and the Count forms (VK_KHR_draw_indirect_count): with a count buffer the number of
// draws is the uint32 there, at most draw_count (maxDrawCount).
struct CmdDrawIndirect : CmdOf<CmdType::kDrawIndirect> {
    Buffer* buffer;
    VkDeviceSize offset;
    uint32_t draw_count, stride;
    Buffer* count_buffer = nullptr;
    VkDeviceSize count_offset = 0;
};
struct CmdDrawIndexedIndirect : CmdOf<CmdType::kDrawIndexedIndirect> {
    Buffer* buffer;
    VkDeviceSize offset;
    uint32_t draw_count, stride;
    Buffer* count_buffer = nullptr;
    VkDeviceSize count_offset = 0;
};
// vkCmdDrawMultiEXT / vkCmdDrawMultiIndexedEXT (VK_EXT_multi_draw): the entries packed (the caller's stride
// applied at record time) as {firstVertex, vertexCount, 0} or {firstIndex, indexCount, vertexOffset}; with
// pVertexOffset every indexed entry takes that one offset.
struct CmdDrawMulti : CmdOf<CmdType::kDrawMulti> {
    bool indexed;
    uint32_t draw_count, instance_count, first_instance;
    const VkMultiDrawIndexedInfoEXT* draws;
};
// vkCmdDispatch (base 0): group_count workgroups from base. vkCmdDispatchIndirect: the counts are the
// VkDispatchIndirectCommand in buffer at offset when the command executes.
struct CmdDispatch : CmdOf<CmdType::kDispatch> {
    uint32_t base[3] = {0, 0, 0};
    uint32_t group_count[3];
};
struct CmdDispatchIndirect : CmdOf<CmdType::kDispatchIndirect> {
    Buffer* buffer;
    VkDeviceSize offset;
};
// vkCmdBeginConditionalRenderingEXT / vkCmdEndConditionalRenderingEXT (VK_EXT_conditional_rendering): the 32-bit
// predicate at `offset` in `buffer` is read when each draw, dispatch or vkCmdClearAttachments between them executes.
struct CmdBeginConditionalRendering : CmdOf<CmdType::kBeginConditionalRendering> {
    Buffer* buffer;
    VkDeviceSize offset;
    bool inverted;  // VK_CONDITIONAL_RENDERING_INVERTED_BIT_EXT
};
struct CmdEndConditionalRendering : CmdOf<CmdType::kEndConditionalRendering> {};
struct CmdExecuteCommands : CmdOf<CmdType::kExecuteCommands> {
    uint32_t count;
    CommandBuffer* const* buffers;
};
struct CmdBeginQuery : CmdOf<CmdType::kBeginQuery> {
    QueryPool* pool;
    uint32_t query;
};
struct CmdEndQuery : CmdOf<CmdType::kEndQuery> {
    QueryPool* pool;
    uint32_t query;
};
struct CmdResetQueryPool : CmdOf<CmdType::kResetQueryPool> {
    QueryPool* pool;
    uint32_t first, count;
};
struct CmdWriteTimestamp : CmdOf<CmdType::kWriteTimestamp> {
    VkPipelineStageFlagBits stage;
    QueryPool* pool;
    uint32_t query;
};
struct CmdCopyQueryPoolResults : CmdOf<CmdType::kCopyQueryPoolResults> {
    QueryPool* pool;
    uint32_t first, count;
    Buffer* dst;
    VkDeviceSize offset, stride;
    VkQueryResultFlags flags;
};

// Reads a recorded command as its own struct: calls f(const CmdName&) for the type its header records. Every
// command type must have an overload in f (a missing one does not compile).
struct CommandCast {
    template <class F>
    static void visit(const Cmd& cmd, F& f) {
        switch (cmd.type) {
#define TILEVK_COMMAND_CASE(name)              \
    case CmdType::k##name:                     \
        f(static_cast<const Cmd##name&>(cmd)); \
        return;
            TILEVK_COMMANDS(TILEVK_COMMAND_CASE)
#undef TILEVK_COMMAND_CASE
        }
    }
};

template <class F>
void visit_command(const Cmd& cmd, F& f) {
    CommandCast::visit(cmd, f);
}

}  // namespace tilevk::icd
