// Anisotropic filtering (samplerAnisotropy) as lavapipe 22.3 does it: the level from the footprint's minor axis
// (lp_bld_sample.c lp_build_pmin) and an elliptical weighted average of nearest texels over the footprint's
// ellipse (lp_bld_sample_soa.c lp_build_sample_aniso, Heckbert's EWA scan), weights from gallivm's 1024-entry
// Gaussian table. The operations and their order are docs/lavapipe-rules.md §10 "Anisotropy", step by step.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>

#include "shader/texture_aniso.h"
#include "shader/texture_fixed8.h"

namespace tilevk::shader::tex {

namespace {

constexpr int kWeights = 1024;

// SSE's minps / maxps: the second operand when either is NaN (lp_build_min / lp_build_max, NaN behaviour undefined).
float minps(float a, float b) {
    return a < b ? a : b;
}
float maxps(float a, float b) {
    return a > b ? a : b;
}

// cvttps2dq: truncation, INT_MIN for NaN and out of range (lp_build_itrunc).
int32_t cvtt(float x) {
    return (x >= -2147483648.0f && x < 2147483648.0f) ? int32_t(x) : INT32_MIN;
}

// More probes than this per pixel (a footprint of over 4096 x 4096 texels at the chosen level) are not run: see
// shader/README.md "Anisotropic filtering" (lavapipe runs them all, for minutes).
constexpr int64_t kMaxProbes = int64_t(1) << 24;

}  // namespace

const std::array<float, 1024>& aniso_weights() {
    // gallivm's table was printed with "%f" from expf(-2 * i / 1023) and is read back as float: the same text
    // here, parsed the same way (lp_bld_sample.c aniso_filter_table and the generator quoted above it)
    static const std::array<float, kWeights> table = [] {
        std::array<float, kWeights> t{};
        for (int i = 0; i < kWeights; ++i) {
            const float r2 = float(i) / float(kWeights - 1);
            const float weight = std::exp(-2.0f * r2);
            char text[32];
            std::snprintf(text, sizeof text, "%f", double(weight));
            t[size_t(i)] = std::stof(text);
        }
        return t;
    }();
    return table;
}

float aniso_raw_lambda(const ImageView& img, const QuadDerivs& d, float max_anisotropy) {
    // the derivatives in texels of the view's first level (lp_build_minify(int_size, first_level))
    const float w = float(img.width), h = float(img.height);
    const float sx = d.dsdx * w, sy = d.dsdy * w, tx = d.dtdx * h, ty = d.dtdy * h;
    const float px2 = sx * sx + tx * tx, py2 = sy * sy + ty * ty;
    const float pmax2 = maxps(px2, py2);
    float pmin2 = minps(px2, py2);
    // lavapipe compares pmin2 (not pmax2) with pmin2 * N^2, so this replacement never happens for N >= 1; kept as
    // written so that the arithmetic is lavapipe's (docs/lavapipe-rules.md §10 "Anisotropy")
    const float n2 = max_anisotropy * max_anisotropy;
    if (pmin2 > pmin2 * n2) pmin2 = pmax2 / n2;
    return fixed8::fast_log2(pmin2) * 0.5f;
}

uint32_t aniso_level(const ImageView& img, float lambda) {
    // lod_ipart = itrunc(lod), then lp_build_nearest_mip_level's clamp to the view's levels
    const int32_t i = cvtt(lambda);
    return uint32_t(std::clamp<int64_t>(i, 0, int64_t(img.levels) - 1));
}

Vec4 sample_aniso(const ImageView& img, const SamplerState& smp, uint32_t lv, uint32_t size_lv, uint32_t layer, float s,
                  float t, const QuadDerivs& d, const SampleArgs& args) {
    // lavapipe scales by the image's level-0 size and 1 / 2^(absolute level) (lp_setup.c: jit width = width0),
    // which differs from the view level's size on non-power-of-two images
    const uint32_t abs_level = img.base_level + lv;
    const float scaling = 1.0f / float(1u << abs_level);
    const float w0 = float(img.width0 ? img.width0 : img.width), h0 = float(img.height0 ? img.height0 : img.height);
    const float wl = float(std::max(1u, img.width >> size_lv)), hl = float(std::max(1u, img.height >> size_lv));
    const float ux = d.dsdx * w0 * scaling, uy = d.dsdy * w0 * scaling;
    const float vx = d.dtdx * h0 * scaling, vy = d.dtdy * h0 * scaling;
    // the ellipse A x^2 + B x y + C y^2 = F
    float a = (vx * vx + vy * vy) + 1.0f;
    float b = (ux * vx + uy * vy) * -2.0f;
    float c = (ux * ux + uy * uy) + 1.0f;
    const float f = a * c - (b * b) / 4.0f;
    const float det = (0.0f - b * b) + (a * c) * 4.0f;
    const float box_u = (2.0f / det) * std::sqrt((det * c) * f);
    const float box_v = (2.0f / det) * std::sqrt((a * det) * f);
    const float form_scale = float(kWeights - 1) / f;
    a = a * form_scale, b = b * form_scale, c = c * form_scale;
    const float ddq = a * 2.0f;
    const float tex_u = s * (w0 * scaling) + -0.5f;
    const float tex_v = t * (h0 * scaling) + -0.5f;
    const int32_t u0 = cvtt(std::floor(tex_u - box_u)), u1 = cvtt(std::ceil(tex_u + box_u));
    const int32_t v0 = cvtt(std::floor(tex_v - box_v)), v1 = cvtt(std::ceil(tex_v + box_v));
    const float uf = float(u0) - tex_u;
    const float dq_base = (uf * 2.0f + 1.0f) * a;
    const float q_base = (uf * uf) * a;
    const std::array<float, kWeights>& table = aniso_weights();
    Vec4 sum{0, 0, 0, 0};
    float den = 0.0f;
    const int64_t probes = (int64_t(u1) - u0 + 1) * (int64_t(v1) - v0 + 1);
    if (probes > kMaxProbes) {
        static std::atomic<bool> said{false};
        if (!said.exchange(true))
            std::fprintf(stderr,
                         "tilevk: samplerAnisotropy: a footprint of over 2^24 texels is filtered bilinearly at its "
                         "level instead (lavapipe probes every texel of it)\n");
    }
    // the loops run at least once (lavapipe's do-while); a probe outside [u0, u1] x [v0, v1] weighs nothing
    for (int64_t v = v0; probes <= kMaxProbes && (v == v0 || v <= v1); ++v) {
        const float vf = float(int32_t(v)) - tex_v;
        float dq = vf * b + dq_base;
        float q = (c * vf + b * uf) * vf + q_base;
        for (int64_t u = u0; u == u0 || u <= u1; ++u) {
            const int32_t qi = cvtt(q);
            const bool inside = qi <= kWeights - 1 && u <= u1 && v <= v1;
            const float weight = inside ? table[size_t(std::max(qi, 0) & (kWeights - 1))] : 0.0f;
            if (weight != 0.0f) {
                // a nearest lookup at the texel's corner, in normalized coordinates of the level
                const Vec4 texel = sample_level(img, smp, lv, layer, float(int32_t(u)) / wl, float(int32_t(v)) / hl,
                                                false, false, args);
                for (int ch = 0; ch < 4; ++ch) sum[size_t(ch)] = sum[size_t(ch)] + texel[size_t(ch)] * weight;
                den = den + weight;
            }
            q = q + dq;
            dq = dq + ddq;
        }
    }
    if (den == 0.0f) return sample_level(img, smp, lv, layer, s, t, true, false, args);  // no probe weighed
    for (float& ch : sum) ch = ch / den;
    return sum;
}

}  // namespace tilevk::shader::tex
