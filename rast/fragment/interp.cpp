#include "rast/fragment/interp.h"

#include <cmath>

namespace tilevk::rast::fragment {

namespace {
// fmuladd as LLVM lowers it: one rounding when fused, two otherwise.
inline float fmuladd(float a, float b, float c, bool fused) {
    return fused ? std::fma(a, b, c) : a * b + c;
}
}  // namespace

void lane_coords(int block_x, int block_y, EvalOffset off, float px[kBlockLanes], float py[kBlockLanes]) {
    const float bx = float(block_x), by = float(block_y);
    for (int l = 0; l < kBlockLanes; ++l) {
        // pixoff = fl(fl(lane offset) + fl(block origin)) + sample/centre offset, in that order.
        float x = float(lane_x(l)) + bx;
        float y = float(lane_y(l)) + by;
        px[l] = x + off.x;
        py[l] = y + off.y;
    }
}

void eval_plane(const Plane& p, int block_x, int block_y, EvalOffset off, bool fused, float out[kBlockLanes]) {
    float px[kBlockLanes], py[kBlockLanes];
    lane_coords(block_x, block_y, off, px, py);
    for (int l = 0; l < kBlockLanes; ++l) {
        // a = fmuladd(dady, py, fmuladd(dadx, px, a0))
        float a = fmuladd(p.dadx, px[l], p.a0, fused);
        out[l] = fmuladd(p.dady, py[l], a, fused);
    }
}

void eval_plane_per_lane(const Plane& p, int block_x, int block_y, const float ox[kBlockLanes],
                         const float oy[kBlockLanes], bool fused, float out[kBlockLanes]) {
    const float bx = float(block_x), by = float(block_y);
    for (int l = 0; l < kBlockLanes; ++l) {
        const float px = (float(lane_x(l)) + bx) + ox[l];
        const float py = (float(lane_y(l)) + by) + oy[l];
        const float a = fmuladd(p.dadx, px, p.a0, fused);
        out[l] = fmuladd(p.dady, py, a, fused);
    }
}

void centroid_offsets(const uint16_t sample_masks[kMaxSamples], float ox[kBlockLanes], float oy[kBlockLanes]) {
    for (int l = 0; l < kBlockLanes; ++l) {
        const uint16_t bit = uint16_t(1u << l);
        ox[l] = oy[l] = 0.5f;
        bool all = true;
        for (int s = kMaxSamples - 1; s >= 0; --s) {  // lowest covered sample wins
            if (sample_masks[s] & bit) {
                ox[l] = kSamplePos4x[s][0];
                oy[l] = kSamplePos4x[s][1];
            } else {
                all = false;
            }
        }
        if (all) ox[l] = oy[l] = 0.5f;
    }
}

void perspective_divide(const float a[kBlockLanes], const float w[kBlockLanes], float out[kBlockLanes]) {
    for (int l = 0; l < kBlockLanes; ++l) {
        // a * (1/w): a reciprocal then a multiply, never a/w
        const float oow = 1.0f / w[l];
        out[l] = a[l] * oow;
    }
}

void eval_flat(float value, float out[kBlockLanes]) {
    for (int l = 0; l < kBlockLanes; ++l) out[l] = value;
}

void frag_coord_xy(int block_x, int block_y, EvalOffset off, float x[kBlockLanes], float y[kBlockLanes]) {
    lane_coords(block_x, block_y, off, x, y);
}

void eval_depth(const Plane& z, float bias_offset, int block_x, int block_y, EvalOffset off, bool fused,
                float out[kBlockLanes]) {
    eval_plane(z, block_x, block_y, off, fused, out);
    for (int l = 0; l < kBlockLanes; ++l) out[l] = out[l] + bias_offset;
}

}  // namespace tilevk::rast::fragment
