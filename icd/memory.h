// VkDeviceMemory: plain host memory (one heap, one host-visible coherent cached type).
#pragma once
#include "object.h"

namespace tilevk::icd {

// Device memory is aligned for the widest SIMD loads and for minMemoryMapAlignment.
constexpr VkDeviceSize kMemoryAlignment = 64;

struct DeviceMemory : NonDispatchableObject {
    using Handle = VkDeviceMemory;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DEVICE_MEMORY;
    DeviceMemory() : NonDispatchableObject(kType) {}
    uint8_t* data = nullptr;
    VkDeviceSize size = 0;
    bool mapped = false;
    bool device_address = false;  // allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT: in shader/'s registry
};

}  // namespace tilevk::icd
