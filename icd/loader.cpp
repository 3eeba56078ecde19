// The three symbols libvulkan_tilevk.so exports to the Vulkan loader (docs/LoaderDriverInterface.md).
// Everything else in the library has hidden visibility; the version script icd.map enforces it.
#include <cstring>

#include "device.h"
#include "entrypoints.h"
#include "extensions.h"
#include "instance.h"

namespace tilevk::icd {

// Interface 5 is the oldest we accept: from 5 on, the loader honours the application's apiVersion handling
// for 1.0 drivers and calls vk_icdGetPhysicalDeviceProcAddr (v4+); older loaders are 2017-era.
constexpr uint32_t kMinLoaderInterface = 5;
constexpr uint32_t kMaxLoaderInterface = 7;

PFN_vkVoidFunction lookup_instance_proc(VkInstance instance, const char* name) {
    const EntryPoint* e = find_entry_point(name);
    if (e == nullptr) return nullptr;
    // With no instance only the global commands are available (vkGetInstanceProcAddr itself included).
    if (e->level == EntryLevel::kGlobal) return e->function;
    if (instance == VK_NULL_HANDLE) return nullptr;
    const Instance* inst = from_handle<Instance>(instance);
    // Device-level names through vkGetInstanceProcAddr: any exposed device extension counts (none is enabled yet).
    return entry_point_enabled(*e, inst->app_api_version, inst->enabled_extensions, nullptr) ? e->function : nullptr;
}

PFN_vkVoidFunction lookup_physical_device_proc(VkInstance instance, const char* name) {
    const EntryPoint* e = find_entry_point(name);
    if (e == nullptr || e->level != EntryLevel::kPhysicalDevice) return nullptr;
    if (instance == VK_NULL_HANDLE) return e->function;
    const Instance* inst = from_handle<Instance>(instance);
    return entry_point_enabled(*e, inst->app_api_version, inst->enabled_extensions, nullptr) ? e->function : nullptr;
}

PFN_vkVoidFunction lookup_device_proc(VkDevice device, const char* name) {
    const EntryPoint* e = find_entry_point(name);
    if (e == nullptr || e->level != EntryLevel::kDevice) return nullptr;
    if (device == VK_NULL_HANDLE) return nullptr;
    const Device* dev = from_handle<Device>(device);
    const Instance* inst = dev->physical_device->instance;
    return entry_point_enabled(*e, inst->app_api_version, inst->enabled_extensions, &dev->enabled_extensions)
               ? e->function
               : nullptr;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL tvk_GetInstanceProcAddr(VkInstance instance, const char* pName) {
    return lookup_instance_proc(instance, pName);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL tvk_GetDeviceProcAddr(VkDevice device, const char* pName) {
    return lookup_device_proc(device, pName);
}

}  // namespace tilevk::icd

extern "C" {

__attribute__((visibility("default"))) VKAPI_ATTR VkResult VKAPI_CALL
vk_icdNegotiateLoaderICDInterfaceVersion(uint32_t* pSupportedVersion) {
    using namespace tilevk::icd;
    if (pSupportedVersion == nullptr) return VK_ERROR_INITIALIZATION_FAILED;
    if (*pSupportedVersion < kMinLoaderInterface) {
        return fail(VK_ERROR_INCOMPATIBLE_DRIVER, "loader interface version %u is older than the %u tilevk needs",
                    *pSupportedVersion, kMinLoaderInterface);
    }
    if (*pSupportedVersion > kMaxLoaderInterface) *pSupportedVersion = kMaxLoaderInterface;
    return VK_SUCCESS;
}

__attribute__((visibility("default"))) VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL
vk_icdGetInstanceProcAddr(VkInstance instance, const char* pName) {
    return tilevk::icd::lookup_instance_proc(instance, pName);
}

__attribute__((visibility("default"))) VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL
vk_icdGetPhysicalDeviceProcAddr(VkInstance instance, const char* pName) {
    return tilevk::icd::lookup_physical_device_proc(instance, pName);
}

}  // extern "C"
