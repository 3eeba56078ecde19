// The compiled tier's Sample for the most common texture: a 2D RGBA8/BGRA8 UNORM image, bilinear min and mag
// filters, REPEAT (power-of-two sizes) or CLAMP_TO_EDGE, implicit, biased or explicit LOD. That is lavapipe's 8-bit
// fixed-point ("AoS") filter, texture.cpp's sample_level_fixed8 and exec_image's LOD selection, computed for 8
// lanes at a time with the same operations in the same order (texture_fixed8.h). Every other case, and any quad
// whose LOD computation meets a NaN (its payload would depend on the C++ compiler's operand order), runs the
// interpreter's exec_image unchanged.
#include "shader/jit/sample_rgba8.h"

#include <immintrin.h>

#include <bit>

namespace tilevk::shader::jit {

namespace {

#define TVK_AVX2 __attribute__((target("avx2,fma")))

// Whether the kernel covers this sampler on a view whose level table `t` covers, wraps checked per axis.
bool sampler_fits(const SamplerState& smp, const ViewLevelTable& t) {
    if (smp.unnormalized || smp.mag_filter != Filter::Linear || smp.min_filter != Filter::Linear) return false;
    if (smp.reduction != Reduction::WeightedAverage) return false;  // its kernel lerps (texture_reduce.h)
    if (smp.max_anisotropy > 1.0f) return false;                    // the interpreter's texture_aniso.cpp filters those
    auto ok_wrap = [](AddressMode m, uint32_t n) {
        return m == AddressMode::ClampToEdge || (m == AddressMode::Repeat && (n & (n - 1)) == 0);
    };
    return ok_wrap(smp.address_u, t.width) && ok_wrap(smp.address_v, t.height);
}

// Whether the view's table was prepared (prepare_view) from the view as it is now.
bool table_current(const ImageView& img) {
    const ViewLevelTable& t = img.table;
    // the swizzles as one word: std::array's operator== is a memcmp call here (~24 instructions a call)
    return t.format == img.format && t.width == img.width && t.height == img.height && t.levels == img.levels &&
           std::bit_cast<uint32_t>(t.swizzle) == std::bit_cast<uint32_t>(img.swizzle);
}

// table[lv] per lane, lv in [0, levels - 1] (at most kMaxMipLevels - 1 = 15): one permute when every lv < 8
// (`narrow`: a view of at most 8 levels, or a call whose levels are all below 8), two otherwise, the second's
// entries taken where lv's bit 3 is set (lv >= 8), moved to the sign bit that vblendvps reads (a compare against 7
// cost GCC a broadcast, vpcmpgtd, vpcmpgtb and vpblendvb).
static_assert(kMaxMipLevels <= 16);
TVK_AVX2 __m256i lookup(const int32_t* table, bool narrow, __m256i lv) {
    const __m256i lo = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(table)), lv);
    if (narrow) return lo;
    const __m256i hi = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(table + 8)), lv);
    const __m256 upper = _mm256_castsi256_ps(_mm256_slli_epi32(lv, 28));
    return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(lo), _mm256_castsi256_ps(hi), upper));
}

struct Axis {
    __m256i i0, i1, w128;  // w128: the 8-bit weight times 128 (lerp16's form)
};

// axis_fixed8 with no offset: c = iround(s * float(n * 256)) - 128; CLAMP: both indices clamped, REPEAT pot:
// masked, the second wrapping to 0.
TVK_AVX2 Axis axis(__m256 s, __m256i n, bool clamp) {
    const __m256 n256 = _mm256_cvtepi32_ps(_mm256_slli_epi32(n, 8));
    const __m256i c = _mm256_sub_epi32(_mm256_cvtps_epi32(_mm256_mul_ps(s, n256)), _mm256_set1_epi32(128));
    const __m256i i = _mm256_srai_epi32(c, 8), one = _mm256_set1_epi32(1);
    const __m256i last = _mm256_sub_epi32(n, one);
    Axis a;
    a.w128 = _mm256_and_si256(_mm256_slli_epi32(c, 7), _mm256_set1_epi32(255 << 7));
    if (clamp) {
        a.i0 = _mm256_min_epi32(_mm256_max_epi32(i, _mm256_setzero_si256()), last);
        // i >= 0 && i < n - 1 ? i0 + 1 : i0
        const __m256i inside =
            _mm256_andnot_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), i), _mm256_cmpgt_epi32(last, i));
        a.i1 = _mm256_sub_epi32(a.i0, inside);  // inside is -1 where true
    } else {
        a.i0 = _mm256_and_si256(i, last);
        const __m256i at_end = _mm256_cmpeq_epi32(a.i0, last);
        a.i1 = _mm256_andnot_si256(at_end, _mm256_add_epi32(a.i0, one));
    }
    return a;
}

// Eight texels' channels as 16-bit values: lo = texels 0, 1 | 4, 5 and hi = texels 2, 3 | 6, 7, four channels each
// (unpacking works within 128-bit lanes).
struct Wide {
    __m256i lo, hi;
};
TVK_AVX2 Wide widen(__m256i texels) {
    const __m256i z = _mm256_setzero_si256();
    return {_mm256_unpacklo_epi8(texels, z), _mm256_unpackhi_epi8(texels, z)};
}

// A per-lane 16-bit weight (the low half of each 32-bit lane) repeated over the lane's four 16-bit channels, in
// widen()'s layout.
TVK_AVX2 Wide spread(__m256i w) {
    const __m256i lo = _mm256_setr_epi8(0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4, 5, 4, 5, 4, 5, 0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4,
                                        5, 4, 5, 4, 5);
    const __m256i hi = _mm256_setr_epi8(8, 9, 8, 9, 8, 9, 8, 9, 12, 13, 12, 13, 12, 13, 12, 13, 8, 9, 8, 9, 8, 9, 8, 9,
                                        12, 13, 12, 13, 12, 13, 12, 13);
    return {_mm256_shuffle_epi8(w, lo), _mm256_shuffle_epi8(w, hi)};
}

// fixed8::lerp on 16-bit channels: a + ((w * (b - a) + 128) >> 8) = a + pmulhrsw(w * 128, b - a), exactly (the
// product and its rounding constant are 128 times the formula's, pmulhrsw shifts by 15; w * 128 <= 32640 and
// |b - a| <= 255 fit its 16-bit operands). The factor 128 rides on the weight, made once per axis, instead of on
// every difference.
TVK_AVX2 __m256i lerp16(__m256i w128, __m256i a, __m256i b) {
    return _mm256_add_epi16(a, _mm256_mulhrs_epi16(w128, _mm256_sub_epi16(b, a)));
}
TVK_AVX2 Wide lerp(const Wide& w, const Wide& a, const Wide& b) {
    return {lerp16(w.lo, a.lo, b.lo), lerp16(w.hi, a.hi, b.hi)};
}

// A pair of lanes' texel pairs: the 64 bits at base + o0 and at base + o1 in the low and the high half.
TVK_AVX2 __m128i pair_at(const uint8_t* base, uint32_t o0, uint32_t o1) {
    const __m128i lo = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(base + o0));
    return _mm_castpd_si128(_mm_loadh_pd(_mm_castsi128_pd(lo), reinterpret_cast<const double*>(base + o1)));
}

// Lanes 0, 1 | 4, 5 (a) and lanes 2, 3 | 6, 7 (b), each lane's two texels side by side, as the left and the right
// texels of the eight lanes in lane order: the even (odd) words of a and b per 128-bit half.
TVK_AVX2 void split_pairs(__m256i a, __m256i b, __m256i& left, __m256i& right) {
    left =
        _mm256_castps_si256(_mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _MM_SHUFFLE(2, 0, 2, 0)));
    right =
        _mm256_castps_si256(_mm256_shuffle_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _MM_SHUFFLE(3, 1, 3, 1)));
}

// The texels at byte offsets `off` and `off + 4` from base for eight lanes, as two vectors in lane order: eight
// 64-bit loads instead of two 8-lane gathers, which take 2-3 times longer on the hosts measured (shader/jit/README.md,
// "The RGBA8 sampler's loads"). llvmpipe fetches its texels with scalar loads too (lp_bld_gather.c).
TVK_AVX2 void load_pairs(const uint8_t* base, __m256i off, __m256i& left, __m256i& right) {
    // unsigned: every offset is in [0, 2^31) (level_table), and a zero-extended index needs no movslq
    alignas(32) uint32_t o[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(o), off);
    split_pairs(_mm256_set_m128i(pair_at(base, o[4], o[5]), pair_at(base, o[0], o[1])),
                _mm256_set_m128i(pair_at(base, o[6], o[7]), pair_at(base, o[2], o[3])), left, right);
}

// Both rows' pairs when the second row is `pitch` bytes after the first in every lane: each offset is taken out of
// the vector once for both rows (the extractions were a third of a row's loads), the rows' loads interleaved so
// that only two offsets are live at a time.
TVK_AVX2 __attribute__((always_inline)) inline void load_rows(const uint8_t* base, uint32_t pitch, __m256i off,
                                                              __m256i& p00, __m256i& p10, __m256i& p01, __m256i& p11) {
    alignas(32) uint32_t o[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(o), off);
    const uint8_t* next = base + pitch;
    __m128i r0[4], r1[4];  // lanes 0, 1 | 2, 3 | 4, 5 | 6, 7 of row 0 and row 1
    for (int k = 0; k < 4; ++k) {
        r0[k] = pair_at(base, o[2 * k], o[2 * k + 1]);
        r1[k] = pair_at(next, o[2 * k], o[2 * k + 1]);
    }
    split_pairs(_mm256_set_m128i(r0[2], r0[0]), _mm256_set_m128i(r0[3], r0[1]), p00, p10);
    split_pairs(_mm256_set_m128i(r1[2], r1[0]), _mm256_set_m128i(r1[3], r1[1]), p01, p11);
}

// sample_level_fixed8, linear, at per-lane level lv: x lerps on both rows, then the y lerp. The footprint's
// texels are the same whichever way they are loaded: side by side (x1 = x0 + 1 in every lane: all but the lanes
// where REPEAT wraps or CLAMP_TO_EDGE holds at the last texel) as pairs, else by gathers.
// Inlined into half(): both levels then share the constants and keep their results in registers.
TVK_AVX2 __attribute__((always_inline)) inline Wide level_bilinear(const ImageView& img, const ViewLevelTable& levels,
                                                                   __m256i lv, bool narrow, __m256 s, __m256 t,
                                                                   bool clamp_u, bool clamp_v) {
    const __m256i off = lookup(levels.offset, narrow, lv), pitch = lookup(levels.pitch, narrow, lv);
    // level sizes max(1, size >> lv) (level_table) by shifts: cheaper than two more look-ups
    const __m256i one = _mm256_set1_epi32(1);
    const __m256i w = _mm256_max_epi32(_mm256_srlv_epi32(_mm256_set1_epi32(int(levels.width)), lv), one);
    const __m256i hgt = _mm256_max_epi32(_mm256_srlv_epi32(_mm256_set1_epi32(int(levels.height)), lv), one);
    const Axis x = axis(s, w, clamp_u), y = axis(t, hgt, clamp_v);
    const __m256i row0 = _mm256_add_epi32(off, _mm256_mullo_epi32(y.i0, pitch));
    const __m256i row1 = _mm256_add_epi32(off, _mm256_mullo_epi32(y.i1, pitch));
    const __m256i x0 = _mm256_slli_epi32(x.i0, 2);
    const __m256i side_by_side = _mm256_cmpeq_epi32(x.i1, _mm256_add_epi32(x.i0, _mm256_set1_epi32(1)));
    // the second row one pitch (lane 0's) after the first in every lane: the rows are adjacent (not wrapped or
    // clamped) and the lanes' levels have that pitch, the usual case inside a level
    const __m256i pitch0 = _mm256_broadcastd_epi32(_mm256_castsi256_si128(pitch));
    const __m256i next_row = _mm256_cmpeq_epi32(row1, _mm256_add_epi32(row0, pitch0));
    __m256i p00, p10, p01, p11;
    if (_mm256_movemask_epi8(_mm256_and_si256(side_by_side, next_row)) == -1) {
        load_rows(img.base, uint32_t(_mm256_cvtsi256_si32(pitch)), _mm256_add_epi32(row0, x0), p00, p10, p01, p11);
    } else if (_mm256_movemask_epi8(side_by_side) == -1) {
        load_pairs(img.base, _mm256_add_epi32(row0, x0), p00, p10);
        load_pairs(img.base, _mm256_add_epi32(row1, x0), p01, p11);
    } else {
        const __m256i x1 = _mm256_slli_epi32(x.i1, 2);
        const int* base = reinterpret_cast<const int*>(img.base);
        p00 = _mm256_i32gather_epi32(base, _mm256_add_epi32(row0, x0), 1);
        p10 = _mm256_i32gather_epi32(base, _mm256_add_epi32(row0, x1), 1);
        p01 = _mm256_i32gather_epi32(base, _mm256_add_epi32(row1, x0), 1);
        p11 = _mm256_i32gather_epi32(base, _mm256_add_epi32(row1, x1), 1);
    }
    const Wide wx = spread(x.w128), wy = spread(y.w128);
    return lerp(wy, lerp(wx, widen(p00), widen(p10)), lerp(wx, widen(p01), widen(p11)));
}

// std::max / std::min / std::clamp as written: (a < b) ? b : a, (b < a) ? b : a
TVK_AVX2 __m256 max_std(__m256 a, __m256 b) {
    return _mm256_blendv_ps(a, b, _mm256_cmp_ps(a, b, _CMP_LT_OQ));
}
TVK_AVX2 __m256 min_std(__m256 a, __m256 b) {
    return _mm256_blendv_ps(a, b, _mm256_cmp_ps(b, a, _CMP_LT_OQ));
}

// fixed8::fast_log2: float(exponent - 128) + mantissa in [1, 2)
TVK_AVX2 __m256 fast_log2(__m256 x) {
    const __m256i b = _mm256_castps_si256(x);
    const __m256i e =
        _mm256_sub_epi32(_mm256_and_si256(_mm256_srli_epi32(b, 23), _mm256_set1_epi32(0xff)), _mm256_set1_epi32(128));
    const __m256 m = _mm256_castsi256_ps(
        _mm256_or_si256(_mm256_and_si256(b, _mm256_set1_epi32(0x7fffff)), _mm256_set1_epi32(0x3f800000)));
    return _mm256_add_ps(_mm256_cvtepi32_ps(e), m);
}

// Register r's eight lanes of half h (a function, not a lambda: lambdas do not inherit the target attribute).
TVK_AVX2 __m256 load_half(const uint32_t* R, uint32_t r, int h) {
    return _mm256_loadu_ps(reinterpret_cast<const float*>(R + size_t(r) * kLanes + 8 * h));
}

// The implicit LOD's rho^2 of the block's four 2x2 quads in one vector: quad 0 | 1 in position 0 of each 128-bit
// half, quad 2 | 3 in position 2 (the other positions hold the same quads' values with rx and ry swapped in
// max_std). Per quad from its top-left pixel, lane order top-left, top-right, bottom-left, bottom-right; the same
// operations as raw_lambda: dsdx = (s[tr] - s[tl]) * width, rx = dsdx * dsdx + dtdx * dtdx, max_std(rx, ry).
TVK_AVX2 __m256 quad_rho2(const uint32_t* R, uint32_t s_reg, const ImageView& img) {
    const __m256 s0 = load_half(R, s_reg, 0), s1 = load_half(R, s_reg, 1);
    const __m256 t0 = load_half(R, s_reg + 1, 0), t1 = load_half(R, s_reg + 1, 1);
    const __m256 w0 = _mm256_set1_ps(float(img.width)), h0 = _mm256_set1_ps(float(img.height));
    // [tr - tl, bl - tl] of quads 0 | 1 (from half 0) and 2 | 3 (from half 1)
    const __m256 ds = _mm256_mul_ps(
        _mm256_sub_ps(_mm256_shuffle_ps(s0, s1, _MM_SHUFFLE(2, 1, 2, 1)), _mm256_shuffle_ps(s0, s1, 0)), w0);
    const __m256 dt = _mm256_mul_ps(
        _mm256_sub_ps(_mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(2, 1, 2, 1)), _mm256_shuffle_ps(t0, t1, 0)), h0);
    const __m256 r = _mm256_add_ps(_mm256_mul_ps(ds, ds), _mm256_mul_ps(dt, dt));  // [rx, ry, rx, ry]
    return max_std(r, _mm256_permute_ps(r, _MM_SHUFFLE(2, 3, 0, 1)));
}

// Quad values of quad_rho2's layout spread over half h's eight lanes (quads 0 | 1 or 2 | 3).
TVK_AVX2 __m256i quad_spread(__m256i v, int h) {
    return h == 0 ? _mm256_shuffle_epi32(v, 0x00) : _mm256_shuffle_epi32(v, 0xAA);
}

// The levels a lane reads and their blend weight.
struct Levels {
    __m256i lv, hi, mw;
};

// From lambda before the sampler's bias: bias, NaN -> 0, clamps, then exec_image's level selection (magnified
// lanes read level 0 only). Inlined: as a call it returned its three vectors through memory.
TVK_AVX2 __attribute__((always_inline)) inline Levels select_levels(__m256 lambda, const ImageView& img,
                                                                    const SamplerState& smp) {
    lambda = _mm256_add_ps(lambda, _mm256_set1_ps(smp.mip_lod_bias));
    lambda = _mm256_and_ps(lambda, _mm256_cmp_ps(lambda, lambda, _CMP_ORD_Q));  // NaN -> 0
    lambda = min_std(max_std(lambda, _mm256_set1_ps(smp.min_lod)), _mm256_set1_ps(smp.max_lod));
    const __m256 mag = _mm256_cmp_ps(lambda, _mm256_setzero_ps(), _CMP_LE_OQ);
    const int32_t max_level = int32_t(img.levels - 1);
    const __m256 max_level_f = _mm256_set1_ps(float(max_level));
    Levels L;
    if (smp.mipmap_mode == MipmapMode::Nearest) {
        // ceil(lambda + 0.5) - 1, clamped to the view's levels
        const __m256 dl =
            _mm256_sub_ps(_mm256_ceil_ps(_mm256_add_ps(lambda, _mm256_set1_ps(0.5f))), _mm256_set1_ps(1.0f));
        const __m256 c = _mm256_blendv_ps(min_std(dl, max_level_f), _mm256_setzero_ps(),
                                          _mm256_cmp_ps(dl, _mm256_setzero_ps(), _CMP_LT_OQ));
        L.lv = _mm256_cvttps_epi32(c);
        L.hi = L.lv;
        L.mw = _mm256_setzero_si256();
    } else {
        const __m256 fl0 = _mm256_floor_ps(lambda);
        const __m256 top = _mm256_cmp_ps(fl0, max_level_f, _CMP_GE_OQ);
        const __m256 inside = _mm256_andnot_ps(top, _mm256_cmp_ps(fl0, _mm256_setzero_ps(), _CMP_GE_OQ));
        const __m256i lo = _mm256_cvttps_epi32(_mm256_and_ps(fl0, inside));
        L.lv = _mm256_blendv_epi8(lo, _mm256_set1_epi32(max_level), _mm256_castps_si256(top));
        L.hi = _mm256_blendv_epi8(L.lv, _mm256_add_epi32(lo, _mm256_set1_epi32(1)), _mm256_castps_si256(inside));
        // mip_weight(lambda - fl0): w = frac * 256; !(w > 0) -> 0; w >= 256 -> 255; else trunc(w)
        const __m256 wf = _mm256_mul_ps(_mm256_sub_ps(lambda, fl0), _mm256_set1_ps(256.0f));
        __m256i wi = _mm256_cvttps_epi32(_mm256_and_ps(wf, _mm256_cmp_ps(wf, _mm256_setzero_ps(), _CMP_GT_OQ)));
        wi = _mm256_blendv_epi8(wi, _mm256_set1_epi32(255),
                                _mm256_castps_si256(_mm256_cmp_ps(wf, _mm256_set1_ps(256.0f), _CMP_GE_OQ)));
        L.mw = _mm256_and_si256(wi, _mm256_castps_si256(inside));
    }
    const __m256i keep = _mm256_castps_si256(mag);
    return {_mm256_andnot_si256(keep, L.lv), _mm256_andnot_si256(keep, L.hi), _mm256_andnot_si256(keep, L.mw)};
}

// Byte shuffles moving channel c's byte of every RGBA (row 0) or BGRA (row 1) word to the bottom of the word, the
// other bytes zeroed (-128: a zero byte)
struct PickTable {
    alignas(32) int8_t bytes[2][4][32];
};
constexpr PickTable make_pick_table() {
    PickTable t{};
    for (int bgra = 0; bgra < 2; ++bgra)
        for (int c = 0; c < 4; ++c) {
            const int src = (bgra && c < 3) ? 2 - c : c;
            for (int i = 0; i < 32; ++i) t.bytes[bgra][c][i] = int8_t(i % 4 == 0 ? src + i % 16 : -128);
        }
    return t;
}
constexpr PickTable kPick = make_pick_table();

// Eight lanes (half h) filtered at their levels L, written as floats per channel in RGBA order to the lanes of half
// h of the destination registers. Inlined: a call per half would pass its results through memory.
TVK_AVX2 __attribute__((always_inline)) inline void filter_half(const Inst& in, uint32_t* R, const ImageView& img,
                                                                const SamplerState& smp, const ViewLevelTable& levels,
                                                                int h, const Levels& L, bool narrow) {
    const __m256 s = load_half(R, in.b, h), t = load_half(R, in.b + 1, h);
    const bool clamp_u = smp.address_u == AddressMode::ClampToEdge, clamp_v = smp.address_v == AddressMode::ClampToEdge;
    Wide a = level_bilinear(img, levels, L.lv, narrow, s, t, clamp_u, clamp_v);
    if (!_mm256_testz_si256(L.mw, L.mw))  // mw = 0 keeps a exactly: a + ((0 + 128) >> 8)
        a = lerp(spread(_mm256_slli_epi32(L.mw, 7)), a,
                 level_bilinear(img, levels, L.hi, narrow, s, t, clamp_u, clamp_v));
    // back to one RGBA word per lane (in lane order), then fl(float(c) * fl(1/255)) per channel in RGBA order
    const __m256i words = _mm256_packus_epi16(a.lo, a.hi);
    const __m256 k = _mm256_set1_ps(float(1.0 / 255.0));
    const auto& pick = kPick.bytes[levels.bgra ? 1 : 0];
    // the destination's address once: the stores below may alias `in` for the compiler, which otherwise reloads
    // in.d and recomputes the address for every channel
    float* const dst = reinterpret_cast<float*>(R + size_t(in.d) * kLanes + 8 * h);
    for (int c = 0; c < 4; ++c) {
        const __m256i ch = _mm256_shuffle_epi8(words, _mm256_load_si256(reinterpret_cast<const __m256i*>(pick[c])));
        _mm256_storeu_ps(dst + size_t(c) * kLanes, _mm256_mul_ps(_mm256_cvtepi32_ps(ch), k));
    }
}

}  // namespace

namespace {

// The instruction on the view, sampler and level table bound to it (bind_sample checked that the kernel covers them).
TVK_AVX2 bool sample_with(const Inst& in, uint32_t* R, const BoundSample& b) {
    const ImageView& img = *b.img;
    const SamplerState& smp = *b.smp;
    // the levels of both halves before any write: a NaN in the implicit LOD sends the whole instruction to
    // exec_image, which must see the registers unchanged (the destination may be a source). After that, half 0's
    // results go straight to their lanes: half 1 reads only lanes 8-15 of its sources (the levels are known), so
    // a destination that is also a source is still intact where it is read.
    Levels L[2];
    if (in.imm & kSampleExplicitLod) {
        for (int h = 0; h < 2; ++h) L[h] = select_levels(load_half(R, in.c, h), img, smp);
    } else {
        // implicit: one LOD per 2x2 quad, all four quads of the block in one vector
        const __m256 rho2 = quad_rho2(R, in.b, img);
        if (_mm256_movemask_ps(_mm256_cmp_ps(rho2, rho2, _CMP_UNORD_Q))) return false;
        const __m256 lambda = _mm256_mul_ps(fast_log2(rho2), _mm256_set1_ps(0.5f));
        if (in.imm & kSampleBias) {  // a bias per lane: the quads' values spread over the lanes first
            for (int h = 0; h < 2; ++h) {
                const __m256 q = _mm256_castsi256_ps(quad_spread(_mm256_castps_si256(lambda), h));
                L[h] = select_levels(_mm256_add_ps(q, load_half(R, in.c, h)), img, smp);
            }
        } else {  // the same for every lane of a quad: selected once, then spread
            const Levels q = select_levels(lambda, img, smp);
            for (int h = 0; h < 2; ++h) L[h] = {quad_spread(q.lv, h), quad_spread(q.hi, h), quad_spread(q.mw, h)};
        }
    }
    // every level the call reads below 8 (hi >= lv in every lane): one permute per look-up, even in a view of more
    // levels (large_textured's 1024x1024 texture has 11 and reads its first few)
    const bool narrow =
        b.table.levels <= 8 || _mm256_testz_si256(_mm256_or_si256(L[0].hi, L[1].hi), _mm256_set1_epi32(8));
    for (int h = 0; h < 2; ++h) filter_half(in, R, img, smp, b.table, h, L[h], narrow);
    return true;
}

// Every lane of the handle register holds h.
TVK_AVX2 bool uniform_handle(const uint32_t* handle, uint32_t h) {
    const __m256i hv = _mm256_set1_epi32(int(h));
    const __m256i same =
        _mm256_and_si256(_mm256_cmpeq_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(handle)), hv),
                         _mm256_cmpeq_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(handle + 8)), hv));
    return _mm256_movemask_epi8(same) == -1;
}

}  // namespace

bool bind_sample(const Inst& in, uint32_t handle, const Descriptor* const* slots, uint32_t num_slots, BoundSample& b) {
    b.handle = handle;
    b.state = BoundSample::State::Interpreter;
    constexpr uint32_t kAllowed = kSampleImplicitLod | kSampleBias | kSampleExplicitLod;
    if (in.op != Op::Sample || (in.imm & ~kAllowed) || in.b == kNoReg) return false;
    if ((in.imm & (kSampleBias | kSampleExplicitLod)) && in.c == kNoReg) return false;
    const uint32_t si = handle & 0xFFFF, ss = handle >> 16;
    if (si >= num_slots || ss >= num_slots || !slots[si] || !slots[ss]) return false;
    const ImageView* img = slots[si]->image;
    const SamplerState* smp = slots[ss]->sampler;
    if (!img || !smp || !img->base) return false;
    if (smp->mipmap_mode == MipmapMode::Nearest && !(in.imm & kSampleExplicitLod)) return false;  // exact log2
    // the table prepare_view made, or (a view filled by hand, or changed since) the one it would make now
    b.table = table_current(*img) ? img->table : level_table(*img);
    if (!b.table.rgba8 || !sampler_fits(*smp, b.table)) return false;
    b.img = img;
    b.smp = smp;
    b.state = BoundSample::State::Kernel;
    return true;
}

TVK_AVX2 bool sample_bound(const Inst& in, uint32_t* R, const BoundSample& b) {
    return b.state == BoundSample::State::Kernel && uniform_handle(R + size_t(in.a) * kLanes, b.handle) &&
           sample_with(in, R, b);
}

TVK_AVX2 bool sample_rgba8(const Inst& in, uint32_t* R, const Descriptor* const* slots, uint32_t num_slots) {
    const uint32_t* handle = R + size_t(in.a) * kLanes;
    if (!uniform_handle(handle, handle[0])) return false;  // one handle for all 16 lanes
    BoundSample b;
    return bind_sample(in, handle[0], slots, num_slots, b) && sample_with(in, R, b);
}

}  // namespace tilevk::shader::jit
