// Recorded commands: plain structs in a command buffer's arena, linked in recording order. Nothing runs at
// record time; vkQueueSubmit walks the list (queue.cpp, execute_*.cpp). Draw-path commands are recorded in full
// so that the render path only has to execute them.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

namespace tilevk::icd {

struct Buffer;
struct Image;
struct Event;
struct Pipeline;
struct PipelineLayout;
struct DescriptorSet;
struct RenderPass;
struct Framebuffer;
struct CommandBuffer;
struct QueryPool;

enum class CmdType : uint8_t {
    // transfer
    kCopyBuffer,
    kCopyImage,
    kCopyBufferToImage,
    kCopyImageToBuffer,
    kUpdateBuffer,
    kFillBuffer,
    kClearColorImage,
    kClearDepthStencilImage,
    kResolveImage,
    kBlitImage,
    // synchronisation
    kPipelineBarrier,
    kSetEvent,
    kResetEvent,
    kWaitEvents,
    // render passes
    kBeginRenderPass,
    kNextSubpass,
    kEndRenderPass,
    kClearAttachments,
    // state and draws (executed by the render path)
    kBindPipeline,
    kBindDescriptorSets,
    kBindVertexBuffers,
    kBindIndexBuffer,
    kPushConstants,
    kSetViewport,
    kSetScissor,
    kSetLineWidth,
    kSetDepthBias,
    kSetBlendConstants,
    kSetDepthBounds,
    kSetStencilCompareMask,
    kSetStencilWriteMask,
    kSetStencilReference,
    kDraw,
    kDrawIndexed,
    kDrawIndirect,
    kDrawIndexedIndirect,
    // secondary command buffers
    kExecuteCommands,
    // queries (execute_query.cpp)
    kBeginQuery,
    kEndQuery,
    kResetQueryPool,
    kWriteTimestamp,
    kCopyQueryPoolResults,
};

struct Cmd {
    CmdType type;
    Cmd* next;
};

template <CmdType T>
struct CmdOf : Cmd {
    static constexpr CmdType kType = T;
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
    VkRect2D area;
    uint32_t clear_count;
    const VkClearValue* clears;
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
struct CmdBindDescriptorSets : CmdOf<CmdType::kBindDescriptorSets> {
    VkPipelineBindPoint bind_point;
    PipelineLayout* layout;
    uint32_t first_set, set_count;
    DescriptorSet* const* sets;
    uint32_t dynamic_offset_count;
    const uint32_t* dynamic_offsets;
};
struct CmdBindVertexBuffers : CmdOf<CmdType::kBindVertexBuffers> {
    uint32_t first_binding, count;
    Buffer* const* buffers;
    const VkDeviceSize* offsets;
};
struct CmdBindIndexBuffer : CmdOf<CmdType::kBindIndexBuffer> {
    Buffer* buffer;
    VkDeviceSize offset;
    VkIndexType index_type;
};
struct CmdPushConstants : CmdOf<CmdType::kPushConstants> {
    PipelineLayout* layout;
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
struct CmdDraw : CmdOf<CmdType::kDraw> {
    uint32_t vertex_count, instance_count, first_vertex, first_instance;
};
struct CmdDrawIndexed : CmdOf<CmdType::kDrawIndexed> {
    uint32_t index_count, instance_count, first_index;
    int32_t vertex_offset;
    uint32_t first_instance;
};
struct CmdDrawIndirect : CmdOf<CmdType::kDrawIndirect> {
    Buffer* buffer;
    VkDeviceSize offset;
    uint32_t draw_count, stride;
};
struct CmdDrawIndexedIndirect : CmdOf<CmdType::kDrawIndexedIndirect> {
    Buffer* buffer;
    VkDeviceSize offset;
    uint32_t draw_count, stride;
};
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

}  // namespace tilevk::icd
