// VkPhysicalDevice: the one CPU device. Properties, limits, features, queues, memory and formats.
#pragma once
#include "object.h"

namespace tilevk::icd {

struct Instance;

// The largest framebuffer/image side: tilevk's 15.8 fixed point keeps coordinates within +-2^15 pixels.
constexpr uint32_t kMaxImageDimension = 16384;
constexpr uint32_t kMaxMipLevels = 15;  // log2(16384) + 1
constexpr uint32_t kMaxArrayLayers = 256;
constexpr uint32_t kMaxTexelBufferElements = 65536;  // the Vulkan 1.0 minimum; texel buffers are 1D views
constexpr VkSampleCountFlags kSampleCounts = VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT;

struct PhysicalDevice : DispatchableObject {
    using Handle = VkPhysicalDevice;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PHYSICAL_DEVICE;
    PhysicalDevice();

    Instance* instance = nullptr;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceFeatures features{};
    VkPhysicalDeviceMemoryProperties memory{};
};
TILEVK_ASSERT_DISPATCHABLE(PhysicalDevice);

}  // namespace tilevk::icd
