// Internal: the set-up primitive stored in a scene, and the setup functions that build it (lp_setup_tri.c rules).
#pragma once

#include <cstdint>

#include "rast/core/primitive.h"

namespace tilevk::rast {

// Planes: shape planes first (3 for triangles, up to 4 for convex/box), then up to 4 whole-pixel box planes that
// bound coverage to the inclusive pixel box [x0,x1] x [y0,y1] (bbox ∩ clip ∩ framebuffer). Box planes are added
// only on sides where the clipped box may be tighter than what the shape implies (see finish_box in setup.cpp).
struct Prim {
    static constexpr int kMaxPlanes = 8;
    EdgePlane planes[kMaxPlanes];
    uint8_t num_planes = 0;
    uint8_t num_shape_planes = 0;
    bool front_facing = true;
    bool is_triangle = false;
    uint16_t sample_mask = 0;  // already limited to the sample count
    uint32_t payload = 0;
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive pixel box
    float fx[3] = {}, fy[3] = {};            // float window coords in plane order (float method only)
};

enum BinCmdFlags : uint32_t { kBinPartial = 0, kBinWholeTile = 1 };

struct BinCmd {
    uint32_t prim;
    uint32_t flags;
};

// Setup entry points; `fb` is the framebuffer as a clip rect. On kAccepted, *out is complete.
SetupStatus setup_triangle(const TriangleInput& in, int samples, const ClipRect& fb, Prim* out);
SetupStatus setup_convex(const ConvexInput& in, int samples, const ClipRect& fb, Prim* out);
SetupStatus setup_box(const BoxInput& in, int samples, const ClipRect& fb, Prim* out);

}  // namespace tilevk::rast
