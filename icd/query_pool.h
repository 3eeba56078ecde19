// VkQueryPool: occlusion and timestamp queries. Pipeline-statistics pools are refused (the feature is not reported).
//
// A query slot moves through three states. Reset (vkCmdResetQueryPool, and at creation) makes it unavailable with
// value 0. vkCmdBeginQuery makes it pending: draws add the samples that pass to its value as their tiles are
// rendered. vkCmdEndQuery — or, for a query ended inside a render pass, the end of the renderer's pass that holds
// its last draws (execute_query.cpp) — makes it available; vkCmdWriteTimestamp writes a value and makes it available
// at once. Submissions execute synchronously, so a pending slot always becomes available before the submission
// that holds it returns; vkGetQueryPoolResults with WAIT blocks only on pending slots.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

#include "object.h"

namespace tilevk::icd {

struct QueryPool : NonDispatchableObject {
    using Handle = VkQueryPool;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_QUERY_POOL;
    QueryPool() : NonDispatchableObject(kType) {}

    enum class State : uint8_t { kUnavailable, kPending, kAvailable };
    struct Slot {
        uint64_t value = 0;  // samples passed (occlusion) or nanoseconds (timestamp)
        State state = State::kUnavailable;
    };

    VkQueryType type = VK_QUERY_TYPE_OCCLUSION;
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
};

// Writes results of queries [first, first + n) in the layout of vkGetQueryPoolResults (`stride` apart, 32- or
// 64-bit values, then the availability word with WITH_AVAILABILITY) into dst[0, dst_size). Entries that would not
// fit are not written (logged). Returns VK_NOT_READY if some query was unavailable and PARTIAL was not asked for
// (its value then is not written, only its availability), else VK_SUCCESS. WAIT blocks on pending queries only when
// `may_wait` (the host call); unavailable ones are never waited for: nothing could make them available.
VkResult write_query_results(QueryPool& pool, uint32_t first, uint32_t n, uint8_t* dst, size_t dst_size,
                             VkDeviceSize stride, VkQueryResultFlags flags, bool may_wait);

// The host's monotonic clock in nanoseconds (timestamps: timestampPeriod 1, 64 valid bits).
uint64_t timestamp_now_ns();

}  // namespace tilevk::icd
