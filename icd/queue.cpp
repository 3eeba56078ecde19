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
    for (uint32_t i = 0; i < submitCount; ++i) {
        const VkSubmitInfo& s = pSubmits[i];
        // Waits on semaphores are satisfied: everything submitted earlier has already finished.
        for (uint32_t j = 0; j < s.waitSemaphoreCount; ++j)
            from_handle<Semaphore>(s.pWaitSemaphores[j])->signaled = false;
        for (uint32_t j = 0; j < s.commandBufferCount; ++j) {
            ExecState st;
            if (q->draw == nullptr) q->draw = create_draw_context();
            st.draw = q->draw;
            execute_command_buffer(from_handle<CommandBuffer>(s.pCommandBuffers[j]), st);
        }
        for (uint32_t j = 0; j < s.signalSemaphoreCount; ++j) {
            from_handle<Semaphore>(s.pSignalSemaphores[j])->signaled = true;
        }
    }
    if (fence != VK_NULL_HANDLE) from_handle<Fence>(fence)->signal();
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueWaitIdle(VkQueue queue) {
    std::lock_guard<std::mutex> lock(from_handle<Queue>(queue)->submit_mutex);
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
