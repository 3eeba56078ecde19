// Internal: per-tile plane state and the two hot kernels of the descent, each with a scalar and an AVX2 version
// that give identical results (tests/rast/core/kernel_test.cpp checks this).
//
// Units. Inside a tile every plane is evaluated on the pixel lattice in "pixel units": for sample s with offset
// (sx, sy), E(X,Y) = c + a*X + b*Y with X = px*256 + sx. Writing C_s = E at the tile origin pixel, and because
// E changes by a multiple of 256 per pixel, E > 0  <=>  ceil(C_s/256) + a*dx + b*dy > 0  (dx, dy pixel offsets
// from the tile origin). So c[s] = ceil(C_s/256) and the pixel steps are a and b themselves.
//
// Why 32 bits suffice inside a tile (tile size T <= 64): |a|, |b| < 2^23 (deltas of coordinates below 2^22).
// A plane is only kept for a tile when it neither accepts nor rejects the whole tile, i.e. its minimum over the
// tile's samples is <= 0 and its maximum is > 0. Across the tile its values span at most
//   (T-1)*(|a|+|b|) + (c_hi - c_lo) <= 63*(|a|+|b|) + (|a|+|b|)*192/256 + 1 < 64*2^24 = 2^30,
// so every value at any pixel/sample of the tile, and every block extreme (which is such a value), lies in
// (-2^30, 2^30]. Lane offsets a*dx + b*dy with dx, dy <= 63 are below 2^30 too, so no sum overflows.
#pragma once

#include "rast/core/isa.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#if TILEVK_SIMD_AVX2
#include <immintrin.h>
#endif

namespace tilevk::rast {

struct TilePlane {
    int32_t c[4];                   // value at the tile origin pixel, per sample (only c[0] is set at 1x)
    int32_t a, b;                   // pixel steps
    int32_t lo, hi;                 // min and max of c[] over samples
    int32_t up, dn;                 // max(a,0) + max(b,0) and min(a,0) + min(b,0): the extreme corner per pixel
    alignas(32) int32_t step[16];   // a*col + b*row for lane (col, row) = (i&3, i>>2): |step| < 3*2^24
    alignas(32) int32_t step4[16];  // step << 2: corner steps of the 4x4-px blocks of a 16x16 block (< 3*2^26; 4x only)
    // The 1x row-threshold kernel (block16_rows), filled by fill_row_table only where hier needs it. The plane is
    // stepped along x with a' = |a| >= 0: when a < 0 it is negated to r' = 1 - r (then "covered" = r' <= 0).
    alignas(32) int32_t rowb[16];  // b'*y, y in kRowOrder (b' = -b when negated): |.| < 15*2^23
    int32_t ra;                    // a' = |a|
    int32_t rflip;                 // -1 when negated (a < 0), else 0
    float rinv, roff;              // threshold estimate q = r'*rinv + roff (block16_rows' comment, row_inverse)
};

// Lane i of a 16-lane block grid: column i&3, row i>>2.
inline constexpr int32_t kLaneCol[16] = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3};
inline constexpr int32_t kLaneRow[16] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};

// Fills p->step, step4, up, dn from a, b (once per plane per tile; the levels reuse the tables). step4 is used at 4x
// only; kStep4 = false skips it (1x).
template <bool kStep4 = true>
TILEVK_KERNEL void fill_step_table_scalar(TilePlane* p) {
    p->up = (p->a > 0 ? p->a : 0) + (p->b > 0 ? p->b : 0);
    p->dn = (p->a < 0 ? p->a : 0) + (p->b < 0 ? p->b : 0);
    for (int i = 0; i < 16; ++i) {
        p->step[i] = p->a * kLaneCol[i] + p->b * kLaneRow[i];
        if constexpr (kStep4) p->step4[i] = p->step[i] * 4;
    }
}

#if TILEVK_SIMD_AVX2
// The same integer products and sums as the scalar loop, eight lanes at a time.
template <bool kStep4 = true>
TILEVK_KERNEL void fill_step_table_avx2(TilePlane* p) {
    p->up = (p->a > 0 ? p->a : 0) + (p->b > 0 ? p->b : 0);
    p->dn = (p->a < 0 ? p->a : 0) + (p->b < 0 ? p->b : 0);
    const __m256i a = _mm256_set1_epi32(p->a), b = _mm256_set1_epi32(p->b);
    const __m256i col = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3), row = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
    const __m256i s0 = _mm256_add_epi32(_mm256_mullo_epi32(a, col), _mm256_mullo_epi32(b, row));  // rows 0, 1
    const __m256i s1 = _mm256_add_epi32(s0, _mm256_add_epi32(b, b));                              // rows 2, 3
    _mm256_store_si256(reinterpret_cast<__m256i*>(p->step), s0);
    _mm256_store_si256(reinterpret_cast<__m256i*>(p->step + 8), s1);
    if constexpr (kStep4) {
        _mm256_store_si256(reinterpret_cast<__m256i*>(p->step4), _mm256_slli_epi32(s0, 2));
        _mm256_store_si256(reinterpret_cast<__m256i*>(p->step4 + 8), _mm256_slli_epi32(s1, 2));
    }
}
#endif

template <bool kStep4 = true>
TILEVK_KERNEL void fill_step_table(TilePlane* p) {
#if TILEVK_SIMD_AVX2
    fill_step_table_avx2<kStep4>(p);
#else
    fill_step_table_scalar<kStep4>(p);
#endif
}

// Row order of TilePlane::rowb and the row kernel's vectors: rows {0-3, 8-11} then {4-7, 12-15}, so that one
// packus_epi32 (which works per 128-bit half) of the two vectors yields the rows 0..15 in order.
inline constexpr int32_t kRowOrder[16] = {0, 1, 2, 3, 8, 9, 10, 11, 4, 5, 6, 7, 12, 13, 14, 15};

// The row kernel's reciprocal for a plane with x step a: -1/|a| to within 1.5*2^-12 relative (block16_rows' proof
// needs far less than that); a = 0: -64 (with roff = 33 in fill_row_table, the row is all covered (r' > 0) or all
// not: q <= -31 or q >= 33 for integer r'). With AVX2 it is the hardware estimate (rcpss, 4 cycles), not a division
// (11+ cycles once per plane and tile, on the path to every block's kernel); the portable build divides. The two can
// differ in rinv, never in a mask: the estimate only picks T_est, which the integer tests make exact.
TILEVK_KERNEL float row_inverse(int32_t a) {
    const int32_t ra = a < 0 ? -a : a;  // |a| < 2^23
    if (ra == 0) return -64.0f;
#if TILEVK_SIMD_AVX2
    return -_mm_cvtss_f32(_mm_rcp_ss(_mm_set_ss(static_cast<float>(ra))));
#else
    return -1.0f / static_cast<float>(ra);
#endif
}

// Fills the row-threshold fields (once per plane per tile, hier at 1x only; tile_setup does not touch them).
TILEVK_KERNEL void fill_row_table(TilePlane* p) {
    const int32_t flip = p->a < 0 ? -1 : 0;
    const int32_t b = (p->b ^ flip) - flip;  // -b when negated
    p->ra = (p->a ^ flip) - flip;
    p->rflip = flip;
    p->rinv = row_inverse(p->a);
    p->roff = p->ra != 0 ? 1.0f : 33.0f;
    for (int i = 0; i < 16; ++i) p->rowb[i] = b * kRowOrder[i];
}

// Classifies the 4x4 grid of sub-blocks of size 2^shift at tile-relative origin (ox, oy) against one plane:
// bit i of *reject: the plane's maximum over sub-block i is <= 0; bit i of *accept: its minimum is > 0.
// Corner value = base + (step[i] << shift) (one vector add over the step table), where base includes the extreme
// corner offset (2^shift - 1)*(max(a,0)+max(b,0)) (reject) or (2^shift - 1)*(min(a,0)+min(b,0)) (accept).
TILEVK_KERNEL void classify16_scalar(const TilePlane& p, int32_t ox, int32_t oy, int shift, uint32_t* reject,
                                     uint32_t* accept) {
    const int32_t origin = p.a * ox + p.b * oy;
    const int32_t hi = p.hi + origin + ((p.up << shift) - p.up);  // + (2^shift - 1)*up
    const int32_t lo = p.lo + origin + ((p.dn << shift) - p.dn);
    uint32_t rej = 0, acc = 0;
    for (int i = 0; i < 16; ++i) {
        const int32_t off = p.step[i] * (1 << shift);
        rej |= static_cast<uint32_t>(hi + off <= 0) << i;
        acc |= static_cast<uint32_t>(lo + off > 0) << i;
    }
    *reject = rej, *accept = acc;
}

// Pixel mask of one plane over a 4x4 block whose top-left pixel has value `base`: bit i set iff base + step[i] > 0.
TILEVK_KERNEL uint32_t plane_mask4x4_scalar(const TilePlane& p, int32_t base) {
    uint32_t bits = 0;
    for (int i = 0; i < 16; ++i) bits |= static_cast<uint32_t>(base + p.step[i] > 0) << i;
    return bits;
}

// Pixel mask of a 4x4 block at tile-relative (ox, oy) for sample s: bit (y*4+x) set iff c[s] + a*(ox+x) +
// b*(oy+y) > 0 for every plane.
TILEVK_KERNEL uint32_t mask4x4_scalar(const TilePlane* const* planes, int n, int s, int32_t ox, int32_t oy) {
    uint32_t m = 0xFFFF;
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        m &= plane_mask4x4_scalar(p, p.c[s] + p.a * ox + p.b * oy);
    }
    return m;
}

// 4x: the four samples' masks of one 4x4 block at tile-relative (ox, oy) in one call, packed with sample s in bits
// 16s..16s+15: mask4x4 for s = 0..3 (each plane's origin value and step table are read once for all four samples).
TILEVK_KERNEL uint64_t mask4x4_samples4_scalar(const TilePlane* const* planes, int n, int32_t ox, int32_t oy) {
    uint64_t m = 0;
    for (int s = 0; s < 4; ++s) m |= uint64_t{mask4x4_scalar(planes, n, s, ox, oy)} << (16 * s);
    return m;
}

// 1x, one 16x16-px block at once (the 16->4 level at one sample per pixel). base[k] = value of plane k at the
// block's top-left pixel. mask[lane] = coverage of the lane's 4x4 block (bit y*4+x set iff every plane is > 0 at
// that pixel); full / empty = the lanes whose mask is 0xFFFF / 0. Both versions do a fixed amount of work per
// block. Aligned for the one 32-byte load that hands the sixteen masks over (Block16, tile_raster.cpp).
struct Block16Masks {
    alignas(32) uint16_t mask[16];
    uint32_t full, empty;
};

TILEVK_KERNEL void block16_masks_scalar(const TilePlane* const* planes, int n, const int32_t* base, Block16Masks* out) {
    uint32_t full = 0, empty = 0;
    for (int lane = 0; lane < 16; ++lane) {
        uint32_t m = 0xFFFF;
        for (int k = 0; k < n; ++k) m &= plane_mask4x4_scalar(*planes[k], base[k] + planes[k]->step4[lane]);
        out->mask[lane] = static_cast<uint16_t>(m);
        full |= static_cast<uint32_t>(m == 0xFFFF) << lane;
        empty |= static_cast<uint32_t>(m == 0) << lane;
    }
    out->full = full, out->empty = empty;
}

// 1x, one 16x16 block by row thresholds (same contract and output as block16_masks). Per plane and row y, with
// r = r'(0, y) (the possibly negated plane value at the row's first pixel, see TilePlane::ra), the pixels x with
// r + a'x > 0 are exactly x >= T, T = floor(-r/a') + 1 (a' > 0), so the row's 16-bit mask is 0xFFFF << clamp(T, 0, 16)
// (complemented when negated: there "covered" is r + a'x <= 0, i.e. x < T). T comes from a float estimate made exact:
//   T_est = clamp(floor(fl(fl(r) * rinv + 1)), 1, 18), rinv = -1/a' (1 + e), |e| <= 1.5*2^-12 (row_inverse),
// then two exact integer tests: r + a'*(T_est - 1) > 0 (<=> T <= T_est - 1: use T_est - 1) and r + a'*T_est <= 0
// (<=> T > T_est: use T_est + 1). The result T' is T whenever |T_est - T| <= 1, and otherwise lies on T's side of
// [0, 16], so clamp(T', 0, 16) = clamp(T, 0, 16); and T' is in [0, 19], so no clamp is needed below 0. Why:
//  - if |r/a'| <= 20 then |r| < 21*2^23 < 2^28 and q = -r/a' + 1 has |q| <= 21; fl(r) and the one rounding of the
//    fma err by at most 2^-24 relative, rinv by 1.5*2^-12, so the estimate is within 21*(2*2^-24 + 1.5*2^-12) +
//    2^-24 < 0.01 of q, its floor
//    within 1 of floor(q) = T; the clamp only raises it to 1 when T <= 1 (if it ends 2 or more above T, T <= -1 and
//    the first test gives 0) and lowers it to 18 when T >= 17 (if it ends 2 or more below T, the second gives 19);
//  - if r/a' > 20 (T <= -20) the estimate is below 1 (-r/a' (1 + e) + 1 < -20*0.999 + 1, plus roundings):
//    T_est = 1, the first test holds, T' = 0; if r/a' < -20
//    (T > 20) it is above 18: T_est = 18, the second test holds, T' = 19 (both clamp as T does);
//  - a' = 0 (a row is all in or all out): rinv = -64, roff = 33 (fill_row_table) give T_est = 1 for r >= 1 (the
//    first test then holds: 0, all covered) and 18 for r <= 0 (the second holds: 19, none).
// 32-bit ranges: r is a plane value at a pixel of the block, within (-2^30 - 15*2^24, 2^30 + 15*2^24] (blocks and
// windows reach at most 15 px past the tile; negation adds 1); a'*T_est <= 18*2^23 < 2^28; so r + a'*T_est and
// r + a'*(T_est - 1) stay below 2^30 + 2^25 + 2^28 < 2^31. The rows' masks of the planes are ANDed, and the sixteen
// 16-bit rows are transposed into the sixteen 4x4 block masks (nibble x/4 of rows 4*by..4*by+3).
TILEVK_KERNEL uint32_t row_mask_scalar(const TilePlane& p, int32_t r) {
    float q = std::fma(static_cast<float>(r), p.rinv, p.roff);
    q = std::min(std::max(q, 1.0f), 18.0f);
    int32_t t = static_cast<int32_t>(q);
    const int32_t v = r + p.ra * t;
    t += static_cast<int32_t>(v <= 0) - static_cast<int32_t>(v - p.ra > 0);  // 0..19
    return ((0xFFFFu << t) ^ static_cast<uint32_t>(p.rflip)) & 0xFFFFu;
}

TILEVK_KERNEL void block16_rows_scalar(const TilePlane* const* planes, int n, const int32_t* base, Block16Masks* out) {
    uint32_t rows[16];
    for (int y = 0; y < 16; ++y) rows[y] = 0xFFFF;
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        const int32_t b0 = (base[k] ^ p.rflip) - 2 * p.rflip;  // 1 - base when negated
        for (int i = 0; i < 16; ++i) rows[kRowOrder[i]] &= row_mask_scalar(p, b0 + p.rowb[i]);
    }
    uint32_t full = 0, empty = 0;
    for (int lane = 0; lane < 16; ++lane) {
        const int bx = lane & 3, by = lane >> 2;
        uint32_t m = 0;
        for (int y = 0; y < 4; ++y) m |= ((rows[4 * by + y] >> (4 * bx)) & 15u) << (4 * y);
        out->mask[lane] = static_cast<uint16_t>(m);
        full |= static_cast<uint32_t>(m == 0xFFFF) << lane;
        empty |= static_cast<uint32_t>(m == 0) << lane;
    }
    out->full = full, out->empty = empty;
}

#if TILEVK_SIMD_AVX2
namespace avx2 {

// Bit i set iff lane i of (v0, v1) is negative: one movemask per 8 lanes (the sign bit), no compare.
// With v = value - 1 this is "value <= 0" (no overflow: every value is in (-2^30, 2^30], tile_kernels.h).
TILEVK_KERNEL uint32_t sign_bits(__m256i v0, __m256i v1) {
    const uint32_t m0 = static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(v0)));
    const uint32_t m1 = static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(v1)));
    return m0 | (m1 << 8);
}

}  // namespace avx2

TILEVK_KERNEL void classify16_avx2(const TilePlane& p, int32_t ox, int32_t oy, int shift, uint32_t* reject,
                                   uint32_t* accept) {
    const int32_t origin = p.a * ox + p.b * oy;
    const int32_t hi = p.hi + origin + ((p.up << shift) - p.up);  // + (2^shift - 1)*up
    const int32_t lo = p.lo + origin + ((p.dn << shift) - p.dn);
    // The 4-px level (shift 2, the hot one) reads the pre-shifted table; other levels shift step.
    const int32_t* table = shift == 2 ? p.step4 : p.step;
    const __m128i sh = _mm_cvtsi32_si128(shift == 2 ? 0 : shift);
    const __m256i t0 = _mm256_sll_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table)), sh);
    const __m256i t1 = _mm256_sll_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table + 8)), sh);
    // x > 0  <=>  sign(x - 1) clear: reject = hi + off <= 0, accept = !(lo + off <= 0).
    const __m256i vhi = _mm256_set1_epi32(hi - 1), vlo = _mm256_set1_epi32(lo - 1);
    *reject = avx2::sign_bits(_mm256_add_epi32(vhi, t0), _mm256_add_epi32(vhi, t1));
    *accept = ~avx2::sign_bits(_mm256_add_epi32(vlo, t0), _mm256_add_epi32(vlo, t1)) & 0xFFFF;
}

TILEVK_KERNEL uint32_t plane_mask4x4_avx2(const TilePlane& p, int32_t base) {
    const __m256i b = _mm256_set1_epi32(base - 1);  // base + step > 0  <=>  base - 1 + step >= 0
    const __m256i t0 = _mm256_load_si256(reinterpret_cast<const __m256i*>(p.step));
    const __m256i t1 = _mm256_load_si256(reinterpret_cast<const __m256i*>(p.step + 8));
    return ~avx2::sign_bits(_mm256_add_epi32(b, t0), _mm256_add_epi32(b, t1)) & 0xFFFF;
}

TILEVK_KERNEL uint32_t mask4x4_avx2(const TilePlane* const* planes, int n, int s, int32_t ox, int32_t oy) {
    uint32_t m = 0xFFFF;
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        m &= plane_mask4x4_avx2(p, p.c[s] + p.a * ox + p.b * oy);
    }
    return m;
}
// mask4x4_samples4 with the planes combined by OR of (value - 1) per lane (the sign bit is set iff some plane is
// <= 0: every value is in (-2^30, 2^30], so no subtraction wraps), so the sign extractions run once per block
// instead of once per plane and sample. A plane's four sample values sit in both 128-bit halves (one in-lane
// shuffle broadcasts sample s). kN = plane count known at compile time (0: use n); n = 0 leaves every lane
// covered, as mask4x4 does. The lanes are taken in the order {0-3, 8-11} and {4-7, 12-15} so that two signed
// packs and one 64-bit permute put two samples' sixteen sign bytes in pixel order for one movemask.
template <int kN>
[[gnu::always_inline]] TILEVK_KERNEL uint64_t mask4x4_samples4_avx2(const TilePlane* const* planes, int n, int32_t ox,
                                                                    int32_t oy) {
    if constexpr (kN != 0) n = kN;
    __m256i acc[8];  // sample s: lanes {0-3, 8-11} in acc[2s], {4-7, 12-15} in acc[2s + 1]
    for (int i = 0; i < 8; ++i) acc[i] = _mm256_setzero_si256();
#pragma GCC unroll 8
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        const __m128i c = _mm_add_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p.c)),
                                        _mm_set1_epi32(p.a * ox + p.b * oy - 1));
        const __m256i cc = _mm256_broadcastsi128_si256(c);
        const __m256i s0 = _mm256_load_si256(reinterpret_cast<const __m256i*>(p.step));
        const __m256i s1 = _mm256_load_si256(reinterpret_cast<const __m256i*>(p.step + 8));
        const __m256i t0 = _mm256_permute2x128_si256(s0, s1, 0x20), t1 = _mm256_permute2x128_si256(s0, s1, 0x31);
        const __m256i c0 = _mm256_shuffle_epi32(cc, 0x00), c1 = _mm256_shuffle_epi32(cc, 0x55);
        const __m256i c2 = _mm256_shuffle_epi32(cc, 0xAA), c3 = _mm256_shuffle_epi32(cc, 0xFF);
        acc[0] = _mm256_or_si256(acc[0], _mm256_add_epi32(c0, t0));
        acc[1] = _mm256_or_si256(acc[1], _mm256_add_epi32(c0, t1));
        acc[2] = _mm256_or_si256(acc[2], _mm256_add_epi32(c1, t0));
        acc[3] = _mm256_or_si256(acc[3], _mm256_add_epi32(c1, t1));
        acc[4] = _mm256_or_si256(acc[4], _mm256_add_epi32(c2, t0));
        acc[5] = _mm256_or_si256(acc[5], _mm256_add_epi32(c2, t1));
        acc[6] = _mm256_or_si256(acc[6], _mm256_add_epi32(c3, t0));
        acc[7] = _mm256_or_si256(acc[7], _mm256_add_epi32(c3, t1));
    }
    // packs_epi32 per 128-bit half: [A0-3 B0-3 | A4-7 B4-7] = lanes [0-7 | 8-15] of one sample; packs_epi16 of two
    // samples: 64-bit chunks [s lanes 0-7, s' lanes 0-7, s lanes 8-15, s' lanes 8-15]; permute 0xD8 orders them.
    const auto two = [&](int s) {
        const __m256i w = _mm256_packs_epi16(_mm256_packs_epi32(acc[2 * s], acc[2 * s + 1]),
                                             _mm256_packs_epi32(acc[2 * s + 2], acc[2 * s + 3]));
        return uint64_t{static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_permute4x64_epi64(w, 0xD8)))};
    };
    return ~(two(0) | (two(2) << 32));
}

// mask4x4_samples4 in 16-bit lanes, for planes whose steps inside a 4x4 block are small (a small primitive's edges):
// one vector per plane and sample holds the sixteen pixels' offsets from the plane's sample-0 value at the block's
// top-left pixel, v[s][i] = (c[s] - c[0]) + step[i], filled once per plane and tile (fill_sample_steps16). Per
// block, base = c[0] + a*ox + b*oy - 1 is saturated to 16 bits and added to v[s] with saturation; the sign of the
// result is the sign of base + v[s][i] (the value - 1) whenever |v| <= 32767: inside the 16-bit range the sum is
// exact or saturates toward its own sign; a base above 32767 saturates to 32767 and 32767 + v >= 0 where the true
// sum is above 0; a base below -32768 saturates to -32768 and -32768 + v <= -1 where the true sum is below -1.
// Planes combine by OR (sign = some plane <= 0) and one signed pack per two samples gives their 32 sign bits.
struct SampleSteps16 {
    alignas(32) int16_t v[4][16];
};

// Fills *out for plane p; false (out unusable) when some |v| would exceed 32767.
TILEVK_KERNEL bool fill_sample_steps16(const TilePlane& p, SampleSteps16* out) {
    int64_t dmax = 0;
    for (int s = 1; s < 4; ++s) dmax = std::max<int64_t>(dmax, std::abs(int64_t{p.c[s]} - p.c[0]));
    if (dmax + 3 * (std::abs(int64_t{p.a}) + std::abs(int64_t{p.b})) > 32767) return false;
#if TILEVK_SIMD_AVX2
    // The steps packed to 16 bits (exact: |step| <= 3(|a| + |b|)); packs works per 128-bit half, 0xD8 reorders.
    const __m256i step =
        _mm256_permute4x64_epi64(_mm256_packs_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(p.step)),
                                                    _mm256_load_si256(reinterpret_cast<const __m256i*>(p.step + 8))),
                                 0xD8);
    for (int s = 0; s < 4; ++s)
        _mm256_store_si256(reinterpret_cast<__m256i*>(out->v[s]),
                           _mm256_add_epi16(step, _mm256_set1_epi16(static_cast<int16_t>(p.c[s] - p.c[0]))));
#else
    for (int s = 0; s < 4; ++s)
        for (int i = 0; i < 16; ++i) out->v[s][i] = static_cast<int16_t>(p.c[s] - p.c[0] + p.step[i]);
#endif
    return true;
}

TILEVK_KERNEL uint64_t mask4x4_samples4_16_scalar(const TilePlane* const* planes, const SampleSteps16* steps, int n,
                                                  int32_t ox, int32_t oy) {
    uint64_t unc = 0;  // uncovered bits, sample s in bits 16s..16s+15
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        const int32_t base = std::clamp(p.c[0] + p.a * ox + p.b * oy - 1, -32768, 32767);
        for (int s = 0; s < 4; ++s)
            for (int i = 0; i < 16; ++i) {
                const int32_t v = std::clamp(base + steps[k].v[s][i], -32768, 32767);
                unc |= uint64_t{v < 0} << (16 * s + i);
            }
    }
    return ~unc;
}

#if TILEVK_SIMD_AVX2
template <int kN>
[[gnu::always_inline]] TILEVK_KERNEL uint64_t mask4x4_samples4_16_avx2(const TilePlane* const* planes,
                                                                       const SampleSteps16* steps, int n, int32_t ox,
                                                                       int32_t oy) {
    if constexpr (kN != 0) n = kN;
    __m256i acc[4] = {_mm256_setzero_si256(), _mm256_setzero_si256(), _mm256_setzero_si256(), _mm256_setzero_si256()};
#pragma GCC unroll 8
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        // packs_epi32 is the signed saturation to 16 bits (the scalar twin's clamp).
        const __m128i b32 = _mm_cvtsi32_si128(p.c[0] + p.a * ox + p.b * oy - 1);
        const __m256i b = _mm256_broadcastw_epi16(_mm_packs_epi32(b32, b32));
        const auto* v = reinterpret_cast<const __m256i*>(steps[k].v);
        // Spelled out: as a loop over the samples GCC kept acc in memory.
        acc[0] = _mm256_or_si256(acc[0], _mm256_adds_epi16(b, _mm256_load_si256(v)));
        acc[1] = _mm256_or_si256(acc[1], _mm256_adds_epi16(b, _mm256_load_si256(v + 1)));
        acc[2] = _mm256_or_si256(acc[2], _mm256_adds_epi16(b, _mm256_load_si256(v + 2)));
        acc[3] = _mm256_or_si256(acc[3], _mm256_adds_epi16(b, _mm256_load_si256(v + 3)));
    }
    // packs_epi16 per 128-bit half: [s lanes 0-7, s' lanes 0-7 | s lanes 8-15, s' lanes 8-15]; 0xD8 orders them.
    const auto two = [&](int s) {
        const __m256i w = _mm256_permute4x64_epi64(_mm256_packs_epi16(acc[s], acc[s + 1]), 0xD8);
        return uint64_t{static_cast<uint32_t>(_mm256_movemask_epi8(w))};
    };
    return ~(two(0) | (two(2) << 32));
}
#endif

// The 256 pixels as 32 row segments of 8 px per plane (row y, x in [0,8) or [8,16)): segment = base - 1 + a*x + b*y,
// one add each (incremental down the rows, + 8a for the right half); planes combine by OR of the values (sign bit =
// some plane <= 0). Four rows of one half are packed 32 -> 16 -> 8 bits with signed saturation (signs kept) and one
// movemask gives the two 4x4 blocks of that half, in the block mask's bit order (y*4 + x), lane order by word.
// kN = plane count known at compile time (0: use n, up to Prim::kMaxPlanes = 8).
template <int kN>
TILEVK_KERNEL void block16_masks_avx2(const TilePlane* const* planes, int n, const int32_t* base, Block16Masks* out) {
    if constexpr (kN != 0) n = kN;
    constexpr int kMax = kN != 0 ? kN : 8;
    // Rows 1-3 of a block row and the next block row from the first row with one add each (short dependency chains).
    __m256i left[kMax], step_b[kMax][4], step_8a[kMax];
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        const __m256i row8 = _mm256_mullo_epi32(_mm256_set1_epi32(p.a), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        left[k] = _mm256_add_epi32(_mm256_set1_epi32(base[k] - 1), row8);             // a*x for x = 0..7
        for (int i = 0; i < 4; ++i) step_b[k][i] = _mm256_set1_epi32(p.b * (i + 1));  // |4b| < 2^25
        step_8a[k] = _mm256_set1_epi32(p.a * 8);
    }
    // Uncovered bits: word 2*by + h = lanes 4*by + 2*h (low half) and + 1 (high half); two words per qword.
    uint64_t words[4];
#pragma GCC unroll 4
    for (int by = 0; by < 4; ++by) {
        __m256i acc[8] = {};  // n >= 1 always overwrites; zero keeps n = 0 defined (no plane: all covered)
#pragma GCC unroll 8
        for (int k = 0; k < n; ++k) {
            __m256i r[8];
            r[0] = left[k];
#pragma GCC unroll 4
            for (int i = 1; i < 4; ++i) r[i] = _mm256_add_epi32(left[k], step_b[k][i - 1]);
            left[k] = _mm256_add_epi32(left[k], step_b[k][3]);
#pragma GCC unroll 4
            for (int i = 0; i < 4; ++i) r[4 + i] = _mm256_add_epi32(r[i], step_8a[k]);
#pragma GCC unroll 8
            for (int i = 0; i < 8; ++i) acc[i] = k == 0 ? r[i] : _mm256_or_si256(acc[i], r[i]);
        }
        uint64_t pair = 0;
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            const __m256i* a = acc + 4 * h;
            const __m256i packed = _mm256_packs_epi16(_mm256_packs_epi32(a[0], a[1]), _mm256_packs_epi32(a[2], a[3]));
            pair |= uint64_t{static_cast<uint32_t>(_mm256_movemask_epi8(packed))} << (32 * h);
        }
        words[by] = pair;
    }
    // Built in registers (a store/reload of the words would stall store forwarding).
    const __m256i unc = _mm256_inserti128_si256(
        _mm256_castsi128_si256(
            _mm_insert_epi64(_mm_cvtsi64_si128(static_cast<int64_t>(words[0])), static_cast<int64_t>(words[1]), 1)),
        _mm_insert_epi64(_mm_cvtsi64_si128(static_cast<int64_t>(words[2])), static_cast<int64_t>(words[3]), 1), 1);
    const __m256i ones = _mm256_set1_epi32(-1);
    // The masks go out as four 8-byte scalar stores: each 2-byte read of one lane is then forwarded from a single
    // store of the same width class (one 32-byte vector store here made every read wait for it to commit).
#pragma GCC unroll 4
    for (int by = 0; by < 4; ++by) {
        const uint64_t covered = ~words[by];
        std::memcpy(out->mask + 4 * by, &covered, 8);
    }
    // Per 16-bit lane: full = no uncovered bit, empty = all uncovered; packed to bytes, ordered [full | empty].
    const __m256i is_full = _mm256_cmpeq_epi16(unc, _mm256_setzero_si256());
    const __m256i is_empty = _mm256_cmpeq_epi16(unc, ones);
    const __m256i both = _mm256_permute4x64_epi64(_mm256_packs_epi16(is_full, is_empty), 0xD8);
    const uint32_t bits = static_cast<uint32_t>(_mm256_movemask_epi8(both));
    out->full = bits & 0xFFFFu, out->empty = bits >> 16;
}
#endif

#if TILEVK_SIMD_AVX2
// block16_rows with 8 rows per vector (kRowOrder): per plane and 8 rows one add, cvt, fma, max, min, cvtt, mullo,
// two exact tests and one sllv that puts the row mask in the high 16 bits of its 32-bit lane (bit 16 + x; nothing
// leaks out, nothing below); the 16 rows are merged into words and transposed by nibbles (one shuffle, two
// maddubs/madd pairs); full and empty lanes as in block16_masks_avx2.
template <int kN>
TILEVK_KERNEL void block16_rows_avx2(const TilePlane* const* planes, int n, const int32_t* base, Block16Masks* out) {
    if constexpr (kN != 0) n = kN;
    const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1), high = _mm256_set1_epi32(-65536);
    const __m256 flo = _mm256_set1_ps(1.0f), fhi = _mm256_set1_ps(18.0f);
    __m256i rows[2] = {high, high};
#pragma GCC unroll 8
    for (int k = 0; k < n; ++k) {
        const TilePlane& p = *planes[k];
        const __m256i b0 = _mm256_set1_epi32((base[k] ^ p.rflip) - 2 * p.rflip);
        const __m256i a = _mm256_set1_epi32(p.ra), flip = _mm256_set1_epi32(p.rflip & -65536);
        const __m256 inv = _mm256_set1_ps(p.rinv), off = _mm256_set1_ps(p.roff);
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            const __m256i r = _mm256_add_epi32(b0, _mm256_load_si256(reinterpret_cast<const __m256i*>(p.rowb + 8 * h)));
            const __m256 q = _mm256_fmadd_ps(_mm256_cvtepi32_ps(r), inv, off);
            __m256i t = _mm256_cvttps_epi32(_mm256_min_ps(_mm256_max_ps(q, flo), fhi));
            const __m256i v = _mm256_add_epi32(r, _mm256_mullo_epi32(a, t));
            t = _mm256_sub_epi32(t, _mm256_cmpgt_epi32(one, v));                        // v <= 0: + 1
            t = _mm256_add_epi32(t, _mm256_cmpgt_epi32(_mm256_sub_epi32(v, a), zero));  // v - a' > 0: - 1
            const __m256i m = _mm256_xor_si256(_mm256_sllv_epi32(high, t), flip);       // t in [0, 19]
            rows[h] = _mm256_and_si256(rows[h], m);
        }
    }
    // Words of w per 128-bit half: rows 0, 4, 1, 5, 2, 6, 3, 7 (+8 in the upper half; kRowOrder). The shuffle makes
    // each 64-bit lane (one block row by) [byte 0 of rows 4by..4by+3, byte 1 of them]; low/high nibbles of those
    // bytes are blocks bx = 2h / 2h + 1; maddubs (1, 16) and madd (1, 256) gather four nibbles into one 16-bit block
    // mask per 32-bit lane.
    const __m256i w = _mm256_or_si256(_mm256_srli_epi32(rows[0], 16), rows[1]);
    const __m256i order = _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 0, 4, 8, 12, 1, 5, 9,
                                           13, 2, 6, 10, 14, 3, 7, 11, 15);
    const __m256i s = _mm256_shuffle_epi8(w, order), nib = _mm256_set1_epi8(0x0F);
    const __m256i m1 = _mm256_set1_epi16(0x1001), m2 = _mm256_set1_epi32(0x01000001);
    const __m256i even = _mm256_madd_epi16(_mm256_maddubs_epi16(_mm256_and_si256(s, nib), m1), m2);
    const __m256i odd = _mm256_madd_epi16(_mm256_maddubs_epi16(_mm256_and_si256(_mm256_srli_epi16(s, 4), nib), m1), m2);
    const __m256i cov = _mm256_or_si256(even, _mm256_slli_epi32(odd, 16));
    // One 32-byte store: the 1x emission (tile_raster.cpp emit_block16_1x) reads the masks back as one vector.
    _mm256_store_si256(reinterpret_cast<__m256i*>(out->mask), cov);
    const __m256i is_full = _mm256_cmpeq_epi16(cov, _mm256_set1_epi32(-1));
    const __m256i is_empty = _mm256_cmpeq_epi16(cov, zero);
    const __m256i both = _mm256_permute4x64_epi64(_mm256_packs_epi16(is_full, is_empty), 0xD8);
    const uint32_t bits = static_cast<uint32_t>(_mm256_movemask_epi8(both));
    out->full = bits & 0xFFFFu, out->empty = bits >> 16;
}
#endif

// The 1x 16x16 kernel the rasterizer uses (planes need fill_row_table): AVX2 when built with it, else the twin.
template <int kN>
TILEVK_KERNEL void block16_rows(const TilePlane* const* planes, int n, const int32_t* base, Block16Masks* out) {
#if TILEVK_SIMD_AVX2
    block16_rows_avx2<kN>(planes, n, base, out);
#else
    block16_rows_scalar(planes, n, base, out);
#endif
}

// The kernels the rasterizer uses: AVX2 when built with it, else the scalar twin.
template <int kN>
TILEVK_KERNEL void block16_masks(const TilePlane* const* planes, int n, const int32_t* base, Block16Masks* out) {
#if TILEVK_SIMD_AVX2
    block16_masks_avx2<kN>(planes, n, base, out);
#else
    block16_masks_scalar(planes, n, base, out);
#endif
}

TILEVK_KERNEL void classify16(const TilePlane& p, int32_t ox, int32_t oy, int shift, uint32_t* reject,
                              uint32_t* accept) {
#if TILEVK_SIMD_AVX2
    classify16_avx2(p, ox, oy, shift, reject, accept);
#else
    classify16_scalar(p, ox, oy, shift, reject, accept);
#endif
}

TILEVK_KERNEL uint32_t mask4x4(const TilePlane* const* planes, int n, int s, int32_t ox, int32_t oy) {
#if TILEVK_SIMD_AVX2
    return mask4x4_avx2(planes, n, s, ox, oy);
#else
    return mask4x4_scalar(planes, n, s, ox, oy);
#endif
}

template <int kN>
[[gnu::always_inline]] TILEVK_KERNEL uint64_t mask4x4_samples4(const TilePlane* const* planes, int n, int32_t ox,
                                                               int32_t oy) {
#if TILEVK_SIMD_AVX2
    return mask4x4_samples4_avx2<kN>(planes, n, ox, oy);
#else
    return mask4x4_samples4_scalar(planes, n, ox, oy);
#endif
}

}  // namespace tilevk::rast
