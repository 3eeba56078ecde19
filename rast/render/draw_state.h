// Everything one draw needs, as plain data: the pipeline's fixed-function state, its shader programs, and the
// draw's dynamic bindings. The driver (icd/) fills these from Vulkan objects; nothing here knows Vulkan.
#pragma once

#include <cstdint>
#include <vector>

#include "rast/core/primitive.h"
#include "rast/core/static_vector.h"
#include "rast/fragment/blend.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/geometry/line_point_setup.h"
#include "rast/geometry/planes.h"
#include "rast/geometry/primitive_assembly.h"
#include "rast/geometry/vertex_fetch.h"
#include "rast/render/raster_statistics.h"
#include "rast/render/targets.h"
#include "rast/render/vertex_stage.h"
#include "shader/program.h"

namespace tilevk::rast::render {

// VkPolygonMode: LINE and POINT draw each surviving triangle's edges / corners (draw's unfilled stage).
enum class PolygonMode : uint8_t { kFill, kLine, kPoint };

struct ViewportRect {
    float x = 0, y = 0, width = 0, height = 0, min_depth = 0, max_depth = 1;
};

// The pipeline's state. Lives at least until the render pass that uses it has ended (Renderer::end). Plain data
// without heap storage: copying it (once per state change) never allocates.
struct PipelineState {
    const shader::Program* vertex = nullptr;
    const shader::Program* fragment = nullptr;  // may be null: no colour output, depth/stencil only

    // Vertex input: attribute i reads `attribs[i]` for shader input location `attrib_locations[i]`.
    StaticVector<geometry::VertexAttribDesc, kMaxVertexInputs> attribs;
    StaticVector<uint32_t, kMaxVertexInputs> attrib_locations;
    struct Binding {
        uint32_t stride = 0;
        geometry::InputRate rate = geometry::InputRate::kVertex;
        uint32_t divisor = 1;  // instance rate: geometry::VertexBufferView::divisor
    };
    StaticVector<Binding, kMaxVertexInputs> bindings;  // indexed by binding number

    geometry::Topology topology = geometry::Topology::kTriangleList;
    bool primitive_restart = false;
    // The provoking vertex (VK_EXT_provoking_vertex): the first (lavapipe's flatshade_first) or the last vertex of
    // each primitive; it orders strip and fan decomposition, the CW fix-up and the clipper's fans as in lavapipe.
    bool flatshade_first = true;

    // Rasterization.
    CullMode cull = CullMode::kNone;
    bool front_ccw = true;
    bool depth_clamp = false;
    // Clip-space depth range: [0, w] (Vulkan) or [-w, w] (VK_EXT_depth_clip_control negativeOneToOne).
    bool clip_halfz = true;
    // Clipping against z (lavapipe's depth_clip_near/far): !depthClampEnable unless VK_EXT_depth_clip_enable says.
    bool depth_clip = true;
    bool depth_bias_enable = false;
    geometry::DepthBias depth_bias;  // factors; format fields are filled by the renderer from the target
    float line_width = 1.0f;
    // Rectangular (Vulkan's default) or Bresenham lines (VK_EXT_line_rasterization; lavapipe-rules §6), for line
    // topologies and polygonMode LINE edges alike.
    geometry::LineMode line_mode = geometry::LineMode::kRectangular;
    PolygonMode polygon_mode = PolygonMode::kFill;

    // Multisample.
    int samples = 1;
    uint32_t sample_mask = 0xffffffffu;
    bool alpha_to_coverage = false;
    // Every colour output's alpha becomes 1.0 after alpha to coverage, before blending (lp_state_fs.c).
    bool alpha_to_one = false;
    // Sample shading: the fragment shader runs once per sample (llvmpipe's min_samples > 1; icd/ decides it from
    // sampleShadingEnable, minSampleShading and the shader, docs/lavapipe-rules.md §3). Only with samples > 1.
    bool per_sample = false;

    fragment::DepthStencilState depth_stencil;  // min/max_depth are filled from the viewport by the renderer
    fragment::BlendAttachment blend[kMaxColorTargets];
    float blend_constants[4] = {0, 0, 0, 0};

    ViewportRect viewport;
    ClipRect scissor = {0, 0, 16384, 16384};

    // Bytes of push constants lavapipe binds as the fragment stage's constant buffer 0 (0: none). llvmpipe's
    // linear shading requires each of those floats to lie in [0, 1].
    uint32_t fragment_push_constant_bytes = 0;
};

// A bound vertex buffer: `data` points at the buffer's bytes from the bind offset, `size` bytes remain.
struct VertexBufferBinding {
    const uint8_t* data = nullptr;
    uint32_t size = 0;
};

struct DrawCall {
    bool indexed = false;
    uint32_t count = 0;  // vertexCount / indexCount
    uint32_t instance_count = 1;
    uint32_t first = 0;  // firstVertex / firstIndex
    int32_t vertex_offset = 0;
    uint32_t first_instance = 0;
    // DrawIndex (SPIR-V): the draw's position within its vkCmdDraw*Indirect* call, 0 for direct draws; lavapipe
    // runs an indirect call as one draw per record with that number (drawid).
    uint32_t draw_index = 0;
    // The first instance's number within the API draw (InstanceIndex - firstInstance): 0, except when a multi-draw
    // runs its entries instance by instance (icd/execute_draw.cpp, VK_EXT_multi_draw).
    uint32_t instance_begin = 0;
    const uint8_t* index_data = nullptr;                                 // from the bind offset
    uint32_t index_bytes = 0;                                            // bytes available from index_data
    uint32_t index_size = 4;                                             // 1, 2 or 4
    StaticVector<VertexBufferBinding, kMaxVertexInputs> vertex_buffers;  // indexed by binding number
    // Occlusion query: when set, the number of samples of this draw that pass every per-sample test (the final
    // per-sample masks after the late depth/stencil test, as lavapipe counts them) is added here when the draw's
    // tiles are rendered (Renderer::end or a mid-pass flush). Must stay valid until then.
    uint64_t* samples_passed = nullptr;
    // Pipeline-statistics query: when set, the draw's counts are added here (the fragment blocks when its tiles are
    // rendered). Must stay valid until then. Null: nothing is counted (no cost to the draw).
    RasterStatistics* statistics = nullptr;
    // The caller's number for this draw, reported by Renderer::interrupted_draw when the stop flag cut it short.
    uint32_t id = 0;
};

}  // namespace tilevk::rast::render
