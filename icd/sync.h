// VkFence, VkSemaphore, VkEvent. Submissions run synchronously inside vkQueueSubmit, so a fence is signalled
// before vkQueueSubmit returns; the condition variable serves submissions made from other threads.
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

struct Semaphore : NonDispatchableObject {
    using Handle = VkSemaphore;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_SEMAPHORE;
    Semaphore() : NonDispatchableObject(kType) {}
    bool signaled = false;  // informational: waits are satisfied by in-order execution on the one queue
};

struct Event : NonDispatchableObject {
    using Handle = VkEvent;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_EVENT;
    Event() : NonDispatchableObject(kType) {}
    std::atomic<bool> set{false};
};

}  // namespace tilevk::icd
