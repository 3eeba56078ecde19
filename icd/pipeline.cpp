#include "pipeline.h"

#include <cstring>

#include "device.h"
#include "entrypoints.h"
#include "physical_device.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreatePipelineCache(VkDevice device, const VkPipelineCacheCreateInfo*,
                                                       const VkAllocationCallbacks* pAllocator,
                                                       VkPipelineCache* pPipelineCache) {
    Device* dev = from_handle<Device>(device);
    auto* cache =
        create_object<PipelineCache>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (cache == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreatePipelineCache: out of host memory");
    *pPipelineCache = to_handle(cache);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPipelineCache(VkDevice, VkPipelineCache cache, const VkAllocationCallbacks*) {
    destroy_object(from_handle<PipelineCache>(cache));
}

// The cache holds nothing yet, so its data is just the header Vulkan requires (version one, 32 bytes).
VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPipelineCacheData(VkDevice device, VkPipelineCache, size_t* pDataSize,
                                                        void* pData) {
    constexpr size_t kHeaderSize = 16 + VK_UUID_SIZE;
    if (pData == nullptr) {
        *pDataSize = kHeaderSize;
        return VK_SUCCESS;
    }
    if (*pDataSize < kHeaderSize) {
        *pDataSize = 0;
        return VK_INCOMPLETE;
    }
    const VkPhysicalDeviceProperties& p = from_handle<Device>(device)->physical_device->properties;
    uint32_t header[4] = {uint32_t(kHeaderSize), VK_PIPELINE_CACHE_HEADER_VERSION_ONE, p.vendorID, p.deviceID};
    std::memcpy(pData, header, sizeof header);
    std::memcpy(static_cast<uint8_t*>(pData) + 16, p.pipelineCacheUUID, VK_UUID_SIZE);
    *pDataSize = kHeaderSize;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_MergePipelineCaches(VkDevice, VkPipelineCache, uint32_t, const VkPipelineCache*) {
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateGraphicsPipelines(VkDevice, VkPipelineCache, uint32_t count,
                                                           const VkGraphicsPipelineCreateInfo*,
                                                           const VkAllocationCallbacks*, VkPipeline* pPipelines) {
    for (uint32_t i = 0; i < count; ++i) pPipelines[i] = VK_NULL_HANDLE;
    // Vulkan 1.0 offers no "unsupported" code for pipelines; OUT_OF_HOST_MEMORY is not true, so the message says
    // what is going on. This goes away when icd/ hands pipelines to rast/ and shader/.
    return fail(VK_ERROR_INITIALIZATION_FAILED,
                "vkCreateGraphicsPipelines: the render path is not connected yet; no graphics pipeline can be created");
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateComputePipelines(VkDevice, VkPipelineCache, uint32_t count,
                                                          const VkComputePipelineCreateInfo*,
                                                          const VkAllocationCallbacks*, VkPipeline* pPipelines) {
    for (uint32_t i = 0; i < count; ++i) pPipelines[i] = VK_NULL_HANDLE;
    return fail(VK_ERROR_INITIALIZATION_FAILED,
                "vkCreateComputePipelines: tilevk has no compute queue and runs no compute shaders");
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPipeline(VkDevice, VkPipeline pipeline, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Pipeline>(pipeline));
}

}  // namespace tilevk::icd
