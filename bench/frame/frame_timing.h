// The timing every frame-bench scene shares, graphics or compute: a frame is recording its command buffer, submitting
// it and waiting for its fence, in milliseconds of wall time.
#pragma once

#include <vulkan/vulkan.h>

#include <chrono>

#include "vk_context.hpp"

namespace tilevk::bench {

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Calls `record` (its time into *record_ms), submits `cb` signalling `fence`, waits and resets the fence; returns
// the whole frame's time.
template <class Record>
double timed_frame(VkDevice dev, VkQueue queue, VkCommandBuffer cb, VkFence fence, Record&& record, double* record_ms) {
    const auto t0 = Clock::now();
    record();
    *record_ms = ms_since(t0);
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    cts::vk_check(vkQueueSubmit(queue, 1, &si, fence), "vkQueueSubmit");
    cts::vk_check(vkWaitForFences(dev, 1, &fence, VK_TRUE, 600ull * 1000 * 1000 * 1000), "vkWaitForFences");
    const double ms = ms_since(t0);
    cts::vk_check(vkResetFences(dev, 1, &fence), "vkResetFences");
    return ms;
}

}  // namespace tilevk::bench
