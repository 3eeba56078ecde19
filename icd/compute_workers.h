// One compute worker's reusable storage, one per thread of the queue's pool (indexed by the pool's worker index).
// The submitting thread sizes every worker's storage before a dispatch, so a worker that ran no workgroup in the
// warm-up frames does not allocate at its first one later (a steady frame allocates nothing).
#pragma once

#include <vector>

#include "shader/program.h"

namespace tilevk::icd {

struct ComputeWorker {
    shader::Scratch scratch;
    std::vector<shader::ComputeBatch> group;  // the workgroup's batches, ids filled per workgroup
};

}  // namespace tilevk::icd
