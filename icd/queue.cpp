// vkQueueSubmit / vkQueueWaitIdle: command buffers run synchronously, in order, on the submitting thread.
#include "command_buffer.h"
#include "device.h"
#include "entrypoints.h"
#include "execute.h"
#include "sync.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueSubmit(VkQueue queue, uint32_t submitCount, const VkSubmitInfo* pSubmits,
                                               VkFence fence) {
    Queue* q = from_handle<Queue>(queue);
    std::lock_guard<std::mutex> lock(q->submit_mutex);
    Device* dev = q->device;
    if (dev->lost) {
        // Nothing runs on a lost device; the fence is signalled so that no waiter hangs.
        if (fence != VK_NULL_HANDLE) from_handle<Fence>(fence)->signal();
        return VK_ERROR_DEVICE_LOST;
    }
    for (uint32_t i = 0; i < submitCount; ++i) {
        const VkSubmitInfo& s = pSubmits[i];
        // Waits on semaphores are satisfied: everything submitted earlier has already finished.
        for (uint32_t j = 0; j < s.waitSemaphoreCount; ++j)
            from_handle<Semaphore>(s.pWaitSemaphores[j])->signaled = false;
        for (uint32_t j = 0; j < s.commandBufferCount; ++j) {
            ExecState st;
            if (q->draw == nullptr) q->draw = create_draw_context();
            st.draw = q->draw;
            const uint64_t hits_before = shader_watchdog_hits(*q->draw);
            execute_command_buffer(from_handle<CommandBuffer>(s.pCommandBuffers[j]), st);
            finish_queries(st);
            if (const uint64_t hits = shader_watchdog_hits(*q->draw) - hits_before; hits != 0) {
                // A shader looped past the watchdog (shader/README.md): its results are incomplete. A GPU would
                // hang here; tilevk reports the device as lost instead of presenting a wrong image as valid.
                log_error(
                    "vkQueueSubmit: %llu shader invocation batch(es) did not terminate within the loop "
                    "watchdog's limit; the device is lost",
                    static_cast<unsigned long long>(hits));
                dev->lost = true;
                if (fence != VK_NULL_HANDLE) from_handle<Fence>(fence)->signal();
                return VK_ERROR_DEVICE_LOST;
            }
        }
        for (uint32_t j = 0; j < s.signalSemaphoreCount; ++j) {
            from_handle<Semaphore>(s.pSignalSemaphores[j])->signaled = true;
        }
    }
    if (fence != VK_NULL_HANDLE) from_handle<Fence>(fence)->signal();
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueWaitIdle(VkQueue queue) {
    Queue* q = from_handle<Queue>(queue);
    std::lock_guard<std::mutex> lock(q->submit_mutex);
    return q->device->lost ? VK_ERROR_DEVICE_LOST : VK_SUCCESS;
}

// The queue family has no VK_QUEUE_SPARSE_BINDING_BIT and no sparse feature is reported, so no resource can be
// sparse and nothing can be bound: refuse the call (nothing is executed, semaphores and the fence are left alone).
VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueBindSparse(VkQueue, uint32_t bindInfoCount, const VkBindSparseInfo*, VkFence) {
    return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                "vkQueueBindSparse: tilevk's queue does not support sparse binding (%u bind info(s) refused)",
                bindInfoCount);
}

}  // namespace tilevk::icd
