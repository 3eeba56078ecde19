// One benchmark scene on one Vulkan device: its objects (made once), and whole frames — record the command buffer,
// submit, wait — as an application renders them.
#pragma once

#include <memory>
#include <string>

#include "frame_scene.h"
#include "vk_context.hpp"

namespace tilevk::bench {

class SceneOnDevice {
  public:
    // Uploads vertices and textures (not timed) and creates the pipelines; cold_pipeline_ms() is the time of
    // vkCreateShaderModule + vkCreateGraphicsPipelines for every pipeline of the scene (SPIR-V compiled before).
    SceneOnDevice(const cts::DeviceContext& ctx, const BenchScene& scene);
    ~SceneOnDevice();
    SceneOnDevice(const SceneOnDevice&) = delete;
    SceneOnDevice& operator=(const SceneOnDevice&) = delete;

    double cold_pipeline_ms() const;
    // One frame: reset and record the command buffer (render pass with its clears, every draw with its state
    // changes, the resolve at 4x), submit it, wait for the fence. Returns milliseconds.
    double frame();
    // Milliseconds of the last frame's recording (part of what frame() returned).
    double last_record_ms() const;
    // 64-bit FNV-1a hash of the final colour image (resolved at 4x), read back after the frames.
    uint64_t image_hash();
    // The bytes image_hash() read (RGBA8 rows, tightly packed).
    const uint8_t* image_bytes() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace tilevk::bench
