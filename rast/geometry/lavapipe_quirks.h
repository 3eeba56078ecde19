// Draw-level oddities of lavapipe that decide whether primitives reach the rasterizer at all.
#pragma once

#include <cstdint>

namespace tilevk::rast::geometry {

// llvmpipe's triangle-list analysis (lp_setup_analysis.c lp_setup_analyse_triangles, reached from
// lp_setup_vbuf.c lp_setup_draw_arrays). It runs on a batch handed to llvmpipe's draw_arrays, i.e. a non-indexed
// TRIANGLE_LIST draw (per instance) in which no vertex has a clip mask, when the fragment shader has no flat input.
// With exactly 9 vertices (after draw trims an incomplete last triangle: vertexCount 9, 10 or 11) whose last
// three window y values are equal, the whole draw is swallowed; only the "aero" pattern
//   x0 == x1 == x5, x2 == x3 == x4, y0 == y3 == y5, y1 == y2 == y4
// is drawn instead, as an axis-aligned rectangle through llvmpipe's rect path (not modelled here).
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

}  // namespace tilevk::rast::geometry
