#include "memory.h"

#include "device.h"
#include "entrypoints.h"
#include "memory_external.h"
#include "physical_device.h"
#include "shader/program.h"
#include "vk_names.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_AllocateMemory(VkDevice device, const VkMemoryAllocateInfo* pAllocateInfo,
                                                  const VkAllocationCallbacks* pAllocator, VkDeviceMemory* pMemory) {
    Device* dev = from_handle<Device>(device);
    if (pAllocateInfo->memoryTypeIndex != 0) {
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory: memory type %u does not exist",
                    pAllocateInfo->memoryTypeIndex);
    }
    bool device_address = false;
    if (const auto* flags = find_in_chain<VkMemoryAllocateFlagsInfo>(pAllocateInfo->pNext,
                                                                     VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO)) {
        // Addresses are host addresses: there is nothing to capture and replay (bufferDeviceAddressCaptureReplay
        // is VK_FALSE).
        if ((flags->flags & VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_CAPTURE_REPLAY_BIT) != 0) {
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkAllocateMemory: VkMemoryAllocateFlagsInfo::flags VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_CAPTURE_"
                        "REPLAY_BIT needs the bufferDeviceAddressCaptureReplay feature, which tilevk does not support");
        }
        device_address = (flags->flags & VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT) != 0;
    }
    VkDeviceSize size = pAllocateInfo->allocationSize;
    if (size > dev->physical_device->memory.memoryHeaps[0].size) {
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory: %llu bytes exceed the heap",
                    (unsigned long long)size);
    }
    DeviceMemory* mem =
        create_object<DeviceMemory>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (mem == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkAllocateMemory: out of host memory");
    const VkResult backed = allocate_memory_backing(*pAllocateInfo, *mem);
    if (backed != VK_SUCCESS) {
        destroy_object(mem);
        return backed;
    }
    // Buffers with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT must be bound to such memory: shaders may reach these
    // bytes, and only these, through PhysicalStorageBuffer pointers (shader/program.h register_device_memory).
    mem->device_address = device_address;
    if (device_address) shader::register_device_memory(mem->data, size);
    *pMemory = to_handle(mem);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_FreeMemory(VkDevice, VkDeviceMemory memory, const VkAllocationCallbacks*) {
    DeviceMemory* mem = from_handle<DeviceMemory>(memory);
    if (mem == nullptr) return;
    if (mem->device_address) shader::unregister_device_memory(mem->data);
    free_memory_backing(*mem);
    destroy_object(mem);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_MapMemory(VkDevice, VkDeviceMemory memory, VkDeviceSize offset, VkDeviceSize,
                                             VkMemoryMapFlags, void** ppData) {
    DeviceMemory* mem = from_handle<DeviceMemory>(memory);
    if (offset > mem->size) {
        *ppData = nullptr;
        return fail(VK_ERROR_MEMORY_MAP_FAILED, "vkMapMemory: offset %llu is past the allocation",
                    (unsigned long long)offset);
    }
    mem->mapped = true;
    *ppData = mem->data + offset;
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_UnmapMemory(VkDevice, VkDeviceMemory memory) {
    from_handle<DeviceMemory>(memory)->mapped = false;
}

// The only memory type is host-coherent: flushes and invalidations have nothing to do.
VKAPI_ATTR VkResult VKAPI_CALL tvk_FlushMappedMemoryRanges(VkDevice, uint32_t, const VkMappedMemoryRange*) {
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_InvalidateMappedMemoryRanges(VkDevice, uint32_t, const VkMappedMemoryRange*) {
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceMemoryCommitment(VkDevice, VkDeviceMemory memory,
                                                         VkDeviceSize* pCommittedMemoryInBytes) {
    *pCommittedMemoryInBytes = from_handle<DeviceMemory>(memory)->size;
}

}  // namespace tilevk::icd
