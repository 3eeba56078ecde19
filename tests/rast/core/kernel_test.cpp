// The AVX2 kernels and their scalar twins agree bit for bit on random planes within the proved 32-bit bounds.
#include <gtest/gtest.h>

#include <random>

#include "rast/core/tile_kernels.h"

namespace tilevk::rast {
namespace {

// A random live plane for a 64-px tile: |a|,|b| < 2^23 and lo/hi in (-2^30, 2^30] consistent with the bound.
TilePlane random_plane(std::mt19937_64& rng) {
    std::uniform_int_distribution<int> scale(0, 23);
    auto rnd = [&](int bits) {
        const int64_t lim = (int64_t{1} << bits) - 1;
        return static_cast<int32_t>(std::uniform_int_distribution<int64_t>(-lim, lim)(rng));
    };
    TilePlane p{};
    p.a = rnd(scale(rng));
    p.b = rnd(scale(rng));
    // A value somewhere in the tile is ~0; the origin value is then within 63*(|a|+|b|) of 0.
    const int64_t span = 63 * (int64_t{std::abs(p.a)} + std::abs(p.b)) + 1;
    const int64_t c0 = std::uniform_int_distribution<int64_t>(-span, span)(rng);
    int64_t lo = c0, hi = c0;
    for (int s = 0; s < 4; ++s) {
        const int64_t d = (int64_t{std::abs(p.a)} + std::abs(p.b)) * 3 / 4;
        p.c[s] = static_cast<int32_t>(c0 + std::uniform_int_distribution<int64_t>(-d, d)(rng));
        lo = std::min<int64_t>(lo, p.c[s]), hi = std::max<int64_t>(hi, p.c[s]);
    }
    p.lo = static_cast<int32_t>(lo), p.hi = static_cast<int32_t>(hi);
    fill_step_table(&p);
    return p;
}

TEST(Kernels, ScalarAndAvx2Agree) {
#if !TILEVK_SIMD_AVX2
    GTEST_SKIP() << "built without AVX2: only the scalar kernels exist";
#else
    std::mt19937_64 rng(1234);
    uint64_t nonzero = 0, partial = 0;
    for (int iter = 0; iter < 200000; ++iter) {
        TilePlane planes[4];
        const TilePlane* list[4] = {&planes[0], &planes[1], &planes[2], &planes[3]};
        const int n = 1 + iter % 4;
        for (int k = 0; k < n; ++k) planes[k] = random_plane(rng);
        const int shift = (iter & 1) ? 4 : 2;
        const int32_t ox = (iter & 1) ? 0 : 16 * ((iter >> 1) & 3), oy = (iter & 1) ? 0 : 16 * ((iter >> 3) & 3);
        for (int k = 0; k < n; ++k) {
            uint32_t r1, a1, r2, a2;
            classify16_scalar(planes[k], ox, oy, shift, &r1, &a1);
            classify16_avx2(planes[k], ox, oy, shift, &r2, &a2);
            ASSERT_EQ(r1, r2) << iter;
            ASSERT_EQ(a1, a2) << iter;
            partial += (r1 | a1) != 0xFFFF;
        }
        const int32_t bx = 4 * ((iter >> 2) & 15), by = 4 * ((iter >> 6) & 15);
        for (int s = 0; s < 4; ++s) {
            const uint32_t m1 = mask4x4_scalar(list, n, s, bx, by), m2 = mask4x4_avx2(list, n, s, bx, by);
            ASSERT_EQ(m1, m2) << iter;
            nonzero += m1 != 0 && m1 != 0xFFFF;
        }
    }
    EXPECT_GT(nonzero, 1000u);  // the random planes do cut blocks
    EXPECT_GT(partial, 1000u);
#endif
}

// Scalar kernel against a direct 64-bit evaluation of the same formula.
TEST(Kernels, ScalarMatchesDefinition) {
    std::mt19937_64 rng(77);
    for (int iter = 0; iter < 50000; ++iter) {
        TilePlane p = random_plane(rng);
        const TilePlane* list[1] = {&p};
        const int32_t ox = 4 * (iter % 16), oy = 4 * ((iter / 16) % 16);
        for (int s = 0; s < 4; ++s) {
            uint32_t expect = 0;
            for (int i = 0; i < 16; ++i)
                if (int64_t{p.c[s]} + int64_t{p.a} * (ox + (i & 3)) + int64_t{p.b} * (oy + (i >> 2)) > 0)
                    expect |= 1u << i;
            ASSERT_EQ(mask4x4_scalar(list, 1, s, ox, oy), expect);
        }
    }
}

}  // namespace
}  // namespace tilevk::rast
