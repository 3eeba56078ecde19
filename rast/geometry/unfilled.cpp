#include "rast/geometry/unfilled.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace tilevk::rast::geometry {
namespace {

// MAX2 / MIN2 of u_math.h: a > b ? a : b and a < b ? a : b (NaN picks b).
float max2(float a, float b) {
    return a > b ? a : b;
}
float min2(float a, float b) {
    return a < b ? a : b;
}

// SATURATE(x) = x < 0 ? 0 : (x > 1 ? 1 : x) (NaN stays NaN).
float saturate(float x) {
    return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
}

}  // namespace

float unfilled_depth_offset(const DepthBias& b, const float* v0, const float* v1, const float* v2) {
    const float ex = v0[0] - v2[0], ey = v0[1] - v2[1], ez = v0[2] - v2[2];
    const float fx = v1[0] - v2[0], fy = v1[1] - v2[1], fz = v1[2] - v2[2];
    // det = ex*fy - ey*fx (draw_pipe_cull.c)
    const float det_p = ex * fy, det_q = ey * fx;
    const float det = det_p - det_q;
    const float inv_det = 1.0f / det;
    // (a, b) = cross(e, f).xy
    const float a1 = ey * fz, a2 = ez * fy;
    const float a = a1 - a2;
    const float b1 = ez * fx, b2 = ex * fz;
    const float bb = b1 - b2;
    const float dzdx = std::fabs(a * inv_det);
    const float dzdy = std::fabs(bb * inv_det);
    const float mult = max2(dzdx, dzdy) * b.slope_factor;
    const float units = depth_bias_units(b);
    float zoffset;
    if (b.float_depth) {
        // maxz's exponent bits minus 23, clamped at 0, read back as a float: 2^(exp - 23)
        const float maxz = max2(max2(std::fabs(v0[2]), std::fabs(v1[2])), std::fabs(v2[2]));
        int32_t e = static_cast<int32_t>(std::bit_cast<uint32_t>(maxz) & (0xFFu << 23)) - (23 << 23);
        if (e < 0) e = 0;
        const float bias = units * std::bit_cast<float>(e);
        zoffset = bias + mult;
    } else {
        zoffset = units + mult;
    }
    if (b.clamp != 0.0f) zoffset = b.clamp < 0.0f ? max2(zoffset, b.clamp) : min2(zoffset, b.clamp);
    return zoffset;
}

void prepare_unfilled_triangle(const UnfilledConfig& cfg, const float* const v[3], float* scratch,
                               const float* out[3]) {
    bool any_flat = false;
    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) any_flat |= cfg.layout.interp[i] == Interp::kFlat;
    for (int k = 0; k < 3; ++k) out[k] = v[k];
    if (!cfg.bias_enable && !any_flat) return;
    const uint32_t stride = vertex_floats(cfg.layout);
    float* c[3];
    for (int k = 0; k < 3; ++k) {
        c[k] = scratch + size_t(k) * stride;
        std::memcpy(c[k], v[k], sizeof(float) * stride);
        out[k] = c[k];
    }
    if (cfg.bias_enable) {
        const float zoffset = unfilled_depth_offset(cfg.bias, win_pos(v[0]), win_pos(v[1]), win_pos(v[2]));
        for (int k = 0; k < 3; ++k) c[k][kWinPosOffset + 2] = saturate(c[k][kWinPosOffset + 2] + zoffset);
    }
    if (any_flat) {
        const int provoking = cfg.flatshade_first ? 0 : 2;
        for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) {
            if (cfg.layout.interp[i] != Interp::kFlat) continue;
            for (int k = 0; k < 3; ++k)
                if (k != provoking) std::memcpy(c[k] + kAttribOffset + 4 * i, attrib(v[provoking], i), 16);
        }
    }
}

bool unfilled_front_facing(bool front_ccw, const float* v0, const float* v1, const float* v2) {
    const float ex = v0[0] - v2[0], ey = v0[1] - v2[1];
    const float fx = v1[0] - v2[0], fy = v1[1] - v2[1];
    const float p = ex * fy, q = ey * fx;
    const float det = p - q;
    return front_ccw ? det < 0.0f : det > 0.0f;
}

uint32_t unfilled_lines(uint8_t edges, uint8_t out[3][2]) {
    uint32_t n = 0;
    if (edges & 4) out[n][0] = 2, out[n][1] = 0, ++n;
    if (edges & 1) out[n][0] = 0, out[n][1] = 1, ++n;
    if (edges & 2) out[n][0] = 1, out[n][1] = 2, ++n;
    return n;
}

}  // namespace tilevk::rast::geometry
