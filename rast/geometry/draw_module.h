// lavapipe's draw module between its pipeline and llvmpipe's setup, as tilevk reproduces it: the vbuf stage that
// collects the primitives leaving draw's pipeline, the triangle pairs lp_setup_vbuf.c offers to llvmpipe's
// rectangle test (rect_detect.h), and llvmpipe's 9-vertex triangle-list analysis. The rules and their Mesa sources:
// docs/lavapipe-rules.md §0.2 (the vbuf's last flush keeps denormals), §1 (direct batch or draw's pipeline), §8
// (linear mode's rectangles, nine vertices); rast/geometry/README.md "Linear mode" and step 7. Mesa:
// src/gallium/auxiliary/draw/draw_pipe_vbuf.c, draw_pt_emit.c; src/gallium/drivers/llvmpipe/lp_setup_vbuf.c,
// lp_setup_rect.c, lp_setup_analysis.c.
//
// The renderer decides which batch goes where (clip masks, batches) and does setup and binning; this module only
// decides, per batch or vbuf filling, which primitives setup gets in which order and shape, through a SetupSink.
#pragma once

#include <cstdint>
#include <vector>

#include "rast/geometry/primitive_assembly.h"
#include "rast/geometry/rect_detect.h"

namespace tilevk::rast::geometry {

// llvmpipe's triangle-list analysis (lp_setup_analysis.c lp_setup_analyse_triangles, reached from
// lp_setup_vbuf.c lp_setup_draw_arrays). It runs on a batch handed to llvmpipe's draw_arrays, i.e. a non-indexed
// TRIANGLE_LIST draw (per instance) in which no vertex has a clip mask, when the fragment shader has no flat input.
// With exactly 9 vertices (after draw trims an incomplete last triangle: vertexCount 9, 10 or 11) whose last
// three window y values are equal, the whole draw is swallowed; only the "aero" pattern
//   x0 == x1 == x5, x2 == x3 == x4, y0 == y3 == y5, y1 == y2 == y4
// is drawn instead, as an axis-aligned rectangle through llvmpipe's rect path (DrawModule::nine_vertex_batch).
// Verified against lavapipe (tests/rast/geometry, NineVertexTriangleListQuirk).
enum class NineVertexQuirk : uint8_t { kNone, kSwallowed, kAeroRect };

struct TriangleListBatch {
    uint32_t vertex_count = 0;  // vertexCount of the draw
    bool indexed = false;
    bool any_vertex_clipped = false;  // any compute_clipmask != 0 in the batch (then draw takes its pipeline path)
    bool fs_has_flat_input = false;
};

// win_xy: window (x, y) of the first 9 vertices (only read when the other conditions hold).
NineVertexQuirk nine_vertex_quirk(const TriangleListBatch& b, const float (*win_xy)[2]);

// llvmpipe's setup as the draw module calls it (lp_setup_tri.c, lp_setup_rect.c lp_rect_cw, lp_setup_line.c,
// lp_setup_point.c): implemented by the renderer for one draw. Vertices are records (vertex.h).
class SetupSink {
  public:
    virtual void triangle(const float* v0, const float* v1, const float* v2) = 0;
    // lp_rect_cw(c0, c1, c2, front): the box of the snapped corners, planes from (c0, c1, c2) as given.
    virtual void rect(const float* c0, const float* c1, const float* c2, bool front) = 0;
    virtual void line(const float* v0, const float* v1, bool front) = 0;
    virtual void point(const float* v, float size, bool front) = 0;

  protected:
    SetupSink() = default;
    SetupSink(const SetupSink&) = default;
    SetupSink& operator=(const SetupSink&) = default;
    ~SetupSink() = default;
};

// The triangles of one batch as primitive assembly ordered them: triangle i is the records of slots
// ids[3i], ids[3i+1], ids[3i+2]; slot s's record starts at records + s * stride.
struct TriangleBatch {
    const uint32_t* ids = nullptr;
    uint32_t count = 0;
    const float* records = nullptr;
    uint32_t stride = 0;

    const float* record(uint32_t slot) const { return records + size_t(slot) * stride; }
    void triangle(uint32_t i, const float* v[3]) const {
        for (int k = 0; k < 3; ++k) v[k] = record(ids[size_t(i) * 3 + k]);
    }
};

struct DrawModuleConfig {
    RectPairConfig rect;           // setup->rect's cull mode, front face and coplanarity layout
    bool linear_mode = false;      // llvmpipe's linear mode: setup->rect tries pairs (lp_setup_vbuf.c rect())
    bool pair_candidates = false;  // filled triangles without flat input (lp_setup_vbuf.c !uses_constant_interp)
    bool flatshade_first = false;  // PipelineState::flatshade_first
    bool single_sample = true;     // the Aero rectangle is a rectangle only at 1x (not modelled in MSAA)
    uint32_t verts_per_prim = 3;   // primitives as setup gets them from the vbuf: 3, 2 (lines) or 1 (points)
    uint32_t record_floats = 0;    // vertex_floats(layout)
    uint32_t vertex_slots = 1;     // lp_state_derived.c compute_vertex_info: 16-byte slots per vbuf vertex
};

class DrawModule {
  public:
    // A new draw: the configuration, and an empty vbuf (the previous draw's flush emptied it).
    void begin_draw(const DrawModuleConfig& cfg);
    uint32_t record_floats() const { return cfg_.record_floats; }

    // A batch that skipped draw's pipeline, as lp_setup_vbuf.c hands its triangle pairs to setup->rect: 6N-vertex
    // lists and strips in linear mode, the non-indexed 4-vertex fan in any mode. False (nothing drawn) for any other
    // batch, which the caller draws triangle by triangle. Only for cfg.pair_candidates draws.
    bool direct_pairs(SetupSink& setup, Topology topology, bool indexed, const TriangleBatch& batch);

    // A 9-vertex non-indexed triangle-list batch that skipped draw's pipeline, through llvmpipe's list analysis:
    // returns how many of its leading triangles the caller still draws one by one (all of them, 2 or none), having
    // drawn the rectangle llvmpipe bins instead.
    uint32_t nine_vertex_batch(SetupSink& setup, const TriangleBatch& batch);

    // draw_pipe_vbuf.c: the primitives leaving draw's pipeline (clipper, float cull, unfilled stage) collect until
    // a direct batch, the end of the draw or a full vertex/index buffer, then reach setup as one indexed list
    // (triangles in linear mode as rectangle pairs where they qualify). `ids` tell draw's vertex headers apart
    // (each is emitted once per buffer); a point carries its size, an unfilled triangle's line or point its facing.
    void vbuf_primitive(SetupSink& setup, const float* const* v, const uint64_t* ids, float point_size = 1.0f,
                        bool front = true);
    // after_draw: the flush at the end of llvmpipe_draw_vbo, outside draw_vbo's denormal flushing, so setup keeps
    // denormals (docs/lavapipe-rules.md §0.2).
    void vbuf_flush(SetupSink& setup, bool after_draw = false);

    // The current filling as Renderer::last_filling_start replays the vbuf's count: vertices counted, indices
    // used, and the buffer's limits.
    static constexpr uint32_t kMaxVbufIndices = 1020;  // lp_setup_vbuf.c LP_MAX_VBUF_INDEXES
    uint32_t vbuf_vertices() const { return vertices_; }
    uint32_t vbuf_indices() const { return records_.empty() ? 0 : uint32_t(records_.size() / cfg_.record_floats); }
    uint32_t vbuf_max_vertices() const { return max_vertices_; }

  private:
    // lp_setup_vbuf.c rect(): setup->rect in linear mode, else (or when it declines) both triangles in order.
    void rect_or_triangles(SetupSink& setup, const float* const t0[3], const float* const t1[3]);
    // setup->rect's outcome applied; returns false when it declined (kTriangles), having drawn nothing.
    bool apply_rect_decision(SetupSink& setup, const float* const t0[3], const float* const t1[3]);
    void vbuf_clear();

    DrawModuleConfig cfg_;
    bool rect_pairs_ = false;  // linear mode and pair candidates
    // The vbuf's current filling.
    std::vector<float> records_;        // verts_per_prim copied vertex records per primitive
    std::vector<float> point_size_;     // per primitive (points)
    std::vector<uint8_t> front_;        // per primitive (lines and points)
    uint32_t vertices_ = 0;             // vbuf->nr_vertices (each vertex counted once per buffer)
    uint32_t max_vertices_ = 0;         // LP_MAX_VBUF_SIZE 4096 bytes / vertex size
    std::vector<uint64_t> emitted_id_;  // vertex ids emitted into the current buffer
};

}  // namespace tilevk::rast::geometry
