// The queue's submissions that cannot run yet: wait-before-signal on timeline semaphores.
// vkQueueSubmit runs a batch on the calling thread when nothing is queued ahead of it and every timeline value it
// waits for is reached (the common case: no thread, no allocation). Otherwise that batch and every later one are
// copied into `pending` and run in submission order by the queue's worker thread, each once its waits are
// satisfied (a host vkSignalSemaphore or an earlier batch's signal). Batch storage is recycled (`spare`), so a
// program that keeps deferring batches of the same shape allocates nothing once warm.
//
// Locks: Queue::submit_mutex is held while command buffers execute (caller or worker); `mutex` guards `pending`
// and every timeline value change and is taken inside submit_mutex, never the other way round.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "entrypoints.h"

namespace tilevk::icd {

struct Fence;
struct Queue;
struct Semaphore;

struct SemaphoreValue {
    Semaphore* semaphore;
    uint64_t value;  // timeline: the value waited for or signalled; binary: unused
};

struct Batch {
    std::vector<SemaphoreValue> waits;  // every wait (binary ones are satisfied by submission order)
    std::vector<VkCommandBuffer> command_buffers;
    std::vector<SemaphoreValue> signals;
    Fence* fence = nullptr;  // the vkQueueSubmit's fence, on its last batch
    uint32_t submit_index = 0;
    void clear();
};

class QueueScheduler {
  public:
    explicit QueueScheduler(Queue& q) : queue_(q) {}
    ~QueueScheduler();  // stops the worker; batches still pending are dropped (destroying a busy device is invalid)
    QueueScheduler(const QueueScheduler&) = delete;
    QueueScheduler& operator=(const QueueScheduler&) = delete;

    std::mutex mutex;
    std::condition_variable cv;  // notified on every timeline change, batch completion and device loss

    // Under `mutex`: no batch is queued.
    bool idle() const { return head_ == pending_.size(); }
    // Under `mutex`: a batch whose storage the caller fills and then hands to enqueue().
    std::unique_ptr<Batch> take_spare();
    // Under `mutex`: queues the batch behind the others and wakes the worker (started at the first use).
    void enqueue(std::unique_ptr<Batch> b);
    // Blocks until no batch is queued (each runs, or is dropped once the device is lost).
    void wait_idle();

  private:
    void run();

    Queue& queue_;
    std::vector<std::unique_ptr<Batch>> pending_;  // [head_, size) queued, in submission order
    size_t head_ = 0;
    std::vector<std::unique_ptr<Batch>> spare_;
    bool quit_ = false;
    std::thread worker_;
};

// Under the scheduler's mutex: every timeline wait of the batch is reached.
bool waits_reached(const std::vector<SemaphoreValue>& waits);
bool waits_reached(const VkSubmitInfo& s);

// Sets a timeline semaphore's counter and wakes everything waiting on the device's timelines.
void signal_timeline(Semaphore* s, uint64_t value);

// Runs one batch's command buffers on the queue (submit_mutex held) and then its signals; false when the device
// was lost on the way (its signals are not performed). Shared by vkQueueSubmit and the worker.
bool execute_batch(Queue& q, uint32_t submit_index, uint32_t command_buffer_count, const VkCommandBuffer* buffers);
void signal_batch(const SemaphoreValue* signals, uint32_t count);

// Marks the device lost and wakes every waiter (vkWaitSemaphores, the worker, vkQueueWaitIdle).
void mark_device_lost(Queue& q);

}  // namespace tilevk::icd
