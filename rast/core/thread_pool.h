// A small fork-join pool for tile rendering. TILEVK_THREADS (default: hardware threads); 0 or 1 = caller only.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

#include "rast/core/function_ref.h"

namespace tilevk::rast {

class ThreadPool {
  public:
    // num_threads: total workers including the calling thread; 0 and 1 both mean "run in the calling thread".
    explicit ThreadPool(unsigned num_threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    // Workers available to run(); worker indices are < this.
    unsigned num_workers() const { return static_cast<unsigned>(threads_.size()) + 1; }

    // Calls fn(worker, task) for every task in [0, num_tasks), each exactly once, and returns when all are done.
    // Tasks are claimed in increasing order from an atomic counter; a task runs wholly on one worker. `fn` is
    // only referenced (no allocation, whatever the lambda captures).
    void run(size_t num_tasks, FunctionRef<void(unsigned worker, size_t task)> fn);

    static unsigned threads_from_env();  // TILEVK_THREADS or std::thread::hardware_concurrency()

  private:
    void worker_main(unsigned worker);
    void work(unsigned worker);

    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable start_cv_, done_cv_;
    const FunctionRef<void(unsigned, size_t)>* fn_ = nullptr;
    size_t num_tasks_ = 0;
    size_t next_task_ = 0;     // guarded by mutex_
    unsigned generation_ = 0;  // guarded by mutex_
    unsigned busy_ = 0;        // guarded by mutex_
    bool stop_ = false;
};

}  // namespace tilevk::rast
