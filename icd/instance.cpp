#include "instance.h"

#include <cstring>

#include "entrypoints.h"
#include "extensions.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumerateInstanceExtensionProperties(const char* pLayerName,
                                                                        uint32_t* pPropertyCount,
                                                                        VkExtensionProperties* pProperties) {
    if (pLayerName != nullptr) return fail(VK_ERROR_LAYER_NOT_PRESENT, "no layer '%s' in tilevk", pLayerName);
    return enumerate_extensions(false, pPropertyCount, pProperties);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumerateInstanceLayerProperties(uint32_t* pPropertyCount, VkLayerProperties*) {
    *pPropertyCount = 0;
    return VK_SUCCESS;
}

// The loader asks the driver (vk_icdGetInstanceProcAddr(NULL, ...)) which instance-level version it supports.
VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumerateInstanceVersion(uint32_t* pApiVersion) {
    *pApiVersion = kApiVersion;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateInstance(const VkInstanceCreateInfo* pCreateInfo,
                                                  const VkAllocationCallbacks* pAllocator, VkInstance* pInstance) {
    for (uint32_t i = 0; i < pCreateInfo->enabledLayerCount; ++i) {
        return fail(VK_ERROR_LAYER_NOT_PRESENT, "vkCreateInstance: layer '%s' is not provided by tilevk",
                    pCreateInfo->ppEnabledLayerNames[i]);
    }
    ExtensionSet enabled;
    if (VkResult r = enable_extensions("vkCreateInstance", false, pCreateInfo->enabledExtensionCount,
                                       pCreateInfo->ppEnabledExtensionNames, &enabled);
        r != VK_SUCCESS) {
        return r;
    }
    uint32_t app_version = VK_API_VERSION_1_0;
    if (pCreateInfo->pApplicationInfo != nullptr && pCreateInfo->pApplicationInfo->apiVersion != 0) {
        app_version = pCreateInfo->pApplicationInfo->apiVersion;
    }
    // No apiVersion check here: from loader interface 5 on (the least tilevk negotiates) the loader validates the
    // application's apiVersion, and a driver must accept any version it passes (LoaderDriverInterface.md, v5).
    const VkAllocationCallbacks& a = pick_allocator(pAllocator, nullptr);
    Instance* inst = create_object<Instance>(a, VK_SYSTEM_ALLOCATION_SCOPE_INSTANCE);
    if (inst == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateInstance: out of host memory");
    inst->app_api_version = app_version;
    inst->enabled_extensions = enabled;
    inst->physical_device = create_object<PhysicalDevice>(a, VK_SYSTEM_ALLOCATION_SCOPE_INSTANCE);
    if (inst->physical_device == nullptr) {
        destroy_object(inst);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateInstance: out of host memory");
    }
    inst->physical_device->instance = inst;
    *pInstance = to_handle(inst);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyInstance(VkInstance instance, const VkAllocationCallbacks*) {
    Instance* inst = from_handle<Instance>(instance);
    if (inst == nullptr) return;
    destroy_object(inst->physical_device);
    destroy_object(inst);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumeratePhysicalDevices(VkInstance instance, uint32_t* pPhysicalDeviceCount,
                                                            VkPhysicalDevice* pPhysicalDevices) {
    Instance* inst = from_handle<Instance>(instance);
    if (pPhysicalDevices == nullptr) {
        *pPhysicalDeviceCount = 1;
        return VK_SUCCESS;
    }
    if (*pPhysicalDeviceCount < 1) return VK_INCOMPLETE;
    pPhysicalDevices[0] = to_handle(inst->physical_device);
    *pPhysicalDeviceCount = 1;
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
