// vkQueueSubmit / vkQueueWaitIdle: command buffers run synchronously, in order, on the submitting thread.
#include "command_buffer.h"

#include <cstdint>
#include <optional>
#include <vector>

#include "device.h"
#include "entrypoints.h"
#include "execute.h"
#include "rast/render/stage_timer.h"
#include "sync.h"

namespace tilevk::icd {

namespace {

// The one stderr line of a device loss: the limit, and what the renderer was working on when it passed.
void report_timeout(const Queue& q, uint32_t submit, uint32_t command_buffer) {
    const long long ms = static_cast<long long>(q.timeout->limit().count());
    if (const std::optional<DrawOrigin> d = interrupted_draw(*q.draw)) {
        log_error(
            "vkQueueSubmit: the submission ran longer than the device timeout (%lld ms, TILEVK_DEVICE_TIMEOUT_MS), "
            "interrupted in draw %u of pSubmits[%u].pCommandBuffers[%u] (VkPipeline 0x%llx); the device is lost",
            ms, d->draw, d->submit, d->command_buffer,
            static_cast<unsigned long long>(reinterpret_cast<uintptr_t>(d->pipeline)));
    } else {
        log_error(
            "vkQueueSubmit: the submission ran longer than the device timeout (%lld ms, TILEVK_DEVICE_TIMEOUT_MS), "
            "interrupted in pSubmits[%u].pCommandBuffers[%u]; the device is lost",
            ms, submit, command_buffer);
    }
}

}  // namespace

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
    if (q->draw == nullptr) q->draw = create_draw_context(q->timeout->flag());
    begin_submission(*q->draw);
    // The time limit covers the whole call: a GPU would reset after this long without the work finishing.
    q->timeout->arm();
    for (uint32_t i = 0; i < submitCount; ++i) {
        const VkSubmitInfo& s = pSubmits[i];
        // Waits on semaphores are satisfied: everything submitted earlier has already finished.
        for (uint32_t j = 0; j < s.waitSemaphoreCount; ++j)
            from_handle<Semaphore>(s.pWaitSemaphores[j])->signaled = false;
        for (uint32_t j = 0; j < s.commandBufferCount; ++j) {
            ExecState st;
            st.draw = q->draw;
            st.stop = q->timeout->flag();
            st.submit_index = i;
            st.command_buffer_index = j;
            execute_command_buffer(from_handle<CommandBuffer>(s.pCommandBuffers[j]), st);
            finish_queries(st);
            if (q->timeout->expired()) {
                // The work was cut short (shader runs ended at a loop back edge, tiles and draws skipped): its
                // results are incomplete. A GPU would hang and reset; tilevk reports the device lost.
                q->timeout->disarm();
                report_timeout(*q, i, j);
                dev->lost = true;
                if (fence != VK_NULL_HANDLE) from_handle<Fence>(fence)->signal();
                return VK_ERROR_DEVICE_LOST;
            }
        }
        for (uint32_t j = 0; j < s.signalSemaphoreCount; ++j) {
            from_handle<Semaphore>(s.pSignalSemaphores[j])->signaled = true;
        }
    }
    q->timeout->disarm();
    rast::render::report_stage_times();  // TILEVK_STAGE_TIMES (the frame benchmark); nothing when off
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

// synchronization2: each VkSubmitInfo2 is the VkSubmitInfo of the same semaphores and command buffers (binary
// semaphores; their stage masks order nothing in a queue that runs submissions in order).
VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueSubmit2(VkQueue queue, uint32_t submitCount, const VkSubmitInfo2* pSubmits,
                                                VkFence fence) {
    std::vector<VkSubmitInfo> infos(submitCount, {VK_STRUCTURE_TYPE_SUBMIT_INFO});
    std::vector<std::vector<VkSemaphore>> waits(submitCount), signals(submitCount);
    std::vector<std::vector<VkPipelineStageFlags>> stages(submitCount);
    std::vector<std::vector<VkCommandBuffer>> buffers(submitCount);
    for (uint32_t i = 0; i < submitCount; ++i) {
        const VkSubmitInfo2& s = pSubmits[i];
        for (uint32_t j = 0; j < s.waitSemaphoreInfoCount; ++j) {
            waits[i].push_back(s.pWaitSemaphoreInfos[j].semaphore);
            stages[i].push_back(VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
        }
        for (uint32_t j = 0; j < s.commandBufferInfoCount; ++j)
            buffers[i].push_back(s.pCommandBufferInfos[j].commandBuffer);
        for (uint32_t j = 0; j < s.signalSemaphoreInfoCount; ++j)
            signals[i].push_back(s.pSignalSemaphoreInfos[j].semaphore);
        infos[i].waitSemaphoreCount = uint32_t(waits[i].size());
        infos[i].pWaitSemaphores = waits[i].data();
        infos[i].pWaitDstStageMask = stages[i].data();
        infos[i].commandBufferCount = uint32_t(buffers[i].size());
        infos[i].pCommandBuffers = buffers[i].data();
        infos[i].signalSemaphoreCount = uint32_t(signals[i].size());
        infos[i].pSignalSemaphores = signals[i].data();
    }
    return tvk_QueueSubmit(queue, submitCount, infos.data(), fence);
}

}  // namespace tilevk::icd
