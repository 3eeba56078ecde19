// Turns a Scene into Vulkan objects and one command buffer on a device, runs it and reads the target back.
#pragma once

#include <string>
#include <vector>

#include "scene.hpp"
#include "vk_context.hpp"

namespace tilevk::cts {

struct RenderResult {
    std::vector<Plane> planes;     // colour (resolved), then depth and stencil when present
    double pipeline_ms = 0;        // total vkCreateGraphicsPipelines time for the scene's draws
    std::vector<double> frame_ms;  // one per timing repetition (submit to fence signalled)
};

// Throws VkError (or std::runtime_error) with the failing call when the device cannot run the scene.
RenderResult render(const DeviceContext& ctx, const Scene& scene, int timing_reps);

// Empty if the device supports everything the scene uses; otherwise what is missing.
std::string unsupported(const DeviceContext& ctx, const Scene& scene);

}  // namespace tilevk::cts
