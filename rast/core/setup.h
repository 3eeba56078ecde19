// Internal: the set-up primitive stored in a scene, and the setup functions that build it (lp_setup_tri.c rules).
#pragma once

#include <cstdint>

#include "rast/core/primitive.h"

namespace tilevk::rast {

// Planes: shape planes first (3 for triangles, up to 4 for convex/box), then up to 2 lavapipe MSAA scissor planes
// (sample-exact: left and top, see finish_box_msaa in setup.cpp; only at 4x), then whole-pixel box planes that
// bound coverage to the inclusive pixel box [x0,x1] x [y0,y1] (bbox ∩ clip ∩ framebuffer). Box planes are added
// only on sides where the clipped box may be tighter than what the shape implies (see finish_box in setup.cpp).
// At most one plane per side beyond the shape planes, so kMaxPlanes = 4 + 4.
// A plane in pixel units (see tile_kernels.h): with d[s] the sample offsets (Prim::d; d[0] = 0), the plane at pixel
// (px, py) and sample s is > 0 iff c0 + d[s] + a*px + b*py > 0, where c0 + d[s] = ceil((c + a*sx_s + b*sy_s) / 256).
// Precomputed once per primitive so that a tile costs one 64-bit multiply-add per plane and no division.
// |c0| < 2^39 (2^48 in the wide range), |d| < 2^24. The tile's extreme steps (max(a,0) + max(b,0) and
// min(a,0) + min(b,0)) and the samples' min/max offsets are derived per tile: a few ALU operations are cheaper
// than the cache line they would take in every primitive.
struct PixelPlane {
    int64_t c0;
    int32_t a, b;
};

// The set-up primitive as the tile loop reads it: per tile and binned primitive, the header and num_planes pixel
// planes (a 1x triangle without box planes: 80 bytes, two cache lines), at 4x also d. 256 bytes, so a record never
// straddles more lines than it uses. The 64-bit edge planes and float coordinates only the reference and float
// methods read stay out of it (PrimEdges).
struct Prim {
    static constexpr int kMaxPlanes = 8;
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive pixel box
    uint32_t payload = 0;
    uint16_t sample_mask = 0;  // already limited to the sample count
    uint8_t num_planes = 0;
    uint8_t num_shape_planes = 0;
    uint8_t num_scissor_planes = 0;  // planes[num_shape_planes..+num_scissor_planes): lavapipe's MSAA scissor planes
    bool front_facing = true;
    bool is_triangle = false;
    PixelPlane pix[kMaxPlanes];
    int32_t d[kMaxPlanes][3];  // 4x only: plane k's offset of samples 1..3 (sample 0's is 0)
};
static_assert(sizeof(Prim) == 256);

// The rest of a set-up primitive: its 64-bit fixed-point planes (the reference evaluates the shape and scissor
// planes directly; setup derives the pixel planes from them) and float window coordinates in plane order (float
// method only). A scene keeps them only when its method reads them.
struct PrimEdges {
    EdgePlane planes[Prim::kMaxPlanes];
    float fx[3] = {}, fy[3] = {};
};

// A tile's command: primitive `prim` of the scene, binned as a whole-tile command or not. The primitive's payload
// is copied here so that the tile loop can hand it to the consumer's prefetch hint commands ahead without first
// reading the primitive (a cache miss of its own).
struct BinCmd {
    uint32_t prim : 31;
    uint32_t whole_tile : 1;
    uint32_t payload;
};
static_assert(sizeof(BinCmd) == 8);

// Setup entry points; `fb` is the framebuffer as a clip rect. On kAccepted, *out and *edges are complete.
SetupStatus setup_triangle(const TriangleInput& in, int samples, const ClipRect& fb, Prim* out, PrimEdges* edges);
SetupStatus setup_convex(const ConvexInput& in, int samples, const ClipRect& fb, Prim* out, PrimEdges* edges);
SetupStatus setup_box(const BoxInput& in, int samples, const ClipRect& fb, Prim* out, PrimEdges* edges);

// Fills prim->pix and prim->d from edges->planes for the sample count (called by the setup functions).
void compute_pixel_planes(int samples, const PrimEdges& edges, Prim* prim);

}  // namespace tilevk::rast
