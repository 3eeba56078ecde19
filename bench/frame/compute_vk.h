// The frame benchmark's compute scenes: one kernel on one Vulkan device, its buffers and pipeline made once; a
// "frame" records the kernel's command buffer (a buffer reset where the kernel accumulates, the dispatch, a barrier
// to the host), submits it and waits — the same timing as a graphics frame, so run_frame_bench.py alternates and
// compares them unchanged.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "vk_context.hpp"

namespace tilevk::bench {

// compute_saxpy (1M floats), compute_histogram256 (1M values, shared-memory bins), compute_matmul512 (512x512
// floats, 16x16 shared tiles).
std::vector<std::string> compute_scene_names();
bool is_compute_scene(const std::string& name);
// The scene's one-line description and its problem size (as the frame table's "size" column shows it).
std::string compute_scene_description(const std::string& name);
void compute_scene_size(const std::string& name, uint32_t& width, uint32_t& height);

class ComputeOnDevice {
  public:
    ComputeOnDevice(const cts::DeviceContext& ctx, const std::string& name);
    ~ComputeOnDevice();
    ComputeOnDevice(const ComputeOnDevice&) = delete;
    ComputeOnDevice& operator=(const ComputeOnDevice&) = delete;

    double cold_pipeline_ms() const;  // vkCreateShaderModule + vkCreateComputePipelines (SPIR-V compiled before)
    double frame();                   // record + submit + wait, milliseconds
    double last_record_ms() const;
    uint64_t image_hash();  // 64-bit FNV-1a of the result buffer
    const uint8_t* image_bytes() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace tilevk::bench
