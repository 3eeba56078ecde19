#include "rast/fragment/msaa.h"

#include <cmath>
#include <cstring>

#include "rast/core/cpu.h"
#include "rast/fragment/resolve_rows.h"

#if defined(__x86_64__) || defined(__i386__)
#include <emmintrin.h>
#endif

namespace tilevk::rast::fragment {

namespace {
// lp_build_cmp(GREATER) is fcmp ugt under DAZ: NaN passes, a denormal alpha counts as zero.
inline bool ugt_daz(float a, float ref) {
    if (std::isnan(a)) return true;
    if (a != 0.0f && std::fabs(a) < 0x1p-126f) a = 0.0f;
    return a > ref;
}
}  // namespace

uint16_t alpha_to_coverage_1x(const float alpha[kBlockLanes], uint16_t lane_mask) {
    uint16_t out = 0;
    for (int l = 0; l < kBlockLanes; ++l)
        if ((lane_mask & (1u << l)) && ugt_daz(alpha[l], 0.5f)) out |= uint16_t(1u << l);
    return out;
}

void alpha_to_coverage_4x(const float alpha[kBlockLanes], uint16_t sample_masks[kMaxSamples]) {
    for (int s = 0; s < kMaxSamples; ++s) {
        // reference = (float)(1.0/4 * s): 0, 0.25, 0.5, 0.75 exactly
        const float ref = float(0.25 * s);
        uint16_t keep = 0;
        for (int l = 0; l < kBlockLanes; ++l)
            if (ugt_daz(alpha[l], ref)) keep |= uint16_t(1u << l);
        sample_masks[s] &= keep;
    }
}

uint16_t coverage_sample_mask(uint32_t sample_mask, int samples) {
    if (sample_mask == 0) return 0;                         // rasterizer discard
    return samples > 1 ? uint16_t(sample_mask & 0xFu) : 1;  // ignored at 1x
}

void apply_sample_mask(uint32_t sample_mask, int samples, uint16_t sample_masks[kMaxSamples]) {
    const uint16_t keep = coverage_sample_mask(sample_mask, samples);
    if (keep != 0 && samples <= 1) return;
    for (int s = 0; s < kMaxSamples; ++s)
        if (!((keep >> s) & 1u)) sample_masks[s] = 0;
}

uint16_t any_sample(const uint16_t sample_masks[kMaxSamples]) {
    return uint16_t(sample_masks[0] | sample_masks[1] | sample_masks[2] | sample_masks[3]);
}

bool resolve_pixel(ColorFormat f, const uint8_t* const samples[kMaxSamples], uint8_t* out, bool fused) {
    const FormatInfo& fi = format_info(f);
    if (format::is_integer(fi)) {
        // u_blitter copies one sample of integer formats (util_make_fs_blit_msaa_color at sample 0), no average
        std::memcpy(out, samples[0], fi.bytes);
        return true;
    }
    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int s = 0; s < kMaxSamples; ++s) {
        float t[4];
        format::decode_color(fi, samples[s], t, fused);
        for (int c = 0; c < 4; ++c) sum[c] = sum[c] + t[c];  // fl(sum + texel), sample order
    }
    float avg[4];
    for (int c = 0; c < 4; ++c) avg[c] = sum[c] * 0.25f;
    format::encode_color(fi, avg, out, fused);
    return true;
}

namespace {

// Formats whose every byte is one UNORM8 channel (R8 ... R8G8B8A8, B8G8R8A8, A8B8G8R8_UNORM_PACK32): resolve_pixel
// then does the same to each byte, which resolve_unorm8_row does without decoding texels one at a time.
bool bytewise_unorm8(const FormatInfo& fi) {
    return fi.kind == format::ChannelKind::Unorm8 && fi.channels == fi.bytes;
}

// resolve_pixel on the BYTES-byte texels of one row, w pixels: per byte the same float operations (decode
// fl(u * fl(1/255)), a sum in sample order from 0, * 0.25, float_to_unorm8 as encode_color's default path). BYTES
// is a constant so that the compiler can do a texel's bytes side by side.
template <size_t BYTES>
void resolve_unorm8_row(const uint8_t* src, size_t sample_stride, size_t src_step, uint8_t* dst, int w) {
    for (int x = 0; x < w; ++x) {
        const uint8_t* p = src + size_t(x) * src_step;
        float sum[BYTES] = {};
        for (int s = 0; s < kMaxSamples; ++s)
            for (size_t c = 0; c < BYTES; ++c) sum[c] = sum[c] + format::unorm8_to_float(p[s * sample_stride + c]);
        for (size_t c = 0; c < BYTES; ++c) dst[size_t(x) * BYTES + c] = format::float_to_unorm8(sum[c] * 0.25f);
    }
}

#if defined(__x86_64__) || defined(__i386__)
// resolve_unorm8_row<4> with a texel's four bytes in SSE2 lanes, each lane doing what the scalar row does:
// cvtdq2ps (exact on bytes) * fl(1/255), addps in sample order from 0, * 0.25, min.ps(1.0, x), * 255, cvtps2dq,
// then packssdw + packuswb = pack_sat_u8. With the samples in planes (src_step 4, the renderer's layout) four
// pixels go together: one 16-byte load per sample, unpacked to one float vector per pixel.
//
// Four equal samples resolve to the sample itself: for every byte u, fl(fl(fl(v + v) + v) + v) * 0.25 * 255 with
// v = fl(u * fl(1/255)) rounds back to u (checked for all 256 values by msaa_test's ResolveOfEqualSamplesIsTheSample),
// so four pixels whose samples are all equal (untouched or cleared parts of the image) are copied.
template <>
void resolve_unorm8_row<4>(const uint8_t* src, size_t sample_stride, size_t src_step, uint8_t* dst, int w) {
    const __m128 k = _mm_set1_ps(float(1.0 / 255.0)), quarter = _mm_set1_ps(0.25f), one = _mm_set1_ps(1.0f),
                 scale = _mm_set1_ps(255.0f);
    const __m128i zero = _mm_setzero_si128();
    const auto finish = [&](__m128 sum) {  // one pixel's four channel sums -> its four unorm8 values as int32
        const __m128 a = _mm_min_ps(one, _mm_mul_ps(sum, quarter));  // minps(1, x): 1 < x ? 1 : x
        return _mm_cvtps_epi32(_mm_mul_ps(a, scale));
    };
    int x = 0;
    if (src_step == 4) {
#if TILEVK_AVX2_VARIANT
        if (kernel_isa() == Isa::kAvx2) x = isa_avx2::resolve_rgba8_planes(src, sample_stride, dst, w);
#endif
        for (; x + 4 <= w; x += 4) {
            const uint8_t* p = src + size_t(x) * 4;
            __m128i v[kMaxSamples];  // the loops unrolled keep the arrays in registers (GCC does not at -O2)
#pragma GCC unroll 4
            for (int s = 0; s < kMaxSamples; ++s)
                v[s] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + s * sample_stride));
            const __m128i eq = _mm_and_si128(_mm_cmpeq_epi32(v[0], v[1]),
                                             _mm_and_si128(_mm_cmpeq_epi32(v[0], v[2]), _mm_cmpeq_epi32(v[0], v[3])));
            if (_mm_movemask_epi8(eq) == 0xFFFF) {
                _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + size_t(x) * 4), v[0]);
                continue;
            }
            __m128 sum[4] = {_mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps()};  // per pixel
#pragma GCC unroll 4
            for (int s = 0; s < kMaxSamples; ++s) {
                const __m128i lo = _mm_unpacklo_epi8(v[s], zero), hi = _mm_unpackhi_epi8(v[s], zero);
                const __m128i px[4] = {_mm_unpacklo_epi16(lo, zero), _mm_unpackhi_epi16(lo, zero),
                                       _mm_unpacklo_epi16(hi, zero), _mm_unpackhi_epi16(hi, zero)};
#pragma GCC unroll 4
                for (int i = 0; i < 4; ++i) sum[i] = _mm_add_ps(sum[i], _mm_mul_ps(_mm_cvtepi32_ps(px[i]), k));
            }
            const __m128i out = _mm_packus_epi16(_mm_packs_epi32(finish(sum[0]), finish(sum[1])),
                                                 _mm_packs_epi32(finish(sum[2]), finish(sum[3])));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + size_t(x) * 4), out);
        }
    }
    for (; x < w; ++x) {
        const uint8_t* p = src + size_t(x) * src_step;
        __m128 sum = _mm_setzero_ps();
        for (int s = 0; s < kMaxSamples; ++s) {
            int32_t word;
            std::memcpy(&word, p + s * sample_stride, 4);
            const __m128i bytes = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(word), zero), zero);
            sum = _mm_add_ps(sum, _mm_mul_ps(_mm_cvtepi32_ps(bytes), k));
        }
        const __m128i q = finish(sum);
        const int32_t out = _mm_cvtsi128_si32(_mm_packus_epi16(_mm_packs_epi32(q, q), zero));
        std::memcpy(dst + size_t(x) * 4, &out, 4);
    }
}
#endif

}  // namespace

void resolve_rect(ColorFormat f, const uint8_t* src, size_t sample_stride, size_t src_pitch, uint8_t* dst,
                  size_t dst_pitch, int w, int h, bool fused, size_t pixel_stride) {
    const FormatInfo& fi = format_info(f);
    const size_t bpp = fi.bytes;
    const size_t src_step = pixel_stride ? pixel_stride : bpp;
    if (bytewise_unorm8(fi)) {
        auto row = bpp == 4   ? &resolve_unorm8_row<4>
                   : bpp == 3 ? &resolve_unorm8_row<3>
                   : bpp == 2 ? &resolve_unorm8_row<2>
                              : &resolve_unorm8_row<1>;
        for (int y = 0; y < h; ++y)
            row(src + size_t(y) * src_pitch, sample_stride, src_step, dst + size_t(y) * dst_pitch, w);
        return;
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const uint8_t* base = src + size_t(y) * src_pitch + size_t(x) * src_step;
            const uint8_t* s[kMaxSamples] = {base, base + sample_stride, base + 2 * sample_stride,
                                             base + 3 * sample_stride};
            resolve_pixel(f, s, dst + size_t(y) * dst_pitch + size_t(x) * bpp, fused);
        }
    }
}

}  // namespace tilevk::rast::fragment
