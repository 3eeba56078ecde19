// Attribute interpolation for one 4x4 block, as lavapipe's fragment shader prologue does it
// (llvmpipe lp_bld_interp.c attribs_update_simple, "single step" method):
//
//   px = fl(fl(lane_x) + fl(block_x)) [+ offset]          exact for |coords| < 2^22
//   a  = fmuladd(dadx, px, a0);  a = fmuladd(dady, py, a)   fused on FMA CPUs, else mul then add
//   perspective: a = fl(a * fl(1.0f / w))                     w = the interpolated 1/w plane (lp_build_rcp = FDiv)
//
// lavapipe does NOT step from a block origin with increments: every lane is evaluated directly from a0 with the
// two fmuladds above (the "simple" method; lp_build_interp_soa_init says so explicitly).
//
// Offsets: at 1x the setup plane origin is pixel (0,0)'s centre, so px, py are the integer pixel coordinates.
// At 4x the origin is the pixel corner: the shader adds 0.5 (centre) or the sample position (sample-qualified
// inputs, per-sample depth) or the centroid offsets below.
#pragma once

#include <cstdint>

#include "rast/fragment/block.h"

namespace tilevk::rast::fragment {

// a(x, y) = a0 + dadx*x + dady*y, in the setup's coordinate frame.
struct Plane {
    float dadx = 0.0f;
    float dady = 0.0f;
    float a0 = 0.0f;
};

// What is added to the integer pixel coordinates before a plane is evaluated.
struct EvalOffset {
    float x = 0.0f;
    float y = 0.0f;
};

// 1x: 0.  4x: 0.5 at the pixel centre (sample < 0) or the sample position of `sample`.
constexpr EvalOffset plane_offset(int samples, int sample) {
    if (samples <= 1) return {0.0f, 0.0f};
    if (sample < 0) return {0.5f, 0.5f};
    return {kSamplePos4x[sample & 3][0], kSamplePos4x[sample & 3][1]};
}

// gl_FragCoord.xy offset: 0.5 (pixel centre) at 1x and 4x, the sample position under sample shading.
constexpr EvalOffset frag_coord_offset(int samples, int sample) {
    if (samples <= 1 || sample < 0) return {0.5f, 0.5f};
    return {kSamplePos4x[sample & 3][0], kSamplePos4x[sample & 3][1]};
}

// The exact float pixel coordinates lavapipe evaluates at, per lane (shader lane order).
void lane_coords(int block_x, int block_y, EvalOffset off, float px[kBlockLanes], float py[kBlockLanes]);

// a = fmuladd(dady, py, fmuladd(dadx, px, a0)) per lane; `fused` selects a true FMA (lavapipe on FMA CPUs).
void eval_plane(const Plane& p, int block_x, int block_y, EvalOffset off, bool fused, float out[kBlockLanes]);

// Per-lane offsets variant (centroid): px = fl(fl(lane_x + block_x) + ox[lane]).
void eval_plane_per_lane(const Plane& p, int block_x, int block_y, const float ox[kBlockLanes],
                         const float oy[kBlockLanes], bool fused, float out[kBlockLanes]);

// 4x centroid offsets (lp_bld_interp.c calc_centroid_offsets): a lane whose samples are all covered, or none, uses
// the centre (0.5, 0.5); otherwise the position of its lowest-numbered covered sample. `sample_masks` (lane order)
// are the masks when the shader runs, i.e. after early depth/stencil. At 1x centroid is the plain centre.
void centroid_offsets(const uint16_t sample_masks[kMaxSamples], float ox[kBlockLanes], float oy[kBlockLanes]);

// Perspective correction: out = fl(a * fl(1.0f / w)).  w is the 1/w plane value (gl_FragCoord.w). lavapipe takes
// w at the pixel centre (plane_offset(samples, -1)) even for sample-qualified inputs (source reading).
void perspective_divide(const float a[kBlockLanes], const float w[kBlockLanes], float out[kBlockLanes]);

// Flat inputs: the provoking vertex's value in every lane.
void eval_flat(float value, float out[kBlockLanes]);

// gl_FragCoord.xy = px + offset (fmuladd(1, px, 0.5) in lavapipe: exact).
void frag_coord_xy(int block_x, int block_y, EvalOffset off, float x[kBlockLanes], float y[kBlockLanes]);

// gl_FragCoord.z / the depth-test value: eval_plane(z) then a plain add of the depth-bias offset
// (lavapipe stores the offset in a0[0].x and adds it with FAdd after interpolation).
// Per-sample depth at 4x uses plane_offset(4, s); the shaded z uses plane_offset(4, -1).
void eval_depth(const Plane& z, float bias_offset, int block_x, int block_y, EvalOffset off, bool fused,
                float out[kBlockLanes]);

}  // namespace tilevk::rast::fragment
