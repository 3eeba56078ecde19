// Dispatches at vkQueueSubmit: the bound compute pipeline's workgroups on the queue's worker threads (the
// renderer's pool, idle outside render passes). A workgroup runs wholly on one worker, its invocations 16 lanes at a
// time through the same shader engine as graphics (shader::Program::run_workgroup: its batches in
// LocalInvocationIndex order, sharing one block of Workgroup memory, in lock-step between barriers). Workgroups see
// each other only through storage-buffer atomics (real atomics), so which worker runs which changes nothing a
// shader may rely on: results whose order the shader does not fix (sums, minima, ...) are the same for every
// thread count.
#include <algorithm>
#include <cstring>
#include <vector>

#include "buffer.h"
#include "compute_workers.h"
#include "execute.h"
#include "physical_device.h"
#include "pipeline.h"
#include "rast/core/thread_pool.h"
#include "shader/program.h"
#include "workers.h"

namespace tilevk::icd {
namespace {

// Tasks per worker: enough that a slow worker does not hold the others up at the end, few enough that claiming a
// task (a mutex in rast::ThreadPool) stays cheap next to the workgroups it runs.
constexpr uint64_t kTasksPerWorker = 8;

// The lanes of each 16-invocation batch of one workgroup: local ids and count; the workgroup id is set per group.
void layout_batches(const std::array<uint32_t, 3>& size, std::vector<shader::ComputeBatch>& out) {
    const uint32_t invocations = size[0] * size[1] * size[2];
    const uint32_t batches = (invocations + shader::kLanes - 1) / shader::kLanes;
    out.resize(batches);
    for (uint32_t b = 0; b < batches; ++b) {
        shader::ComputeBatch& cb = out[b];
        cb.count = std::min<uint32_t>(shader::kLanes, invocations - b * shader::kLanes);
        for (uint32_t l = 0; l < uint32_t(shader::kLanes); ++l) {
            // Lanes past count run nothing; they get the last invocation's ids so that no id is out of range.
            const uint32_t i = b * shader::kLanes + std::min(l, cb.count - 1);
            cb.local_index[l] = i;
            cb.local_id[0][l] = i % size[0];
            cb.local_id[1][l] = (i / size[0]) % size[1];
            cb.local_id[2][l] = i / (size[0] * size[1]);
        }
    }
}

// Runs workgroups base + (0..count) of the bound compute pipeline.
void run_dispatch(ExecState& st, const uint32_t base[3], const uint32_t count[3]) {
    const Pipeline* p = st.bound.compute_pipeline;
    if (p == nullptr || !p->compute) {
        log_error("vkCmdDispatch*: no compute pipeline is bound; the dispatch does nothing");
        return;
    }
    if (st.render_pass != nullptr) {  // VUID-vkCmdDispatch-renderpass
        log_error("vkCmdDispatch*: recorded inside a render pass; the dispatch does nothing");
        return;
    }
    static const char* const kAxis[3] = {"X", "Y", "Z"};
    for (int i = 0; i < 3; ++i) {
        if (count[i] > kMaxComputeWorkGroupCount || uint64_t(base[i]) + count[i] > kMaxComputeWorkGroupCount) {
            log_error(
                "vkCmdDispatch*: groupCount%s = %u (from base %u) is more than "
                "VkPhysicalDeviceLimits::maxComputeWorkGroupCount[%d] = %u; the dispatch does nothing",
                kAxis[i], count[i], base[i], i, kMaxComputeWorkGroupCount);
            return;
        }
        if (count[i] == 0) return;
    }
    const shader::Program& program = *p->compute;
    // Reused from dispatch to dispatch on the submitting thread; the workers read them through these references.
    static thread_local shader::Bindings bindings_storage;
    static thread_local std::vector<shader::ComputeBatch> batches_storage;
    shader::Bindings& bindings = bindings_storage;
    std::vector<shader::ComputeBatch>& batches = batches_storage;
    build_compute_bindings(st, program, bindings);
    layout_batches(program.interface().local_size, batches);

    const uint64_t groups = uint64_t(count[0]) * count[1] * count[2];
    count_dispatch_statistics(st, groups, program.interface().local_size);
    rast::ThreadPool& pool = worker_pool(st);
    const uint64_t tasks = std::min<uint64_t>(groups, uint64_t(pool.num_workers()) * kTasksPerWorker);
    const std::atomic<bool>* stop = st.stop;
    const std::span<ComputeWorker> workers = compute_workers(st);
    for (ComputeWorker& w : workers) {  // sized here, so that no worker allocates in its task
        w.scratch.set_stop_flag(stop);
        program.reserve(w.scratch);
        w.group.reserve(batches.size());
    }
    const auto run_task = [&](unsigned worker, size_t task) {
        ComputeWorker& w = workers[worker];
        std::vector<shader::ComputeBatch>& group = w.group;
        shader::Scratch& scratch = w.scratch;
        group = batches;
        const uint64_t first = groups * task / tasks, end = groups * (task + 1) / tasks;
        for (uint64_t g = first; g < end; ++g) {
            if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;  // past the time limit
            const uint32_t id[3] = {uint32_t(g % count[0]), uint32_t(g / count[0] % count[1]),
                                    uint32_t(g / (uint64_t(count[0]) * count[1]))};
            for (shader::ComputeBatch& cb : group)
                for (int i = 0; i < 3; ++i) {
                    cb.workgroup_id[i] = base[i] + id[i];
                    cb.num_workgroups[i] = count[i];
                }
            program.run_workgroup(bindings, group, scratch);
        }
    };
    if (tasks == 1)
        run_task(0, 0);
    else
        pool.run(size_t(tasks), run_task);
}

}  // namespace

void exec_dispatch(ExecState& st, const CmdDispatch& c) {
    run_dispatch(st, c.base, c.group_count);
}

// The counts are read when the command executes: an earlier command of the same submission may have written them.
void exec_dispatch(ExecState& st, const CmdDispatchIndirect& c) {
    VkDispatchIndirectCommand d{};
    const Buffer* b = c.buffer;
    if (b == nullptr || b->memory == nullptr || c.offset > b->size || b->size - c.offset < sizeof d) {
        log_error("vkCmdDispatchIndirect: offset %llu + 12 bytes lies outside the buffer; the dispatch does nothing",
                  static_cast<unsigned long long>(c.offset));
        return;
    }
    std::memcpy(&d, b->data() + c.offset, sizeof d);
    const uint32_t base[3] = {0, 0, 0}, count[3] = {d.x, d.y, d.z};
    run_dispatch(st, base, count);
}

}  // namespace tilevk::icd
