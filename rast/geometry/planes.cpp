#include "rast/geometry/planes.h"

#include <bit>
#include <cmath>

namespace tilevk::rast::geometry {
namespace {

float fabs_bits(float f) {
    return std::bit_cast<float>(std::bit_cast<uint32_t>(f) & 0x7FFFFFFFu);
}

// SSE maxps semantics (a > b ? a : b); only reached with NaN z, where lavapipe's choice is this one.
float max_sse(float a, float b) {
    return a > b ? a : b;
}

struct Deltas {
    float x0c, y0c;
    float dx20o, dy20o, dx01o, dy01o;
};

// calc_coef4 for one lane
void coef(const Deltas& d, float a0, float a1, float a2, float* o_a0, float* o_dadx, float* o_dady) {
    const float da01 = a0 - a1;
    const float da20 = a2 - a0;
    // dadx = da01*dy20o - da20*dy01o
    const float p = da01 * d.dy20o;
    const float q = da20 * d.dy01o;
    const float dadx = p - q;
    // dady = da20*dx01o - da01*dx20o
    const float r = da20 * d.dx01o;
    const float s = da01 * d.dx20o;
    const float dady = r - s;
    // a0' = a_v0 - (dadx*x0c + dady*y0c)
    const float ax = dadx * d.x0c;
    const float ay = dady * d.y0c;
    const float sum = ax + ay;
    *o_a0 = a0 - sum;
    *o_dadx = dadx;
    *o_dady = dady;
}

void coef4(const Deltas& d, const float* a0, const float* a1, const float* a2, AttribPlane* out) {
    for (int c = 0; c < 4; ++c) coef(d, a0[c], a1[c], a2[c], &out->a0[c], &out->dadx[c], &out->dady[c]);
}

}  // namespace

float depth_bias_units(const DepthBias& b) {
    if (b.float_depth) return b.constant_factor;
    const uint32_t bits = b.unorm_bits == 0 ? 24 : b.unorm_bits;
    const double mrd = 1.0 / static_cast<double>((1ull << bits) - 1);
    return static_cast<float>(static_cast<double>(b.constant_factor) * mrd * 2);
}

float triangle_depth_offset(const DepthBias& b, const float* w0, const float* w1, const float* w2, float ooa) {
    const float units = depth_bias_units(b);
    if (b.slope_factor == 0.0f && units == 0.0f) return 0.0f;
    const float dx01 = w0[0] - w1[0], dy01 = w0[1] - w1[1], dz01 = w0[2] - w1[2];
    const float dx20 = w2[0] - w0[0], dy20 = w2[1] - w0[1], dz20 = w2[2] - w0[2];
    // res1 = dz20*dy01 - dy20*dz01 ; res2 = dx20*dz01 - dz20*dx01
    const float p1 = dz20 * dy01, q1 = dy20 * dz01;
    const float p2 = dx20 * dz01, q2 = dz20 * dx01;
    const float res1 = p1 - q1, res2 = p2 - q2;
    const float dzdx = fabs_bits(res1 * ooa);
    const float dzdy = fabs_bits(res2 * ooa);
    // unordered dzdx > dzdy ? dzdx : dzdy
    const float maxd = !(dzdx <= dzdy) ? dzdx : dzdy;
    const float mult = maxd * b.slope_factor;
    float offset;
    if (b.float_depth) {
        // units * 2^(exponent(max|z|) - 23), the power built from the exponent bits, clamped at 0 bits
        const float maxz = max_sse(fabs_bits(w2[2]), max_sse(fabs_bits(w0[2]), fabs_bits(w1[2])));
        int32_t e = static_cast<int32_t>(std::bit_cast<uint32_t>(maxz) & 0x7F800000u) - (23 << 23);
        if (e < 0) e = 0;
        const float scale = std::bit_cast<float>(static_cast<uint32_t>(e));
        const float bias = scale * units;
        offset = bias + mult;
    } else {
        offset = units + mult;
    }
    if (b.clamp > 0.0f) {
        offset = b.clamp < offset ? b.clamp : offset;  // lp_build_min
    } else if (b.clamp < 0.0f) {
        offset = b.clamp > offset ? b.clamp : offset;  // lp_build_max
    }
    return offset;
}

void setup_triangle_planes(const PlaneSetupConfig& cfg, const float* v0, const float* v1, const float* v2,
                           TrianglePlanes* out, AttribPlane* attribs) {
    const float* p0 = win_pos(v0);
    const float* p1 = win_pos(v1);
    const float* p2 = win_pos(v2);
    const float pc = cfg.multisample ? 0.0f : 0.5f;
    const float dx01 = p0[0] - p1[0], dy01 = p0[1] - p1[1];
    const float dx20 = p2[0] - p0[0], dy20 = p2[1] - p0[1];
    // ooa = 1 / (dx01*dy20 - dy01*dx20)
    const float e = dx01 * dy20;
    const float f = dy01 * dx20;
    const float ooa = 1.0f / (e - f);
    Deltas d;
    d.x0c = p0[0] - pc;
    d.y0c = p0[1] - pc;
    d.dx20o = dx20 * ooa;
    d.dy20o = dy20 * ooa;
    d.dx01o = dx01 * ooa;
    d.dy01o = dy01 * ooa;

    out->one_over_area = ooa;
    out->depth_offset = triangle_depth_offset(cfg.bias, p0, p1, p2, ooa);
    coef4(d, p0, p1, p2, &out->pos);
    out->pos.a0[0] = out->depth_offset;

    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) {
        const float* a0 = attrib(v0, i);
        const float* a1 = attrib(v1, i);
        const float* a2 = attrib(v2, i);
        AttribPlane& o = attribs[i];
        switch (cfg.layout.interp[i]) {
            case Interp::kFlat: {
                const float* src = cfg.flatshade_first ? a0 : a2;
                for (int c = 0; c < 4; ++c) {
                    o.a0[c] = src[c];
                    o.dadx[c] = 0.0f;
                    o.dady[c] = 0.0f;
                }
                break;
            }
            case Interp::kNoPerspective:
                coef4(d, a0, a1, a2, &o);
                break;
            case Interp::kPerspective: {
                // premultiply each vertex's value by its 1/w: fl(a * oow_i)
                float b0[4], b1[4], b2[4];
                for (int c = 0; c < 4; ++c) {
                    b0[c] = a0[c] * p0[3];
                    b1[c] = a1[c] * p1[3];
                    b2[c] = a2[c] * p2[3];
                }
                coef4(d, b0, b1, b2, &o);
                break;
            }
        }
    }
}

}  // namespace tilevk::rast::geometry
