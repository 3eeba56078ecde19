// The AVX2 kernels and their scalar twins agree bit for bit on random planes within the proved 32-bit bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include "rast/core/cpu.h"
#include "rast/core/tile_kernels.h"

#if TILEVK_SIMD_AVX2
// Built with the AVX2/FMA translation units' flags: on a CPU without them every test here is skipped.
class RequireAvx2 : public ::testing::Environment {
  public:
    void SetUp() override {
        if (!tilevk::rast::cpu_has_avx2_kernels()) GTEST_SKIP() << "this CPU cannot run the AVX2/FMA kernels";
    }
};
[[maybe_unused]] const auto* const kRequireAvx2 = ::testing::AddGlobalTestEnvironment(new RequireAvx2);
#endif

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
    int64_t lo = INT64_MAX, hi = INT64_MIN;  // exact min/max over the samples, as tile_setup makes them
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
        // The per-plane 4x4 mask from a block value anywhere in the tile (the 16->4 level's entry point).
        for (int k = 0; k < n; ++k) {
            const int32_t bx4 = 4 * ((iter >> 3) & 15), by4 = 4 * ((iter >> 7) & 15);
            for (int s = 0; s < 4; ++s) {
                const int32_t base = planes[k].c[s] + planes[k].a * bx4 + planes[k].b * by4;
                ASSERT_EQ(plane_mask4x4_scalar(planes[k], base), plane_mask4x4_avx2(planes[k], base)) << iter;
            }
        }
        // Step tables: the AVX2 fill equals the scalar one field for field.
        for (int k = 0; k < n; ++k) {
            TilePlane x = planes[k], y = planes[k];
            fill_step_table_scalar(&x);
            fill_step_table_avx2(&y);
            ASSERT_EQ(x.up, y.up);
            ASSERT_EQ(x.dn, y.dn);
            for (int i = 0; i < 16; ++i) {
                ASSERT_EQ(x.step[i], y.step[i]) << iter;
                ASSERT_EQ(x.step4[i], y.step4[i]) << iter;
            }
        }
        const int32_t bx = 4 * ((iter >> 2) & 15), by = 4 * ((iter >> 6) & 15);
        for (int s = 0; s < 4; ++s) {
            const uint32_t m1 = mask4x4_scalar(list, n, s, bx, by), m2 = mask4x4_avx2(list, n, s, bx, by);
            ASSERT_EQ(m1, m2) << iter;
            nonzero += m1 != 0 && m1 != 0xFFFF;
        }
        // The four samples at once (4x small-primitive scan and 16->4 partial lanes); no plane: all covered.
        const uint64_t q = mask4x4_samples4_scalar(list, n, bx, by);
        ASSERT_EQ(q, mask4x4_samples4_avx2<0>(list, n, bx, by)) << iter;
        if (n == 3) {
            ASSERT_EQ(q, mask4x4_samples4_avx2<3>(list, n, bx, by)) << iter;
        }
        for (int s = 0; s < 4; ++s) ASSERT_EQ((q >> (16 * s)) & 0xFFFF, mask4x4_scalar(list, n, s, bx, by)) << iter;
        ASSERT_EQ(mask4x4_samples4_avx2<0>(list, 0, bx, by), ~uint64_t{0});
    }
    EXPECT_GT(nonzero, 1000u);  // the random planes do cut blocks
    EXPECT_GT(partial, 1000u);
#endif
}

#if TILEVK_SIMD_AVX2  // SampleSteps16 and its kernels exist only in the AVX2 build (tile_kernels.h)
// The 16-bit 4x kernel (small steps) against mask4x4_samples4_scalar: planes with |a| + |b| up to the bound, block
// values anywhere in (-2^30, 2^30] (saturated bases) and near 0 (exact sums).
TEST(Kernels, SampleSteps16MatchesMask4x4Samples4) {
    std::mt19937_64 rng(4242);
    uint64_t used = 0, partial = 0;
    for (int iter = 0; iter < 200000; ++iter) {
        TilePlane planes[3];
        SampleSteps16 steps[3];
        const TilePlane* list[3] = {&planes[0], &planes[1], &planes[2]};
        bool fits = true;
        for (int k = 0; k < 3; ++k) {
            TilePlane& p = planes[k];
            p = TilePlane{};
            const int32_t lim = (iter % 5 == 0) ? 8191 : 2048;  // 8191: the bound reached with the sample offsets
            p.a = static_cast<int32_t>(std::uniform_int_distribution<int32_t>(-lim, lim)(rng));
            const int32_t rest = lim - std::abs(p.a);
            p.b = static_cast<int32_t>(std::uniform_int_distribution<int32_t>(-rest, rest)(rng));
            const int64_t near = 16 * (int64_t{std::abs(p.a)} + std::abs(p.b)) + 40000;
            const int64_t c0 = (iter % 3 == 0) ? std::uniform_int_distribution<int64_t>(-(1 << 29), 1 << 29)(rng)
                                               : std::uniform_int_distribution<int64_t>(-near, near)(rng);
            const int64_t d = (int64_t{std::abs(p.a)} + std::abs(p.b)) * 7 / 8 + 1;
            for (int s = 0; s < 4; ++s)
                p.c[s] = static_cast<int32_t>(c0 + (s ? std::uniform_int_distribution<int64_t>(-d, d)(rng) : 0));
            fill_step_table(&p);
            fits &= fill_sample_steps16(p, &steps[k]);
        }
        if (!fits) continue;
        ++used;
        for (int k = 0; k < 3; ++k)
            for (int s = 0; s < 4; ++s)
                for (int i = 0; i < 16; ++i)
                    ASSERT_EQ(steps[k].v[s][i], planes[k].c[s] - planes[k].c[0] + planes[k].step[i]);
        const int32_t bx = 4 * ((iter >> 2) & 15), by = 4 * ((iter >> 6) & 15);
        for (int n = 1; n <= 3; ++n) {
            const uint64_t expect = mask4x4_samples4_scalar(list, n, bx, by);
            ASSERT_EQ(mask4x4_samples4_16_scalar(list, steps, n, bx, by), expect) << iter;
#if TILEVK_SIMD_AVX2
            ASSERT_EQ(mask4x4_samples4_16_avx2<0>(list, steps, n, bx, by), expect) << iter;
            if (n == 3) {
                ASSERT_EQ(mask4x4_samples4_16_avx2<3>(list, steps, n, bx, by), expect) << iter;
            }
#endif
            partial += expect != 0 && expect != ~uint64_t{0};
        }
    }
    EXPECT_GT(used, 100000u);
    EXPECT_GT(partial, 10000u);
}
#endif  // TILEVK_SIMD_AVX2

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
            const int64_t base = int64_t{p.c[s]} + int64_t{p.a} * ox + int64_t{p.b} * oy;
            ASSERT_EQ(plane_mask4x4_scalar(p, static_cast<int32_t>(base)), expect);
        }
        // Step tables from their definition.
        for (int i = 0; i < 16; ++i) {
            ASSERT_EQ(p.step[i], p.a * (i & 3) + p.b * (i >> 2));
            ASSERT_EQ(p.step4[i], 4 * (p.a * (i & 3) + p.b * (i >> 2)));
        }
    }
}

// classify16_scalar against brute force: the true minimum and maximum of the plane over every sample of every
// pixel of each sub-block (64-bit), at the 16-px level of a 64-px tile and the 4-px level of each 16-px block.
TEST(Kernels, ClassifyMatchesBruteForce) {
    std::mt19937_64 rng(4242);
    uint64_t rejects = 0, accepts = 0, partial = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        const TilePlane p = random_plane(rng);
        const int shift = (iter & 1) ? 4 : 2;
        const int32_t ox = (iter & 1) ? 0 : 16 * ((iter >> 1) & 3), oy = (iter & 1) ? 0 : 16 * ((iter >> 3) & 3);
        const int w = 1 << shift;
        uint32_t expect_rej = 0, expect_acc = 0;
        for (int lane = 0; lane < 16; ++lane) {
            int64_t lo = INT64_MAX, hi = INT64_MIN;
            for (int y = 0; y < w; ++y)
                for (int x = 0; x < w; ++x)
                    for (int s = 0; s < 4; ++s) {
                        const int64_t v = int64_t{p.c[s]} + int64_t{p.a} * (ox + (lane & 3) * w + x) +
                                          int64_t{p.b} * (oy + (lane >> 2) * w + y);
                        lo = std::min(lo, v), hi = std::max(hi, v);
                    }
            expect_rej |= static_cast<uint32_t>(hi <= 0) << lane;
            expect_acc |= static_cast<uint32_t>(lo > 0) << lane;
        }
        uint32_t rej, acc;
        classify16_scalar(p, ox, oy, shift, &rej, &acc);
        ASSERT_EQ(rej, expect_rej) << iter;
        ASSERT_EQ(acc, expect_acc) << iter;
        rejects += std::popcount(rej), accepts += std::popcount(acc), partial += 16 - std::popcount(rej | acc);
    }
    EXPECT_GT(rejects, 1000u);
    EXPECT_GT(accepts, 1000u);
    EXPECT_GT(partial, 1000u);
}

// The 1x 16x16 kernel (block16_masks): the scalar twin against the 64-bit definition pixel by pixel, and the AVX2
// version (the runtime plane count and every compile-time count) against the scalar twin, field for field.
void expect_same_block16(const Block16Masks& x, const Block16Masks& y, int iter) {
    for (int lane = 0; lane < 16; ++lane) ASSERT_EQ(x.mask[lane], y.mask[lane]) << iter << " lane " << lane;
    ASSERT_EQ(x.full, y.full) << iter;
    ASSERT_EQ(x.empty, y.empty) << iter;
}

TEST(Kernels, Block16MasksMatchDefinitionAndTwins) {
    std::mt19937_64 rng(9090);
    uint64_t full = 0, empty = 0, partial = 0;
    for (int iter = 0; iter < 60000; ++iter) {
        const int n = 1 + iter % 4;
        TilePlane planes[4];
        const TilePlane* list[4] = {&planes[0], &planes[1], &planes[2], &planes[3]};
        for (int k = 0; k < n; ++k) planes[k] = random_plane(rng);
        const int32_t ox = 16 * ((iter >> 2) & 3), oy = 16 * ((iter >> 4) & 3);
        int32_t base[4];
        for (int k = 0; k < n; ++k) base[k] = planes[k].c[0] + planes[k].a * ox + planes[k].b * oy;
        Block16Masks s;
        std::memset(&s, 0xA5, sizeof s);  // every checked field must be written
        block16_masks_scalar(list, n, base, &s);
        uint32_t expect_full = 0, expect_empty = 0;
        for (int lane = 0; lane < 16; ++lane) {
            uint32_t expect = 0;
            for (int i = 0; i < 16; ++i) {
                const int32_t x = ox + 4 * (lane & 3) + (i & 3), y = oy + 4 * (lane >> 2) + (i >> 2);
                bool inside = true;
                for (int k = 0; k < n; ++k)
                    inside =
                        inside && int64_t{planes[k].c[0]} + int64_t{planes[k].a} * x + int64_t{planes[k].b} * y > 0;
                expect |= static_cast<uint32_t>(inside) << i;
            }
            ASSERT_EQ(s.mask[lane], expect) << iter << " lane " << lane;
            expect_full |= static_cast<uint32_t>(expect == 0xFFFF) << lane;
            expect_empty |= static_cast<uint32_t>(expect == 0) << lane;
        }
        ASSERT_EQ(s.full, expect_full) << iter;
        ASSERT_EQ(s.empty, expect_empty) << iter;
        full += std::popcount(expect_full), empty += std::popcount(expect_empty);
        partial += 16 - std::popcount(expect_full | expect_empty);
#if TILEVK_SIMD_AVX2
        Block16Masks v;
        std::memset(&v, 0x5A, sizeof v);
        block16_masks_avx2<0>(list, n, base, &v);
        expect_same_block16(s, v, iter);
        std::memset(&v, 0x5A, sizeof v);
        if (n == 1) block16_masks_avx2<1>(list, n, base, &v);
        if (n == 2) block16_masks_avx2<2>(list, n, base, &v);
        if (n == 3) block16_masks_avx2<3>(list, n, base, &v);
        if (n <= 3) expect_same_block16(s, v, iter);
#endif
        // The row-threshold kernel (block16_rows): its scalar twin against s (checked against the definition
        // above), the AVX2 version at every plane count against the twin.
        for (int k = 0; k < n; ++k) {
            fill_row_table(&planes[k]);
            // row_inverse's bound (the hardware estimate with AVX2, the quotient in the portable build).
            const double ra = std::abs(double(planes[k].a));
            if (ra != 0) {
                ASSERT_NEAR(double(planes[k].rinv) * ra, -1.0, 1.5 / 4096) << iter;
            }
        }
        Block16Masks rs;
        std::memset(&rs, 0xA5, sizeof rs);
        block16_rows_scalar(list, n, base, &rs);
        expect_same_block16(s, rs, iter);
        // The masks do not depend on which reciprocal picked the estimate: the exact quotient, and estimates off
        // by the bound's full 1.5*2^-12 either way, give the same result.
        for (const double err : {0.0, 1.5 / 4096, -1.5 / 4096}) {
            TilePlane other[4];
            const TilePlane* other_list[4];
            for (int k = 0; k < n; ++k) {
                other[k] = planes[k];
                other_list[k] = &other[k];
                if (other[k].ra != 0) other[k].rinv = float(-1.0 / other[k].ra * (1.0 + err));
            }
            Block16Masks o;
            std::memset(&o, 0xA5, sizeof o);
            block16_rows_scalar(other_list, n, base, &o);
            expect_same_block16(s, o, iter);
        }
#if TILEVK_SIMD_AVX2
        std::memset(&v, 0x5A, sizeof v);
        block16_rows_avx2<0>(list, n, base, &v);
        expect_same_block16(rs, v, iter);
        std::memset(&v, 0x5A, sizeof v);
        if (n == 1) block16_rows_avx2<1>(list, n, base, &v);
        if (n == 2) block16_rows_avx2<2>(list, n, base, &v);
        if (n == 3) block16_rows_avx2<3>(list, n, base, &v);
        if (n <= 3) expect_same_block16(rs, v, iter);
#endif
    }
    EXPECT_GT(full, 1000u);
    EXPECT_GT(empty, 1000u);
    EXPECT_GT(partial, 1000u);
}

}  // namespace
}  // namespace tilevk::rast
