// vkQueueSubmit / vkQueueWaitIdle: a batch runs on the submitting thread when nothing is queued ahead of it and
// its timeline waits are reached; otherwise it and the batches after it wait for the queue's worker
// (queue_scheduler.h), which runs them in order.
#include <cstdint>
#include <new>

#include "device.h"
#include "entrypoints.h"
#include "queue_scheduler.h"
#include "rast/render/stage_timer.h"
#include "sync.h"

namespace tilevk::icd {

namespace {

const VkTimelineSemaphoreSubmitInfo* timeline_values(const VkSubmitInfo& s) {
    return find_in_chain<VkTimelineSemaphoreSubmitInfo>(s.pNext, VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO);
}

uint64_t value_at(const uint64_t* values, uint32_t count, uint32_t j) {
    return j < count ? values[j] : 0;
}

// The submission's semaphores as the scheduler's (wait, signal) lists; values of binary semaphores are ignored.
void copy_semaphores(const VkSubmitInfo& s, Batch* b) {
    const VkTimelineSemaphoreSubmitInfo* t = timeline_values(s);
    for (uint32_t j = 0; j < s.waitSemaphoreCount; ++j) {
        b->waits.push_back({from_handle<Semaphore>(s.pWaitSemaphores[j]),
                            t ? value_at(t->pWaitSemaphoreValues, t->waitSemaphoreValueCount, j) : 0});
    }
    for (uint32_t j = 0; j < s.signalSemaphoreCount; ++j) {
        b->signals.push_back({from_handle<Semaphore>(s.pSignalSemaphores[j]),
                              t ? value_at(t->pSignalSemaphoreValues, t->signalSemaphoreValueCount, j) : 0});
    }
}

// A batch that runs now: its binary waits are consumed (their signals were submitted earlier, so they have run).
void consume_binary_waits(const VkSubmitInfo& s) {
    for (uint32_t j = 0; j < s.waitSemaphoreCount; ++j) {
        Semaphore* sem = from_handle<Semaphore>(s.pWaitSemaphores[j]);
        if (sem->type == VK_SEMAPHORE_TYPE_BINARY) sem->signaled = false;
    }
}

void signal_submit(const VkSubmitInfo& s) {
    const VkTimelineSemaphoreSubmitInfo* t = timeline_values(s);
    for (uint32_t j = 0; j < s.signalSemaphoreCount; ++j) {
        Semaphore* sem = from_handle<Semaphore>(s.pSignalSemaphores[j]);
        if (sem->type == VK_SEMAPHORE_TYPE_TIMELINE) {
            signal_timeline(sem, t ? value_at(t->pSignalSemaphoreValues, t->signalSemaphoreValueCount, j) : 0);
        } else {
            sem->signaled = true;
        }
    }
}

// Queues pSubmits[first, count) for the worker; the fence goes with the last one (or with an empty batch when
// every submission ran but earlier batches are still queued).
VkResult defer(QueueScheduler& sched, uint32_t first, uint32_t count, const VkSubmitInfo* pSubmits, Fence* fence) {
    std::lock_guard<std::mutex> lock(sched.mutex);
    if (first == count && sched.idle()) {
        if (fence != nullptr) fence->signal();
        return VK_SUCCESS;
    }
    try {
        if (first == count) {
            std::unique_ptr<Batch> b = sched.take_spare();
            b->fence = fence;
            sched.enqueue(std::move(b));
        }
        for (uint32_t i = first; i < count; ++i) {
            std::unique_ptr<Batch> b = sched.take_spare();
            const VkSubmitInfo& s = pSubmits[i];
            copy_semaphores(s, b.get());
            b->command_buffers.assign(s.pCommandBuffers, s.pCommandBuffers + s.commandBufferCount);
            b->submit_index = i;
            if (i + 1 == count) b->fence = fence;
            sched.enqueue(std::move(b));
        }
    } catch (const std::bad_alloc&) {
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkQueueSubmit: out of host memory queueing pSubmits[%u..%u)", first,
                    count);
    }
    return VK_SUCCESS;
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueSubmit(VkQueue queue, uint32_t submitCount, const VkSubmitInfo* pSubmits,
                                               VkFence fence) {
    Queue* q = from_handle<Queue>(queue);
    std::lock_guard<std::mutex> lock(q->submit_mutex);
    Fence* f = fence != VK_NULL_HANDLE ? from_handle<Fence>(fence) : nullptr;
    if (q->device->lost) {
        // Nothing runs on a lost device; the fence is signalled so that no waiter hangs.
        if (f != nullptr) f->signal();
        return VK_ERROR_DEVICE_LOST;
    }
    QueueScheduler& sched = *q->scheduler;
    uint32_t i = 0;
    for (; i < submitCount; ++i) {
        const VkSubmitInfo& s = pSubmits[i];
        {
            std::lock_guard<std::mutex> state(sched.mutex);
            if (!sched.idle() || !waits_reached(s)) break;  // wait-before-signal: the worker runs it later
        }
        consume_binary_waits(s);
        if (!execute_batch(*q, i, s.commandBufferCount, s.pCommandBuffers)) {
            if (f != nullptr) f->signal();
            return VK_ERROR_DEVICE_LOST;
        }
        signal_submit(s);
    }
    if (i > 0) rast::render::report_stage_times();  // TILEVK_STAGE_TIMES (the frame benchmark); nothing when off
    return defer(sched, i, submitCount, pSubmits, f);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueWaitIdle(VkQueue queue) {
    Queue* q = from_handle<Queue>(queue);
    q->scheduler->wait_idle();                          // the worker's batches (dropped once the device is lost)
    std::lock_guard<std::mutex> lock(q->submit_mutex);  // a submission running on another thread
    return q->device->lost ? VK_ERROR_DEVICE_LOST : VK_SUCCESS;
}

// The queue family has no VK_QUEUE_SPARSE_BINDING_BIT and no sparse feature is reported, so no resource can be
// sparse and nothing can be bound: refuse the call (nothing is executed, semaphores and the fence are left alone).
VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueBindSparse(VkQueue, uint32_t bindInfoCount, const VkBindSparseInfo*, VkFence) {
    return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                "vkQueueBindSparse: tilevk's queue does not support sparse binding (%u bind info(s) refused)",
                bindInfoCount);
}

// synchronization2: each VkSubmitInfo2 is the VkSubmitInfo of the same semaphores (with their timeline values)
// and command buffers; stage masks order nothing in a queue that runs its batches in order. The translation lives
// in the queue's scratch (the queue is externally synchronized), so a steady frame allocates nothing here.
VKAPI_ATTR VkResult VKAPI_CALL tvk_QueueSubmit2(VkQueue queue, uint32_t submitCount, const VkSubmitInfo2* pSubmits,
                                                VkFence fence) {
    Submit2Scratch& x = from_handle<Queue>(queue)->submit2;
    VkSubmitInfo info0{};
    info0.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    VkTimelineSemaphoreSubmitInfo timeline0{};
    timeline0.sType = VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO;
    x.infos.assign(submitCount, info0);
    x.timelines.assign(submitCount, timeline0);
    size_t waits = 0, signals = 0, buffers = 0;
    for (uint32_t i = 0; i < submitCount; ++i) {
        waits += pSubmits[i].waitSemaphoreInfoCount;
        signals += pSubmits[i].signalSemaphoreInfoCount;
        buffers += pSubmits[i].commandBufferInfoCount;
    }
    // Sized first: the VkSubmitInfos point into these arrays.
    x.semaphores.resize(waits + signals);
    x.values.resize(waits + signals);
    x.stages.assign(waits, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
    x.buffers.resize(buffers);
    size_t sem = 0, buf = 0;
    for (uint32_t i = 0; i < submitCount; ++i) {
        const VkSubmitInfo2& s = pSubmits[i];
        VkSubmitInfo& info = x.infos[i];
        VkTimelineSemaphoreSubmitInfo& t = x.timelines[i];
        info.pNext = &t;
        info.waitSemaphoreCount = t.waitSemaphoreValueCount = s.waitSemaphoreInfoCount;
        info.pWaitSemaphores = x.semaphores.data() + sem;
        info.pWaitDstStageMask = x.stages.data();  // every entry is ALL_COMMANDS, as many as all the waits
        t.pWaitSemaphoreValues = x.values.data() + sem;
        for (uint32_t j = 0; j < s.waitSemaphoreInfoCount; ++j, ++sem) {
            x.semaphores[sem] = s.pWaitSemaphoreInfos[j].semaphore;
            x.values[sem] = s.pWaitSemaphoreInfos[j].value;
        }
        info.signalSemaphoreCount = t.signalSemaphoreValueCount = s.signalSemaphoreInfoCount;
        info.pSignalSemaphores = x.semaphores.data() + sem;
        t.pSignalSemaphoreValues = x.values.data() + sem;
        for (uint32_t j = 0; j < s.signalSemaphoreInfoCount; ++j, ++sem) {
            x.semaphores[sem] = s.pSignalSemaphoreInfos[j].semaphore;
            x.values[sem] = s.pSignalSemaphoreInfos[j].value;
        }
        info.commandBufferCount = s.commandBufferInfoCount;
        info.pCommandBuffers = x.buffers.data() + buf;
        for (uint32_t j = 0; j < s.commandBufferInfoCount; ++j, ++buf)
            x.buffers[buf] = s.pCommandBufferInfos[j].commandBuffer;
    }
    return tvk_QueueSubmit(queue, submitCount, x.infos.data(), fence);
}

}  // namespace tilevk::icd
