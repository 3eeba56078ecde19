// vkGetPhysicalDevice*2 (VK_KHR_get_physical_device_properties2, core in Vulkan 1.1): the Vulkan 1.0 answers plus
// every pNext struct tilevk knows, filled from the same homes (device_features.cpp, device_properties.cpp).
#include <cstring>
#include <vector>

#include "device_features.h"
#include "device_properties.h"
#include "entrypoints.h"
#include "formats.h"
#include "memory_external.h"
#include "object.h"
#include "physical_device.h"

namespace tilevk::icd {
namespace {

template <class Fn>
void for_each_out(void* chain, Fn fn) {
    for (auto* s = static_cast<VkBaseOutStructure*>(chain); s != nullptr; s = s->pNext) fn(s);
}

template <class Fn>
void for_each_in(const void* chain, Fn fn) {
    for (auto* s = static_cast<const VkBaseInStructure*>(chain); s != nullptr; s = s->pNext) fn(s);
}

}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceFeatures2(VkPhysicalDevice, VkPhysicalDeviceFeatures2* pFeatures) {
    const Features& f = supported_features();
    pFeatures->features = f.core10;
    for_each_out(pFeatures->pNext, [&](VkBaseOutStructure* s) { write_feature_struct(f, s); });
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceProperties2(VkPhysicalDevice physicalDevice,
                                                            VkPhysicalDeviceProperties2* pProperties) {
    const PhysicalDevice& pd = *from_handle<PhysicalDevice>(physicalDevice);
    pProperties->properties = pd.properties;
    for_each_out(pProperties->pNext, [&](VkBaseOutStructure* s) { write_property_struct(pd, s); });
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceFormatProperties2(VkPhysicalDevice physicalDevice, VkFormat format,
                                                                  VkFormatProperties2* pFormatProperties) {
    const VkFormatProperties& p = pFormatProperties->formatProperties;
    tvk_GetPhysicalDeviceFormatProperties(physicalDevice, format, &pFormatProperties->formatProperties);
    for_each_out(pFormatProperties->pNext, [&](VkBaseOutStructure* s) {
        if (s->sType != VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3) return;
        // VK_KHR_format_feature_flags2: the 32 bits of Vulkan 1.0 are the same bits of the 64-bit flags. Of the
        // bits above them, depth comparison: every sampled depth format takes OpImage*Dref* lookups
        // (shader/texture.cpp shadow compare; api_breadth DepthCompareSampling); stores without a format: every
        // storage image and storage texel buffer format, the view's format converting the value
        // (shaderStorageImageWriteWithoutFormat, device_features.cpp; lvp_formats.c sets the bit on the same sets).
        auto* p3 = reinterpret_cast<VkFormatProperties3*>(s);
        const FormatInfo* f = find_format(format);
        const bool depth = f != nullptr && (f->aspects & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
        auto widen = [depth](VkFormatFeatureFlags v1) {
            VkFormatFeatureFlags2 v2 = v1;
            if (depth && (v1 & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT))
                v2 |= VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_DEPTH_COMPARISON_BIT;
            if (v1 & (VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT))
                v2 |= VK_FORMAT_FEATURE_2_STORAGE_WRITE_WITHOUT_FORMAT_BIT;
            return v2;
        };
        p3->linearTilingFeatures = widen(p.linearTilingFeatures);
        p3->optimalTilingFeatures = widen(p.optimalTilingFeatures);
        p3->bufferFeatures = widen(p.bufferFeatures);
    });
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceImageFormatProperties2(
    VkPhysicalDevice physicalDevice, const VkPhysicalDeviceImageFormatInfo2* pInfo,
    VkImageFormatProperties2* pProperties) {
    VkImageUsageFlags usage = pInfo->usage;
    const VkPhysicalDeviceExternalImageFormatInfo* external = nullptr;
    for_each_in(pInfo->pNext, [&](const VkBaseInStructure* s) {
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_IMAGE_FORMAT_INFO) {
            external = reinterpret_cast<const VkPhysicalDeviceExternalImageFormatInfo*>(s);
        } else if (s->sType == VK_STRUCTURE_TYPE_IMAGE_STENCIL_USAGE_CREATE_INFO) {
            usage |= reinterpret_cast<const VkImageStencilUsageCreateInfo*>(s)->stencilUsage;
        }
    });
    pProperties->imageFormatProperties = {};
    // An image's bytes are plain linear memory whatever holds them, so the handle types of memory_external.h serve
    // every image tilevk can make; any other handle type serves none.
    ExternalMemorySupport ext;
    if (external != nullptr && external->handleType != 0) {
        ext = external_memory_support(external->handleType);
        if (!ext.supported) return VK_ERROR_FORMAT_NOT_SUPPORTED;
    }
    const VkResult r =
        tvk_GetPhysicalDeviceImageFormatProperties(physicalDevice, pInfo->format, pInfo->type, pInfo->tiling, usage,
                                                   pInfo->flags, &pProperties->imageFormatProperties);
    if (r != VK_SUCCESS) return r;
    for_each_out(pProperties->pNext, [&](VkBaseOutStructure* s) {
        if (s->sType == VK_STRUCTURE_TYPE_EXTERNAL_IMAGE_FORMAT_PROPERTIES) {
            reinterpret_cast<VkExternalImageFormatProperties*>(s)->externalMemoryProperties = ext.properties;
        }
    });
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceQueueFamilyProperties2(VkPhysicalDevice physicalDevice,
                                                                       uint32_t* pCount,
                                                                       VkQueueFamilyProperties2* pProperties) {
    uint32_t families = 0;
    tvk_GetPhysicalDeviceQueueFamilyProperties(physicalDevice, &families, nullptr);
    std::vector<VkQueueFamilyProperties> all(families);
    tvk_GetPhysicalDeviceQueueFamilyProperties(physicalDevice, &families, all.data());
    if (pProperties == nullptr) {
        *pCount = families;
        return;
    }
    const uint32_t n = *pCount < families ? *pCount : families;
    for (uint32_t i = 0; i < n; ++i) pProperties[i].queueFamilyProperties = all[i];
    *pCount = n;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceMemoryProperties2(VkPhysicalDevice physicalDevice,
                                                                  VkPhysicalDeviceMemoryProperties2* pProperties) {
    tvk_GetPhysicalDeviceMemoryProperties(physicalDevice, &pProperties->memoryProperties);
}

VKAPI_ATTR void VKAPI_CALL
tvk_GetPhysicalDeviceSparseImageFormatProperties2(VkPhysicalDevice, const VkPhysicalDeviceSparseImageFormatInfo2*,
                                                  uint32_t* pPropertyCount, VkSparseImageFormatProperties2*) {
    *pPropertyCount = 0;  // no sparse resources
}

// External memory (memory_external.h): OPAQUE_FD and HOST_ALLOCATION, for buffers of any usage.
VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceExternalBufferProperties(
    VkPhysicalDevice, const VkPhysicalDeviceExternalBufferInfo* pInfo, VkExternalBufferProperties* pProperties) {
    pProperties->externalMemoryProperties = external_memory_support(pInfo->handleType).properties;
}

// External fences and semaphores (VK_KHR_external_{fence,semaphore}_capabilities): no handle type can be exported
// or imported, so every query answers with no features and no compatible types.

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceExternalFenceProperties(VkPhysicalDevice,
                                                                        const VkPhysicalDeviceExternalFenceInfo*,
                                                                        VkExternalFenceProperties* pProperties) {
    pProperties->exportFromImportedHandleTypes = 0;
    pProperties->compatibleHandleTypes = 0;
    pProperties->externalFenceFeatures = 0;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPhysicalDeviceExternalSemaphoreProperties(
    VkPhysicalDevice, const VkPhysicalDeviceExternalSemaphoreInfo*, VkExternalSemaphoreProperties* pProperties) {
    pProperties->exportFromImportedHandleTypes = 0;
    pProperties->compatibleHandleTypes = 0;
    pProperties->externalSemaphoreFeatures = 0;
}

// VK_KHR_device_group_creation: one group holding the one device (no subset allocation: there is nothing to split).
VKAPI_ATTR VkResult VKAPI_CALL tvk_EnumeratePhysicalDeviceGroups(VkInstance instance, uint32_t* pCount,
                                                                 VkPhysicalDeviceGroupProperties* pGroups) {
    if (pGroups == nullptr) {
        *pCount = 1;
        return VK_SUCCESS;
    }
    if (*pCount == 0) return VK_INCOMPLETE;
    uint32_t one = 1;
    VkPhysicalDevice pd = VK_NULL_HANDLE;
    tvk_EnumeratePhysicalDevices(instance, &one, &pd);
    pGroups[0].physicalDeviceCount = 1;
    std::memset(pGroups[0].physicalDevices, 0, sizeof pGroups[0].physicalDevices);
    pGroups[0].physicalDevices[0] = pd;
    pGroups[0].subsetAllocation = VK_FALSE;
    *pCount = 1;
    return VK_SUCCESS;
}

// VK_EXT_tooling_info: tilevk is no tool and knows of none.
VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceToolProperties(VkPhysicalDevice, uint32_t* pCount,
                                                                   VkPhysicalDeviceToolProperties*) {
    *pCount = 0;
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
