// VkPhysicalDevice: the one CPU device. Properties, limits, features, queues, memory and formats.
#pragma once
#include "core_structs.h"
#include "object.h"

namespace tilevk::icd {

struct Instance;

// The largest framebuffer/image side: tilevk's 15.8 fixed point keeps coordinates within +-2^15 pixels.
constexpr uint32_t kMaxImageDimension = 16384;
constexpr uint32_t kMaxMipLevels = 15;  // log2(16384) + 1
constexpr uint32_t kMaxArrayLayers = 256;
// maxImageDimension3D and a 3D image's maxExtent.depth: lavapipe's 1 << PIPE_CAP_MAX_TEXTURE_3D_LEVELS
// (frontends/lavapipe/lvp_device.c, lvp_formats.c; drivers/llvmpipe/lp_limits.h LP_MAX_TEXTURE_3D_LEVELS = 12), i.e.
// 4096 although 12 levels end at 2048. tilevk's layout (image.h) has no such bound: it takes the reported value.
constexpr uint32_t kMaxImageDimension3D = 4096;
constexpr uint32_t kMaxTexelBufferElements = 65536;  // the Vulkan 1.0 minimum; texel buffers are 1D views
constexpr VkSampleCountFlags kSampleCounts = VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT;
constexpr uint32_t kMaxMultiviewViews = 6;  // maxMultiviewViewCount (lavapipe 22.3 reports 6)
// VK_KHR_depth_stencil_resolve: SAMPLE_ZERO (the spec's one required mode) for both aspects, neither
// independentResolve nor independentResolveNone. lavapipe 22.3 also reports depth AVERAGE, but its AVERAGE returns
// sample 0 (execute_transfer.cpp resolve_depth_stencil_rect gives the Mesa paths): not a mode to copy.
constexpr VkResolveModeFlags kDepthResolveModes = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
constexpr VkResolveModeFlags kStencilResolveModes = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
constexpr uint32_t kMaxViewports = 16;           // multiViewport: all accepted, viewport 0 used (pipeline.cpp)
constexpr uint32_t kMaxBoundDescriptorSets = 8;  // BoundState::kMaxSets (execute.h)
constexpr uint32_t kMaxColorAttachments = 8;     // rast/render kMaxColorTargets, shader/ kMaxColorOutputs
// Compute (lavapipe's values): a workgroup runs 16 invocations at a time, so its size only sets how many batches it
// has; vkCreateComputePipelines refuses a local size past these, a dispatch counts past kMaxComputeWorkGroupCount.
constexpr uint32_t kMaxComputeWorkGroupInvocations = 1024;
constexpr uint32_t kMaxComputeWorkGroupSize = 1024;  // each of x, y, z
constexpr uint32_t kMaxComputeWorkGroupCount = 65535;
// Workgroup variables of a compute pipeline, in bytes (shader/ packs them tightly, 4 bytes per 32-bit scalar, so a
// shader within the limit under Vulkan's layout rules is within it here too); lavapipe's value.
constexpr uint32_t kMaxComputeSharedMemorySize = 32768;

struct PhysicalDevice : DispatchableObject {
    using Handle = VkPhysicalDevice;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PHYSICAL_DEVICE;
    PhysicalDevice();

    Instance* instance = nullptr;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    CoreProperties core_properties;  // Vulkan 1.1-1.3 properties (device_properties.cpp)
};
TILEVK_ASSERT_DISPATCHABLE(PhysicalDevice);

}  // namespace tilevk::icd
