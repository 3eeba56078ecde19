// The queue's worker threads (the renderer's pool) lent to other per-pixel work of the command stream.
#pragma once

#include <cstddef>
#include <span>

#include "rast/core/function_ref.h"

namespace tilevk::rast {
class ThreadPool;
}

namespace tilevk::icd {

struct ExecState;
struct ComputeWorker;

// Calls fn(task) for every task in [0, num_tasks) on the queue's worker threads and returns when all are done.
// Only while the renderer is idle (outside begin_rendering..finish_rendering): the pool is the renderer's.
// `fn` is only referenced (no allocation).
void run_on_workers(ExecState& st, size_t num_tasks, rast::FunctionRef<void(size_t task)> fn);
// The pool itself, for rast/ work that schedules its own tasks (blits); the same condition applies.
rast::ThreadPool& worker_pool(ExecState& st);
// One ComputeWorker per worker of that pool (compute_workers.h).
std::span<ComputeWorker> compute_workers(ExecState& st);

}  // namespace tilevk::icd
