// The clipper in extended precision, for the triangles that lavapipe's float clipper provably gets wrong
// (rast/geometry/README.md, "Extreme coordinates"; clip.h clip_triangle_precise). The algorithm is draw's
// (Sutherland-Hodgman over the set planes in bit order, interpolating from the vertex nearer the plane, the fan
// re-emitted from the first vertex), but positions and plane distances are 237-bit binary floats with an exponent
// range far beyond float's: the distances of float inputs are exact and an intersection's error is about 2^-237 of
// the inputs' magnitude, so nothing overflows, flushes or cancels out. Only the results are rounded to float.
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <cstring>

#include "rast/core/fixed_point.h"
#include "rast/geometry/clip.h"

namespace tilevk::rast::geometry {
namespace {

using Real =
    boost::multiprecision::number<boost::multiprecision::cpp_bin_float<237, boost::multiprecision::digit_base_2>,
                                  boost::multiprecision::et_off>;

constexpr float kPlanes[6][4] = {
    {-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1},
};

// A polygon vertex: the extended-precision clip position and the float record the clipper writes for it (the
// input record, or a scratch one whose attributes are interpolated).
// NOLINTNEXTLINE(bugprone-reserved-identifier): clang-tidy 14 names the loop of the implicit array copy, not ours
struct PreciseVertex {
    Real pos[4];
    const float* record;
};

Real distance(const Real pos[4], uint32_t plane, bool clip_halfz) {
    const float* p = kPlanes[plane];
    const float w = plane == 4 && clip_halfz ? 0.0f : p[3];
    return pos[0] * Real(p[0]) + pos[1] * Real(p[1]) + pos[2] * Real(p[2]) + pos[3] * Real(w);
}

float to_float(const Real& r) {
    return r.convert_to<float>();
}

}  // namespace

bool clip_inputs_finite(const float* v0, const float* v1, const float* v2) {
    for (const float* vert : {v0, v1, v2}) {
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(clip_pos(vert)[c])) return false;  // no exact answer: lavapipe's result stands
        // |w| >= 2^126: lavapipe's FTZ flushes 1/w and puts the vertex on the viewport's centre; that float
        // environment defines the vertex, and tilevk follows it (rast/geometry/README.md, "Extreme coordinates").
        // Unless x, y and z are so small beside w (at most 2^-64 |w|) that the exact projection is the centre too,
        // within 2^-49 px on any viewport: then the answer is exact either way (seeds 2215 and 6638).
        const float w = std::fabs(clip_pos(vert)[3]);
        const float centred = w * 0x1p-64f;
        if (w >= 0x1p126f && !(std::fabs(clip_pos(vert)[0]) <= centred && std::fabs(clip_pos(vert)[1]) <= centred &&
                               std::fabs(clip_pos(vert)[2]) <= centred))
            return false;
    }
    return true;
}

bool clip_needs_precision(const float* v0, const float* v1, const float* v2, const ClippedTriangle* out, uint32_t n) {
    for (uint32_t t = 0; t < n; ++t) {
        for (int k = 0; k < 3; ++k) {
            const float* w = win_pos(out[t].v[k]);
            const float* u = win_pos(out[t].v[(k + 1) % 3]);
            // Past llvmpipe's 2^31 fixed-point snap (cvtps2dq gives INT_MIN there) or not finite, or an edge its
            // 32-bit plane values cannot hold (rast/core/setup.cpp: |DX| + |DY| >= 2^23 fixed).
            if (!(std::fabs(w[0]) < kMaxLavapipePixels && std::fabs(w[1]) < kMaxLavapipePixels) ||
                !(std::fabs(w[0] - u[0]) + std::fabs(w[1] - u[1]) < kMaxLavapipeEdgePixels))
                return clip_inputs_finite(v0, v1, v2);
        }
    }
    return false;
}

uint32_t clip_triangle_precise(const ClipConfig& cfg, const float* v0, const float* v1, const float* v2,
                               uint32_t clipmask, float* scratch, ClippedTriangle* out) {
    const uint32_t stride = vertex_floats(cfg.layout);
    PreciseVertex a[kMaxClippedVertices], b[kMaxClippedVertices];
    PreciseVertex* in = a;
    PreciseVertex* outl = b;
    const float* v[3] = {v0, v1, v2};
    for (int i = 0; i < 3; ++i) {
        for (int c = 0; c < 4; ++c) in[i].pos[c] = Real(clip_pos(v[i])[c]);
        in[i].record = v[i];
    }
    uint32_t n = 3, tmpnr = 0;
    clipmask &= 0x3Fu;
    while (clipmask && n >= 3) {
        const uint32_t plane = static_cast<uint32_t>(__builtin_ctz(clipmask));
        clipmask &= ~(1u << plane);
        if (n >= kMaxClippedVertices) return 0;
        in[n] = in[0];
        uint32_t outcount = 0;
        PreciseVertex* prev = &in[0];
        Real dp_prev = distance(prev->pos, plane, cfg.clip_halfz);
        for (uint32_t i = 1; i <= n; ++i) {
            PreciseVertex* cur = &in[i];
            const Real dp = distance(cur->pos, plane, cfg.clip_halfz);
            bool different_sign;
            if (dp_prev >= 0) {
                if (outcount >= kMaxClippedVertices) return 0;
                outl[outcount++] = *prev;
                different_sign = dp < 0;
            } else {
                different_sign = !(dp < 0);
            }
            if (different_sign) {
                if (tmpnr >= kClipScratchVertices || outcount >= kMaxClippedVertices) return 0;
                float* rec = scratch + static_cast<size_t>(stride) * tmpnr++;
                // From the vertex nearer the plane (draw's choice): dst = from + t * (to - from).
                const bool going_out = dp < 0;
                const bool from_cur = going_out ? -dp < dp_prev : !(-dp_prev < dp);
                const PreciseVertex& from = from_cur ? *cur : *prev;
                const PreciseVertex& to = from_cur ? *prev : *cur;
                const Real t = from_cur ? dp / (dp - dp_prev) : -dp_prev / (dp - dp_prev);
                PreciseVertex nv;
                for (int c = 0; c < 4; ++c) nv.pos[c] = from.pos[c] + t * (to.pos[c] - from.pos[c]);
                // The record: clip position and window coordinates rounded from the exact values; attributes
                // interpolated with t rounded to float (perspective and noperspective alike: screen and clip t
                // agree to float precision for such vertices), flat ones from `from`.
                std::memcpy(rec, from.record, sizeof(float) * stride);
                const float tf = to_float(t);
                for (uint32_t s = 0; s < cfg.layout.num_attribs; ++s) {
                    if (cfg.layout.interp[s] == Interp::kFlat) continue;
                    float* d = rec + kAttribOffset + 4 * s;
                    const float* fa = attrib(from.record, s);
                    const float* ta = attrib(to.record, s);
                    for (int c = 0; c < 4; ++c) d[c] = fa[c] + tf * (ta[c] - fa[c]);
                }
                float* cp = rec + kClipPosOffset;
                float* wp = rec + kWinPosOffset;
                for (int c = 0; c < 4; ++c) cp[c] = to_float(nv.pos[c]);
                const Real oow = Real(1) / nv.pos[3];
                for (int c = 0; c < 3; ++c)
                    wp[c] = to_float(nv.pos[c] * oow * Real(cfg.vp.scale[c]) + Real(cfg.vp.translate[c]));
                wp[3] = to_float(oow);
                nv.record = rec;
                outl[outcount++] = nv;
            }
            prev = cur;
            dp_prev = dp;
        }
        std::swap(in, outl);
        n = outcount;
    }
    if (n < 3) return 0;
    const float* provoking = cfg.flatshade_first ? v0 : v2;
    const float* first = in[0].record;
    bool flat = false;
    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) flat |= cfg.layout.interp[i] == Interp::kFlat;
    if (flat && first != provoking) {
        if (tmpnr >= kClipScratchVertices) return 0;
        float* dup = scratch + static_cast<size_t>(stride) * tmpnr++;
        std::memcpy(dup, first, sizeof(float) * stride);
        for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i)
            if (cfg.layout.interp[i] == Interp::kFlat)
                std::memcpy(dup + kAttribOffset + 4 * i, attrib(provoking, i), 16);
        first = dup;
    }
    uint32_t count = 0;
    for (uint32_t i = 2; i < n; ++i) {
        if (cfg.flatshade_first)
            out[count++] = {{first, in[i - 1].record, in[i].record}, kAllEdges};
        else
            out[count++] = {{in[i - 1].record, in[i].record, first}, kAllEdges};
    }
    return count;
}

}  // namespace tilevk::rast::geometry
