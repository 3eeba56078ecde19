// Triangle attribute planes exactly as llvmpipe's setup JIT (lp_state_setup.c: init_args, calc_coef4,
// apply_perspective_corr, emit_tri_coef, lp_do_offset_tri). Every operation is a separate float mul/sub: no FMA.
#pragma once

#include <cstdint>

#include "rast/geometry/vertex.h"

namespace tilevk::rast::geometry {

// A plane per vec4 lane: value(px, py) = a0 + dadx*px + dady*py, with (px, py) measured from pixel (0,0)'s
// centre at 1x (pc = 0.5) or from the framebuffer corner in MSAA (pc = 0). The fragment stage evaluates it with
// fmuladd (lavapipe-rules §4) and, for perspective inputs, multiplies by 1/(1/w plane).
struct AttribPlane {
    float a0[4];
    float dadx[4];
    float dady[4];
};

// Depth bias as lavapipe feeds it (VkPipelineRasterizationStateCreateInfo; disabled = all zero).
struct DepthBias {
    float constant_factor = 0.0f;
    float slope_factor = 0.0f;
    float clamp = 0.0f;
    bool float_depth = false;  // D32_SFLOAT(_S8): exponent rule; else unorm
    uint32_t unorm_bits = 24;  // 16 or 24; lavapipe uses 24 when there is no depth attachment
};

// The units value llvmpipe bakes into the setup key: float depth -> constant_factor;
// unorm -> (float)((double)constant_factor * (1.0 / (2^bits - 1)) * 2)  (the factor 2, lp_state_setup.c).
float depth_bias_units(const DepthBias& b);

struct PlaneSetupConfig {
    VertexLayout layout;
    bool multisample = false;     // pc = 0 in MSAA, else 0.5 (half_pixel_center is always on in lavapipe)
    bool flatshade_first = true;  // flat inputs from v0 (else v2)
    DepthBias bias;
};

struct TrianglePlanes {
    // Slot 0: lanes z (2) and 1/w (3) are the depth and 1/w planes; lanes x, y are computed like any attribute
    // but unused, except pos.a0[0], which llvmpipe overwrites with the depth offset (also in depth_offset).
    AttribPlane pos;
    float depth_offset;
    float one_over_area;  // ooa = 1 / fl(fl(dx01*dy20) - fl(dy01*dx20)) from the float window coordinates
};

// Planes of a triangle from its three vertex records in the FINAL order handed to the rasterizer (after
// rast/core's CW->CCW swap: v1<->v2 with flatshade_first, v0<->v1 otherwise), from the float window
// coordinates (record lanes 4..7). Writes layout.num_attribs planes to attribs[]; flat attributes get
// a0 = provoking value, dadx = dady = 0; perspective ones are premultiplied by each vertex's 1/w (win lane 3).
// A degenerate triangle yields Inf/NaN planes exactly as lavapipe (it is dropped by the core before use).
void setup_triangle_planes(const PlaneSetupConfig& cfg, const float* v0, const float* v1, const float* v2,
                           TrianglePlanes* out, AttribPlane* attribs);

// The depth-bias value alone (lp_do_offset_tri) from window positions (x, y, z) of the final-order vertices and
// ooa as computed by setup_triangle_planes. Returns 0 when units and slope are both 0.
float triangle_depth_offset(const DepthBias& b, const float* w0, const float* w1, const float* w2, float ooa);

}  // namespace tilevk::rast::geometry
