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

}  // namespace
#endif

bool blend_rgba8_block(const Rgba8Blend& b, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block,
                       size_t pitch) {
#if TILEVK_SIMD_AVX2
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
