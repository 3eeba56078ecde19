// The queue's worker threads (the renderer's pool) lent to other per-pixel work of the command stream.
#pragma once

#include <cstddef>
#include <functional>

namespace tilevk::icd {

struct ExecState;

// Calls fn(task) for every task in [0, num_tasks) on the queue's worker threads and returns when all are done.
// Only while the renderer is idle (outside begin_rendering..finish_rendering): the pool is the renderer's.
void run_on_workers(ExecState& st, size_t num_tasks, const std::function<void(size_t task)>& fn);

}  // namespace tilevk::icd
