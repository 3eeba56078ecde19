// Compute cases (cases_compute*.cpp): a list of steps — dispatches, transfers and at most one draw — recorded into
// one command buffer with a pipeline barrier between consecutive steps, over storage buffers and storage images
// that every step shares. Every buffer and image is read back as a plane and judged byte for byte against the
// reference; a case's analytic check reads the same planes (buffer_words).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene.hpp"

namespace tilevk::cts {

struct DeviceContext;

// Set 0, binding i: buffer i (a storage buffer, or a uniform buffer when `uniform`); it is host-visible, starts
// with `words` and is read back as the plane "buffer<i>" (R32_UINT words, one row) unless `read_back` is false.
// With `texel_format` set, binding i is a storage texel buffer of that format over the whole buffer instead.
struct ComputeBuffer {
    std::vector<uint32_t> words;
    bool uniform = false;
    bool read_back = true;
    VkFormat texel_format = VK_FORMAT_UNDEFINED;
    // VK_EXT_robustness2: with `null_descriptor` the binding (and the draw's vertex binding, when this is its vertex
    // buffer) is written with VK_NULL_HANDLE (nullDescriptor); the buffer is still made and read back. A `range`
    // other than 0 is the descriptor's range in bytes (robustBufferAccess2's exact bounds) instead of VK_WHOLE_SIZE.
    bool null_descriptor = false;
    uint32_t range = 0;
};

// Set 0, binding (number of buffers) + j: storage image j, 2D, one level, VK_IMAGE_LAYOUT_GENERAL throughout,
// uploaded from `init` (tightly packed texels; empty: zeros) and read back as the plane "image<j>". `attachment`
// also makes it the colour attachment of the spec's draw.
struct ComputeImage {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 16, height = 16;
    std::vector<uint8_t> init;
    bool attachment = false;
    // More than 1: a multisampled colour attachment of the draw (`attachment` must be set), bound as a combined
    // image sampler (sampler2DMS, nearest) instead of a storage image; the draw's render pass clears it to zero;
    // it is neither uploaded nor read back (a dispatch copies its samples into a buffer).
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool linear = false;  // VK_IMAGE_TILING_LINEAR (single-sample, not an attachment) instead of OPTIMAL
    // A single-sample image bound as a combined image sampler (nearest) instead of a storage image; and, with
    // `null_descriptor`, its binding written with imageView VK_NULL_HANDLE (VK_EXT_robustness2 nullDescriptor).
    bool sampled = false;
    bool null_descriptor = false;
};

struct ComputeStep {
    enum class Kind {
        kDispatch,
        kDispatchIndirect,
        kDispatchBase,
        kFill,
        kCopyBuffer,
        kCopyBufferToImage,
        kCopyImageToBuffer,
        kDraw
    };
    Kind kind = Kind::kDispatch;
    uint32_t shader = 0;             // dispatches: index into ComputeSpec::shaders
    uint32_t groups[3] = {1, 1, 1};  // kDispatch, kDispatchBase: group counts
    uint32_t base[3] = {0, 0, 0};    // kDispatchBase: the first workgroup (vkCmdDispatchBaseKHR)
    uint32_t src = 0, dst = 0;       // buffer/image indices; kDispatchIndirect: the buffer in src, byte offset in dst
    uint32_t value = 0;              // kFill: the word
    // Dispatches, when >= 0: recorded between vkCmdBeginConditionalRenderingEXT and End on buffer `condition`, the
    // predicate at byte `condition_offset` (VK_EXT_conditional_rendering; the spec's buffers get the usage bit).
    int condition = -1;
    uint32_t condition_offset = 0;
    bool condition_inverted = false;
};
ComputeStep dispatch(uint32_t shader, uint32_t x, uint32_t y = 1, uint32_t z = 1);
ComputeStep dispatch_indirect(uint32_t shader, uint32_t buffer, uint32_t offset);
// vkCmdDispatchBaseKHR (VK_KHR_device_group; its pipelines get VK_PIPELINE_CREATE_DISPATCH_BASE_BIT).
ComputeStep dispatch_base(uint32_t shader, const uint32_t base[3], const uint32_t groups[3]);
ComputeStep fill(uint32_t buffer, uint32_t value);
ComputeStep copy_buffer(uint32_t src, uint32_t dst);  // the smaller of the two sizes
ComputeStep copy_buffer_to_image(uint32_t buffer, uint32_t image);
ComputeStep copy_image_to_buffer(uint32_t image, uint32_t buffer);
ComputeStep draw();

// The graphics side of a spec with a kDraw step: `vertex_count` vertices (a triangle list) into the attachment
// image, its previous contents loaded; when vertex_buffer >= 0, that buffer is also binding 0 of the vertex input
// (a vec4 at location 0, 16-byte stride). The shaders see the same descriptor set and push constants.
struct ComputeDraw {
    std::string vertex_glsl, fragment_glsl;
    uint32_t vertex_count = 3;
    int vertex_buffer = -1;
    float min_sample_shading = -1.0f;  // >= 0: sampleShadingEnable with this minSampleShading
    bool alpha_to_coverage = false;
};

struct ComputeSpec {
    std::vector<std::string> shaders;   // compute GLSL
    std::vector<uint32_t> spec_values;  // specialization constants 0..n-1 (32-bit each) for every shader
    std::vector<uint32_t> push;         // push-constant words (every stage)
    std::vector<ComputeBuffer> buffers;
    std::vector<ComputeImage> images;
    std::vector<ComputeStep> steps;  // empty: dispatch(0, 1)
    ComputeDraw draw;
    // The shaders use 32-bit float atomics (VK_EXT_shader_atomic_float: buffer, shared and image features, add too).
    bool atomic_float = false;
    // ... and 32-bit float min / max (VK_EXT_shader_atomic_float2: buffer, shared and image MinMax features).
    bool atomic_float_min_max = false;
    // 64-bit integer atomics on buffers and shared memory (VK_KHR_shader_atomic_int64, with shaderInt64).
    bool atomic_int64 = false;
};

// Records the steps on one device, submits, waits and reads back every plane.
std::vector<Plane> run_compute(const DeviceContext& c, const ComputeSpec& s);
// What the device lacks for the spec (image formats without STORAGE_IMAGE, ...); empty when supported.
std::string compute_unsupported(const DeviceContext& c, const ComputeSpec& s);
// A scene that runs the spec (Scene::run / Scene::unsupported).
Scene compute_scene(ComputeSpec s);
// The words of plane "buffer<i>" (empty if absent).
std::vector<uint32_t> buffer_words(const std::vector<Plane>& planes, uint32_t i);

}  // namespace tilevk::cts
