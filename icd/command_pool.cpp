// vkCreateCommandPool ... vkEndCommandBuffer: command buffer lifetime and states.
#include <algorithm>

#include "command_buffer.h"
#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {

void CommandBuffer::out_of_memory() {
    if (record_result == VK_SUCCESS) {
        record_result = fail(VK_ERROR_OUT_OF_HOST_MEMORY, "command buffer recording: out of host memory");
    }
}

void CommandBuffer::reset(bool release_memory) {
    if (release_memory)
        arena.release();
    else
        arena.rewind();
    first = last = nullptr;
    rendering.clear();
    pushed_sets.clear();
    record_result = VK_SUCCESS;
    state = State::kInitial;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateCommandPool(VkDevice device, const VkCommandPoolCreateInfo* ci,
                                                     const VkAllocationCallbacks* pAllocator,
                                                     VkCommandPool* pCommandPool) {
    Device* dev = from_handle<Device>(device);
    if (ci->queueFamilyIndex != 0) {
        return fail(VK_ERROR_INITIALIZATION_FAILED, "vkCreateCommandPool: queue family %u does not exist",
                    ci->queueFamilyIndex);
    }
    auto* pool =
        create_object<CommandPool>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (pool == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateCommandPool: out of host memory");
    pool->device = dev;
    pool->flags = ci->flags;
    *pCommandPool = to_handle(pool);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyCommandPool(VkDevice, VkCommandPool commandPool, const VkAllocationCallbacks*) {
    CommandPool* pool = from_handle<CommandPool>(commandPool);
    if (pool == nullptr) return;
    for (CommandBuffer* cb : pool->buffers) destroy_object(cb);
    destroy_object(pool);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_ResetCommandPool(VkDevice, VkCommandPool commandPool,
                                                    VkCommandPoolResetFlags flags) {
    for (CommandBuffer* cb : from_handle<CommandPool>(commandPool)->buffers)
        cb->reset((flags & VK_COMMAND_POOL_RESET_RELEASE_RESOURCES_BIT) != 0);
    return VK_SUCCESS;
}

// maintenance1: the arena blocks command buffers keep for their next recording go back to the pool's allocator.
VKAPI_ATTR void VKAPI_CALL tvk_TrimCommandPool(VkDevice, VkCommandPool commandPool, VkCommandPoolTrimFlags) {
    for (CommandBuffer* cb : from_handle<CommandPool>(commandPool)->buffers) cb->arena.trim();
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_AllocateCommandBuffers(VkDevice, const VkCommandBufferAllocateInfo* ai,
                                                          VkCommandBuffer* pCommandBuffers) {
    CommandPool* pool = from_handle<CommandPool>(ai->commandPool);
    for (uint32_t i = 0; i < ai->commandBufferCount; ++i) {
        CommandBuffer* cb = create_object<CommandBuffer>(pool->allocator, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
        bool ok = cb != nullptr;
        if (ok) {
            try {
                pool->buffers.push_back(cb);
            } catch (const std::bad_alloc&) {
                destroy_object(cb);
                ok = false;
            }
        }
        if (!ok) {
            for (uint32_t j = 0; j < i; ++j) {  // all or nothing
                CommandBuffer* done = from_handle<CommandBuffer>(pCommandBuffers[j]);
                pool->buffers.erase(std::find(pool->buffers.begin(), pool->buffers.end(), done));
                destroy_object(done);
            }
            for (uint32_t j = 0; j < ai->commandBufferCount; ++j) pCommandBuffers[j] = VK_NULL_HANDLE;
            return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkAllocateCommandBuffers: out of host memory");
        }
        cb->pool = pool;
        cb->level = ai->level;
        cb->arena.set_callbacks(&pool->allocator);
        pCommandBuffers[i] = to_handle(cb);
    }
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_FreeCommandBuffers(VkDevice, VkCommandPool commandPool, uint32_t count,
                                                  const VkCommandBuffer* pCommandBuffers) {
    CommandPool* pool = from_handle<CommandPool>(commandPool);
    for (uint32_t i = 0; i < count; ++i) {
        CommandBuffer* cb = from_handle<CommandBuffer>(pCommandBuffers[i]);
        if (cb == nullptr) continue;
        auto it = std::find(pool->buffers.begin(), pool->buffers.end(), cb);
        if (it != pool->buffers.end()) pool->buffers.erase(it);
        destroy_object(cb);
    }
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_BeginCommandBuffer(VkCommandBuffer commandBuffer,
                                                      const VkCommandBufferBeginInfo* pBeginInfo) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    if (cb->state != CommandBuffer::State::kInitial) cb->reset();  // implicit reset (pool allows it, VU says so)
    cb->usage = pBeginInfo->flags;
    cb->state = CommandBuffer::State::kRecording;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_EndCommandBuffer(VkCommandBuffer commandBuffer) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    cb->state = CommandBuffer::State::kExecutable;
    return cb->record_result;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_ResetCommandBuffer(VkCommandBuffer commandBuffer, VkCommandBufferResetFlags flags) {
    from_handle<CommandBuffer>(commandBuffer)->reset((flags & VK_COMMAND_BUFFER_RESET_RELEASE_RESOURCES_BIT) != 0);
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
