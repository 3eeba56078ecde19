// VkFence, VkSemaphore (binary and timeline), VkEvent. A submission whose waits are satisfied runs inside
// vkQueueSubmit; one that waits for a timeline value not yet reached runs later on the queue's worker
// (queue_scheduler.h), which signals its semaphores and fence: the condition variables serve those waits.
#pragma once
#include <atomic>
#include <condition_variable>
#include <mutex>

#include "object.h"

namespace tilevk::icd {

struct Fence : NonDispatchableObject {
    using Handle = VkFence;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_FENCE;
    Fence() : NonDispatchableObject(kType) {}
    std::mutex mutex;
    std::condition_variable cv;
    bool signaled = false;

    void signal();
};

struct Device;

struct Semaphore : NonDispatchableObject {
    using Handle = VkSemaphore;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_SEMAPHORE;
    Semaphore() : NonDispatchableObject(kType) {}
    Device* device = nullptr;
    VkSemaphoreType type = VK_SEMAPHORE_TYPE_BINARY;
    // Binary: informational (a binary wait is satisfied by in-order execution on the one queue: its signal was
    // submitted earlier, VUID-vkQueueSubmit-pWaitSemaphores-03238).
    bool signaled = false;
    // Timeline: the counter. Written only under the queue scheduler's mutex (which wakes the waiters), read
    // anywhere.
    std::atomic<uint64_t> value{0};
};

struct Event : NonDispatchableObject {
    using Handle = VkEvent;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_EVENT;
    Event() : NonDispatchableObject(kType) {}
    std::atomic<bool> set{false};
};

}  // namespace tilevk::icd
