#include "rast/core/thread_pool.h"

#include <cstdio>
#include <cstdlib>

namespace tilevk::rast {

unsigned ThreadPool::threads_from_env() {
    if (const char* env = std::getenv("TILEVK_THREADS"); env && *env) {
        char* end = nullptr;
        const long v = std::strtol(env, &end, 10);
        if (end && *end == '\0' && v >= 0 && v <= 256) return static_cast<unsigned>(v);
        std::fprintf(stderr, "tilevk: ignoring TILEVK_THREADS=%s (want 0..256)\n", env);
    }
    const unsigned hw = std::thread::hardware_concurrency();
    return hw ? hw : 1;
}

ThreadPool::ThreadPool(unsigned num_threads) {
    const unsigned extra = num_threads > 1 ? num_threads - 1 : 0;
    threads_.reserve(extra);
    for (unsigned i = 0; i < extra; ++i) threads_.emplace_back([this, i] { worker_main(i + 1); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    start_cv_.notify_all();
    for (auto& t : threads_) t.join();
}

// Claims tasks one by one under the mutex until none are left (tiles are coarse, so the lock is not hot).
void ThreadPool::work(unsigned worker) {
    for (;;) {
        size_t task;
        const FunctionRef<void(unsigned, size_t)>* fn;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (next_task_ >= num_tasks_) return;
            task = next_task_++;
            fn = fn_;
        }
        (*fn)(worker, task);
    }
}

void ThreadPool::worker_main(unsigned worker) {
    unsigned seen = 0;
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            start_cv_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
            ++busy_;
        }
        work(worker);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            --busy_;
        }
        done_cv_.notify_all();
    }
}

void ThreadPool::run(size_t num_tasks, FunctionRef<void(unsigned, size_t)> fn) {
    if (num_tasks == 0) return;
    if (threads_.empty() || num_tasks == 1) {
        for (size_t i = 0; i < num_tasks; ++i) fn(0, i);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        fn_ = &fn;
        num_tasks_ = num_tasks;
        next_task_ = 0;
        ++generation_;
    }
    start_cv_.notify_all();
    work(0);
    // All tasks are claimed; wait until every worker that joined this generation has finished its last task.
    std::unique_lock<std::mutex> lock(mutex_);
    done_cv_.wait(lock, [&] { return busy_ == 0; });
    fn_ = nullptr;
    num_tasks_ = 0;
}

}  // namespace tilevk::rast
