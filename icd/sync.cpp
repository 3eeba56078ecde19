#include "sync.h"

#include <chrono>

#include "device.h"
#include "entrypoints.h"
#include "queue_scheduler.h"

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

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateSemaphore(VkDevice device, const VkSemaphoreCreateInfo* ci,
                                                   const VkAllocationCallbacks* pAllocator, VkSemaphore* pSemaphore) {
    Device* dev = from_handle<Device>(device);
    const auto* type =
        find_in_chain<VkSemaphoreTypeCreateInfo>(ci->pNext, VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO);
    const bool timeline = type != nullptr && type->semaphoreType == VK_SEMAPHORE_TYPE_TIMELINE;
    if (timeline && !dev->enabled_features.core.v12.timelineSemaphore) {
        // VUID-VkSemaphoreTypeCreateInfo-timelineSemaphore-03252
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateSemaphore: VK_SEMAPHORE_TYPE_TIMELINE needs the timelineSemaphore feature enabled");
    }
    Semaphore* s =
        create_object<Semaphore>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (s == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSemaphore: out of host memory");
    s->device = dev;
    if (timeline) {
        s->type = VK_SEMAPHORE_TYPE_TIMELINE;
        s->value.store(type->initialValue);
    }
    *pSemaphore = to_handle(s);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroySemaphore(VkDevice, VkSemaphore semaphore, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Semaphore>(semaphore));
}

// Timeline semaphores (Vulkan 1.2, VK_KHR_timeline_semaphore). The counters change under the queue scheduler's
// mutex, whose condition variable every waiter sleeps on (queue_scheduler.h).
VKAPI_ATTR VkResult VKAPI_CALL tvk_GetSemaphoreCounterValue(VkDevice device, VkSemaphore semaphore, uint64_t* pValue) {
    *pValue = from_handle<Semaphore>(semaphore)->value.load(std::memory_order_acquire);
    return from_handle<Device>(device)->lost ? VK_ERROR_DEVICE_LOST : VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_WaitSemaphores(VkDevice device, const VkSemaphoreWaitInfo* pWaitInfo,
                                                  uint64_t timeout) {
    using Clock = std::chrono::steady_clock;
    Device* dev = from_handle<Device>(device);
    const bool any = (pWaitInfo->flags & VK_SEMAPHORE_WAIT_ANY_BIT) != 0;
    const auto done = [&] {
        uint32_t reached = 0;
        for (uint32_t i = 0; i < pWaitInfo->semaphoreCount; ++i) {
            const Semaphore* s = from_handle<Semaphore>(pWaitInfo->pSemaphores[i]);
            if (s->value.load(std::memory_order_acquire) >= pWaitInfo->pValues[i]) ++reached;
        }
        return any ? reached > 0 || pWaitInfo->semaphoreCount == 0 : reached == pWaitInfo->semaphoreCount;
    };
    QueueScheduler& sched = *dev->queue->scheduler;
    std::unique_lock<std::mutex> lock(sched.mutex);
    const auto woken = [&] { return done() || dev->lost; };
    if (timeout >= (uint64_t(1) << 62)) {
        sched.cv.wait(lock, woken);  // "forever" (UINT64_MAX), or far enough that the clock would overflow
    } else if (timeout > 0) {
        sched.cv.wait_until(lock, Clock::now() + std::chrono::nanoseconds(timeout), woken);
    }
    if (done()) return VK_SUCCESS;
    return dev->lost ? VK_ERROR_DEVICE_LOST : VK_TIMEOUT;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_SignalSemaphore(VkDevice, const VkSemaphoreSignalInfo* pSignalInfo) {
    Semaphore* s = from_handle<Semaphore>(pSignalInfo->semaphore);
    const uint64_t now = s->value.load(std::memory_order_acquire);
    if (pSignalInfo->value <= now) {
        // VUID-VkSemaphoreSignalInfo-value-03258 (invalid usage): counters only grow, so the value is left as is.
        log_error("vkSignalSemaphore: value %llu is not greater than the semaphore's current value %llu (ignored)",
                  static_cast<unsigned long long>(pSignalInfo->value), static_cast<unsigned long long>(now));
        return VK_SUCCESS;
    }
    signal_timeline(s, pSignalInfo->value);
    return VK_SUCCESS;
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
