// Primitive input to the rasterizer core: triangles (float window coords, snapped here), generic convex primitives
// of up to 4 fixed-point edge planes (lines), and axis-aligned fixed-point boxes (points, rectangles).
#pragma once

#include <cstdint>

#include "rast/core/fixed_point.h"

namespace tilevk::rast {

// Clip rectangle in whole pixels, half-open [x0,x1) x [y0,y1): framebuffer ∩ scissor ∩ viewport rect, given per
// primitive: lavapipe's draw_regions. Applied as lavapipe does: whole pixels at 1x and for boxes; at 4x, triangles
// and convex primitives (lines) get lavapipe's scissor planes, which also pass samples more than half a pixel left
// of / above the rectangle, bounded by lavapipe's 64-px binning tiles (setup.cpp finish_box_msaa; deliberate, the
// spec discards them).
struct ClipRect {
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

enum class CullMode : uint8_t { kNone = 0, kFront = 1, kBack = 2, kBoth = 3 };

// Common per-primitive data.
struct PrimCommon {
    ClipRect clip;
    uint32_t payload = 0;        // draw-local index handed back to the consumer to find state/vertices
    uint16_t sample_mask = 0xF;  // ANDed into every sample mask (bit s = sample s; bit 0 only at 1x)
};

// A triangle in float window coordinates (y down), as produced by the viewport transform.
struct TriangleInput {
    float x[3], y[3];
    PrimCommon common;
    CullMode cull = CullMode::kNone;
    bool front_ccw = true;        // VK_FRONT_FACE_COUNTER_CLOCKWISE: area > 0 ("ccw" in lavapipe) is front
    bool flatshade_first = true;  // provoking vertex first (Vulkan default): CW fix-up swaps v1,v2 else v0,v1
    // lavapipe's bottom_edge_rule (u_blitter's rasterizer state; lp_setup_tri.c): a horizontal edge gets the
    // bias when it runs right-to-left (a bottom edge) instead of left-to-right, and the pixel box's y range moves
    // one fixed-point unit down ((minY + 1) >> 8 .. maxY >> 8).
    bool bottom_edge_rule = false;
};

// The vertex order rast/core rasterizes a triangle in (its CW -> CCW fix-up keeps the provoking vertex): order[i]
// is the input vertex at position i. Attribute planes must be built in this order. Identity for triangles that
// are out of range or degenerate (they are never rasterized).
void triangle_vertex_order(const TriangleInput& in, int samples, int order[3]);

// One edge plane in fixed point: a sample at fixed (X, Y) is inside iff c + a*X + b*Y > 0.
// For a triangle edge i->j: a = -(y_i - y_j), b = (x_i - x_j), c = DY*x_i - DX*y_i + bias (lavapipe-rules §2).
// |a|, |b| must be < 2^23 and |c| < 2^47 (true for any plane built from coordinates with |X| < 2^22); triangles in
// setup's wide range (coordinates below 2^31, edges below 2^23) reach |c| < 2^55.
struct EdgePlane {
    int64_t c = 0;
    int32_t a = 0, b = 0;
};

// Generic convex primitive (a wide line is a 4-plane rectangle built by rast/geometry): the intersection of
// `num_planes` planes, limited to the fixed-point box [min_x, max_x) x [min_y, max_y) (pixel box as for
// triangles: min>>8 .. (max-1)>>8 inclusive). The geometry helper computes planes and box. At 4x the box is also
// lavapipe's line bbox (lp_setup_line.c: min rounded up), which decides its scissor planes and binned tiles.
struct ConvexInput {
    EdgePlane planes[4];
    int num_planes = 0;
    int32_t min_x = 0, min_y = 0, max_x = 0, max_y = 0;
    PrimCommon common;
    bool front_facing = true;
};

// Axis-aligned box (point sprite or rectangle) in fixed point, half-open [x0, x1) x [y0, y1) with the top-left
// rule: sample X covered iff x0 <= X < x1 (lavapipe's point planes with c++ on left and top, lavapipe-rules §6).
struct BoxInput {
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    PrimCommon common;
    bool front_facing = true;
};

// Result of adding a primitive. Anything but kAccepted means nothing was binned.
enum class SetupStatus : uint8_t {
    kAccepted,
    kCulled,      // facing culled
    kDegenerate,  // zero area / empty box / empty sample mask
    kClipped,     // bbox ∩ clip rect is empty
    kOutOfRange,  // NaN/Inf or |coordinate| >= 16384 px (triangles: 2^23 px, or an edge spanning >= 32768 px)
    kInvalid,     // bad plane count or plane magnitudes
};

const char* to_string(SetupStatus s);

}  // namespace tilevk::rast
