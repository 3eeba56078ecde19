// Vertex stage of a draw: fetch attributes, run the vertex shader 16 vertices at a time, and leave one geometry
// record per shaded vertex (clip position, window position, the varyings the fragment shader reads).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "rast/core/static_vector.h"
#include "rast/core/thread_pool.h"
#include "rast/geometry/vertex.h"
#include "rast/geometry/vertex_fetch.h"
#include "rast/geometry/viewport.h"
#include "shader/program.h"

namespace tilevk::rast::render {

// At most this many vertex attributes, vertex buffer bindings and bound vertex buffers (icd/ reports 32).
inline constexpr size_t kMaxVertexInputs = 32;

// Where the vertex shader's inputs come from: one attribute per shader input location.
struct VertexInputState {
    StaticVector<geometry::VertexAttribDesc, kMaxVertexInputs> attribs;  // indexed like `locations`
    StaticVector<uint32_t, kMaxVertexInputs> locations;                  // shader input location of attribs[i]
    StaticVector<geometry::VertexBufferView, kMaxVertexInputs> buffers;  // indexed by binding
};

// How vertex-shader outputs become geometry records: record attribute slot i carries VS output location
// `slot_location[i]` (the fragment shader's input at that location), interpolated as `slot_interp[i]`.
// With `carry_point_size`, the record has one more attribute after the fragment inputs: (PointSize, 0, 0, 0),
// perspective-interpolated by the clipper as draw does for PSIZE (draw_pipe_clip.c find_interp's default), so a
// vertex the clipper makes in polygonMode POINT gets lavapipe's interpolated size. slot_interp then has one more
// entry than slot_location; the fragment stage reads slot_location.size() slots only.
// `point_coord_slot` (>= 0 when the fragment shader reads gl_PointCoord) is one more attribute after those: lavapipe
// turns PointCoord into a perspective fragment input (nir_lower_sysvals_to_varyings, VARYING_SLOT_PNTC) whose
// planes point setup computes (lp_setup_point.c texcoord_coef); vertices carry zeros in it.
// `distance_slot` (>= 0 when the vertex shader writes ClipDistance or CullDistance) starts the slots after those that
// carry its combined distance array (geometry::ClipConfig::distance_slot: clip distances, then cull distances, four
// per slot, perspective-interpolated by the clipper as draw does for CLIPDIST).
struct VaryingMap {
    std::vector<uint32_t> slot_location;
    std::vector<geometry::Interp> slot_interp;
    bool carry_point_size = false;
    int32_t point_coord_slot = -1;
    int32_t distance_slot = -1;
    uint32_t num_clip_distances = 0;
    uint32_t num_cull_distances = 0;
    geometry::VertexLayout layout() const { return {static_cast<uint32_t>(slot_interp.size()), slot_interp.data()}; }
    uint32_t point_size_slot() const { return static_cast<uint32_t>(slot_location.size()); }
};

// The shaded vertices of one draw instance.
struct ShadedVertices {
    uint32_t floats_per_vertex = 0;
    std::vector<float> records;      // floats_per_vertex per vertex (geometry record layout)
    std::vector<uint32_t> clipmask;  // per vertex
    std::vector<float> point_size;   // per vertex (1.0 when the shader does not write it)
    const float* record(uint32_t i) const { return records.data() + size_t(i) * floats_per_vertex; }
};

struct VertexStageConfig {
    const shader::Program* program = nullptr;
    const shader::Bindings* bindings = nullptr;
    const VertexInputState* input = nullptr;
    const VaryingMap* varyings = nullptr;
    geometry::ViewportConfig viewport;
    geometry::ClipMaskConfig clip;
    uint32_t first_instance = 0;
    uint32_t instance = 0;  // instance id within the draw (InstanceIndex = first_instance + instance)
    uint32_t base_vertex = 0;
    uint32_t draw_index = 0;                  // DrawCall::draw_index
    uint32_t view_index = 0;                  // Framebuffer::view_index
    const std::atomic<bool>* stop = nullptr;  // Renderer::set_stop_flag: once true, the remaining batches are skipped
};

// One worker's working memory for the vertex stage (reused from draw to draw: nothing is allocated per draw).
struct VertexWorker {
    shader::Scratch scratch;
    shader::VertexBatch batch;
};

// Shades the vertices whose indices are `indices` (any order, may repeat); vertex k of the result belongs to
// indices[k]. Runs the shader in batches of shader::kLanes: on workers[0] (the calling thread), or, for many
// vertices of a shader without memory writes, in chunks on `pool` (worker w uses workers[w]). Every vertex is
// shaded alone, so the result is the same for any thread count.
void shade_vertices(const VertexStageConfig& cfg, std::span<const uint32_t> indices, ThreadPool& pool,
                    std::span<const std::unique_ptr<VertexWorker>> workers, ShadedVertices* out);

}  // namespace tilevk::rast::render
