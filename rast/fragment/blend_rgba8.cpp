// blend_rgba8_block (blend_rgba8.h), built once per instruction set like rast/render/fragment_block.cpp.
#include "rast/fragment/blend_rgba8.h"

#include "rast/fragment/blend_codes.h"
#include "rast/fragment/block.h"
#include "rast/fragment/block_kernels.h"

namespace tilevk::rast::fragment {
inline namespace TILEVK_ISA {

#if TILEVK_SIMD_AVX2
namespace {

// mul_norm8 on 32 bytes: p = a*b; p += p >> 8; p += 0x80; p >> 8, in 16-bit lanes.
inline __m256i mul_norm_epu8(__m256i a, __m256i b) {
    const __m256i zero = _mm256_setzero_si256(), half = _mm256_set1_epi16(0x80);
    auto part = [&](__m256i x, __m256i y) {
        __m256i p = _mm256_mullo_epi16(x, y);
        p = _mm256_add_epi16(p, _mm256_srli_epi16(p, 8));
        return _mm256_srli_epi16(_mm256_add_epi16(p, half), 8);
    };
    const __m256i lo = part(_mm256_unpacklo_epi8(a, zero), _mm256_unpacklo_epi8(b, zero));
    const __m256i hi = part(_mm256_unpackhi_epi8(a, zero), _mm256_unpackhi_epi8(b, zero));
    return _mm256_packus_epi16(lo, hi);
}

// factor8 for every byte: `alpha` selects the alpha channel's rules (SRC_ALPHA_SATURATE is ONE there).
inline __m256i factor_epu8(uint8_t f, bool alpha, __m256i s, __m256i d, __m256i k) {
    const __m256i ones = _mm256_set1_epi8(-1);
    const __m256i bcast_alpha = _mm256_setr_epi8(3, 3, 3, 3, 7, 7, 7, 7, 11, 11, 11, 11, 15, 15, 15, 15, 3, 3, 3, 3, 7,
                                                 7, 7, 7, 11, 11, 11, 11, 15, 15, 15, 15);
    switch (PipeFactor(f)) {
        case kZero:
            return _mm256_setzero_si256();
        case kOne:
            return ones;
        case kSrcColor:
            return s;
        case kSrcAlpha:
            return _mm256_shuffle_epi8(s, bcast_alpha);
        case kDstColor:
            return d;
        case kDstAlpha:
            return _mm256_shuffle_epi8(d, bcast_alpha);
        case kSrcAlphaSat:
            // min(src alpha, 255 - dst alpha)
            if (alpha) return ones;
            return _mm256_min_epu8(_mm256_shuffle_epi8(s, bcast_alpha),
                                   _mm256_xor_si256(_mm256_shuffle_epi8(d, bcast_alpha), ones));
        case kConstColor:
            return k;
        case kConstAlpha:
            return _mm256_shuffle_epi8(k, bcast_alpha);
        case kInvSrcColor:
            return _mm256_xor_si256(s, ones);  // 255 - x
        case kInvSrcAlpha:
            return _mm256_xor_si256(_mm256_shuffle_epi8(s, bcast_alpha), ones);
        case kInvDstColor:
            return _mm256_xor_si256(d, ones);
        case kInvDstAlpha:
            return _mm256_xor_si256(_mm256_shuffle_epi8(d, bcast_alpha), ones);
        case kInvConstColor:
            return _mm256_xor_si256(k, ones);
        case kInvConstAlpha:
            return _mm256_xor_si256(_mm256_shuffle_epi8(k, bcast_alpha), ones);
        default:
            return _mm256_setzero_si256();
    }
}

// func8 on bytes: saturating add / subtract, min, max.
inline __m256i op_epu8(BlendOp op, __m256i a, __m256i b) {
    switch (op) {
        case BlendOp::Add:
            return _mm256_adds_epu8(a, b);
        case BlendOp::Subtract:
            return _mm256_subs_epu8(a, b);
        case BlendOp::ReverseSubtract:
            return _mm256_subs_epu8(b, a);
        case BlendOp::Min:
            return _mm256_min_epu8(a, b);
        case BlendOp::Max:
            return _mm256_max_epu8(a, b);
    }
    return a;
}

// Bytes of the channels in `mem_mask` (bit i = memory channel i) of every pixel.
inline __m256i channel_bytes(uint8_t mem_mask) {
    uint32_t word = 0;
    for (int i = 0; i < 4; ++i)
        if (mem_mask & (1u << i)) word |= 0xffu << (8 * i);
    return _mm256_set1_epi32(int(word));
}

// The block's source colours as two row pairs (rows 0|1, rows 2|3, one row per 128-bit half): pack_rgba8_rows'
// conversion (float_to_unorm8, UnormPath::Avx8) written out straight, the rows placed by one qword permute.
inline void pack_rgba8_pairs(bool bgra, const float src[4][kBlockLanes], __m256i pairs[2]) {
    const __m256 one = _mm256_set1_ps(1.0f), k255 = _mm256_set1_ps(255.0f);
    const __m256i order = bgra ? _mm256_setr_epi8(8, 4, 0, 12, 9, 5, 1, 13, 10, 6, 2, 14, 11, 7, 3, 15, 8, 4, 0, 12, 9,
                                                  5, 1, 13, 10, 6, 2, 14, 11, 7, 3, 15)
                               : _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 0, 4, 8, 12, 1,
                                                  5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
    auto unorm = [&](const float* x) {
        return _mm256_cvtps_epi32(_mm256_mul_ps(_mm256_min_ps(one, _mm256_loadu_ps(x)), k255));
    };
    for (int h = 0; h < 2; ++h) {
        const __m256i r = unorm(src[0] + 8 * h), g = unorm(src[1] + 8 * h);
        const __m256i bl = unorm(src[2] + 8 * h), a = unorm(src[3] + 8 * h);
        const __m256i px =
            _mm256_shuffle_epi8(_mm256_packus_epi16(_mm256_packs_epi32(r, g), _mm256_packs_epi32(bl, a)), order);
        // qwords: (0,0)(1,0) | (0,1)(1,1) | (2,0)(3,0) | (2,1)(3,1) -> row 2h = q0 q2, row 2h+1 = q1 q3
        pairs[h] = _mm256_permute4x64_epi64(px, 0xd8);
    }
}

// The general kernel's per-pair steps for b.over, in 16-bit lanes: every byte is
// adds(mul_norm(s, sa), mul_norm(d, 255 - sa)). The factor bytes are taken after the unpack (the same values), and
// the saturating byte add is packus of the 16-bit sum (both terms are <= 255, so both saturate at 255 alike).
inline __m256i over_pair(__m256i s, __m256i d) {
    const __m256i zero = _mm256_setzero_si256(), half = _mm256_set1_epi16(0x80), inv = _mm256_set1_epi16(0xff);
    const __m256i bcast_alpha16 = _mm256_setr_epi8(6, -1, 6, -1, 6, -1, 6, -1, 14, -1, 14, -1, 14, -1, 14, -1, 6, -1, 6,
                                                   -1, 6, -1, 6, -1, 14, -1, 14, -1, 14, -1, 14, -1);
    auto norm = [&](__m256i p) {  // mul_norm8 of the 16-bit product p
        p = _mm256_add_epi16(p, _mm256_srli_epi16(p, 8));
        return _mm256_srli_epi16(_mm256_add_epi16(p, half), 8);
    };
    auto part = [&](__m256i s16, __m256i d16) {
        const __m256i sa = _mm256_shuffle_epi8(s16, bcast_alpha16);
        return _mm256_add_epi16(norm(_mm256_mullo_epi16(s16, sa)),
                                norm(_mm256_mullo_epi16(d16, _mm256_xor_si256(sa, inv))));
    };
    return _mm256_packus_epi16(part(_mm256_unpacklo_epi8(s, zero), _mm256_unpacklo_epi8(d, zero)),
                               part(_mm256_unpackhi_epi8(s, zero), _mm256_unpackhi_epi8(d, zero)));
}

// blend_rgba8_block for b.over (standard alpha blending, the common state).
void blend_over(const Rgba8Blend& b, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block,
                size_t pitch) {
    __m256i pairs[2];
    pack_rgba8_pairs(b.bgra, src, pairs);
    const uint32_t raster = lanes_to_raster(lane_mask);
    const __m256i write_bytes = channel_bytes(b.wmask_mem);
    for (int pair = 0; pair < 2; ++pair) {
        const uint32_t pixels = (raster >> (8 * pair)) & 0xffu;  // rows 2*pair and 2*pair+1, 4 pixels each
        if (!pixels) continue;
        uint8_t* row0 = block + size_t(2 * pair) * pitch;
        uint8_t* row1 = row0 + pitch;
        const __m256i d =
            _mm256_loadu2_m128i(reinterpret_cast<const __m128i*>(row1), reinterpret_cast<const __m128i*>(row0));
        const __m256i keep = _mm256_and_si256(write_bytes, detail::lane_mask8(pixels));
        const __m256i res = _mm256_blendv_epi8(d, over_pair(pairs[pair], d), keep);
        _mm256_storeu2_m128i(reinterpret_cast<__m128i*>(row1), reinterpret_cast<__m128i*>(row0), res);
    }
}

}  // namespace
#endif

bool blend_rgba8_block(const Rgba8Blend& b, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block,
                       size_t pitch) {
#if TILEVK_SIMD_AVX2
    if (b.over) {
        blend_over(b, src, lane_mask, block, pitch);
        return true;
    }
    __m128i rows[4];
    detail::pack_rgba8_rows(b.bgra, src, rows);
    const uint32_t raster = lanes_to_raster(lane_mask);
    const __m256i k = _mm256_set1_epi32(
        int(uint32_t(b.k[0]) | uint32_t(b.k[1]) << 8 | uint32_t(b.k[2]) << 16 | uint32_t(b.k[3]) << 24));
    const __m256i alpha_bytes = channel_bytes(0x8), write_bytes = channel_bytes(b.wmask_mem);
    for (int pair = 0; pair < 2; ++pair) {
        const uint32_t pixels = (raster >> (8 * pair)) & 0xffu;  // rows 2*pair and 2*pair+1, 4 pixels each
        if (!pixels) continue;
        uint8_t* row0 = block + size_t(2 * pair) * pitch;
        uint8_t* row1 = row0 + pitch;
        const __m256i s = _mm256_set_m128i(rows[2 * pair + 1], rows[2 * pair]);
        const __m256i d = _mm256_set_m128i(_mm_loadu_si128(reinterpret_cast<const __m128i*>(row1)),
                                           _mm_loadu_si128(reinterpret_cast<const __m128i*>(row0)));
        __m256i res = s;
        if (b.blend) {
            // per channel: func(mul_norm(s, src factor), mul_norm(d, dst factor)), the alpha channel by its own rules
            const __m256i sf = _mm256_blendv_epi8(factor_epu8(b.rgb_src, false, s, d, k),
                                                  factor_epu8(b.a_src, true, s, d, k), alpha_bytes);
            const __m256i df = _mm256_blendv_epi8(factor_epu8(b.rgb_dst, false, s, d, k),
                                                  factor_epu8(b.a_dst, true, s, d, k), alpha_bytes);
            const __m256i st = mul_norm_epu8(s, sf), dt = mul_norm_epu8(d, df);
            res = _mm256_blendv_epi8(op_epu8(b.rgb_op, st, dt), op_epu8(b.a_op, st, dt), alpha_bytes);
        }
        const __m256i keep = _mm256_and_si256(write_bytes, detail::lane_mask8(pixels));
        res = _mm256_blendv_epi8(d, res, keep);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row0), _mm256_castsi256_si128(res));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row1), _mm256_extracti128_si256(res, 1));
    }
    return true;
#else
    (void)b, (void)src, (void)lane_mask, (void)block, (void)pitch;
    return false;
#endif
}

}  // namespace TILEVK_ISA
}  // namespace tilevk::rast::fragment
