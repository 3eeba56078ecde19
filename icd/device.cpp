#include "device.h"
#include "execute.h"

#include "device_features.h"
#include "entrypoints.h"
#include "extensions.h"
#include "physical_device.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateDevice(VkPhysicalDevice physicalDevice, const VkDeviceCreateInfo* pCreateInfo,
                                                const VkAllocationCallbacks* pAllocator, VkDevice* pDevice) {
    PhysicalDevice* pd = from_handle<PhysicalDevice>(physicalDevice);
    ExtensionSet extensions_enabled;
    if (VkResult r = enable_extensions("vkCreateDevice", true, pCreateInfo->enabledExtensionCount,
                                       pCreateInfo->ppEnabledExtensionNames, &extensions_enabled);
        r != VK_SUCCESS) {
        return r;
    }
    for (uint32_t i = 0; i < pCreateInfo->queueCreateInfoCount; ++i) {
        const VkDeviceQueueCreateInfo& q = pCreateInfo->pQueueCreateInfos[i];
        if (q.queueFamilyIndex != 0 || q.queueCount != 1) {
            return fail(VK_ERROR_INITIALIZATION_FAILED, "vkCreateDevice: only queue family 0 with one queue exists");
        }
        if (q.flags != 0) {  // VK_DEVICE_QUEUE_CREATE_PROTECTED_BIT: protectedMemory is not supported
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkCreateDevice: VkDeviceQueueCreateInfo::flags 0x%x (protected queues need the "
                        "protectedMemory feature, which tilevk does not support)",
                        q.flags);
        }
    }
    Features features_enabled;
    if (VkResult r = enable_features(*pCreateInfo, &features_enabled); r != VK_SUCCESS) return r;
    const VkAllocationCallbacks& a = pick_allocator(pAllocator, &pd->allocator);
    Device* dev = create_object<Device>(a, VK_SYSTEM_ALLOCATION_SCOPE_DEVICE);
    if (dev == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDevice: out of host memory");
    dev->physical_device = pd;
    dev->enabled_extensions = extensions_enabled;
    dev->enabled_features = features_enabled;
    dev->queue = create_object<Queue>(a, VK_SYSTEM_ALLOCATION_SCOPE_DEVICE);
    if (dev->queue == nullptr) {
        destroy_object(dev);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDevice: out of host memory");
    }
    dev->queue->device = dev;
    try {
        dev->queue->timeout = std::make_unique<SubmitTimeout>(device_timeout_from_env());
        dev->queue->scheduler = std::make_unique<QueueScheduler>(*dev->queue);
    } catch (const std::bad_alloc&) {
        destroy_object(dev->queue);
        destroy_object(dev);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDevice: out of host memory");
    }
    *pDevice = to_handle(dev);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyDevice(VkDevice device, const VkAllocationCallbacks*) {
    Device* dev = from_handle<Device>(device);
    if (dev == nullptr) return;
    if (dev->queue) {
        dev->queue->scheduler.reset();  // stops the worker before the renderer it uses goes
        destroy_draw_context(dev->queue->draw);
    }
    destroy_object(dev->queue);
    destroy_object(dev);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceQueue(VkDevice device, uint32_t, uint32_t, VkQueue* pQueue) {
    *pQueue = to_handle(from_handle<Device>(device)->queue);
}

// The one queue was created with flags 0: a VkDeviceQueueInfo2 asking for other flags matches no queue.
VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceQueue2(VkDevice device, const VkDeviceQueueInfo2* pQueueInfo, VkQueue* pQueue) {
    const bool match = pQueueInfo->flags == 0 && pQueueInfo->queueFamilyIndex == 0 && pQueueInfo->queueIndex == 0;
    *pQueue = match ? to_handle(from_handle<Device>(device)->queue) : VK_NULL_HANDLE;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_DeviceWaitIdle(VkDevice device) {
    // The device's one queue: its worker's batches, then a submission in flight on another thread.
    return tvk_QueueWaitIdle(to_handle(from_handle<Device>(device)->queue));
}

}  // namespace tilevk::icd
