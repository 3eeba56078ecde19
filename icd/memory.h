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
    // Where the bytes live (memory_external.h): tilevk's own heap block, an application's host allocation
    // (VK_EXT_external_memory_host, never freed here), or a shared file mapped for VK_KHR_external_memory_fd.
    enum class Backing : uint8_t { Heap, HostPointer, SharedFile };
    Backing backing = Backing::Heap;
    int fd = -1;              // SharedFile: the file descriptor tilevk owns, duplicated by vkGetMemoryFdKHR
    size_t mapped_bytes = 0;  // SharedFile: the length of the mapping
};

}  // namespace tilevk::icd
