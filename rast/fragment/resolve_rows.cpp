#include "rast/fragment/resolve_rows.h"

#include "rast/core/isa.h"

#if TILEVK_SIMD_AVX2
#include <immintrin.h>
#endif

namespace tilevk::rast::fragment::TILEVK_ISA {

// Each 256-bit vector holds two pixels' four channels as floats; the operations per lane are msaa.cpp's
// resolve_unorm8_row<4>: cvtdq2ps (exact on bytes) * fl(1/255), addps in sample order from 0, * 0.25,
// minps(1.0, x), * 255, cvtps2dq, packssdw + packuswb. Eight pixels whose samples are all equal are copied (four
// equal UNORM8 samples resolve to themselves, msaa.cpp).
int resolve_rgba8_planes(const uint8_t* src, size_t sample_stride, uint8_t* dst, int w) {
#if TILEVK_SIMD_AVX2
    const __m256 k = _mm256_set1_ps(float(1.0 / 255.0)), quarter = _mm256_set1_ps(0.25f), one = _mm256_set1_ps(1.0f),
                 scale = _mm256_set1_ps(255.0f);
    // the packs work within 128-bit halves: pixels 0 2 4 6 | 1 3 5 7 -> 0 .. 7
    const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
    int x = 0;
    for (; x + 8 <= w; x += 8) {
        const uint8_t* p = src + size_t(x) * 4;
        __m256i v[4];
#pragma GCC unroll 4
        for (int s = 0; s < 4; ++s) v[s] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + s * sample_stride));
        const __m256i eq =
            _mm256_and_si256(_mm256_cmpeq_epi32(v[0], v[1]),
                             _mm256_and_si256(_mm256_cmpeq_epi32(v[0], v[2]), _mm256_cmpeq_epi32(v[0], v[3])));
        if (_mm256_movemask_epi8(eq) == -1) {
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + size_t(x) * 4), v[0]);
            continue;
        }
        __m256 sum[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
#pragma GCC unroll 4
        for (int s = 0; s < 4; ++s)
#pragma GCC unroll 4
            for (int i = 0; i < 4; ++i) {  // pixels 2i and 2i+1
                const __m128i two = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p + s * sample_stride + 8 * i));
                sum[i] = _mm256_add_ps(sum[i], _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(two)), k));
            }
        __m256i q[4];
#pragma GCC unroll 4
        for (int i = 0; i < 4; ++i)
            q[i] = _mm256_cvtps_epi32(_mm256_mul_ps(_mm256_min_ps(one, _mm256_mul_ps(sum[i], quarter)), scale));
        const __m256i packed = _mm256_packus_epi16(_mm256_packs_epi32(q[0], q[1]), _mm256_packs_epi32(q[2], q[3]));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + size_t(x) * 4),
                            _mm256_permutevar8x32_epi32(packed, order));
    }
    return x;
#else
    (void)src, (void)sample_stride, (void)dst, (void)w;
    return 0;
#endif
}

}  // namespace tilevk::rast::fragment::TILEVK_ISA
