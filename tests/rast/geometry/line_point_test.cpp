// Line and point setup: snapping quirks, plane coverage by brute force, attribute planes by hand.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <limits>
#include <vector>

#include "rast/geometry/line_point_setup.h"

using namespace tilevk::rast::geometry;

namespace {

struct V {
    float f[8 + 4 * 2];
};
const Interp kModes[2] = {Interp::kNoPerspective, Interp::kFlat};

V make(float x, float y, float a, float z = 0.5f, float oow = 1.0f) {
    V v{};
    v.f[4] = x, v.f[5] = y, v.f[6] = z, v.f[7] = oow;
    for (int i = 0; i < 8; ++i) v.f[8 + i] = a + static_cast<float>(i);
    return v;
}

// Brute force: pixel (px, py) at 1x samples fixed (px*256, py*256); inside iff all planes > 0.
std::vector<std::pair<int, int>> covered(const LineSetup& l, int w, int h) {
    std::vector<std::pair<int, int>> out;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            bool in = true;
            for (const auto& p : l.planes) in = in && p.c + int64_t{p.a} * (px * 256) + int64_t{p.b} * (py * 256) > 0;
            if (in) out.emplace_back(px, py);
        }
    return out;
}

}  // namespace

TEST(Snap, UtilIroundQuirks) {
    EXPECT_EQ(util_iround(0.5f), 1);
    EXPECT_EQ(util_iround(-0.5f), -1);  // half away from zero
    EXPECT_EQ(util_iround(2.5f), 3);    // not to even
    // 0.5 - 2^-25: the float add 0.5f gives 1 - 2^-25, a tie rounded to even 1.0 -> 1 (true rounding says 0)
    EXPECT_EQ(util_iround(0.5f - std::ldexp(1.0f, -25)), 1);
    bool ok = true;
    EXPECT_EQ(util_iround(std::numeric_limits<float>::quiet_NaN(), &ok), INT32_MIN);
    EXPECT_FALSE(ok);
    ok = true;
    EXPECT_EQ(util_iround(3e9f, &ok), INT32_MIN);
    EXPECT_FALSE(ok);
    EXPECT_EQ(subpixel_snap(10.0f), 2560);
    EXPECT_EQ(subpixel_snap(-0.001953125f), -1);  // -0.5 fixed -> -1
}

TEST(LineSetup, RectangularHorizontalLineByHand) {
    // (10.5, 20.5) -> (30.5, 20.5), width 1: dx = -20, dy = 0, scale = 0.5/20; tx = snap(-0) = 0, ty = snap(-0.5)
    // = -128. Corners x = (2560, 7680, 7680, 2560), y = (5248, 5248, 4992, 4992).
    V a = make(10.5f, 20.5f, 0), b = make(30.5f, 20.5f, 20);
    LineSetupConfig cfg;
    cfg.layout = {2, kModes};
    LineSetup l;
    AttribPlane p[2];
    ASSERT_EQ(setup_line(cfg, a.f, b.f, &l, p), PrimSetupStatus::kOk);
    EXPECT_EQ(l.corner_x[0], 2560);
    EXPECT_EQ(l.corner_x[1], 7680);
    EXPECT_EQ(l.corner_y[0], 5248);
    EXPECT_EQ(l.corner_y[2], 4992);
    EXPECT_EQ(l.min_x, 2560);
    EXPECT_EQ(l.max_y, 5248);
    // covered: row 20, pixels 10..29 (left edge in by the top-left rule, right edge at 7680 out)
    const auto cov = covered(l, 40, 40);
    ASSERT_EQ(cov.size(), 20u);
    EXPECT_EQ(cov.front(), std::make_pair(10, 20));
    EXPECT_EQ(cov.back(), std::make_pair(29, 20));
    // attribute 0.x: 0 at v0, 20 at v1: da21 = -20, dadx = (-20*-20)/400 = 1, a0 = 0 - 1*(10.5-0.5) = -10
    EXPECT_EQ(p[0].dadx[0], 1.0f);
    EXPECT_EQ(p[0].dady[0], 0.0f);
    EXPECT_EQ(p[0].a0[0], -10.0f);
    // flat from the first vertex
    EXPECT_EQ(p[1].a0[0], 4.0f);
    EXPECT_EQ(p[1].dadx[0], 0.0f);
    // z plane constant 0.5
    EXPECT_EQ(l.pos.a0[2], 0.5f);
    EXPECT_EQ(l.pos.dadx[2], 0.0f);
}

TEST(LineSetup, WideDiagonalContainsItsAxisAndZeroLengthIsEmpty) {
    V a = make(5.5f, 5.5f, 0), b = make(25.5f, 15.5f, 0);
    LineSetupConfig cfg;
    cfg.layout = {2, kModes};
    cfg.width = 3.0f;
    LineSetup l;
    AttribPlane p[2];
    ASSERT_EQ(setup_line(cfg, a.f, b.f, &l, p), PrimSetupStatus::kOk);
    const auto cov = covered(l, 40, 40);
    auto has = [&](int x, int y) {
        for (auto& c : cov)
            if (c.first == x && c.second == y) return true;
        return false;
    };
    EXPECT_TRUE(has(15, 10));   // the centre of the segment
    EXPECT_FALSE(has(15, 14));  // 4 px off the axis, beyond half-width 1.5
    // area = 20^2 + 10^2 = 500 px^2; width 3 -> about 3 * sqrt(500) = 67 pixels
    EXPECT_GT(cov.size(), 55u);
    EXPECT_LT(cov.size(), 80u);
    V c = make(5.5f, 5.5f, 0);
    EXPECT_EQ(setup_line(cfg, a.f, c.f, &l, p), PrimSetupStatus::kEmpty);
    V n = make(std::numeric_limits<float>::quiet_NaN(), 1, 0);
    EXPECT_NE(setup_line(cfg, a.f, n.f, &l, p), PrimSetupStatus::kOk);
}

TEST(LineSetup, BresenhamDiamondExitDropsTheEndPixel) {
    // Same horizontal line as above in Bresenham mode: the start pixel centre is inside its diamond (drawn), the
    // end is not drawn: the end is pulled in by half a pixel -> x from 2560 to snap(29.5) = 7552, pixels 10..29.
    V a = make(10.5f, 20.5f, 0), b = make(30.5f, 20.5f, 20);
    LineSetupConfig cfg;
    cfg.layout = {2, kModes};
    cfg.mode = LineMode::kBresenham;
    LineSetup l;
    AttribPlane p[2];
    ASSERT_EQ(setup_line(cfg, a.f, b.f, &l, p), PrimSetupStatus::kOk);
    EXPECT_EQ(l.min_x, 2560);
    EXPECT_EQ(l.max_x, 7552);
    EXPECT_EQ(l.min_y, 4992);
    EXPECT_EQ(l.max_y, 5248);
    const auto cov = covered(l, 40, 40);
    ASSERT_EQ(cov.size(), 20u);
    EXPECT_EQ(cov.front(), std::make_pair(10, 20));
    // x-major: info.dx = dx*(1 + 0) = -20, dy = 0, both from before the swap, and the planes keep the draw-order
    // vertices (lp_line_info is filled before the swap): a1 = 0, a2 = 20: dadx = (-20*-20)/400 = 1,
    // a0 = 0 - 1*(10.5-0.5) = -10
    EXPECT_EQ(p[0].dadx[0], 1.0f);
    EXPECT_EQ(p[0].a0[0], -10.0f);
}

TEST(PointSetup, SquaresSizesAndPointCoord) {
    PointSetupConfig cfg;
    const Interp modes[2] = {Interp::kPerspective, Interp::kNoPerspective};
    cfg.layout = {2, modes};
    cfg.point_coord_attrib = 1;
    PointSetup s;
    AttribPlane p[2];
    V v = make(10.5f, 20.5f, 3, 0.25f, 0.5f);
    // size 1: fixed width 256, x0 = snap(10) - 128 = 2432 -> covers X = 2560 only (pixel 10)
    ASSERT_EQ(setup_point(cfg, v.f, 1.0f, &s, p), PrimSetupStatus::kOk);
    EXPECT_EQ(s.x0, 2432);
    EXPECT_EQ(s.x1, 2688);
    EXPECT_EQ(s.y0, 5120 - 128);
    // perspective attribute premultiplied by 1/w = 0.5, constant
    EXPECT_EQ(p[0].a0[0], 1.5f);
    EXPECT_EQ(p[0].dadx[0], 0.0f);
    // z, 1/w constant
    EXPECT_EQ(s.pos.a0[2], 0.25f);
    EXPECT_EQ(s.pos.a0[3], 0.5f);
    // size 2: width 512, x0 = 2560 - 256 = 2304 -> pixels 9, 10. PointCoord: dadx = 256/512 = 0.5,
    // a0 = 0.5 - 0.5*(10.5 - 0.5) = -4.5
    ASSERT_EQ(setup_point(cfg, v.f, 2.0f, &s, p), PrimSetupStatus::kOk);
    EXPECT_EQ(s.x0, 2304);
    EXPECT_EQ(s.x1, 2816);
    EXPECT_EQ(p[1].dadx[0], 0.5f);
    EXPECT_EQ(p[1].a0[0], -4.5f);
    EXPECT_EQ(p[1].dady[1], 0.5f);
    EXPECT_EQ(p[1].a0[1], 0.5f - 0.5f * 20.0f);
    EXPECT_EQ(p[1].a0[3], 1.0f);
    // tiny, NaN and negative sizes give one pixel; huge sizes clamp to 255
    for (float sz : {0.3f, -4.0f, std::numeric_limits<float>::quiet_NaN()}) {
        ASSERT_EQ(setup_point(cfg, v.f, sz, &s, p), PrimSetupStatus::kOk);
        EXPECT_EQ(s.x1 - s.x0, 256) << sz;
    }
    ASSERT_EQ(setup_point(cfg, v.f, 1e9f, &s, p), PrimSetupStatus::kOk);
    EXPECT_EQ(s.x1 - s.x0, 255 * 256);
    // MSAA: no 0.5 snap offset
    cfg.multisample = true;
    ASSERT_EQ(setup_point(cfg, v.f, 1.0f, &s, p), PrimSetupStatus::kOk);
    EXPECT_EQ(s.x0, subpixel_snap(10.5f) - 128);
    // far away / non-finite positions never overflow
    V far = make(1e12f, 0, 0);
    EXPECT_EQ(setup_point(cfg, far.f, 1.0f, &s, p), PrimSetupStatus::kOutOfRange);
}
