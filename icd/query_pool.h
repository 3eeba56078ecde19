// VkQueryPool: occlusion, timestamp and pipeline-statistics queries.
//
// A query slot moves through three states. Reset (vkCmdResetQueryPool, and at creation) makes it unavailable with
// value 0. vkCmdBeginQuery makes it pending: draws add the samples that pass to its value as their tiles are
// rendered. vkCmdEndQuery — or, for a query ended inside a render pass, the end of the renderer's pass that holds
// its last draws (execute_query.cpp) — makes it available; vkCmdWriteTimestamp writes a value and makes it available
// at once. Submissions execute synchronously, so a pending slot always becomes available before the submission
// that holds it returns; vkGetQueryPoolResults with WAIT blocks only on pending slots.
#pragma once
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

#include "object.h"

namespace tilevk::icd {

// Pipeline-statistics counters, indexed by the bit position of their VkQueryPipelineStatisticFlagBits (the order
// of Mesa's pipe_query_data_pipeline_statistics too, which lavapipe relies on).
inline constexpr uint32_t kStatisticCount = 11;
using StatisticCounters = std::array<uint64_t, kStatisticCount>;

// The counters tilevk counts exactly as lavapipe does (execute_statistics.cpp); a pool asking for another is
// refused with VK_ERROR_FEATURE_NOT_PRESENT.
inline constexpr VkQueryPipelineStatisticFlags kSupportedStatistics =
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_PRIMITIVES_BIT | VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT | VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_CONTROL_SHADER_PATCHES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;

struct QueryPool : NonDispatchableObject {
    using Handle = VkQueryPool;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_QUERY_POOL;
    QueryPool() : NonDispatchableObject(kType) {}

    enum class State : uint8_t { kUnavailable, kPending, kAvailable };
    struct Slot {
        uint64_t value = 0;  // samples passed (occlusion) or nanoseconds (timestamp)
        State state = State::kUnavailable;
        // Pipeline statistics: while pending, the queue's totals when it began; once available, its counts.
        StatisticCounters stats{};
    };

    VkQueryType type = VK_QUERY_TYPE_OCCLUSION;
    VkQueryPipelineStatisticFlags statistics = 0;  // pipeline-statistics pools: the counters asked for
    uint32_t count = 0;
    std::unique_ptr<Slot[]> slots;
    // Guards the slot states for hosts waiting in vkGetQueryPoolResults on another thread; `value` of a pending
    // occlusion query is written by the renderer on the submitting thread (read only as a PARTIAL result).
    std::mutex mutex;
    std::condition_variable available_cv;

    // Slot transitions at execution time (execute_query.cpp) and on the host.
    void reset(uint32_t first, uint32_t n);
    void begin(uint32_t query);
    void make_available(uint32_t query);
    void write_timestamp(uint32_t query, uint64_t ns);
    // Pipeline statistics: begin records the totals so far, end stores totals - start and makes it available.
    void begin_statistics(uint32_t query, const StatisticCounters& totals);
    // `raster`: the renderer's counts of its draws (CLIPPING_PRIMITIVES, FRAGMENT_SHADER_INVOCATIONS), added as they
    // are.
    void end_statistics(uint32_t query, const StatisticCounters& totals, const StatisticCounters& raster);
};

// Writes results of queries [first, first + n) in the layout of vkGetQueryPoolResults (`stride` apart, 32- or
// 64-bit values — one per statistic asked for, in bit order, for a pipeline-statistics pool — then the availability
// word with WITH_AVAILABILITY) into dst[0, dst_size). Entries that would not fit are not written (logged). Returns
// VK_NOT_READY if some query was unavailable and PARTIAL was not asked for (its values then are not written, only
// its availability), else VK_SUCCESS. `host`: vkGetQueryPoolResults (else vkCmdCopyQueryPoolResults): only there
// does WAIT block on pending queries (unavailable ones are never waited for: nothing could make them available),
// and an unwritten statistics query's availability follows lavapipe's host layout (query_pool.cpp).
VkResult write_query_results(QueryPool& pool, uint32_t first, uint32_t n, uint8_t* dst, size_t dst_size,
                             VkDeviceSize stride, VkQueryResultFlags flags, bool host);

// The host's monotonic clock in nanoseconds (timestamps: timestampPeriod 1, 64 valid bits).
uint64_t timestamp_now_ns();

}  // namespace tilevk::icd
