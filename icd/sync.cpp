#include "sync.h"

#include <chrono>

#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {

void Fence::signal() {
    {
        std::lock_guard<std::mutex> lock(mutex);
        signaled = true;
    }
    cv.notify_all();
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateFence(VkDevice device, const VkFenceCreateInfo* ci,
                                               const VkAllocationCallbacks* pAllocator, VkFence* pFence) {
    Device* dev = from_handle<Device>(device);
    Fence* f = create_object<Fence>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (f == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateFence: out of host memory");
    f->signaled = (ci->flags & VK_FENCE_CREATE_SIGNALED_BIT) != 0;
    *pFence = to_handle(f);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyFence(VkDevice, VkFence fence, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Fence>(fence));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_ResetFences(VkDevice, uint32_t fenceCount, const VkFence* pFences) {
    for (uint32_t i = 0; i < fenceCount; ++i) {
        Fence* f = from_handle<Fence>(pFences[i]);
        std::lock_guard<std::mutex> lock(f->mutex);
        f->signaled = false;
    }
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetFenceStatus(VkDevice, VkFence fence) {
    Fence* f = from_handle<Fence>(fence);
    std::lock_guard<std::mutex> lock(f->mutex);
    return f->signaled ? VK_SUCCESS : VK_NOT_READY;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_WaitForFences(VkDevice, uint32_t fenceCount, const VkFence* pFences,
                                                 VkBool32 waitAll, uint64_t timeout) {
    using Clock = std::chrono::steady_clock;
    // Clamp the timeout so that now + timeout cannot overflow the clock (UINT64_MAX means "forever").
    const auto deadline = Clock::now() + std::chrono::nanoseconds(std::min<uint64_t>(timeout, uint64_t(1) << 62));
    for (;;) {
        uint32_t done = 0;
        for (uint32_t i = 0; i < fenceCount; ++i) {
            Fence* f = from_handle<Fence>(pFences[i]);
            std::lock_guard<std::mutex> lock(f->mutex);
            if (f->signaled) ++done;
        }
        if (waitAll ? done == fenceCount : done > 0) return VK_SUCCESS;
        if (timeout == 0 || Clock::now() >= deadline) return VK_TIMEOUT;
        // Wait on the first unsignalled fence for a short while, then re-check all of them.
        for (uint32_t i = 0; i < fenceCount; ++i) {
            Fence* f = from_handle<Fence>(pFences[i]);
            std::unique_lock<std::mutex> lock(f->mutex);
            if (!f->signaled) {
                f->cv.wait_until(lock, std::min(deadline, Clock::now() + std::chrono::milliseconds(1)));
                break;
            }
        }
    }
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateSemaphore(VkDevice device, const VkSemaphoreCreateInfo*,
                                                   const VkAllocationCallbacks* pAllocator, VkSemaphore* pSemaphore) {
    Device* dev = from_handle<Device>(device);
    Semaphore* s =
        create_object<Semaphore>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (s == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSemaphore: out of host memory");
    *pSemaphore = to_handle(s);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroySemaphore(VkDevice, VkSemaphore semaphore, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Semaphore>(semaphore));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateEvent(VkDevice device, const VkEventCreateInfo*,
                                               const VkAllocationCallbacks* pAllocator, VkEvent* pEvent) {
    Device* dev = from_handle<Device>(device);
    Event* e = create_object<Event>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (e == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateEvent: out of host memory");
    *pEvent = to_handle(e);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyEvent(VkDevice, VkEvent event, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Event>(event));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetEventStatus(VkDevice, VkEvent event) {
    return from_handle<Event>(event)->set.load() ? VK_EVENT_SET : VK_EVENT_RESET;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_SetEvent(VkDevice, VkEvent event) {
    from_handle<Event>(event)->set.store(true);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_ResetEvent(VkDevice, VkEvent event) {
    from_handle<Event>(event)->set.store(false);
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
