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
// A plane in pixel units (see tile_kernels.h): with d[s] the sample offsets, the plane at pixel (px, py) and sample s
// is > 0 iff c0 + d[s] + a*px + b*py > 0, where c0 + d[s] = ceil((c + a*sx_s + b*sy_s) / 256). Precomputed once per
// primitive so that a tile costs one 64-bit multiply-add per plane and no division. |c0| < 2^39 (2^48 in the wide range), |d| < 2^24.
struct PixelPlane {
    int64_t c0;
    int32_t a, b;
    int32_t d[4];
    int32_t dlo, dhi;  // min and max of d[] over the samples
    int32_t up, dn;    // max(a,0) + max(b,0) and min(a,0) + min(b,0): extreme steps per pixel (tile corners)
};

// Hot fields first (read per tile by hier/bbox); the 64-bit planes and floats (reference/float methods, setup)
// come last so the rasterizer's cache lines hold only what it needs.
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
    EdgePlane planes[kMaxPlanes];  // 64-bit fixed-point planes (the reference evaluates the shape planes directly)
    float fx[3] = {}, fy[3] = {};  // float window coords in plane order (float method only)
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

// Setup entry points; `fb` is the framebuffer as a clip rect. On kAccepted, *out is complete.
SetupStatus setup_triangle(const TriangleInput& in, int samples, const ClipRect& fb, Prim* out);
SetupStatus setup_convex(const ConvexInput& in, int samples, const ClipRect& fb, Prim* out);
SetupStatus setup_box(const BoxInput& in, int samples, const ClipRect& fb, Prim* out);

// Fills prim->pix from prim->planes for the sample count (called by the setup functions).
void compute_pixel_planes(int samples, Prim* prim);

}  // namespace tilevk::rast
