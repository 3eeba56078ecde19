// vkCreateQueryPool, vkDestroyQueryPool, vkGetQueryPoolResults and the slot bookkeeping shared with execution.
#include "query_pool.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iterator>

#include "device.h"
#include "entrypoints.h"
#include "vk_names.h"

namespace tilevk::icd {

void QueryPool::reset(uint32_t first, uint32_t n) {
    std::lock_guard lock(mutex);
    for (uint32_t i = first; i < first + n && i < count; ++i) slots[i] = Slot{};
}

void QueryPool::begin(uint32_t query) {
    if (query >= count) return;
    std::lock_guard lock(mutex);
    slots[query] = Slot{0, State::kPending};
}

void QueryPool::make_available(uint32_t query) {
    if (query >= count) return;
    {
        std::lock_guard lock(mutex);
        slots[query].state = State::kAvailable;
    }
    available_cv.notify_all();
}

void QueryPool::write_timestamp(uint32_t query, uint64_t ns) {
    if (query >= count) return;
    {
        std::lock_guard lock(mutex);
        slots[query] = Slot{ns, State::kAvailable};
    }
    available_cv.notify_all();
}

void QueryPool::begin_statistics(uint32_t query, const StatisticCounters& totals) {
    if (query >= count) return;
    std::lock_guard lock(mutex);
    slots[query] = Slot{0, State::kPending, totals};
}

void QueryPool::end_statistics(uint32_t query, const StatisticCounters& totals, const StatisticCounters& raster) {
    if (query >= count) return;
    {
        std::lock_guard lock(mutex);
        Slot& s = slots[query];
        // Unsigned differences, as llvmpipe_end_query takes them: a total that went down (lavapipe zeroes the
        // clipping invocations at a draw that discards rasterization) wraps.
        for (uint32_t i = 0; i < kStatisticCount; ++i) s.stats[i] = totals[i] - s.stats[i] + raster[i];
        s.state = State::kAvailable;
    }
    available_cv.notify_all();
}

uint64_t timestamp_now_ns() {
    // steady_clock is CLOCK_MONOTONIC on Linux, the clock lavapipe's os_time_get_nano reads.
    return uint64_t(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count());
}

VkResult write_query_results(QueryPool& pool, uint32_t first, uint32_t n, uint8_t* dst, size_t dst_size,
                             VkDeviceSize stride, VkQueryResultFlags flags, bool host) {
    const bool wide = flags & VK_QUERY_RESULT_64_BIT;
    const bool with_availability = flags & VK_QUERY_RESULT_WITH_AVAILABILITY_BIT;
    const bool partial = flags & VK_QUERY_RESULT_PARTIAL_BIT;
    const size_t word = wide ? 8 : 4;
    const bool statistics = pool.type == VK_QUERY_TYPE_PIPELINE_STATISTICS;
    const size_t values = statistics ? size_t(__builtin_popcount(pool.statistics)) : 1;
    const size_t entry = word * (values + (with_availability ? 1 : 0));
    if (first >= pool.count || n > pool.count - first) {
        log_error("query results: queries [%u, %u) lie outside the pool of %u; only those inside are written", first,
                  first + n, pool.count);
        n = first >= pool.count ? 0 : pool.count - first;
    }
    auto put = [&](uint8_t* at, uint64_t v) {
        if (wide) {
            std::memcpy(at, &v, 8);
        } else {
            const uint32_t v32 = v > UINT32_MAX ? UINT32_MAX : uint32_t(v);  // saturate, as lavapipe does
            std::memcpy(at, &v32, 4);
        }
    };
    VkResult result = VK_SUCCESS;
    std::unique_lock lock(pool.mutex);
    for (uint32_t i = 0; i < n; ++i) {
        const size_t offset = size_t(stride) * i;
        if (offset > dst_size || entry > dst_size - offset) {
            log_error("query results: query %u's entry does not fit in the %zu bytes given; not written", first + i,
                      dst_size);
            break;
        }
        QueryPool::Slot& slot = pool.slots[first + i];
        if ((flags & VK_QUERY_RESULT_WAIT_BIT) && host)
            pool.available_cv.wait(lock, [&] { return slot.state != QueryPool::State::kPending; });
        const bool ready = slot.state == QueryPool::State::kAvailable;
        if (!ready && !partial) result = VK_NOT_READY;
        uint8_t* at = dst + offset;
        if ((ready || partial) && statistics) {
            size_t k = 0;
            for (uint32_t bit = 0; bit < kStatisticCount; ++bit)
                if (pool.statistics & (1u << bit)) put(at + word * k++, slot.stats[bit]);
        } else if (ready || partial) {
            put(at, slot.value);
        }
        // lavapipe's vkGetQueryPoolResults steps over one value, not all of them, when it writes none (an
        // unavailable statistics query without PARTIAL: lvp_query.c), so its availability word lands after the
        // first value's slot. Matched on the host; vkCmdCopyQueryPoolResults places it correctly.
        const size_t skipped = statistics && host && !ready && !partial ? 1 : values;
        if (with_availability) put(at + word * skipped, ready ? 1 : 0);
    }
    return result;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateQueryPool(VkDevice device, const VkQueryPoolCreateInfo* pCreateInfo,
                                                   const VkAllocationCallbacks* pAllocator, VkQueryPool* pQueryPool) {
    Device* dev = from_handle<Device>(device);
    const VkQueryType type = pCreateInfo->queryType;
    if (type != VK_QUERY_TYPE_OCCLUSION && type != VK_QUERY_TYPE_TIMESTAMP && type != VK_QUERY_TYPE_PIPELINE_STATISTICS)
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateQueryPool: %s is not supported", vk_enum_name(type));
    if (type == VK_QUERY_TYPE_PIPELINE_STATISTICS) {
        if (!dev->enabled_features.core10.pipelineStatisticsQuery)
            return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                        "vkCreateQueryPool: VK_QUERY_TYPE_PIPELINE_STATISTICS needs the pipelineStatisticsQuery "
                        "feature, which the device was created without");
        if (const VkQueryPipelineStatisticFlags missing = pCreateInfo->pipelineStatistics & ~kSupportedStatistics)
            return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateQueryPool: tilevk does not count %s",
                        vk_flags_name<VkQueryPipelineStatisticFlagBits>(missing).c_str());
    }
    QueryPool* pool =
        create_object<QueryPool>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (pool == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateQueryPool: out of host memory");
    pool->type = type;
    if (type == VK_QUERY_TYPE_PIPELINE_STATISTICS) pool->statistics = pCreateInfo->pipelineStatistics;
    pool->count = pCreateInfo->queryCount;
    pool->slots.reset(new (std::nothrow) QueryPool::Slot[std::max(pool->count, 1u)]);
    if (!pool->slots) {
        destroy_object(pool);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateQueryPool: out of host memory for %u queries",
                    pCreateInfo->queryCount);
    }
    *pQueryPool = to_handle(pool);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyQueryPool(VkDevice, VkQueryPool queryPool, const VkAllocationCallbacks*) {
    destroy_object(from_handle<QueryPool>(queryPool));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetQueryPoolResults(VkDevice device, VkQueryPool queryPool, uint32_t firstQuery,
                                                       uint32_t queryCount, size_t dataSize, void* pData,
                                                       VkDeviceSize stride, VkQueryResultFlags flags) {
    if (from_handle<Device>(device)->lost.load()) return VK_ERROR_DEVICE_LOST;
    return write_query_results(*from_handle<QueryPool>(queryPool), firstQuery, queryCount, static_cast<uint8_t*>(pData),
                               dataSize, stride, flags, true);
}

// hostQueryReset (VK_EXT_host_query_reset, core in Vulkan 1.2): the same reset vkCmdResetQueryPool performs.
VKAPI_ATTR void VKAPI_CALL tvk_ResetQueryPool(VkDevice, VkQueryPool queryPool, uint32_t firstQuery,
                                              uint32_t queryCount) {
    from_handle<QueryPool>(queryPool)->reset(firstQuery, queryCount);
}

// VK_EXT_calibrated_timestamps: the device's timestamps are CLOCK_MONOTONIC nanoseconds (timestamp_now_ns), so the
// two domains lavapipe offers are one clock read once; the deviation is that clock's 1 ns resolution.
namespace {
constexpr VkTimeDomainEXT kTimeDomains[] = {VK_TIME_DOMAIN_DEVICE_EXT, VK_TIME_DOMAIN_CLOCK_MONOTONIC_EXT};
}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceCalibrateableTimeDomainsEXT(VkPhysicalDevice,
                                                                                uint32_t* pTimeDomainCount,
                                                                                VkTimeDomainEXT* pTimeDomains) {
    constexpr uint32_t kCount = uint32_t(std::size(kTimeDomains));
    if (pTimeDomains == nullptr) {
        *pTimeDomainCount = kCount;
        return VK_SUCCESS;
    }
    const uint32_t n = std::min(*pTimeDomainCount, kCount);
    std::copy_n(kTimeDomains, n, pTimeDomains);
    *pTimeDomainCount = n;
    return n < kCount ? VK_INCOMPLETE : VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetCalibratedTimestampsEXT(VkDevice, uint32_t timestampCount,
                                                              const VkCalibratedTimestampInfoEXT* pTimestampInfos,
                                                              uint64_t* pTimestamps, uint64_t* pMaxDeviation) {
    const uint64_t now = timestamp_now_ns();
    for (uint32_t i = 0; i < timestampCount; ++i) {
        const VkTimeDomainEXT d = pTimestampInfos[i].timeDomain;
        if (std::find(std::begin(kTimeDomains), std::end(kTimeDomains), d) == std::end(kTimeDomains))
            return fail(VK_ERROR_UNKNOWN,
                        "vkGetCalibratedTimestampsEXT: pTimestampInfos[%u].timeDomain %s is not one "
                        "of vkGetPhysicalDeviceCalibrateableTimeDomainsEXT's",
                        i, vk_enum_name(d));
        pTimestamps[i] = now;
    }
    *pMaxDeviation = 1;
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
