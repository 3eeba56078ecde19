// VkDevice and its single VkQueue.
#pragma once
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include "device_features.h"
#include "device_timeout.h"
#include "entrypoints.h"
#include "object.h"
#include "queue_scheduler.h"
#include "shader/program_cache.h"

namespace tilevk::icd {

struct PhysicalDevice;
struct Device;
struct DrawContext;

// vkQueueSubmit2's translation into VkSubmitInfos, kept between calls so that it allocates only when it grows.
struct Submit2Scratch {
    std::vector<VkSubmitInfo> infos;
    std::vector<VkTimelineSemaphoreSubmitInfo> timelines;
    std::vector<VkSemaphore> semaphores;
    std::vector<uint64_t> values;
    std::vector<VkPipelineStageFlags> stages;
    std::vector<VkCommandBuffer> buffers;
};

struct Queue : DispatchableObject {
    using Handle = VkQueue;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_QUEUE;
    Queue() : DispatchableObject(kType) {}
    Device* device = nullptr;
    // Command buffers execute in order, one batch at a time, under submit_mutex (on the submitting thread or the
    // scheduler's worker).
    std::mutex submit_mutex;
    std::unique_ptr<QueueScheduler> scheduler;  // wait-before-signal batches (queue_scheduler.h)
    Submit2Scratch submit2;
    DrawContext* draw = nullptr;             // the queue's renderer, created at the first submission (execute_draw.cpp)
    std::unique_ptr<SubmitTimeout> timeout;  // the device's time limit per submission; outlives `draw`
};
TILEVK_ASSERT_DISPATCHABLE(Queue);

struct Device : DispatchableObject {
    using Handle = VkDevice;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DEVICE;
    Device() : DispatchableObject(kType) {}
    PhysicalDevice* physical_device = nullptr;
    Queue* queue = nullptr;
    Features enabled_features;        // every feature the application enabled (features.h)
    ExtensionSet enabled_extensions;  // the device extensions the application enabled
    // Set when a submission ran past the device's time limit (device_timeout.h; its work was cut short): from then
    // on submissions and waits return VK_ERROR_DEVICE_LOST, as after a GPU hang and reset. Set through
    // mark_device_lost (queue_scheduler.h), which wakes every waiter.
    std::atomic<bool> lost{false};
    // Shader programs by their exact inputs (module words, stage, entry point, specialization): pipelines that
    // share shaders build each program once per device (shader/program_cache.h).
    shader::ProgramCache programs;
};
TILEVK_ASSERT_DISPATCHABLE(Device);

}  // namespace tilevk::icd
