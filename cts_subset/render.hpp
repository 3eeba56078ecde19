// Turns a Scene into Vulkan objects and one command buffer on a device, runs it and reads the target back.
#pragma once

#include <memory>
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

// A scene built on a device (objects, one recorded command buffer), ready to be submitted again and again; used
// to time two devices interleaved. The constructor throws like render(). `selftest_bad_command` records one
// invalid (but harmless) barrier, which the validation layer must report (the --validation self-test).
class Frame {
  public:
    Frame(const DeviceContext& ctx, const Scene& scene, bool selftest_bad_command = false);
    ~Frame();
    Frame(const Frame&) = delete;
    Frame& operator=(const Frame&) = delete;
    double submit();                    // one run of the command buffer: milliseconds from submit to fence
    std::vector<Plane> planes() const;  // the read-back of the last submit
    double pipeline_ms() const;         // total vkCreateGraphicsPipelines time

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Throws VkError (or std::runtime_error) with the failing call when the device cannot run the scene.
RenderResult render(const DeviceContext& ctx, const Scene& scene, int timing_reps, bool selftest_bad_command = false);

// Empty if the device supports everything the scene uses; otherwise what is missing.
std::string unsupported(const DeviceContext& ctx, const Scene& scene);

}  // namespace tilevk::cts
