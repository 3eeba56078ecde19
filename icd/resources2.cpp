// The extensible forms of the buffer and image memory commands: vkBind{Buffer,Image}Memory2 (VK_KHR_bind_memory2),
// vkGet{Buffer,Image,ImageSparse}MemoryRequirements2 (VK_KHR_get_memory_requirements2) with
// VkMemoryDedicatedRequirements (VK_KHR_dedicated_allocation). Each is the Vulkan 1.0 command it extends (images bound
// to swapchain memory aside).
#include "buffer.h"
#include "device.h"
#include "entrypoints.h"
#include "image.h"
#include "wsi/swapchain.h"

namespace tilevk::icd {
namespace {

// One memory type, plain host memory: nothing prefers or requires a dedicated allocation.
void write_requirements_chain(void* chain) {
    for (auto* s = static_cast<VkBaseOutStructure*>(chain); s != nullptr; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS) {
            auto* d = reinterpret_cast<VkMemoryDedicatedRequirements*>(s);
            d->prefersDedicatedAllocation = VK_FALSE;
            d->requiresDedicatedAllocation = VK_FALSE;
        }
    }
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_BindBufferMemory2(VkDevice device, uint32_t count,
                                                     const VkBindBufferMemoryInfo* pInfos) {
    // VkBindBufferMemoryDeviceGroupInfo may only name device 0 of a one-device group: nothing to do.
    for (uint32_t i = 0; i < count; ++i)
        if (VkResult r = tvk_BindBufferMemory(device, pInfos[i].buffer, pInfos[i].memory, pInfos[i].memoryOffset);
            r != VK_SUCCESS)
            return r;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_BindImageMemory2(VkDevice device, uint32_t count,
                                                    const VkBindImageMemoryInfo* pInfos) {
    // VkBindImageMemoryDeviceGroupInfo may only name device 0 and no split-instance regions (images with
    // VK_IMAGE_CREATE_SPLIT_INSTANCE_BIND_REGIONS_BIT are refused): nothing to do. VkBindImageMemorySwapchainInfoKHR
    // binds the image to a swapchain image's memory instead of pInfos[i].memory (VK_NULL_HANDLE then).
    for (uint32_t i = 0; i < count; ++i) {
        const auto* swapchain = find_in_chain<VkBindImageMemorySwapchainInfoKHR>(
            pInfos[i].pNext, VK_STRUCTURE_TYPE_BIND_IMAGE_MEMORY_SWAPCHAIN_INFO_KHR);
        const VkResult r = swapchain != nullptr && swapchain->swapchain != VK_NULL_HANDLE
                               ? bind_swapchain_memory(from_handle<Image>(pInfos[i].image), *swapchain)
                               : tvk_BindImageMemory(device, pInfos[i].image, pInfos[i].memory, pInfos[i].memoryOffset);
        if (r != VK_SUCCESS) return r;
    }
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetBufferMemoryRequirements2(VkDevice device,
                                                            const VkBufferMemoryRequirementsInfo2* pInfo,
                                                            VkMemoryRequirements2* pReqs) {
    tvk_GetBufferMemoryRequirements(device, pInfo->buffer, &pReqs->memoryRequirements);
    write_requirements_chain(pReqs->pNext);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetImageMemoryRequirements2(VkDevice device, const VkImageMemoryRequirementsInfo2* pInfo,
                                                           VkMemoryRequirements2* pReqs) {
    tvk_GetImageMemoryRequirements(device, pInfo->image, &pReqs->memoryRequirements);
    write_requirements_chain(pReqs->pNext);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetImageSparseMemoryRequirements2(VkDevice, const VkImageSparseMemoryRequirementsInfo2*,
                                                                 uint32_t* pCount, VkSparseImageMemoryRequirements2*) {
    *pCount = 0;  // no sparse images
}

// ---- VK_KHR_maintenance4: the requirements of a buffer or image not made yet -------------------------------
// The same functions answer as for a made object (buffer_requirements, check_image_create_info +
// compute_image_layout + image_requirements), so the two answers cannot differ. An image create info vkCreateImage
// would refuse is invalid usage here (VUID-VkDeviceImageMemoryRequirements-pCreateInfo-parameter): logged, all zero.

VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceBufferMemoryRequirements(VkDevice,
                                                                 const VkDeviceBufferMemoryRequirements* pInfo,
                                                                 VkMemoryRequirements2* pReqs) {
    pReqs->memoryRequirements = buffer_requirements(pInfo->pCreateInfo->size);
    write_requirements_chain(pReqs->pNext);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceImageMemoryRequirements(VkDevice device,
                                                                const VkDeviceImageMemoryRequirements* pInfo,
                                                                VkMemoryRequirements2* pReqs) {
    const VkImageCreateInfo* ci = pInfo->pCreateInfo;
    const FormatInfo* f = nullptr;
    pReqs->memoryRequirements = {};
    if (check_image_create_info(*from_handle<Device>(device), ci, "vkGetDeviceImageMemoryRequirements", &f) ==
        VK_SUCCESS)
        pReqs->memoryRequirements =
            image_requirements(compute_image_layout(*f, ci->extent, ci->mipLevels, ci->arrayLayers, ci->samples));
    write_requirements_chain(pReqs->pNext);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceImageSparseMemoryRequirements(VkDevice, const VkDeviceImageMemoryRequirements*,
                                                                      uint32_t* pCount,
                                                                      VkSparseImageMemoryRequirements2*) {
    *pCount = 0;  // no sparse images
}

}  // namespace tilevk::icd
