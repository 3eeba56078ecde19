// Interpolation: lane order, the exact float operation order, and a double-precision bound.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rast/fragment/interp.h"

using namespace tilevk::rast::fragment;

TEST(FragmentLanes, LaneOrderIsQuadMajorBijection) {
    bool seen[16] = {};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const int l = lane_of(x, y);
            ASSERT_GE(l, 0);
            ASSERT_LT(l, 16);
            EXPECT_FALSE(seen[l]);
            seen[l] = true;
            EXPECT_EQ(lane_x(l), x);
            EXPECT_EQ(lane_y(l), y);
            // the 2x2 quad containing (x,y) owns lanes 4q..4q+3 (derivatives need intact quads)
            EXPECT_EQ(l / 4, (y / 2) * 2 + x / 2);
        }
    EXPECT_EQ(lane_of(1, 0), 1);
    EXPECT_EQ(lane_of(0, 1), 2);
    EXPECT_EQ(lane_of(2, 0), 4);
    EXPECT_EQ(lane_of(0, 2), 8);
}

TEST(FragmentLanes, MaskConversionRoundTrips) {
    for (uint32_t m = 0; m < 65536; ++m) {
        const uint16_t lanes = raster_to_lanes(uint16_t(m));
        ASSERT_EQ(lanes_to_raster(lanes), m);
        ASSERT_EQ(__builtin_popcount(lanes), __builtin_popcount(m));
    }
    EXPECT_EQ(raster_to_lanes(1u << (0 * 4 + 1)), 1u << 1);  // (1,0)
    EXPECT_EQ(raster_to_lanes(1u << (1 * 4 + 0)), 1u << 2);  // (0,1)
}

TEST(FragmentInterp, OffsetsFollowSampleCount) {
    EXPECT_EQ(plane_offset(1, -1).x, 0.0f);
    EXPECT_EQ(plane_offset(4, -1).x, 0.5f);
    EXPECT_EQ(plane_offset(4, 2).x, 0.125f);
    EXPECT_EQ(plane_offset(4, 2).y, 0.625f);
    EXPECT_EQ(frag_coord_offset(1, -1).y, 0.5f);
    EXPECT_EQ(frag_coord_offset(4, 3).x, 0.625f);
}

// Written independently of the kernel: explicit fmaf / separate mul+add per the stated order.
static float step_by_step(float dadx, float dady, float a0, float px, float py, bool fused) {
    if (fused) {
        float a = fmaf(dadx, px, a0);
        return fmaf(dady, py, a);
    }
    volatile float m1 = dadx * px;
    volatile float a = m1 + a0;
    volatile float m2 = dady * py;
    return m2 + a;
}

TEST(FragmentInterp, PlaneMatchesOperationOrderAndDoubleBound) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> coef(-4.0f, 4.0f);
    std::uniform_int_distribution<int> blk(0, 1023);
    int fused_differs = 0;
    for (int iter = 0; iter < 20000; ++iter) {
        Plane p{coef(rng), coef(rng), coef(rng) * 100.0f};
        const int bx = blk(rng) * 4, by = blk(rng) * 4;
        for (int samples : {1, 4}) {
            for (int s = -1; s < (samples == 4 ? 4 : 0); ++s) {
                const EvalOffset off = plane_offset(samples, s);
                float out_f[16], out_u[16];
                eval_plane(p, bx, by, off, true, out_f);
                eval_plane(p, bx, by, off, false, out_u);
                for (int l = 0; l < 16; ++l) {
                    const float px = float(bx + lane_x(l)) + off.x, py = float(by + lane_y(l)) + off.y;
                    ASSERT_EQ(out_f[l], step_by_step(p.dadx, p.dady, p.a0, px, py, true));
                    ASSERT_EQ(out_u[l], step_by_step(p.dadx, p.dady, p.a0, px, py, false));
                    fused_differs += out_f[l] != out_u[l];
                    // Error bound: each result is within a few ulps of the exact value (2 roundings each op).
                    const double exact = double(p.a0) + double(p.dadx) * px + double(p.dady) * py;
                    const double mag =
                        std::fabs(double(p.a0)) + std::fabs(double(p.dadx) * px) + std::fabs(double(p.dady) * py);
                    const double bound = mag * 4.0 * 0x1p-24;
                    ASSERT_LE(std::fabs(double(out_f[l]) - exact), bound);
                    ASSERT_LE(std::fabs(double(out_u[l]) - exact), bound);
                }
            }
        }
    }
    // Fusing must matter somewhere, otherwise the flag would be untested.
    EXPECT_GT(fused_differs, 0);
}

TEST(FragmentInterp, PerspectiveIsMultiplyByReciprocal) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> d(0.01f, 10.0f);
    int differs_from_div = 0;
    for (int i = 0; i < 100000; ++i) {
        float a[16], w[16], out[16];
        for (int l = 0; l < 16; ++l) {
            a[l] = d(rng);
            w[l] = d(rng);
        }
        perspective_divide(a, w, out);
        for (int l = 0; l < 16; ++l) {
            volatile float r = 1.0f / w[l];
            ASSERT_EQ(out[l], a[l] * r);
            differs_from_div += out[l] != a[l] / w[l];
        }
    }
    EXPECT_GT(differs_from_div, 0);
}

TEST(FragmentInterp, FragCoordAndDepth) {
    float x[16], y[16];
    frag_coord_xy(8, 12, frag_coord_offset(1, -1), x, y);
    for (int l = 0; l < 16; ++l) {
        EXPECT_EQ(x[l], 8.5f + lane_x(l));
        EXPECT_EQ(y[l], 12.5f + lane_y(l));
    }
    frag_coord_xy(0, 0, frag_coord_offset(4, 1), x, y);
    EXPECT_EQ(x[lane_of(3, 2)], 3.875f);
    EXPECT_EQ(y[lane_of(3, 2)], 2.375f);

    // Depth: plane at the sample position, then a separate add of the bias.
    Plane z{0.001f, -0.0003f, 0.25f};
    const float bias = 1.0f / 65536.0f;
    float out[16];
    eval_depth(z, bias, 16, 4, plane_offset(4, 3), true, out);
    for (int l = 0; l < 16; ++l) {
        const float px = float(16 + lane_x(l)) + 0.625f, py = float(4 + lane_y(l)) + 0.875f;
        const float a = step_by_step(z.dadx, z.dady, z.a0, px, py, true);
        EXPECT_EQ(out[l], a + bias);
    }
    float flat[16];
    eval_flat(3.5f, flat);
    for (float v : flat) EXPECT_EQ(v, 3.5f);
}

TEST(FragmentInterp, CentroidPicksLowestCoveredSampleOrCentre) {
    uint16_t m[4] = {0, 0, 0, 0};
    // lane 0: all covered -> centre; lane 1: none -> centre; lane 2: samples 2,3 -> sample 2; lane 3: only 3
    for (int s = 0; s < 4; ++s) m[s] |= 1u << 0;
    m[2] |= 1u << 2;
    m[3] |= (1u << 2) | (1u << 3);
    float ox[16], oy[16];
    centroid_offsets(m, ox, oy);
    EXPECT_EQ(ox[0], 0.5f);
    EXPECT_EQ(oy[1], 0.5f);
    EXPECT_EQ(ox[2], 0.125f);
    EXPECT_EQ(oy[2], 0.625f);
    EXPECT_EQ(ox[3], 0.625f);
    EXPECT_EQ(oy[3], 0.875f);
    // per-lane evaluation with uniform offsets equals eval_plane
    Plane p{0.37f, -1.3f, 12.0f};
    float u[16], a[16], b[16];
    for (int l = 0; l < 16; ++l) u[l] = 0.5f;
    eval_plane_per_lane(p, 40, 8, u, u, true, a);
    eval_plane(p, 40, 8, plane_offset(4, -1), true, b);
    for (int l = 0; l < 16; ++l) EXPECT_EQ(a[l], b[l]);
    // and with the centroid offsets matches the step-by-step formula
    eval_plane_per_lane(p, 40, 8, ox, oy, true, a);
    for (int l = 0; l < 16; ++l)
        EXPECT_EQ(a[l], step_by_step(p.dadx, p.dady, p.a0, float(40 + lane_x(l)) + ox[l], float(8 + lane_y(l)) + oy[l],
                                     true));
}
