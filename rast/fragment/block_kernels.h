// The hot per-4x4-block kernels of the fragment stage, each as a scalar twin and an AVX2 version that give
// identical bytes (tests/rast/fragment/kernel_test.cpp checks every pair, NaN/Inf/denormals included):
//   eval_planes   a = fmuladd(dady, py, fmuladd(dadx, px, a0)) for one block's lane coordinates (interp.h rules)
//   reciprocal    oow = fl(1/w), computed once per block and reused by every perspective input: a * oow
//   depth_block   D16 / D32F depth test (+ write) of 16 lanes, no stencil: depth_stencil_test's rules exactly
//   store_rgba8   opaque RGBA8 / BGRA8 UNORM write (blend off, all channels): float_to_unorm8's rules exactly
// All work in the shader's lane order (block.h); memory stays raster order, converted with 64-bit unpacks:
//   row 0 = lanes {0,1,4,5}, row 1 = {2,3,6,7}, row 2 = {8,9,12,13}, row 3 = {10,11,14,15}.
#pragma once

#include "rast/core/isa.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "rast/fragment/block.h"
#include "rast/fragment/color.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/interp.h"

#if TILEVK_SIMD_AVX2
#include <immintrin.h>
#endif

namespace tilevk::rast::fragment {

// ---------------------------------------------------------------------------------------------------------------
// Interpolation

// The float pixel coordinates of a block's 16 lanes (interp.h lane_coords), computed once per block.
struct alignas(32) LaneCoords {
    float x[kBlockLanes];
    float y[kBlockLanes];
};

inline constexpr float kLaneXf[kBlockLanes] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
inline constexpr float kLaneYf[kBlockLanes] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};

TILEVK_KERNEL void eval_plane_scalar(const Plane& p, const LaneCoords& c, bool fused, float out[kBlockLanes]) {
    for (int l = 0; l < kBlockLanes; ++l) {
        // a = fmuladd(dady, py, fmuladd(dadx, px, a0))
        const float a = fused ? std::fma(p.dadx, c.x[l], p.a0) : p.dadx * c.x[l] + p.a0;
        out[l] = fused ? std::fma(p.dady, c.y[l], a) : p.dady * c.y[l] + a;
    }
}

// oow = fl(1 / w) per lane.
TILEVK_KERNEL void reciprocal_scalar(const float w[kBlockLanes], float oow[kBlockLanes]) {
    for (int l = 0; l < kBlockLanes; ++l) oow[l] = 1.0f / w[l];
}

// a = fl(a * oow) per lane (perspective_divide with the reciprocal hoisted; the same two roundings).
TILEVK_KERNEL void mul_lanes_scalar(float a[kBlockLanes], const float oow[kBlockLanes]) {
    for (int l = 0; l < kBlockLanes; ++l) a[l] = a[l] * oow[l];
}

#if TILEVK_SIMD_AVX2
TILEVK_KERNEL void eval_plane_avx2(const Plane& p, const LaneCoords& c, bool fused, float out[kBlockLanes]) {
    const __m256 dadx = _mm256_set1_ps(p.dadx), dady = _mm256_set1_ps(p.dady), a0 = _mm256_set1_ps(p.a0);
    for (int h = 0; h < kBlockLanes; h += 8) {
        const __m256 px = _mm256_load_ps(c.x + h), py = _mm256_load_ps(c.y + h);
        __m256 a;
        if (fused) {
            a = _mm256_fmadd_ps(dady, py, _mm256_fmadd_ps(dadx, px, a0));
        } else {
            // -ffp-contract=off keeps these two roundings apart
            a = _mm256_add_ps(_mm256_mul_ps(dadx, px), a0);
            a = _mm256_add_ps(_mm256_mul_ps(dady, py), a);
        }
        _mm256_storeu_ps(out + h, a);
    }
}

TILEVK_KERNEL void reciprocal_avx2(const float w[kBlockLanes], float oow[kBlockLanes]) {
    const __m256 one = _mm256_set1_ps(1.0f);
    for (int h = 0; h < kBlockLanes; h += 8) _mm256_storeu_ps(oow + h, _mm256_div_ps(one, _mm256_loadu_ps(w + h)));
}

// a * oow with the reference's NaN choice: when both are NaN the result is oow's (quieted), as the scalar loop's
// VMULSS (oow first) returns it. A plain _mm256_mul_ps would leave that to the compiler's operand order.
TILEVK_KERNEL __m256 mul_oow(__m256 a, __m256 oow) {
    const __m256 oow_nan = _mm256_cmp_ps(oow, oow, _CMP_UNORD_Q);
    const __m256 quiet = _mm256_or_ps(oow, _mm256_castsi256_ps(_mm256_set1_epi32(0x00400000)));
    return _mm256_blendv_ps(_mm256_mul_ps(a, oow), quiet, oow_nan);
}

TILEVK_KERNEL void mul_lanes_avx2(float a[kBlockLanes], const float oow[kBlockLanes]) {
    for (int h = 0; h < kBlockLanes; h += 8)
        _mm256_storeu_ps(a + h, mul_oow(_mm256_loadu_ps(a + h), _mm256_loadu_ps(oow + h)));
}
#endif

// lane coordinates: px = fl(fl(lane_x) + fl(block_x)) + off.x (exact for |coords| < 2^22)
TILEVK_KERNEL void make_lane_coords(int block_x, int block_y, EvalOffset off, LaneCoords& c) {
    const float bx = float(block_x), by = float(block_y);
    for (int l = 0; l < kBlockLanes; ++l) {
        c.x[l] = (kLaneXf[l] + bx) + off.x;
        c.y[l] = (kLaneYf[l] + by) + off.y;
    }
}

TILEVK_KERNEL void eval_plane_fast(const Plane& p, const LaneCoords& c, bool fused, float out[kBlockLanes]) {
#if TILEVK_SIMD_AVX2
    eval_plane_avx2(p, c, fused, out);
#else
    eval_plane_scalar(p, c, fused, out);
#endif
}
TILEVK_KERNEL void reciprocal_fast(const float w[kBlockLanes], float oow[kBlockLanes]) {
#if TILEVK_SIMD_AVX2
    reciprocal_avx2(w, oow);
#else
    reciprocal_scalar(w, oow);
#endif
}

// One shader input component straight into the shader's lane words (float bits): eval_plane, then * oow when
// `oow` is not null (perspective). The AVX2 form stores through may_alias vector types; the scalar form copies.
TILEVK_KERNEL void interpolate_input(const Plane& p, const LaneCoords& c, bool fused, const float* oow,
                                     uint32_t out[kBlockLanes]) {
#if TILEVK_SIMD_AVX2
    const __m256 dadx = _mm256_set1_ps(p.dadx), dady = _mm256_set1_ps(p.dady), a0 = _mm256_set1_ps(p.a0);
    for (int h = 0; h < kBlockLanes; h += 8) {
        const __m256 px = _mm256_load_ps(c.x + h), py = _mm256_load_ps(c.y + h);
        __m256 a = fused ? _mm256_fmadd_ps(dady, py, _mm256_fmadd_ps(dadx, px, a0))
                         : _mm256_add_ps(_mm256_mul_ps(dady, py), _mm256_add_ps(_mm256_mul_ps(dadx, px), a0));
        if (oow) a = mul_oow(a, _mm256_loadu_ps(oow + h));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + h), _mm256_castps_si256(a));
    }
#else
    float a[kBlockLanes];
    eval_plane_scalar(p, c, fused, a);
    if (oow) mul_lanes_scalar(a, oow);
    std::memcpy(out, a, sizeof a);
#endif
}

// ---------------------------------------------------------------------------------------------------------------
// Depth without stencil

// A depth state the fast kernels handle: depth test on, no stencil test, a D16 or D32F plane.
struct DepthFast {
    const DepthStencilState* state = nullptr;  // the full state (the scalar twin reuses depth_stencil.h's rules)
    DepthFormat format = DepthFormat::D32F;
    CompareOp op = CompareOp::Less;
    bool write = false;      // state->depth_write
    bool restrict01 = true;  // clamp to [0, 1] (all but unrestricted D32F)
    bool clamp = false;      // depthClamp to [min_depth, max_depth]
    float min_depth = 0.0f, max_depth = 1.0f;
};

// True when `s` with format `f` can use the kernels below.
TILEVK_KERNEL bool depth_fast_supported(const DepthStencilState& s, DepthFormat f) {
    return s.depth_test && !s.stencil_test && (f == DepthFormat::D16 || f == DepthFormat::D32F);
}

TILEVK_KERNEL DepthFast make_depth_fast(const DepthStencilState& s, DepthFormat f) {
    DepthFast d;
    d.state = &s;
    d.format = f;
    d.op = s.depth_compare;
    d.write = s.depth_write;
    d.restrict01 = !(s.unrestricted_depth && f == DepthFormat::D32F);
    d.clamp = s.depth_clamp;
    d.min_depth = s.min_depth;
    d.max_depth = s.max_depth;
    return d;
}

// Tests the lanes of `mask` of the block whose texel (0,0) is at `origin` (rows `pitch` bytes apart) against the
// stored depth; with `write` (and depth writes enabled) passing lanes store their depth. Returns the passing lanes.
// Only texels of `mask` lanes are touched. Equals depth_stencil_test with the stencil test off.
TILEVK_KERNEL uint16_t depth_block_scalar(const DepthFast& d, const float z[kBlockLanes], uint16_t mask,
                                          uint8_t* origin, size_t pitch, bool write) {
    const size_t bytes = d.format == DepthFormat::D16 ? 2 : 4;
    uint16_t pass = 0;
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(mask & (1u << l))) continue;
        uint8_t* texel = origin + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * bytes;
        uint32_t stored = 0;
        std::memcpy(&stored, texel, bytes);
        const uint32_t src = depth_to_stored(clamp_depth(z[l], *d.state, d.format), d.format);
        bool ok;
        if (d.format == DepthFormat::D32F) {
            float a, b;
            std::memcpy(&a, &src, 4);
            std::memcpy(&b, &stored, 4);
            ok = compare_float(d.op, a, b);
        } else {
            ok = compare(d.op, src, stored);
        }
        if (!ok) continue;
        pass |= uint16_t(1u << l);
        if (write && d.write) std::memcpy(texel, &src, bytes);
    }
    return pass;
}

#if TILEVK_SIMD_AVX2
namespace detail {
// Lanes of `bits` (8 lanes from bit 0) as an all-ones / zero vector.
TILEVK_KERNEL __m256i lane_mask8(uint32_t bits) {
    const __m256i sel = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(bits)), sel), sel);
}
// Denormals (not zero) -> +0, as the DAZ clamps and compares see them.
TILEVK_KERNEL __m256 daz(__m256 v) {
    const __m256 abs = _mm256_and_ps(v, _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff)));
    const __m256 tiny = _mm256_cmp_ps(abs, _mm256_set1_ps(0x1p-126f), _CMP_LT_OQ);
    const __m256 nonzero = _mm256_cmp_ps(v, _mm256_setzero_ps(), _CMP_NEQ_UQ);
    return _mm256_andnot_ps(_mm256_and_ps(tiny, nonzero), v);
}
// a OP b on floats, unordered (NaN passes all but NEVER), as compare_float after DAZ.
TILEVK_KERNEL __m256 compare_ps(CompareOp op, __m256 a, __m256 b) {
    switch (op) {
        case CompareOp::Never:
            return _mm256_setzero_ps();
        case CompareOp::Less:
            return _mm256_cmp_ps(a, b, _CMP_NGE_UQ);
        case CompareOp::Equal:
            return _mm256_cmp_ps(a, b, _CMP_EQ_UQ);
        case CompareOp::LessOrEqual:
            return _mm256_cmp_ps(a, b, _CMP_NGT_UQ);
        case CompareOp::Greater:
            return _mm256_cmp_ps(a, b, _CMP_NLE_UQ);
        case CompareOp::NotEqual:
            return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ);
        case CompareOp::GreaterOrEqual:
            return _mm256_cmp_ps(a, b, _CMP_NLT_UQ);
        case CompareOp::Always:
            break;
    }
    return _mm256_castsi256_ps(_mm256_set1_epi32(-1));
}
// a OP b on non-negative int32 (D16 values < 2^16: the signed compares are the unsigned ones).
TILEVK_KERNEL __m256i compare_epi32(CompareOp op, __m256i a, __m256i b) {
    const __m256i ones = _mm256_set1_epi32(-1);
    switch (op) {
        case CompareOp::Never:
            return _mm256_setzero_si256();
        case CompareOp::Less:
            return _mm256_cmpgt_epi32(b, a);
        case CompareOp::Equal:
            return _mm256_cmpeq_epi32(a, b);
        case CompareOp::LessOrEqual:
            return _mm256_xor_si256(_mm256_cmpgt_epi32(a, b), ones);
        case CompareOp::Greater:
            return _mm256_cmpgt_epi32(a, b);
        case CompareOp::NotEqual:
            return _mm256_xor_si256(_mm256_cmpeq_epi32(a, b), ones);
        case CompareOp::GreaterOrEqual:
            return _mm256_xor_si256(_mm256_cmpgt_epi32(b, a), ones);
        case CompareOp::Always:
            break;
    }
    return ones;
}
}  // namespace detail

// All 16 texels of the block must exist (the caller checks the framebuffer edge): whole rows are read and, when
// a lane passes with writes on, written back (unchanged texels keep their bytes). Specialised on the format and the
// compare op (depth_block_avx2 dispatches), so that a block is one straight sequence of vector operations.
// kRaster: `z` and `mask` are in raster order (lane 4 * row + column, fragment_block.cpp's fused 1x blocks), so
// each half is two whole rows as they lie in memory; otherwise the shader's lane order (block.h).
template <bool kD16, CompareOp kOp, bool kRaster = false>
TILEVK_KERNEL uint16_t depth_block_avx2_op(const DepthFast& d, const float z[kBlockLanes], uint16_t mask,
                                           uint8_t* origin, size_t pitch, bool write) {
    __m256i stored[2];
#pragma GCC unroll 2  // both halves in registers: rolled, GCC kept stored/src/pass_v on the stack
    for (int h = 0; h < 2; ++h) {
        const uint8_t* row0 = origin + size_t(2 * h) * pitch;
        if constexpr (kD16) {
            // rows of 4 x u16; lane order: unpacklo_epi32(row0, row1) = lanes 0..7 in u16; raster: row0, row1
            const __m128i r0 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(row0));
            const __m128i r1 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(row0 + pitch));
            stored[h] = _mm256_cvtepu16_epi32(kRaster ? _mm_unpacklo_epi64(r0, r1) : _mm_unpacklo_epi32(r0, r1));
        } else {
            const __m128i r0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row0));
            const __m128i r1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row0 + pitch));
            stored[h] = kRaster ? _mm256_set_m128i(r1, r0)
                                : _mm256_set_m128i(_mm_unpackhi_epi64(r0, r1), _mm_unpacklo_epi64(r0, r1));
        }
    }
    // After the DAZ and the [0, 1] clamp (max(min(z, 1), 0) turns NaN into 1) z is no denormal, so the compare's own
    // DAZ of it is needed only where no clamp ran, or where depthClamp's bounds (viewport floats) might be denormal.
    const bool daz_z = !d.restrict01 || d.clamp;
    const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
    __m256i src[2], pass_v[2];
    uint32_t pass = 0;
#pragma GCC unroll 2  // both halves in registers: rolled, GCC kept stored/src/pass_v on the stack
    for (int h = 0; h < 2; ++h) {
        __m256 v = _mm256_loadu_ps(z + 8 * h);
        // clamp_depth: DAZ, then max(min(z, 1), 0), then max(min(z, max_depth), min_depth) (SSE NaN rules)
        if (d.restrict01 || d.clamp) v = detail::daz(v);
        if (d.restrict01) v = _mm256_max_ps(_mm256_min_ps(v, one), zero);
        if (d.clamp) v = _mm256_max_ps(_mm256_min_ps(v, _mm256_set1_ps(d.max_depth)), _mm256_set1_ps(d.min_depth));
        __m256i ok;
        if constexpr (kD16) {
            // t = fl(z * (65535/65536)); bits(fl(t + 128)) & 0xffff
            const __m256 t = _mm256_mul_ps(v, _mm256_set1_ps(65535.0f / 65536.0f));
            src[h] = _mm256_and_si256(_mm256_castps_si256(_mm256_add_ps(t, _mm256_set1_ps(128.0f))),
                                      _mm256_set1_epi32(0xffff));
            ok = detail::compare_epi32(kOp, src[h], stored[h]);
        } else {
            src[h] = _mm256_castps_si256(v);
            ok = _mm256_castps_si256(
                detail::compare_ps(kOp, daz_z ? detail::daz(v) : v, detail::daz(_mm256_castsi256_ps(stored[h]))));
        }
        pass_v[h] = _mm256_and_si256(ok, detail::lane_mask8((mask >> (8 * h)) & 0xffu));
        pass |= uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(pass_v[h]))) << (8 * h);
    }
    if (write && d.write && pass) {
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            const __m256i v = _mm256_blendv_epi8(stored[h], src[h], pass_v[h]);
            const __m128i lo = _mm256_castsi256_si128(v), hi = _mm256_extracti128_si256(v, 1);
            uint8_t* row0 = origin + size_t(2 * h) * pitch;
            uint8_t* row1 = row0 + pitch;
            if constexpr (kD16) {
                // back to u16 (values < 2^16), lanes {0,1,4,5} -> row 0, {2,3,6,7} -> row 1 (raster: 0..3, 4..7)
                const __m128i p = _mm_packus_epi32(lo, hi);  // lanes 0..7 as u16
                const __m128i rows = kRaster ? p : _mm_shuffle_epi32(p, _MM_SHUFFLE(3, 1, 2, 0));
                _mm_storel_epi64(reinterpret_cast<__m128i*>(row0), rows);
                _mm_storel_epi64(reinterpret_cast<__m128i*>(row1), _mm_unpackhi_epi64(rows, rows));
            } else if constexpr (kRaster) {
                _mm_storeu_si128(reinterpret_cast<__m128i*>(row0), lo);
                _mm_storeu_si128(reinterpret_cast<__m128i*>(row1), hi);
            } else {
                _mm_storeu_si128(reinterpret_cast<__m128i*>(row0), _mm_unpacklo_epi64(lo, hi));
                _mm_storeu_si128(reinterpret_cast<__m128i*>(row1), _mm_unpackhi_epi64(lo, hi));
            }
        }
    }
    return uint16_t(pass);
}

template <bool kD16, bool kRaster>
TILEVK_KERNEL uint16_t depth_block_avx2_format(const DepthFast& d, const float z[kBlockLanes], uint16_t mask,
                                               uint8_t* origin, size_t pitch, bool write) {
    switch (d.op) {
        case CompareOp::Never:
            return depth_block_avx2_op<kD16, CompareOp::Never, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::Less:
            return depth_block_avx2_op<kD16, CompareOp::Less, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::Equal:
            return depth_block_avx2_op<kD16, CompareOp::Equal, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::LessOrEqual:
            return depth_block_avx2_op<kD16, CompareOp::LessOrEqual, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::Greater:
            return depth_block_avx2_op<kD16, CompareOp::Greater, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::NotEqual:
            return depth_block_avx2_op<kD16, CompareOp::NotEqual, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::GreaterOrEqual:
            return depth_block_avx2_op<kD16, CompareOp::GreaterOrEqual, kRaster>(d, z, mask, origin, pitch, write);
        case CompareOp::Always:
            break;
    }
    return depth_block_avx2_op<kD16, CompareOp::Always, kRaster>(d, z, mask, origin, pitch, write);
}

TILEVK_KERNEL uint16_t depth_block_avx2(const DepthFast& d, const float z[kBlockLanes], uint16_t mask, uint8_t* origin,
                                        size_t pitch, bool write) {
    return d.format == DepthFormat::D16 ? depth_block_avx2_format<true, false>(d, z, mask, origin, pitch, write)
                                        : depth_block_avx2_format<false, false>(d, z, mask, origin, pitch, write);
}

// depth_block_avx2 with `z`, `mask` and the result in raster order (bit 4 * row + column).
TILEVK_KERNEL uint16_t depth_block_raster_avx2(const DepthFast& d, const float z[kBlockLanes], uint16_t mask,
                                               uint8_t* origin, size_t pitch, bool write) {
    return d.format == DepthFormat::D16 ? depth_block_avx2_format<true, true>(d, z, mask, origin, pitch, write)
                                        : depth_block_avx2_format<false, true>(d, z, mask, origin, pitch, write);
}
#endif

// `inside`: all 16 texels of the block exist (else the scalar twin, which touches only `mask` lanes, runs).
TILEVK_KERNEL uint16_t depth_block_fast(const DepthFast& d, const float z[kBlockLanes], uint16_t mask, uint8_t* origin,
                                        size_t pitch, bool write, bool inside) {
#if TILEVK_SIMD_AVX2
    if (inside) return depth_block_avx2(d, z, mask, origin, pitch, write);
#endif
    (void)inside;
    return depth_block_scalar(d, z, mask, origin, pitch, write);
}

// ---------------------------------------------------------------------------------------------------------------
// Opaque RGBA8 / BGRA8 store

// The lanes of `mask` get float_to_unorm8(src) of every channel (bgra: stored B, G, R, A).
TILEVK_KERNEL void store_rgba8_scalar(bool bgra, const float src[4][kBlockLanes], uint16_t mask, uint8_t* origin,
                                      size_t pitch, UnormPath path) {
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(mask & (1u << l))) continue;
        uint8_t* px = origin + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * 4;
        const uint8_t r = float_to_unorm8(src[0][l], path), g = float_to_unorm8(src[1][l], path),
                      b = float_to_unorm8(src[2][l], path), a = float_to_unorm8(src[3][l], path);
        px[0] = bgra ? b : r;
        px[1] = g;
        px[2] = bgra ? r : b;
        px[3] = a;
    }
}

#if TILEVK_SIMD_AVX2
namespace detail {
// u8 = packus(packs(cvtps2dq(fl(min(1, x) * 255)))): float_to_unorm8 with UnormPath::Avx8.
TILEVK_KERNEL __m256i unorm8_lanes(__m256 x) {
    return _mm256_cvtps_epi32(_mm256_mul_ps(_mm256_min_ps(_mm256_set1_ps(1.0f), x), _mm256_set1_ps(255.0f)));
}
// Eight lanes of RGBA floats -> 32 bytes of pixels in memory order (R G B A, or B G R A), lane i at byte 4 * i.
// Four named vectors rather than an array: GCC keeps an array of vectors on the stack, and the packs then wait on
// store forwarding.
TILEVK_KERNEL __m256i pack_row8(bool bgra, __m256 r, __m256 g, __m256 b, __m256 a) {
    // bytes r0..r3 g0..g3 b0..b3 a0..a3 (per 128-bit half) -> pixels r g b a (or b g r a)
    const __m256i order = bgra ? _mm256_setr_epi8(8, 4, 0, 12, 9, 5, 1, 13, 10, 6, 2, 14, 11, 7, 3, 15, 8, 4, 0, 12, 9,
                                                  5, 1, 13, 10, 6, 2, 14, 11, 7, 3, 15)
                               : _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 0, 4, 8, 12, 1,
                                                  5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
    const __m256i rg = _mm256_packs_epi32(unorm8_lanes(r), unorm8_lanes(g));
    const __m256i ba = _mm256_packs_epi32(unorm8_lanes(b), unorm8_lanes(a));
    return _mm256_shuffle_epi8(_mm256_packus_epi16(rg, ba), order);
}

// The block's source colours as UNORM8 pixels in memory order, raster rows 0..3.
TILEVK_KERNEL void pack_rgba8_rows(bool bgra, const float src[4][kBlockLanes], __m128i rows[4]) {
    for (int h = 0; h < 2; ++h) {
        const __m256i px = pack_row8(bgra, _mm256_loadu_ps(src[0] + 8 * h), _mm256_loadu_ps(src[1] + 8 * h),
                                     _mm256_loadu_ps(src[2] + 8 * h), _mm256_loadu_ps(src[3] + 8 * h));
        // lanes 0..3 = (0,0) (1,0) (0,1) (1,1), lanes 4..7 = (2,0) (3,0) (2,1) (3,1)
        const __m128i lo = _mm256_castsi256_si128(px), hi = _mm256_extracti128_si256(px, 1);
        rows[2 * h] = _mm_unpacklo_epi64(lo, hi);
        rows[2 * h + 1] = _mm_unpackhi_epi64(lo, hi);
    }
}

// Row mask (bit i: pixel i of a row of four) -> the 32-bit lanes it selects: one load instead of three operations.
struct RowSelect {
    alignas(16) uint32_t lanes[16][4];
};
inline constexpr RowSelect kRowSelect = [] {
    RowSelect t{};
    for (uint32_t m = 0; m < 16; ++m)
        for (uint32_t i = 0; i < 4; ++i) t.lanes[m][i] = (m >> i) & 1u ? ~0u : 0u;
    return t;
}();
}  // namespace detail

// UnormPath::Avx8 only. `src` is read through may_alias vector loads only (pack_rgba8_rows), so it may be the
// shader's output lane words (rast/render/fragment_block.cpp). `inside`: all 16 pixels exist, so a partly covered row
// is read, merged and written back whole (VPMASKMOVD stores are microcoded and slow on some CPUs); otherwise masked
// stores touch only `mask` pixels.
// store_rgba8_rows_avx2 writes rows already packed by detail::pack_rgba8_rows: at 4x the samples of a block share
// one shader output, so the conversion runs once per block and the store once per sample.
// store_rgba8_raster_rows_avx2 takes the mask in raster order (bit 4*row + column), as the rasterizer hands it over.
TILEVK_KERNEL void store_rgba8_raster_rows_avx2(const __m128i rows[4], uint32_t raster, uint8_t* origin, size_t pitch,
                                                bool inside) {
    for (int r = 0; r < 4; ++r) {
        const uint32_t row_bits = (raster >> (4 * r)) & 0xfu;
        if (!row_bits) continue;
        uint8_t* dst = origin + size_t(r) * pitch;
        if (row_bits == 0xf) {
            _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), rows[r]);
            continue;
        }
        const __m128i m4 = _mm_load_si128(reinterpret_cast<const __m128i*>(detail::kRowSelect.lanes[row_bits]));
        if (inside) {
            const __m128i old = _mm_loadu_si128(reinterpret_cast<const __m128i*>(dst));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm_blendv_epi8(old, rows[r], m4));
        } else {
            _mm_maskstore_epi32(reinterpret_cast<int*>(dst), m4, rows[r]);
        }
    }
}

// store_rgba8_raster_rows_avx2 for a block inside the framebuffer without branches: the raster mask is widened to
// one 32-bit lane per pixel (broadcast, and with each lane's bit, compare) and every row is read, merged and written
// back, covered or not. For the 4x uniform store, whose blocks are mostly partial rows in a pattern the branches of
// the row loop could not predict; the rows a mask does not cover are written with the bytes read.
TILEVK_KERNEL void store_rgba8_raster_block_avx2(const __m128i rows[4], uint32_t raster, uint8_t* origin,
                                                 size_t pitch) {
    const __m256i m = _mm256_set1_epi32(static_cast<int>(raster));
    const __m256i bits01 = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i bits23 = _mm256_slli_epi32(bits01, 8);
    const __m256i m01 = _mm256_cmpeq_epi32(_mm256_and_si256(m, bits01), bits01);
    const __m256i m23 = _mm256_cmpeq_epi32(_mm256_and_si256(m, bits23), bits23);
    // Spelled out row by row: as a loop over an array of masks GCC kept the masks in memory and re-derived each one
    // with a compare.
    const auto merge = [&](int r, __m128i sel) {
        auto* dst = reinterpret_cast<__m128i*>(origin + size_t(r) * pitch);
        _mm_storeu_si128(dst, _mm_blendv_epi8(_mm_loadu_si128(dst), rows[r], sel));
    };
    merge(0, _mm256_castsi256_si128(m01));
    merge(1, _mm256_extracti128_si256(m01, 1));
    merge(2, _mm256_castsi256_si128(m23));
    merge(3, _mm256_extracti128_si256(m23, 1));
}

TILEVK_KERNEL void store_rgba8_rows_avx2(const __m128i rows[4], uint16_t mask, uint8_t* origin, size_t pitch,
                                         bool inside) {
    store_rgba8_raster_rows_avx2(rows, lanes_to_raster(mask), origin, pitch, inside);
}

TILEVK_KERNEL void store_rgba8_avx2(bool bgra, const float src[4][kBlockLanes], uint16_t mask, uint8_t* origin,
                                    size_t pitch, bool inside) {
    __m128i rows[4];
    detail::pack_rgba8_rows(bgra, src, rows);
    store_rgba8_rows_avx2(rows, mask, origin, pitch, inside);
}
#endif

TILEVK_KERNEL void store_rgba8_fast(bool bgra, const float src[4][kBlockLanes], uint16_t mask, uint8_t* origin,
                                    size_t pitch, UnormPath path, bool inside) {
#if TILEVK_SIMD_AVX2
    if (path == UnormPath::Avx8) return store_rgba8_avx2(bgra, src, mask, origin, pitch, inside);
#endif
    (void)inside;
    store_rgba8_scalar(bgra, src, mask, origin, pitch, path);
}

}  // namespace tilevk::rast::fragment
