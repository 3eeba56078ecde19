#include "buffer.h"

#include "device.h"
#include "entrypoints.h"
#include "vk_names.h"

namespace tilevk::icd {

// Buffer alignment: covers min{Uniform,Storage,Texel}BufferOffsetAlignment (16) and 16-byte vector loads.
constexpr VkDeviceSize kBufferAlignment = 16;

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateBuffer(VkDevice device, const VkBufferCreateInfo* pCreateInfo,
                                                const VkAllocationCallbacks* pAllocator, VkBuffer* pBuffer) {
    Device* dev = from_handle<Device>(device);
    if (pCreateInfo->flags != 0) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateBuffer: buffer create flags %s are not supported",
                    vk_flags_name<VkBufferCreateFlagBits>(pCreateInfo->flags).c_str());
    }
    Buffer* buf = create_object<Buffer>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (buf == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateBuffer: out of host memory");
    buf->size = pCreateInfo->size;
    buf->usage = pCreateInfo->usage;
    *pBuffer = to_handle(buf);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyBuffer(VkDevice, VkBuffer buffer, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Buffer>(buffer));
}

// The size is the create size aligned to the alignment (never more: a guarantee of VK_KHR_maintenance4).
VkMemoryRequirements buffer_requirements(VkDeviceSize size) {
    return {(size + kBufferAlignment - 1) & ~(kBufferAlignment - 1), kBufferAlignment, 1};
}

VKAPI_ATTR void VKAPI_CALL tvk_GetBufferMemoryRequirements(VkDevice, VkBuffer buffer, VkMemoryRequirements* pReqs) {
    *pReqs = buffer_requirements(from_handle<Buffer>(buffer)->size);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_BindBufferMemory(VkDevice, VkBuffer buffer, VkDeviceMemory memory,
                                                    VkDeviceSize memoryOffset) {
    Buffer* buf = from_handle<Buffer>(buffer);
    buf->memory = from_handle<DeviceMemory>(memory);
    buf->memory_offset = memoryOffset;
    return VK_SUCCESS;
}

// Vulkan 1.2 core commands (VK_KHR_buffer_device_address): a buffer's address is where its bytes are in host memory,
// which shaders reach through PhysicalStorageBuffer pointers (shader/translate_pointer.cpp) when the memory was
// allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT (memory.cpp). bufferDeviceAddressCaptureReplay is VK_FALSE,
// so nothing has an opaque capture address: 0, as the spec allows when no capture address was asked for.
VKAPI_ATTR VkDeviceAddress VKAPI_CALL tvk_GetBufferDeviceAddress(VkDevice, const VkBufferDeviceAddressInfo* pInfo) {
    const Buffer* buf = from_handle<Buffer>(pInfo->buffer);
    return buf->memory == nullptr ? 0 : VkDeviceAddress(reinterpret_cast<uintptr_t>(buf->data()));
}

VKAPI_ATTR uint64_t VKAPI_CALL tvk_GetBufferOpaqueCaptureAddress(VkDevice, const VkBufferDeviceAddressInfo*) {
    return 0;
}

VKAPI_ATTR uint64_t VKAPI_CALL tvk_GetDeviceMemoryOpaqueCaptureAddress(VkDevice,
                                                                       const VkDeviceMemoryOpaqueCaptureAddressInfo*) {
    return 0;
}

}  // namespace tilevk::icd
