// The extensible forms of Vulkan 1.0 commands (VK_KHR_copy_commands2 and VK_KHR_synchronization2, core in Vulkan
// 1.3): each takes one info struct and records exactly what its 1.0 form records, region for region. No pNext struct
// of these infos is implemented (they belong to extensions tilevk does not offer), so none changes the result.
// Barriers and events: execution is serial and in order, so their stage and access masks order nothing that is not
// already ordered; image layouts are all the same layout (icd/README.md "Commands").
#include <vector>

#include "entrypoints.h"

namespace tilevk::icd {
namespace {

VkBufferImageCopy region_of(const VkBufferImageCopy2& r) {
    return {r.bufferOffset, r.bufferRowLength, r.bufferImageHeight, r.imageSubresource, r.imageOffset, r.imageExtent};
}

}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyBuffer2(VkCommandBuffer commandBuffer, const VkCopyBufferInfo2* pInfo) {
    std::vector<VkBufferCopy> regions;
    for (uint32_t i = 0; i < pInfo->regionCount; ++i) {
        const VkBufferCopy2& r = pInfo->pRegions[i];
        regions.push_back({r.srcOffset, r.dstOffset, r.size});
    }
    tvk_CmdCopyBuffer(commandBuffer, pInfo->srcBuffer, pInfo->dstBuffer, uint32_t(regions.size()), regions.data());
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyImage2(VkCommandBuffer commandBuffer, const VkCopyImageInfo2* pInfo) {
    std::vector<VkImageCopy> regions;
    for (uint32_t i = 0; i < pInfo->regionCount; ++i) {
        const VkImageCopy2& r = pInfo->pRegions[i];
        regions.push_back({r.srcSubresource, r.srcOffset, r.dstSubresource, r.dstOffset, r.extent});
    }
    tvk_CmdCopyImage(commandBuffer, pInfo->srcImage, pInfo->srcImageLayout, pInfo->dstImage, pInfo->dstImageLayout,
                     uint32_t(regions.size()), regions.data());
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyBufferToImage2(VkCommandBuffer commandBuffer,
                                                     const VkCopyBufferToImageInfo2* pInfo) {
    std::vector<VkBufferImageCopy> regions;
    for (uint32_t i = 0; i < pInfo->regionCount; ++i) regions.push_back(region_of(pInfo->pRegions[i]));
    tvk_CmdCopyBufferToImage(commandBuffer, pInfo->srcBuffer, pInfo->dstImage, pInfo->dstImageLayout,
                             uint32_t(regions.size()), regions.data());
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdCopyImageToBuffer2(VkCommandBuffer commandBuffer,
                                                     const VkCopyImageToBufferInfo2* pInfo) {
    std::vector<VkBufferImageCopy> regions;
    for (uint32_t i = 0; i < pInfo->regionCount; ++i) regions.push_back(region_of(pInfo->pRegions[i]));
    tvk_CmdCopyImageToBuffer(commandBuffer, pInfo->srcImage, pInfo->srcImageLayout, pInfo->dstBuffer,
                             uint32_t(regions.size()), regions.data());
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdBlitImage2(VkCommandBuffer commandBuffer, const VkBlitImageInfo2* pInfo) {
    std::vector<VkImageBlit> regions;
    for (uint32_t i = 0; i < pInfo->regionCount; ++i) {
        const VkImageBlit2& r = pInfo->pRegions[i];
        regions.push_back({r.srcSubresource,
                           {r.srcOffsets[0], r.srcOffsets[1]},
                           r.dstSubresource,
                           {r.dstOffsets[0], r.dstOffsets[1]}});
    }
    tvk_CmdBlitImage(commandBuffer, pInfo->srcImage, pInfo->srcImageLayout, pInfo->dstImage, pInfo->dstImageLayout,
                     uint32_t(regions.size()), regions.data(), pInfo->filter);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdResolveImage2(VkCommandBuffer commandBuffer, const VkResolveImageInfo2* pInfo) {
    std::vector<VkImageResolve> regions;
    for (uint32_t i = 0; i < pInfo->regionCount; ++i) {
        const VkImageResolve2& r = pInfo->pRegions[i];
        regions.push_back({r.srcSubresource, r.srcOffset, r.dstSubresource, r.dstOffset, r.extent});
    }
    tvk_CmdResolveImage(commandBuffer, pInfo->srcImage, pInfo->srcImageLayout, pInfo->dstImage, pInfo->dstImageLayout,
                        uint32_t(regions.size()), regions.data());
}

// ---- synchronization2 ---------------------------------------------------------------------------------------
namespace {

// The 64-bit stage masks of synchronization2 as the 1.0 masks the recorded barrier keeps (the bits above 31 are
// stages that exist only in the 64-bit form; barriers are no-ops at execution either way).
VkPipelineStageFlags stages32(VkPipelineStageFlags2 stages) {
    return VkPipelineStageFlags(stages & 0x7fffffffull);
}

}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_CmdPipelineBarrier2(VkCommandBuffer commandBuffer, const VkDependencyInfo* pInfo) {
    VkPipelineStageFlags2 src = 0, dst = 0;
    for (uint32_t i = 0; i < pInfo->memoryBarrierCount; ++i) {
        src |= pInfo->pMemoryBarriers[i].srcStageMask;
        dst |= pInfo->pMemoryBarriers[i].dstStageMask;
    }
    for (uint32_t i = 0; i < pInfo->bufferMemoryBarrierCount; ++i) {
        src |= pInfo->pBufferMemoryBarriers[i].srcStageMask;
        dst |= pInfo->pBufferMemoryBarriers[i].dstStageMask;
    }
    for (uint32_t i = 0; i < pInfo->imageMemoryBarrierCount; ++i) {
        src |= pInfo->pImageMemoryBarriers[i].srcStageMask;
        dst |= pInfo->pImageMemoryBarriers[i].dstStageMask;
    }
    tvk_CmdPipelineBarrier(commandBuffer, stages32(src), stages32(dst), pInfo->dependencyFlags, 0, nullptr, 0, nullptr,
                           0, nullptr);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetEvent2(VkCommandBuffer commandBuffer, VkEvent event, const VkDependencyInfo*) {
    tvk_CmdSetEvent(commandBuffer, event, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdResetEvent2(VkCommandBuffer commandBuffer, VkEvent event,
                                              VkPipelineStageFlags2 stageMask) {
    tvk_CmdResetEvent(commandBuffer, event, stages32(stageMask));
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdWaitEvents2(VkCommandBuffer commandBuffer, uint32_t eventCount,
                                              const VkEvent* pEvents, const VkDependencyInfo*) {
    tvk_CmdWaitEvents(commandBuffer, eventCount, pEvents, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                      VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, nullptr, 0, nullptr, 0, nullptr);
}

// The stage decides whether the timestamp follows the binned draws (queries: any stage but the top of the pipe
// renders them first), so NONE and TOP_OF_PIPE stay the top of the pipe and every other stage is later.
VKAPI_ATTR void VKAPI_CALL tvk_CmdWriteTimestamp2(VkCommandBuffer commandBuffer, VkPipelineStageFlags2 stage,
                                                  VkQueryPool queryPool, uint32_t query) {
    const bool top = stage == VK_PIPELINE_STAGE_2_NONE || stage == VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT;
    tvk_CmdWriteTimestamp(commandBuffer, top ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                          queryPool, query);
}

}  // namespace tilevk::icd

// ---- create_renderpass2 -------------------------------------------------------------------------------------
// VkSubpassBeginInfo / VkSubpassEndInfo carry the contents and nothing tilevk offers in their chains (fragment
// density map offsets are a QCOM extension); VkRenderPassAttachmentBeginInfo rides on the VkRenderPassBeginInfo,
// which the 1.0 command reads.
namespace tilevk::icd {

VKAPI_ATTR void VKAPI_CALL tvk_CmdBeginRenderPass2(VkCommandBuffer commandBuffer,
                                                   const VkRenderPassBeginInfo* pRenderPassBegin,
                                                   const VkSubpassBeginInfo* pSubpassBeginInfo) {
    tvk_CmdBeginRenderPass(commandBuffer, pRenderPassBegin, pSubpassBeginInfo->contents);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdNextSubpass2(VkCommandBuffer commandBuffer,
                                               const VkSubpassBeginInfo* pSubpassBeginInfo, const VkSubpassEndInfo*) {
    tvk_CmdNextSubpass(commandBuffer, pSubpassBeginInfo->contents);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdEndRenderPass2(VkCommandBuffer commandBuffer, const VkSubpassEndInfo*) {
    tvk_CmdEndRenderPass(commandBuffer);
}

}  // namespace tilevk::icd
