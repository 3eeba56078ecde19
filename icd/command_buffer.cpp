// vkCmd*: every command is recorded as a plain struct (commands.h); execution happens at vkQueueSubmit.
#include "command_buffer.h"

#include <atomic>
#include <cstring>
#include <type_traits>
#include <vector>

#include "buffer.h"
#include "descriptor_pool.h"
#include "device.h"
#include "device_group.h"
#include "entrypoints.h"
#include "framebuffer.h"
#include "image.h"
#include "pipeline.h"
#include "query_pool.h"
#include "render_pass.h"
#include "sync.h"

namespace tilevk::icd {
namespace {

CommandBuffer* cb_of(VkCommandBuffer h) {
    return from_handle<CommandBuffer>(h);
}

// Copies an array of handles into the arena as object pointers.
template <class T>
T* const* objects(CommandBuffer* cb, const typename T::Handle* handles, uint32_t count) {
    if (count == 0) return nullptr;
    auto** out = static_cast<T**>(cb->arena.allocate(sizeof(T*) * count, alignof(T*)));
    if (out == nullptr) {
        cb->out_of_memory();
        return nullptr;
    }
    for (uint32_t i = 0; i < count; ++i) out[i] = from_handle<T>(handles[i]);
    return out;
}

// The copy/resolve commands: two objects and an array of regions copied into the command buffer's arena.
template <class Cmd, class SrcHandle, class DstHandle, class Region>
void record_regions(VkCommandBuffer commandBuffer, SrcHandle src, DstHandle dst, uint32_t count,
                    const Region* regions) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<Cmd>()) {
        c->src = from_handle<std::remove_pointer_t<decltype(c->src)>>(src);
        c->dst = from_handle<std::remove_pointer_t<decltype(c->dst)>>(dst);
        c->count = count;
        c->regions = cb->copy(regions, count);
    }
}

// A VK_NULL_HANDLE vertex buffer without the nullDescriptor feature (VK_EXT_robustness2) is invalid usage: the command
// is skipped with a line naming the VUID. With the feature, the binding has no bytes and its attributes read zeros.
bool null_vertex_buffer_refused(const CommandBuffer& cb, const VkBuffer* buffers, uint32_t count, const char* command,
                                const char* vuid) {
    if (cb.pool->device->enabled_features.robustness2.nullDescriptor) return false;
    for (uint32_t i = 0; i < count; ++i) {
        if (buffers[i] != VK_NULL_HANDLE) continue;
        log_error(
            "%s: pBuffers[%u] is VK_NULL_HANDLE, which needs the nullDescriptor feature of "
            "VkPhysicalDeviceRobustness2FeaturesEXT enabled (%s); the command is skipped",
            command, i, vuid);
        return true;
    }
    return false;
}

}  // namespace

// ---- transfer ------------------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyBuffer(VkCommandBuffer commandBuffer, VkBuffer srcBuffer, VkBuffer dstBuffer,
                                             uint32_t regionCount, const VkBufferCopy* pRegions) {
    record_regions<CmdCopyBuffer>(commandBuffer, srcBuffer, dstBuffer, regionCount, pRegions);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyImage(VkCommandBuffer commandBuffer, VkImage srcImage, VkImageLayout,
                                            VkImage dstImage, VkImageLayout, uint32_t regionCount,
                                            const VkImageCopy* pRegions) {
    record_regions<CmdCopyImage>(commandBuffer, srcImage, dstImage, regionCount, pRegions);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyBufferToImage(VkCommandBuffer commandBuffer, VkBuffer srcBuffer, VkImage dstImage,
                                                    VkImageLayout, uint32_t regionCount,
                                                    const VkBufferImageCopy* pRegions) {
    record_regions<CmdCopyBufferToImage>(commandBuffer, srcBuffer, dstImage, regionCount, pRegions);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyImageToBuffer(VkCommandBuffer commandBuffer, VkImage srcImage, VkImageLayout,
                                                    VkBuffer dstBuffer, uint32_t regionCount,
                                                    const VkBufferImageCopy* pRegions) {
    record_regions<CmdCopyImageToBuffer>(commandBuffer, srcImage, dstBuffer, regionCount, pRegions);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdUpdateBuffer(VkCommandBuffer commandBuffer, VkBuffer dstBuffer,
                                               VkDeviceSize dstOffset, VkDeviceSize dataSize, const void* pData) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdUpdateBuffer>()) {
        c->dst = from_handle<Buffer>(dstBuffer);
        c->offset = dstOffset;
        c->size = dataSize;
        c->data = cb->copy(static_cast<const uint8_t*>(pData), size_t(dataSize));
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdFillBuffer(VkCommandBuffer commandBuffer, VkBuffer dstBuffer, VkDeviceSize dstOffset,
                                             VkDeviceSize size, uint32_t data) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdFillBuffer>()) {
        c->dst = from_handle<Buffer>(dstBuffer);
        c->offset = dstOffset;
        c->size = size;
        c->data = data;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdClearColorImage(VkCommandBuffer commandBuffer, VkImage image, VkImageLayout,
                                                  const VkClearColorValue* pColor, uint32_t rangeCount,
                                                  const VkImageSubresourceRange* pRanges) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdClearColorImage>()) {
        c->image = from_handle<Image>(image);
        c->color = *pColor;
        c->count = rangeCount;
        c->ranges = cb->copy(pRanges, rangeCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdClearDepthStencilImage(VkCommandBuffer commandBuffer, VkImage image, VkImageLayout,
                                                         const VkClearDepthStencilValue* pDepthStencil,
                                                         uint32_t rangeCount, const VkImageSubresourceRange* pRanges) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdClearDepthStencilImage>()) {
        c->image = from_handle<Image>(image);
        c->value = *pDepthStencil;
        c->count = rangeCount;
        c->ranges = cb->copy(pRanges, rangeCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdResolveImage(VkCommandBuffer commandBuffer, VkImage srcImage, VkImageLayout,
                                               VkImage dstImage, VkImageLayout, uint32_t regionCount,
                                               const VkImageResolve* pRegions) {
    record_regions<CmdResolveImage>(commandBuffer, srcImage, dstImage, regionCount, pRegions);
}

// ---- synchronisation -----------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdPipelineBarrier(VkCommandBuffer commandBuffer, VkPipelineStageFlags srcStageMask,
                                                  VkPipelineStageFlags dstStageMask, VkDependencyFlags, uint32_t,
                                                  const VkMemoryBarrier*, uint32_t, const VkBufferMemoryBarrier*,
                                                  uint32_t, const VkImageMemoryBarrier*) {
    // Layout transitions are no-ops: tilevk has one layout for every VkImageLayout.
    if (auto* c = cb_of(commandBuffer)->append<CmdPipelineBarrier>()) {
        c->src_stages = srcStageMask;
        c->dst_stages = dstStageMask;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetEvent(VkCommandBuffer commandBuffer, VkEvent event, VkPipelineStageFlags) {
    if (auto* c = cb_of(commandBuffer)->append<CmdSetEvent>()) c->event = from_handle<Event>(event);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdResetEvent(VkCommandBuffer commandBuffer, VkEvent event, VkPipelineStageFlags) {
    if (auto* c = cb_of(commandBuffer)->append<CmdResetEvent>()) c->event = from_handle<Event>(event);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdWaitEvents(VkCommandBuffer commandBuffer, uint32_t eventCount, const VkEvent* pEvents,
                                             VkPipelineStageFlags, VkPipelineStageFlags, uint32_t,
                                             const VkMemoryBarrier*, uint32_t, const VkBufferMemoryBarrier*, uint32_t,
                                             const VkImageMemoryBarrier*) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdWaitEvents>()) {
        c->count = eventCount;
        c->events = objects<Event>(cb, pEvents, eventCount);
    }
}

// ---- render passes -------------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdBeginRenderPass(VkCommandBuffer commandBuffer,
                                                  const VkRenderPassBeginInfo* pRenderPassBegin, VkSubpassContents) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdBeginRenderPass>()) {
        c->render_pass = from_handle<RenderPass>(pRenderPassBegin->renderPass);
        c->framebuffer = from_handle<Framebuffer>(pRenderPassBegin->framebuffer);
        c->view_count = uint32_t(c->framebuffer->attachments.size());
        c->views = c->framebuffer->attachments.data();
        if (c->framebuffer->imageless) {
            const auto* views = find_in_chain<VkRenderPassAttachmentBeginInfo>(
                pRenderPassBegin->pNext, VK_STRUCTURE_TYPE_RENDER_PASS_ATTACHMENT_BEGIN_INFO);
            if (views != nullptr && views->attachmentCount == c->framebuffer->imageless_count) {
                c->views = objects<ImageView>(cb, views->pAttachments, views->attachmentCount);
                c->view_count = c->views != nullptr ? views->attachmentCount : 0;  // null: out of memory, recorded
            } else {
                // VUID-VkRenderPassBeginInfo-framebuffer-03207/03208: invalid usage. The pass runs with no views,
                // so its load ops, draws, clears and resolves write nothing.
                log_error(
                    "vkCmdBeginRenderPass: the framebuffer was made with VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT "
                    "but pRenderPassBegin chains no VkRenderPassAttachmentBeginInfo with attachmentCount %u; "
                    "the render pass instance renders into nothing",
                    c->framebuffer->imageless_count);
                c->view_count = 0;
                c->views = nullptr;
            }
        }
        c->area = render_area_of(*pRenderPassBegin);
        c->clear_count = pRenderPassBegin->clearValueCount;
        c->clears = cb->copy(pRenderPassBegin->pClearValues, pRenderPassBegin->clearValueCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdNextSubpass(VkCommandBuffer commandBuffer, VkSubpassContents) {
    cb_of(commandBuffer)->append<CmdNextSubpass>();
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdEndRenderPass(VkCommandBuffer commandBuffer) {
    cb_of(commandBuffer)->append<CmdEndRenderPass>();
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdClearAttachments(VkCommandBuffer commandBuffer, uint32_t attachmentCount,
                                                   const VkClearAttachment* pAttachments, uint32_t rectCount,
                                                   const VkClearRect* pRects) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdClearAttachments>()) {
        c->attachment_count = attachmentCount;
        c->attachments = cb->copy(pAttachments, attachmentCount);
        c->rect_count = rectCount;
        c->rects = cb->copy(pRects, rectCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdExecuteCommands(VkCommandBuffer commandBuffer, uint32_t commandBufferCount,
                                                  const VkCommandBuffer* pCommandBuffers) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdExecuteCommands>()) {
        c->count = commandBufferCount;
        c->buffers = objects<CommandBuffer>(cb, pCommandBuffers, commandBufferCount);
    }
}

// ---- state and draws -----------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdBindPipeline(VkCommandBuffer commandBuffer, VkPipelineBindPoint bindPoint,
                                               VkPipeline pipeline) {
    if (auto* c = cb_of(commandBuffer)->append<CmdBindPipeline>()) {
        c->bind_point = bindPoint;
        c->pipeline = from_handle<Pipeline>(pipeline);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdBindDescriptorSets(VkCommandBuffer commandBuffer, VkPipelineBindPoint bindPoint,
                                                     VkPipelineLayout, uint32_t firstSet, uint32_t descriptorSetCount,
                                                     const VkDescriptorSet* pSets, uint32_t dynamicOffsetCount,
                                                     const uint32_t* pDynamicOffsets) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdBindDescriptorSets>()) {
        c->bind_point = bindPoint;
        c->first_set = firstSet;
        c->set_count = descriptorSetCount;
        c->sets = objects<DescriptorSet>(cb, pSets, descriptorSetCount);
        c->dynamic_offset_count = dynamicOffsetCount;
        c->dynamic_offsets = cb->copy(pDynamicOffsets, dynamicOffsetCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdBindVertexBuffers(VkCommandBuffer commandBuffer, uint32_t firstBinding,
                                                    uint32_t bindingCount, const VkBuffer* pBuffers,
                                                    const VkDeviceSize* pOffsets) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (null_vertex_buffer_refused(*cb, pBuffers, bindingCount, "vkCmdBindVertexBuffers",
                                   "VUID-vkCmdBindVertexBuffers-pBuffers-04001"))
        return;
    if (auto* c = cb->append<CmdBindVertexBuffers>()) {
        c->first_binding = firstBinding;
        c->count = bindingCount;
        c->buffers = objects<Buffer>(cb, pBuffers, bindingCount);
        c->offsets = cb->copy(pOffsets, bindingCount);
    }
}

// Extended dynamic state: the bound ranges (pSizes) and, for VERTEX_INPUT_BINDING_STRIDE, the strides.
VKAPI_ATTR void VKAPI_CALL tvk_CmdBindVertexBuffers2(VkCommandBuffer commandBuffer, uint32_t firstBinding,
                                                     uint32_t bindingCount, const VkBuffer* pBuffers,
                                                     const VkDeviceSize* pOffsets, const VkDeviceSize* pSizes,
                                                     const VkDeviceSize* pStrides) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (null_vertex_buffer_refused(*cb, pBuffers, bindingCount, "vkCmdBindVertexBuffers2",
                                   "VUID-vkCmdBindVertexBuffers2-pBuffers-04111"))
        return;
    if (auto* c = cb->append<CmdBindVertexBuffers>()) {
        c->first_binding = firstBinding;
        c->count = bindingCount;
        c->buffers = objects<Buffer>(cb, pBuffers, bindingCount);
        c->offsets = cb->copy(pOffsets, bindingCount);
        if (pSizes != nullptr) c->sizes = cb->copy(pSizes, bindingCount);
        if (pStrides != nullptr) c->strides = cb->copy(pStrides, bindingCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdBindIndexBuffer(VkCommandBuffer commandBuffer, VkBuffer buffer, VkDeviceSize offset,
                                                  VkIndexType indexType) {
    if (auto* c = cb_of(commandBuffer)->append<CmdBindIndexBuffer>()) {
        c->buffer = from_handle<Buffer>(buffer);
        c->offset = offset;
        c->index_type = indexType;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdPushConstants(VkCommandBuffer commandBuffer, VkPipelineLayout,
                                                VkShaderStageFlags stageFlags, uint32_t offset, uint32_t size,
                                                const void* pValues) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdPushConstants>()) {
        c->stages = stageFlags;
        c->offset = offset;
        c->size = size;
        c->values = cb->copy(static_cast<const uint8_t*>(pValues), size);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetViewport(VkCommandBuffer commandBuffer, uint32_t firstViewport,
                                              uint32_t viewportCount, const VkViewport* pViewports) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdSetViewport>()) {
        c->first = firstViewport;
        c->count = viewportCount;
        c->viewports = cb->copy(pViewports, viewportCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetScissor(VkCommandBuffer commandBuffer, uint32_t firstScissor,
                                             uint32_t scissorCount, const VkRect2D* pScissors) {
    CommandBuffer* cb = cb_of(commandBuffer);
    if (auto* c = cb->append<CmdSetScissor>()) {
        c->first = firstScissor;
        c->count = scissorCount;
        c->scissors = cb->copy(pScissors, scissorCount);
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetLineWidth(VkCommandBuffer commandBuffer, float lineWidth) {
    if (auto* c = cb_of(commandBuffer)->append<CmdSetLineWidth>()) c->width = lineWidth;
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetDepthBias(VkCommandBuffer commandBuffer, float constantFactor, float clamp,
                                               float slopeFactor) {
    if (auto* c = cb_of(commandBuffer)->append<CmdSetDepthBias>()) {
        c->constant_factor = constantFactor;
        c->clamp = clamp;
        c->slope_factor = slopeFactor;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetBlendConstants(VkCommandBuffer commandBuffer, const float blendConstants[4]) {
    if (auto* c = cb_of(commandBuffer)->append<CmdSetBlendConstants>()) {
        for (int i = 0; i < 4; ++i) c->constants[i] = blendConstants[i];
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetDepthBounds(VkCommandBuffer commandBuffer, float minDepthBounds,
                                                 float maxDepthBounds) {
    if (auto* c = cb_of(commandBuffer)->append<CmdSetDepthBounds>()) {
        c->min = minDepthBounds;
        c->max = maxDepthBounds;
    }
}

// vkCmdSetStencilCompareMask, WriteMask and Reference: three command types (commands.h) of one layout.
namespace {
template <class Cmd>
void record_stencil_state(VkCommandBuffer commandBuffer, VkStencilFaceFlags faces, uint32_t value) {
    if (auto* c = cb_of(commandBuffer)->append<Cmd>()) {
        c->faces = faces;
        c->value = value;
    }
}
}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetStencilCompareMask(VkCommandBuffer commandBuffer, VkStencilFaceFlags faceMask,
                                                        uint32_t compareMask) {
    record_stencil_state<CmdSetStencilCompareMask>(commandBuffer, faceMask, compareMask);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetStencilWriteMask(VkCommandBuffer commandBuffer, VkStencilFaceFlags faceMask,
                                                      uint32_t writeMask) {
    record_stencil_state<CmdSetStencilWriteMask>(commandBuffer, faceMask, writeMask);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetStencilReference(VkCommandBuffer commandBuffer, VkStencilFaceFlags faceMask,
                                                      uint32_t reference) {
    record_stencil_state<CmdSetStencilReference>(commandBuffer, faceMask, reference);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDraw(VkCommandBuffer commandBuffer, uint32_t vertexCount, uint32_t instanceCount,
                                       uint32_t firstVertex, uint32_t firstInstance) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDraw>()) {
        c->vertex_count = vertexCount;
        c->instance_count = instanceCount;
        c->first_vertex = firstVertex;
        c->first_instance = firstInstance;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawIndexed(VkCommandBuffer commandBuffer, uint32_t indexCount,
                                              uint32_t instanceCount, uint32_t firstIndex, int32_t vertexOffset,
                                              uint32_t firstInstance) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDrawIndexed>()) {
        c->index_count = indexCount;
        c->instance_count = instanceCount;
        c->first_index = firstIndex;
        c->vertex_offset = vertexOffset;
        c->first_instance = firstInstance;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawIndirect(VkCommandBuffer commandBuffer, VkBuffer buffer, VkDeviceSize offset,
                                               uint32_t drawCount, uint32_t stride) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDrawIndirect>()) {
        c->buffer = from_handle<Buffer>(buffer);
        c->offset = offset;
        c->draw_count = drawCount;
        c->stride = stride;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawIndexedIndirect(VkCommandBuffer commandBuffer, VkBuffer buffer,
                                                      VkDeviceSize offset, uint32_t drawCount, uint32_t stride) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDrawIndexedIndirect>()) {
        c->buffer = from_handle<Buffer>(buffer);
        c->offset = offset;
        c->draw_count = drawCount;
        c->stride = stride;
    }
}

// VK_KHR_draw_indirect_count (core in Vulkan 1.2): the number of draws is read from countBuffer when they execute.
VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawIndirectCount(VkCommandBuffer commandBuffer, VkBuffer buffer, VkDeviceSize offset,
                                                    VkBuffer countBuffer, VkDeviceSize countBufferOffset,
                                                    uint32_t maxDrawCount, uint32_t stride) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDrawIndirect>()) {
        c->buffer = from_handle<Buffer>(buffer);
        c->offset = offset;
        c->draw_count = maxDrawCount;
        c->stride = stride;
        c->count_buffer = from_handle<Buffer>(countBuffer);
        c->count_offset = countBufferOffset;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawIndexedIndirectCount(VkCommandBuffer commandBuffer, VkBuffer buffer,
                                                           VkDeviceSize offset, VkBuffer countBuffer,
                                                           VkDeviceSize countBufferOffset, uint32_t maxDrawCount,
                                                           uint32_t stride) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDrawIndexedIndirect>()) {
        c->buffer = from_handle<Buffer>(buffer);
        c->offset = offset;
        c->draw_count = maxDrawCount;
        c->stride = stride;
        c->count_buffer = from_handle<Buffer>(countBuffer);
        c->count_offset = countBufferOffset;
    }
}

// VK_EXT_multi_draw: the entries are read at `stride` now (the caller's array need not outlive the call). An
// entry's vertexOffset is replaced by *pVertexOffset when given (lavapipe: index_bias_varies false).
namespace {
void record_multi(VkCommandBuffer commandBuffer, bool indexed, uint32_t drawCount, const void* info,
                  uint32_t instanceCount, uint32_t firstInstance, uint32_t stride, const int32_t* vertex_offset) {
    CommandBuffer* cb = cb_of(commandBuffer);
    std::vector<VkMultiDrawIndexedInfoEXT> entries(info != nullptr ? drawCount : 0);
    for (size_t i = 0; i < entries.size(); ++i) {
        const auto* at = static_cast<const uint8_t*>(info) + i * size_t(stride);
        VkMultiDrawIndexedInfoEXT& e = entries[i];
        if (indexed) {
            std::memcpy(&e, at, sizeof e);
            if (vertex_offset != nullptr) e.vertexOffset = *vertex_offset;
        } else {
            VkMultiDrawInfoEXT d;
            std::memcpy(&d, at, sizeof d);
            e = {d.firstVertex, d.vertexCount, 0};
        }
    }
    if (entries.empty()) return;  // no draws: nothing to record
    const VkMultiDrawIndexedInfoEXT* draws = cb->copy(entries.data(), entries.size());
    if (draws == nullptr) return;
    if (auto* c = cb->append<CmdDrawMulti>()) {
        c->indexed = indexed;
        c->draw_count = uint32_t(entries.size());
        c->instance_count = instanceCount;
        c->first_instance = firstInstance;
        c->draws = draws;
    }
}
}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawMultiEXT(VkCommandBuffer commandBuffer, uint32_t drawCount,
                                               const VkMultiDrawInfoEXT* pVertexInfo, uint32_t instanceCount,
                                               uint32_t firstInstance, uint32_t stride) {
    record_multi(commandBuffer, false, drawCount, pVertexInfo, instanceCount, firstInstance, stride, nullptr);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDrawMultiIndexedEXT(VkCommandBuffer commandBuffer, uint32_t drawCount,
                                                      const VkMultiDrawIndexedInfoEXT* pIndexInfo,
                                                      uint32_t instanceCount, uint32_t firstInstance, uint32_t stride,
                                                      const int32_t* pVertexOffset) {
    record_multi(commandBuffer, true, drawCount, pIndexInfo, instanceCount, firstInstance, stride, pVertexOffset);
}

// ---- queries (executed in execute_query.cpp) -----------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdBeginQuery(VkCommandBuffer commandBuffer, VkQueryPool queryPool, uint32_t query,
                                             VkQueryControlFlags) {
    // PRECISE or not, the count is exact (occlusionQueryPrecise is reported), as in lavapipe.
    if (auto* c = cb_of(commandBuffer)->append<CmdBeginQuery>()) {
        c->pool = from_handle<QueryPool>(queryPool);
        c->query = query;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdEndQuery(VkCommandBuffer commandBuffer, VkQueryPool queryPool, uint32_t query) {
    if (auto* c = cb_of(commandBuffer)->append<CmdEndQuery>()) {
        c->pool = from_handle<QueryPool>(queryPool);
        c->query = query;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdResetQueryPool(VkCommandBuffer commandBuffer, VkQueryPool queryPool,
                                                 uint32_t firstQuery, uint32_t queryCount) {
    if (auto* c = cb_of(commandBuffer)->append<CmdResetQueryPool>()) {
        c->pool = from_handle<QueryPool>(queryPool);
        c->first = firstQuery;
        c->count = queryCount;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdWriteTimestamp(VkCommandBuffer commandBuffer, VkPipelineStageFlagBits pipelineStage,
                                                 VkQueryPool queryPool, uint32_t query) {
    if (auto* c = cb_of(commandBuffer)->append<CmdWriteTimestamp>()) {
        c->stage = pipelineStage;
        c->pool = from_handle<QueryPool>(queryPool);
        c->query = query;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyQueryPoolResults(VkCommandBuffer commandBuffer, VkQueryPool queryPool,
                                                       uint32_t firstQuery, uint32_t queryCount, VkBuffer dstBuffer,
                                                       VkDeviceSize dstOffset, VkDeviceSize stride,
                                                       VkQueryResultFlags flags) {
    if (auto* c = cb_of(commandBuffer)->append<CmdCopyQueryPoolResults>()) {
        c->pool = from_handle<QueryPool>(queryPool);
        c->first = firstQuery;
        c->count = queryCount;
        c->dst = from_handle<Buffer>(dstBuffer);
        c->offset = dstOffset;
        c->stride = stride;
        c->flags = flags;
    }
}

// ---- compute ---------------------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdDispatch(VkCommandBuffer commandBuffer, uint32_t groupCountX, uint32_t groupCountY,
                                           uint32_t groupCountZ) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDispatch>()) {
        c->group_count[0] = groupCountX;
        c->group_count[1] = groupCountY;
        c->group_count[2] = groupCountZ;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdDispatchIndirect(VkCommandBuffer commandBuffer, VkBuffer buffer,
                                                   VkDeviceSize offset) {
    if (auto* c = cb_of(commandBuffer)->append<CmdDispatchIndirect>()) {
        c->buffer = from_handle<Buffer>(buffer);
        c->offset = offset;
    }
}

// ---- VK_EXT_conditional_rendering (executed in execute.cpp) --------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdBeginConditionalRenderingEXT(
    VkCommandBuffer commandBuffer, const VkConditionalRenderingBeginInfoEXT* pConditionalRenderingBegin) {
    if (auto* c = cb_of(commandBuffer)->append<CmdBeginConditionalRendering>()) {
        c->buffer = from_handle<Buffer>(pConditionalRenderingBegin->buffer);
        c->offset = pConditionalRenderingBegin->offset;
        c->inverted = (pConditionalRenderingBegin->flags & VK_CONDITIONAL_RENDERING_INVERTED_BIT_EXT) != 0;
    }
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdEndConditionalRenderingEXT(VkCommandBuffer commandBuffer) {
    cb_of(commandBuffer)->append<CmdEndConditionalRendering>();
}

}  // namespace tilevk::icd
