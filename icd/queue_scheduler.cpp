#include "queue_scheduler.h"

#include <optional>

#include "command_buffer.h"
#include "device.h"
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

bool reached(const Semaphore* s, uint64_t value) {
    return s->type != VK_SEMAPHORE_TYPE_TIMELINE || s->value.load(std::memory_order_acquire) >= value;
}

}  // namespace

void Batch::clear() {
    waits.clear();
    command_buffers.clear();
    signals.clear();
    fence = nullptr;
    submit_index = 0;
}

QueueScheduler::~QueueScheduler() {
    {
        std::lock_guard<std::mutex> lock(mutex);
        quit_ = true;
    }
    cv.notify_all();
    if (worker_.joinable()) worker_.join();
}

std::unique_ptr<Batch> QueueScheduler::take_spare() {
    if (spare_.empty()) return std::make_unique<Batch>();
    std::unique_ptr<Batch> b = std::move(spare_.back());
    spare_.pop_back();
    return b;
}

void QueueScheduler::enqueue(std::unique_ptr<Batch> b) {
    pending_.push_back(std::move(b));
    if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
    cv.notify_all();
}

void QueueScheduler::wait_idle() {
    std::unique_lock<std::mutex> lock(mutex);
    cv.wait(lock, [&] { return idle(); });
}

// The worker: the front batch runs once its waits are reached; on a lost device every batch is dropped (its
// fence still signalled, so that no host waits forever).
void QueueScheduler::run() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
        cv.wait(lock,
                [&] { return quit_ || (!idle() && (queue_.device->lost || waits_reached(pending_[head_]->waits))); });
        if (quit_) return;
        Batch* b = pending_[head_].get();
        lock.unlock();
        {
            std::lock_guard<std::mutex> exec(queue_.submit_mutex);
            if (!queue_.device->lost) {
                for (const SemaphoreValue& w : b->waits)
                    if (w.semaphore->type == VK_SEMAPHORE_TYPE_BINARY) w.semaphore->signaled = false;
                if (execute_batch(queue_, b->submit_index, uint32_t(b->command_buffers.size()),
                                  b->command_buffers.data())) {
                    signal_batch(b->signals.data(), uint32_t(b->signals.size()));
                }
                rast::render::report_stage_times();
            }
            if (b->fence != nullptr) b->fence->signal();
            lock.lock();
            b->clear();
            spare_.push_back(std::move(pending_[head_]));
            if (++head_ == pending_.size()) {
                pending_.clear();  // keeps its capacity
                head_ = 0;
            }
        }
        cv.notify_all();
    }
}

bool waits_reached(const std::vector<SemaphoreValue>& waits) {
    for (const SemaphoreValue& w : waits)
        if (!reached(w.semaphore, w.value)) return false;
    return true;
}

bool waits_reached(const VkSubmitInfo& s) {
    const auto* values =
        find_in_chain<VkTimelineSemaphoreSubmitInfo>(s.pNext, VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO);
    for (uint32_t j = 0; j < s.waitSemaphoreCount; ++j) {
        const Semaphore* sem = from_handle<Semaphore>(s.pWaitSemaphores[j]);
        const uint64_t v =
            values != nullptr && j < values->waitSemaphoreValueCount ? values->pWaitSemaphoreValues[j] : 0;
        if (!reached(sem, v)) return false;
    }
    return true;
}

void signal_timeline(Semaphore* s, uint64_t value) {
    QueueScheduler& sched = *s->device->queue->scheduler;
    {
        std::lock_guard<std::mutex> lock(sched.mutex);
        s->value.store(value, std::memory_order_release);
    }
    sched.cv.notify_all();
}

void signal_batch(const SemaphoreValue* signals, uint32_t count) {
    for (uint32_t j = 0; j < count; ++j) {
        if (signals[j].semaphore->type == VK_SEMAPHORE_TYPE_TIMELINE) {
            signal_timeline(signals[j].semaphore, signals[j].value);
        } else {
            signals[j].semaphore->signaled = true;
        }
    }
}

void mark_device_lost(Queue& q) {
    {
        std::lock_guard<std::mutex> lock(q.scheduler->mutex);
        q.device->lost = true;
    }
    q.scheduler->cv.notify_all();
}

bool execute_batch(Queue& q, uint32_t submit_index, uint32_t command_buffer_count, const VkCommandBuffer* buffers) {
    if (q.draw == nullptr) q.draw = create_draw_context(q.timeout->flag());
    begin_submission(*q.draw);
    // The time limit covers the whole batch: a GPU would reset after this long without the work finishing.
    q.timeout->arm();
    for (uint32_t j = 0; j < command_buffer_count; ++j) {
        ExecState st;
        st.draw = q.draw;
        st.stop = q.timeout->flag();
        st.submit_index = submit_index;
        st.command_buffer_index = j;
        execute_command_buffer(from_handle<CommandBuffer>(buffers[j]), st);
        finish_queries(st);
        if (q.timeout->expired()) {
            // The work was cut short (shader runs ended at a loop back edge, tiles and draws skipped): its
            // results are incomplete. A GPU would hang and reset; tilevk reports the device lost.
            q.timeout->disarm();
            report_timeout(q, submit_index, j);
            mark_device_lost(q);
            return false;
        }
    }
    q.timeout->disarm();
    return true;
}

}  // namespace tilevk::icd
