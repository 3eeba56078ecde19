// draw's clipper and float cull (draw_pipe_clip.c do_clip_tri / do_clip_line / clip_point_guard_xy,
// draw_pipe_cull.c cull_tri), reproduced operation by operation.
#pragma once

#include <cstdint>

#include "rast/geometry/vertex.h"
#include "rast/geometry/viewport.h"

namespace tilevk::rast::geometry {

// Most vertices a clipped triangle can have (draw: MAX_CLIPPED_VERTICES with 6 planes + 8 user planes).
inline constexpr uint32_t kMaxClippedVertices = 2 * (6 + 8) + 1;
// Scratch vertices one clip_triangle call may create (new intersections plus the flat-attribute copy).
inline constexpr uint32_t kClipScratchVertices = kMaxClippedVertices + 1;
// Most triangles one clipped triangle turns into.
inline constexpr uint32_t kMaxClippedTriangles = kMaxClippedVertices - 2;

// The window depths whose fragments the depth test rejects whatever the depth buffer holds: lavapipe clamps a
// fragment's depth to [0, 1] before the test (lavapipe-rules §4), so with LESS nothing at z >= 1 passes and with
// GREATER nothing at z <= 0 (the renderer decides it: rast/render/renderer.cpp hidden_depth).
enum class HiddenDepth : uint8_t { kNone, kFromOne, kUpToZero };

struct ClipConfig {
    VertexLayout layout;
    Viewport vp;                  // draw->viewports[0]: new vertices are transformed with it in C
    bool clip_halfz = true;       // plane 4 is z >= 0 (else z + w >= 0)
    bool flatshade_first = true;  // Vulkan's provoking vertex = first
    // llvmpipe's linear mode (draw_set_driver_clipping guard_band_xy): planes 0-3 become the 2x guard band
    // |x|, |y| <= 2w. The clip mask (compute_clipmask) still tests the viewport, so a triangle crossing the
    // viewport edge enters the clipper, is cut only beyond the guard band, and is re-emitted as a fan.
    bool guard_band_xy = false;
    // Off for polygonMode POINT: lavapipe rejects a triangle whose three vertices are outside one x/y plane, but cuts
    // it along the z and user planes only, so a vertex outside the viewport stays a point that the draw region
    // (viewport, scissor, framebuffer) bounds at rasterization. Found by experiment (cts quirks.unfilled.point_*:
    // a vertex just right of the viewport is drawn in part; a cut at x = w would be a point on the edge, which draw's
    // edge flags would draw and lavapipe does not; a vertex outside the right and near planes gets its near-plane
    // point); where draw's source decides it was not found (draw_pipe_clip.c cuts every set plane).
    bool cut_xy = true;
    // Re-clip in extended precision the triangles lavapipe's float clipper provably gets wrong (filled polygons;
    // clip_triangle_precise). Off: draw's result always, e.g. for polygonMode LINE/POINT (edge flags).
    bool precise_fallback = false;
    // The framebuffer's sample count: where draw's result and the precise one must agree for draw's to be kept.
    uint32_t samples = 1;
    // Where draw's result and the precise one are compared, the part of either beyond this depth is left out: an
    // intersection parameter flushed to 0 may leave draw's polygon a vertex past the far (near) plane, and what it
    // adds there is never drawn (cts extreme.regression.w_zero_far_plane).
    HiddenDepth hidden_depth = HiddenDepth::kNone;
    // The vertex shader's ClipDistance and CullDistance outputs, as lavapipe's NIR holds them: one array, clip
    // distances first (nir_lower_clip_cull_distance_arrays), in the record's perspective attribute slots from
    // `distance_slot` on, four per slot (draw's two ccdistance outputs). User plane i is clip-mask bit 6 + i
    // (kClipUserShift); its distance is element i, interpolated at new vertices like every perspective attribute.
    int32_t distance_slot = -1;
    uint32_t num_clip_distances = 0;
    uint32_t num_cull_distances = 0;
};

// Element i of a record's combined ClipDistance/CullDistance array (ClipConfig::distance_slot).
inline float clip_distance_element(const ClipConfig& cfg, const float* record, uint32_t i) {
    return attrib(record, static_cast<uint32_t>(cfg.distance_slot) + i / 4)[i % 4];
}

// draw_pipe_user_cull.c: a primitive (n = 1, 2 or 3 vertices) is culled when, for some CullDistance, every vertex
// has a distance below 0 or not finite. Runs on draw's pipeline path, before the clipper, only when the vertex
// shader writes CullDistance (which sends every batch down that path: draw_pipe_validate.c draw_need_pipeline).
bool cull_distance_keep(const ClipConfig& cfg, const float* const* v, uint32_t n);

// Edge bit k: the edge from v[k] to v[(k+1)%3] (k = 0, 1, 2) is drawn by polygonMode LINE, and v[k] is drawn by
// polygonMode POINT (draw_pipe_unfilled.c: header flag DRAW_PIPE_EDGE_FLAG_k and v[k]->edgeflag).
inline constexpr uint8_t kAllEdges = 7;

struct ClippedTriangle {
    const float* v[3];  // vertex records (inputs or scratch)
    uint8_t edges = kAllEdges;
};

// Clips one triangle whose vertices have clip masks m0..m2 (compute_clipmask). Returns the number of triangles
// written to out[] (capacity kMaxClippedTriangles):
//   m0|m1|m2 == 0 -> 1, the input triangle untouched (no re-ordering);
//   m0&m1&m2 != 0 -> 0 (trivially outside);
//   otherwise Sutherland-Hodgman over the set bits in bit order (the six frustum planes, then the user planes of
//   ClipDistance); a NaN/Inf plane distance discards everything;
//   emitted as a fan (p0, p[i-1], p[i]) with flatshade_first, else (p[i-1], p[i], p0). This re-ordering also
//   happens when nothing was cut. Edge flags (draw_pipe_clip.c do_clip_tri / emit_poly): the fan's inner edges
//   and the edges the clipper creates along a frustum plane are not drawn in polygonMode LINE (along a user plane
//   they are, and the vertex going out is drawn in polygonMode POINT); a vertex created
//   where the polygon leaves a plane is not drawn in polygonMode POINT, one where it comes back in is. With flat
//   attributes, p0 (when it is not the original provoking vertex) is copied into scratch and given the provoking
//   vertex's flat attributes.
// `scratch` holds kClipScratchVertices records of vertex_floats(layout) floats each. Output pointers refer to
// the inputs or to scratch, so scratch must outlive the use of out[].
uint32_t clip_triangle(const ClipConfig& cfg, const float* v0, const float* v1, const float* v2, uint32_t m0,
                       uint32_t m1, uint32_t m2, float* scratch, ClippedTriangle* out);

// A named difference from lavapipe (rast/geometry/README.md, "Extreme coordinates"): for a triangle with finite
// clip coordinates whose float clip (draw's, above) overflowed (a plane distance of Inf), flushed an intersection
// parameter to 0 (FTZ; a vertex beyond ~1e38 of a plane), or produced a vertex lavapipe's setup cannot snap
// (|window coordinate| >= 2^23 px: INT_MIN) or an edge it cannot hold (>= 32768 px: wrapped 32-bit planes),
// lavapipe draws the wrong pixels (often none); with ClipConfig::precise_fallback, clip_triangle clips such a
// triangle again with 237-bit positions (clip_precise.cpp) and hands setup the rounded result.
uint32_t clip_triangle_precise(const ClipConfig& cfg, const float* v0, const float* v1, const float* v2,
                               uint32_t clipmask, float* scratch, ClippedTriangle* out);
// The tests of that decision: inputs with an exact answer in lavapipe's float environment (finite, |w| < 2^126 or
// x, y, z at most 2^-64 |w|, where FTZ's centre is the exact projection),
// and float output that lavapipe's setup cannot rasterize faithfully.
bool clip_inputs_finite(const float* v0, const float* v1, const float* v2);
bool clip_needs_precision(const float* v0, const float* v1, const float* v2, const ClippedTriangle* out, uint32_t n);

// Line clip (do_clip_line: parametric t0/t1 per plane, discard when t0 + t1 >= 1). Returns false when discarded.
// A clipped end is replaced by a scratch vertex (scratch: 2 records) with the provoking vertex's flat attributes.
bool clip_line(const ClipConfig& cfg, const float* v0, const float* v1, uint32_t m0, uint32_t m1, float* scratch,
               const float** out0, const float** out1);

// Points (lavapipe: single viewport -> clip_point_guard_xy): kept if the mask is 0; with only x/y bits kept unless
// w <= 0 or x/y is NaN/Inf; any z bit drops the point.
bool clip_point_keep(const float clip[4], uint32_t mask);

// draw_pipe_cull.c: det = fl(fl(ex*fy) - fl(ey*fx)), e = v0-v2, f = v1-v2 over window x, y. det < 0 is "ccw".
// det == 0 counts as back-facing; NaN det is a non-ccw (cw) triangle. Runs only on the pipeline path (a batch
// with any clipped vertex) and only when a cull mode is set. Returns true when the triangle survives.
struct FloatCull {
    bool cull_front = false;
    bool cull_back = false;
    bool front_ccw = true;  // VK_FRONT_FACE_COUNTER_CLOCKWISE
};
bool float_cull_keep(const FloatCull& c, const float* w0, const float* w1, const float* w2);

// Plane distance as draw computes it: dot4 in C, left to right, no FMA (exposed for tests).
float clip_plane_distance(const float clip[4], uint32_t plane, bool clip_halfz, bool guard_band_xy = false);

}  // namespace tilevk::rast::geometry
