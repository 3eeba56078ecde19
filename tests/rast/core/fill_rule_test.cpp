// Snap rules, top-left fill rule with vertices/edges exactly on sample points (expected sets derived by hand),
// watertightness of fans, strips and jittered grids, boxes and convex planes.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "grid_consumer.h"
#include "rast/core/fixed_point.h"

namespace tilevk::rast::test {
namespace {

TEST(Snap, TriangleRoundHalfEvenWithOffset) {
    int32_t v = 0;
    // 1x: X = rne((x - 0.5) * 256)
    ASSERT_TRUE(snap_triangle_coord(0.5f + 1.5f / 256, 0.5f, &v));
    EXPECT_EQ(v, 2);  // 1.5 -> 2 (even)
    ASSERT_TRUE(snap_triangle_coord(0.5f + 2.5f / 256, 0.5f, &v));
    EXPECT_EQ(v, 2);  // 2.5 -> 2 (even)
    ASSERT_TRUE(snap_triangle_coord(0.5f - 2.5f / 256, 0.5f, &v));
    EXPECT_EQ(v, -2);
    ASSERT_TRUE(snap_triangle_coord(0.5f + 3.5f / 256, 0.5f, &v));
    EXPECT_EQ(v, 4);
    ASSERT_TRUE(snap_triangle_coord(10.5f, 0.5f, &v));
    EXPECT_EQ(v, 2560);
    // 4x: offset 0
    EXPECT_EQ(triangle_snap_offset(4), 0.0f);
    EXPECT_EQ(triangle_snap_offset(1), 0.5f);
    ASSERT_TRUE(snap_triangle_coord(10.5f, 0.0f, &v));
    EXPECT_EQ(v, 2688);
    // fl(x - 0.5) rounds first: 16383.7 - 0.5 in float then *256.
    const float x = 1000.3f;
    ASSERT_TRUE(snap_triangle_coord(x, 0.5f, &v));
    EXPECT_EQ(v, int32_t(std::nearbyint(double(float(x - 0.5f)) * 256.0)));
}

TEST(Snap, RangeAndNonFinite) {
    int32_t v = 7;
    EXPECT_TRUE(snap_triangle_coord(16383.0f, 0.0f, &v));
    EXPECT_EQ(v, 16383 * 256);
    EXPECT_FALSE(snap_triangle_coord(16384.0f, 0.0f, &v));
    EXPECT_FALSE(snap_triangle_coord(-16384.0f, 0.0f, &v));
    EXPECT_FALSE(snap_triangle_coord(-16383.5f, 0.5f, &v));  // fl(-16383.5 - 0.5) * 256 = -2^22: out of range
    EXPECT_TRUE(snap_triangle_coord(-16383.0f, 0.5f, &v));
    EXPECT_EQ(v, -16383 * 256 - 128);
    v = 7;
    EXPECT_FALSE(snap_triangle_coord(std::nanf(""), 0.5f, &v));
    EXPECT_FALSE(snap_triangle_coord(INFINITY, 0.5f, &v));
    EXPECT_FALSE(snap_triangle_coord(-INFINITY, 0.5f, &v));
    EXPECT_FALSE(snap_triangle_coord(3e38f, 0.5f, &v));
    EXPECT_EQ(v, 7);
}

TEST(Snap, RoundHalfAwayFromZero) {
    int32_t v = 0;
    ASSERT_TRUE(snap_round_half_away(1.5f / 256, &v));
    EXPECT_EQ(v, 2);
    ASSERT_TRUE(snap_round_half_away(2.5f / 256, &v));
    EXPECT_EQ(v, 3);
    ASSERT_TRUE(snap_round_half_away(-2.5f / 256, &v));
    EXPECT_EQ(v, -3);
    ASSERT_TRUE(snap_round_half_away(-0.4f / 256, &v));
    EXPECT_EQ(v, 0);
    EXPECT_FALSE(snap_round_half_away(std::nanf(""), &v));
    EXPECT_FALSE(snap_round_half_away(16384.0f, &v));
}

TriangleInput tri(float x0, float y0, float x1, float y1, float x2, float y2) {
    TriangleInput t;
    t.x[0] = x0, t.y[0] = y0, t.x[1] = x1, t.y[1] = y1, t.x[2] = x2, t.y[2] = y2;
    t.common.clip = {0, 0, 64, 64};
    return t;
}

const Method kAllExact[] = {Method::kReference, Method::kHier, Method::kBBox};

// Triangle (0.5,0.5) (4.5,0.5) (0.5,4.5) at 1x: vertices on pixel centres. Top edge y=0.5 and left edge x=0.5 are
// top/left -> samples on them are in; the hypotenuse x+y=5 (window) is a right/bottom edge -> the centres with
// px+py == 4 are out. By hand: {(px,py): px,py >= 0, px+py <= 3}, 10 pixels.
TEST(FillRule, TopLeftOnSamplePoints1x) {
    SampleSet expect;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x + y <= 3; ++x) expect.insert({x, y, 0});
    for (bool reverse : {false, true}) {
        for (Method m : kAllExact) {
            Scene scene({.width = 64, .height = 64, .samples = 1});
            ASSERT_EQ(scene.add_triangle(reverse ? tri(0.5f, 0.5f, 0.5f, 4.5f, 4.5f, 0.5f)
                                                 : tri(0.5f, 0.5f, 4.5f, 0.5f, 0.5f, 4.5f)),
                      SetupStatus::kAccepted);
            EXPECT_EQ(covered(scene, m), expect) << to_string(m) << " reverse " << reverse;
        }
    }
}

// The complementary triangle (4.5,0.5) (4.5,4.5) (0.5,4.5): right edge x=4.5 and bottom edge y=4.5 exclude their
// samples; the diagonal is its top-left edge, so centres with px+py == 4 are in. By hand: px,py <= 3, px+py >= 4.
TEST(FillRule, ComplementOnSamplePoints1x) {
    SampleSet expect;
    for (int y = 0; y <= 3; ++y)
        for (int x = 0; x <= 3; ++x)
            if (x + y >= 4) expect.insert({x, y, 0});
    ASSERT_EQ(expect.size(), 6u);
    for (Method m : kAllExact) {
        Scene scene({.width = 64, .height = 64, .samples = 1});
        ASSERT_EQ(scene.add_triangle(tri(4.5f, 0.5f, 4.5f, 4.5f, 0.5f, 4.5f)), SetupStatus::kAccepted);
        EXPECT_EQ(covered(scene, m), expect) << to_string(m);
    }
}

// 4x: a rectangle x in [0.375, 2], y in [0, 1] from two triangles. Sample 0 of pixel 0 sits at x = 96/256 = 0.375,
// exactly on the left edge (left -> in); sample 2 at x = 0.125 is outside; pixel 1's samples are all inside.
// Samples (y = 32,96,160,224 /256) are strictly inside [0,1]. x = 2 is the right edge: no sample of pixel 2.
TEST(FillRule, LeftEdgeThroughSample4x) {
    SampleSet expect = {{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {1, 0, 0}, {1, 0, 1}, {1, 0, 2}, {1, 0, 3}};
    for (Method m : kAllExact) {
        Scene scene({.width = 64, .height = 64, .samples = 4});
        ASSERT_EQ(scene.add_triangle(tri(0.375f, 0, 2, 0, 0.375f, 1)), SetupStatus::kAccepted);
        ASSERT_EQ(scene.add_triangle(tri(2, 0, 2, 1, 0.375f, 1)), SetupStatus::kAccepted);
        EXPECT_EQ(covered(scene, m), expect) << to_string(m);
    }
}

// 4x: horizontal top edge at y = 32/256 passes through sample 0 (top -> in); bottom edge at y = 160/256 passes
// through sample 2 (bottom -> out). x spans the whole pixel [0,1]. In: sample 0 (y 32) and sample 1 (y 96).
TEST(FillRule, TopAndBottomEdgesThroughSamples4x) {
    SampleSet expect = {{0, 0, 0}, {0, 0, 1}};
    for (Method m : kAllExact) {
        Scene scene({.width = 64, .height = 64, .samples = 4});
        const float t = 32.0f / 256, b = 160.0f / 256;
        ASSERT_EQ(scene.add_triangle(tri(0, t, 1, t, 0, b)), SetupStatus::kAccepted);
        ASSERT_EQ(scene.add_triangle(tri(1, t, 1, b, 0, b)), SetupStatus::kAccepted);
        EXPECT_EQ(covered(scene, m), expect) << to_string(m);
    }
}

TEST(FillRule, ZeroAreaAndCulling) {
    Scene scene({.width = 64, .height = 64, .samples = 1});
    EXPECT_EQ(scene.add_triangle(tri(1, 1, 5, 5, 9, 9)), SetupStatus::kDegenerate);
    // y-down: clockwise on screen; area = dx01*dy20 - dx20*dy01 = (-4)(4) - 0 < 0, Vulkan's a = -8 < 0: "cw".
    TriangleInput t = tri(0.5f, 0.5f, 4.5f, 0.5f, 0.5f, 4.5f);
    t.cull = CullMode::kBack;
    t.front_ccw = true;  // cw is back-facing
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kCulled);
    t.front_ccw = false;  // cw is front-facing
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kAccepted);
    t.cull = CullMode::kBoth;
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kCulled);
    t.cull = CullMode::kFront;
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kCulled);
    t.front_ccw = true;
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kAccepted);
}

TEST(FillRule, FrontFacingFlag) {
    struct Rec : CoverageConsumer {
        std::vector<bool> faces;
        void begin_tile(unsigned, const TileInfo&) override {}
        void primitive(unsigned, const TileInfo&, const PrimCoverage& c) override { faces.push_back(c.front_facing); }
        void end_tile(unsigned, const TileInfo&) override {}
    } rec;
    Scene scene({.width = 64, .height = 64, .samples = 1});
    scene.add_triangle(tri(0.5f, 0.5f, 0.5f, 4.5f, 4.5f, 0.5f));  // area > 0 ("ccw"): front with front_ccw
    scene.add_triangle(tri(0.5f, 0.5f, 4.5f, 0.5f, 0.5f, 4.5f));  // area < 0: back
    ThreadPool pool(1);
    scene.rasterize(rec, pool);
    EXPECT_EQ(rec.faces, (std::vector<bool>{true, false}));
}

// Watertightness: a jittered grid of quads (two triangles each, both diagonals, both windings) that covers more
// than the framebuffer must cover every sample exactly once.
TEST(Watertight, JitteredGridCoversEverySampleOnce) {
    for (int samples : {1, 4}) {
        for (Method m : kAllExact) {
            std::mt19937 rng(samples * 17 + int(m));
            std::uniform_real_distribution<float> jit(-0.2f, 0.2f);
            const int n = 14;
            const float cell = 11.3f;
            float gx[n + 1][n + 1], gy[n + 1][n + 1];
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= n; ++i)
                    gx[j][i] = -5 + cell * (i + (i > 0 && i < n ? jit(rng) : 0)),
                    gy[j][i] = -5 + cell * (j + (j > 0 && j < n ? jit(rng) : 0));
            Scene scene({.width = 140, .height = 130, .samples = samples});
            uint32_t id = 0;
            auto add = [&](int a, int b, int c, int d, int e, int f) {
                TriangleInput t = tri(gx[a][b], gy[a][b], gx[c][d], gy[c][d], gx[e][f], gy[e][f]);
                t.common.clip = {0, 0, 140, 130};
                t.common.payload = id++;
                scene.add_triangle(t);
            };
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    if ((i + j) & 1) {
                        add(j, i, j, i + 1, j + 1, i + 1), add(j, i, j + 1, i + 1, j + 1, i);
                    } else {
                        add(j, i, j + 1, i, j, i + 1), add(j, i + 1, j + 1, i, j + 1, i + 1);
                    }
                }
            ThreadPool pool(1);
            GridConsumer g = render(scene, m, pool);
            size_t bad = 0;
            for (uint32_t c : g.count) bad += c != 1;
            EXPECT_EQ(bad, 0u) << to_string(m) << " " << samples << "x";
        }
    }
}

// A fan around an interior centre whose rim encloses the framebuffer, and a strip across it.
TEST(Watertight, FanAndStripCoverEverySampleOnce) {
    for (int samples : {1, 4}) {
        const float cx = 61.37f, cy = 47.91f;
        const int n = 37;
        Scene fan({.width = 120, .height = 100, .samples = samples});
        for (int i = 0; i < n; ++i) {
            const float a0 = 6.2831853f * i / n, a1 = 6.2831853f * ((i + 1) % n) / n;
            TriangleInput t = tri(cx, cy, cx + 200 * std::cos(a0), cy + 200 * std::sin(a0), cx + 200 * std::cos(a1),
                                  cy + 200 * std::sin(a1));
            t.common.clip = {0, 0, 120, 100};
            t.common.payload = i;
            fan.add_triangle(t);
        }
        // Strip: two zig-zag rows of vertices spanning the frame, triangles (v_i, v_i+1, v_i+2).
        Scene strip({.width = 120, .height = 100, .samples = samples});
        std::vector<float> vx, vy;
        for (int i = 0; i < 40; ++i) vx.push_back(-10 + 4.1f * i + 0.37f * (i % 3)), vy.push_back(i % 2 ? 130 : -20);
        for (int i = 0; i + 2 < 40; ++i) {
            TriangleInput t = tri(vx[i], vy[i], vx[i + 1], vy[i + 1], vx[i + 2], vy[i + 2]);
            t.common.clip = {0, 0, 120, 100};
            t.common.payload = i;
            strip.add_triangle(t);
        }
        for (Method m : kAllExact) {
            ThreadPool pool(1);
            for (Scene* s : {&fan, &strip}) {
                GridConsumer g = render(*s, m, pool);
                size_t bad = 0;
                for (uint32_t c : g.count) bad += c != 1;
                EXPECT_EQ(bad, 0u) << to_string(m) << " " << samples << "x " << (s == &fan ? "fan" : "strip");
            }
        }
    }
}

// Boxes: [x0, x1) in fixed point with the top-left rule. Box x in [256, 768) at 1x (lattice X = px*256) covers
// px 1 and 2; y in [0, 256) covers py 0. At 4x, [96, 352): samples with X = px*256 + sx in range: px 0 s0 (96),
// s1 (224), s3 (160); px 1 s2 (256+32=288); y [0, 256) covers all sample rows of py 0.
TEST(Box, HalfOpenTopLeft) {
    for (Method m : kAllExact) {
        Scene s1({.width = 64, .height = 64, .samples = 1});
        BoxInput b;
        b.x0 = 256, b.x1 = 768, b.y0 = 0, b.y1 = 256;
        b.common.clip = {0, 0, 64, 64};
        ASSERT_EQ(s1.add_box(b), SetupStatus::kAccepted);
        EXPECT_EQ(covered(s1, m), (SampleSet{{1, 0, 0}, {2, 0, 0}})) << to_string(m);
        Scene s4({.width = 64, .height = 64, .samples = 4});
        b.x0 = 96, b.x1 = 352;
        ASSERT_EQ(s4.add_box(b), SetupStatus::kAccepted);
        EXPECT_EQ(covered(s4, m), (SampleSet{{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {1, 0, 2}})) << to_string(m);
    }
}

// A convex 4-plane primitive (an axis-aligned rectangle written as planes, like a line's) equals the same box.
TEST(Convex, FourPlanesMatchBox) {
    for (int samples : {1, 4}) {
        ConvexInput cv;
        // x0 <= X < x1, y0 <= Y < y1 with x0=300, x1=5000, y0=77, y1=3001 (fixed).
        cv.planes[0] = {-300 + 1, 1, 0};
        cv.planes[1] = {5000, -1, 0};
        cv.planes[2] = {-77 + 1, 0, 1};
        cv.planes[3] = {3001, 0, -1};
        cv.num_planes = 4;
        cv.min_x = 300, cv.max_x = 5000, cv.min_y = 77, cv.max_y = 3001;
        cv.common.clip = {0, 0, 64, 64};
        BoxInput b;
        b.x0 = 300, b.x1 = 5000, b.y0 = 77, b.y1 = 3001;
        b.common.clip = {0, 0, 64, 64};
        for (Method m : kAllExact) {
            Scene a({.width = 64, .height = 64, .samples = samples}),
                c({.width = 64, .height = 64, .samples = samples});
            ASSERT_EQ(a.add_convex(cv), SetupStatus::kAccepted);
            ASSERT_EQ(c.add_box(b), SetupStatus::kAccepted);
            const SampleSet pa = covered(a, m);
            EXPECT_EQ(pa, covered(c, m)) << to_string(m);
            EXPECT_FALSE(pa.empty());
        }
    }
}

}  // namespace
}  // namespace tilevk::rast::test
