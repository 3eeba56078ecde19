// VkBuffer: a range of device memory.
#pragma once
#include "memory.h"

namespace tilevk::icd {

struct Buffer : NonDispatchableObject {
    using Handle = VkBuffer;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_BUFFER;
    Buffer() : NonDispatchableObject(kType) {}
    VkDeviceSize size = 0;
    VkBufferUsageFlags usage = 0;
    DeviceMemory* memory = nullptr;
    VkDeviceSize memory_offset = 0;

    uint8_t* data() const { return memory->data + memory_offset; }
};

// The memory requirements of a buffer of `size` bytes (vkGetBufferMemoryRequirements, and without a buffer
// vkGetDeviceBufferMemoryRequirements: one home for both).
VkMemoryRequirements buffer_requirements(VkDeviceSize size);

}  // namespace tilevk::icd
