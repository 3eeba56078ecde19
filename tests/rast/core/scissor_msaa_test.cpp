// lavapipe's 4x scissor (lp_setup.c lp_setup_add_scissor_planes with adj 127, scissor_planes_needed, binning in
// 64-px tiles of bbox ∩ scissor; lp_setup_line.c's bbox for lines), which rast/core reproduces on purpose. Every
// expected set is derived by hand from those rules and the 4x sample offsets (96,32) (224,96) (32,160) (160,224):
// the left plane keeps sample X of pixel x0-1 iff sx > 127 (samples 1, 3), the top plane sy > 127 (samples 2, 3).
#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include "grid_consumer.h"

namespace tilevk::rast::test {
namespace {

const Method kAllExact[] = {Method::kReference, Method::kHier, Method::kBBox};

// A triangle far larger than the target: its bbox crosses every side of any clip rect.
TriangleInput huge_triangle(const ClipRect& clip) {
    TriangleInput t;
    t.x[0] = -50, t.y[0] = -50, t.x[1] = 500, t.y[1] = -50, t.x[2] = -50, t.y[2] = 500;
    t.common.clip = clip;
    return t;
}

// Every sample of [x0,x1) x [y0,y1), plus (at 4x) the partial column/row the left/top planes pass when asked.
SampleSet expected(const ClipRect& r, int samples, bool left_column, bool top_row) {
    SampleSet e;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            for (int s = 0; s < samples; ++s) e.insert({x, y, s});
    if (left_column)
        for (int y = r.y0; y < r.y1; ++y) e.insert({r.x0 - 1, y, 1}), e.insert({r.x0 - 1, y, 3});
    if (top_row)
        for (int x = r.x0; x < r.x1; ++x) e.insert({x, r.y0 - 1, 2}), e.insert({x, r.y0 - 1, 3});
    if (left_column && top_row) e.insert({r.x0 - 1, r.y0 - 1, 3});
    return e;
}

struct ClipCase {
    ClipRect clip;
    bool left_column, top_row;  // at 4x
};

TEST(ScissorMsaa, TrianglePlanesPassHalfPixelLeftAndAbove) {
    const ClipCase cases[] = {
        {{5, 3, 12, 12}, true, true},      // 2*9 + 2*7 + 1 = 33 extra samples
        {{64, 64, 70, 70}, false, false},  // x0, y0 on a 64-px tile boundary: column/row 63 is in an unbinned tile
        {{64, 10, 70, 20}, false, true},   // only the row above
        {{10, 64, 20, 90}, true, false},   // only the column left
        {{65, 1, 66, 2}, true, true},      // one pixel
        {{0, 0, 128, 96}, false, false},   // the whole target: no planes
        {{120, 90, 400, 400}, true, true}  // past the bottom right: right/bottom cut by the framebuffer
    };
    for (const ClipCase& c : cases) {
        for (int samples : {1, 4}) {
            const ClipRect inside = {c.clip.x0, c.clip.y0, std::min(c.clip.x1, 128), std::min(c.clip.y1, 96)};
            const SampleSet want = expected(inside, samples, samples == 4 && c.left_column, samples == 4 && c.top_row);
            for (Method m : kAllExact) {
                Scene s({.width = 128, .height = 96, .samples = samples});
                ASSERT_EQ(s.add_triangle(huge_triangle(c.clip)), SetupStatus::kAccepted);
                EXPECT_EQ(covered(s, m), want)
                    << to_string(m) << " " << samples << "x clip " << c.clip.x0 << "," << c.clip.y0;
            }
        }
    }
}

// A triangle whose bbox stays inside the clip on the left/top gets no plane there: nothing outside.
TEST(ScissorMsaa, NoPlaneWhereTheBoxIsInside) {
    TriangleInput t;
    // Window x from 10 to 40, y from 10 to 40: bbox x0 = y0 = 10 = clip x0/y0; right/bottom cut at 20.
    t.x[0] = 10, t.y[0] = 10, t.x[1] = 60, t.y[1] = 10, t.x[2] = 10, t.y[2] = 60;
    t.common.clip = {10, 10, 20, 20};
    for (Method m : kAllExact) {
        Scene s({.width = 64, .height = 64, .samples = 4});
        ASSERT_EQ(s.add_triangle(t), SetupStatus::kAccepted);
        EXPECT_EQ(covered(s, m), expected({10, 10, 20, 20}, 4, false, false)) << to_string(m);
    }
}

// An axis-aligned "line" (convex) X in [left, 40*256), Y in [10*256, 20*256): lavapipe's line bbox starts at
// ceil(left/256). left = 2560-200: bbox x0 = 10 = clip x0, so no plane: column 9 keeps the shape's samples with
// X >= 2360, i.e. sx >= 56: samples 0, 1, 3. left = 2560-300: bbox x0 = 9 < 10, plane: column 9 samples 1, 3.
// left = 64*256-100 with the whole target as clip: bbox x0 = 64, tile 1 only, so column 63 (tile 0) is empty.
ConvexInput rect_line(int32_t left, const ClipRect& clip) {
    ConvexInput cv;
    cv.planes[0] = {-int64_t{left} + 1, 1, 0};
    cv.planes[1] = {40 * 256, -1, 0};
    cv.planes[2] = {-10 * 256 + 1, 0, 1};
    cv.planes[3] = {20 * 256, 0, -1};
    cv.num_planes = 4;
    cv.min_x = left, cv.max_x = 40 * 256, cv.min_y = 10 * 256, cv.max_y = 20 * 256;
    if (left > 40 * 256) cv.planes[1].c = 80 * 256, cv.max_x = 80 * 256;
    cv.common.clip = clip;
    return cv;
}

TEST(ScissorMsaa, LineBoxRoundsMinUp) {
    for (Method m : kAllExact) {
        {
            Scene s({.width = 128, .height = 96, .samples = 4});
            ASSERT_EQ(s.add_convex(rect_line(2560 - 200, {10, 0, 128, 96})), SetupStatus::kAccepted);
            SampleSet want = expected({10, 10, 40, 20}, 4, false, false);
            for (int y = 10; y < 20; ++y) want.insert({9, y, 0}), want.insert({9, y, 1}), want.insert({9, y, 3});
            EXPECT_EQ(covered(s, m), want) << to_string(m);
        }
        {
            Scene s({.width = 128, .height = 96, .samples = 4});
            ASSERT_EQ(s.add_convex(rect_line(2560 - 300, {10, 0, 128, 96})), SetupStatus::kAccepted);
            EXPECT_EQ(covered(s, m), expected({10, 10, 40, 20}, 4, true, false)) << to_string(m);
        }
        {
            Scene s({.width = 128, .height = 96, .samples = 4});
            ASSERT_EQ(s.add_convex(rect_line(64 * 256 - 100, {0, 0, 128, 96})), SetupStatus::kAccepted);
            EXPECT_EQ(covered(s, m), expected({64, 10, 80, 20}, 4, false, false)) << to_string(m);
        }
        {
            // 1x: lattice samples, whole pixels at the clip as before (column 9 has no sample X >= 2360).
            Scene s({.width = 128, .height = 96, .samples = 1});
            ASSERT_EQ(s.add_convex(rect_line(2560 - 200, {10, 0, 128, 96})), SetupStatus::kAccepted);
            EXPECT_EQ(covered(s, m), expected({10, 10, 40, 20}, 1, false, false)) << to_string(m);
        }
    }
}

// An axis-aligned strip lo <= X < hi, 10*256 <= Y < 20*256 as a line's convex (left/top planes biased as the top-left
// rule does).
ConvexInput strip(int32_t lo, int32_t hi) {
    ConvexInput cv;
    cv.planes[0] = {-int64_t{lo} + 1, 1, 0};
    cv.planes[1] = {hi, -1, 0};
    cv.planes[2] = {-10 * 256 + 1, 0, 1};
    cv.planes[3] = {20 * 256, 0, -1};
    cv.num_planes = 4;
    cv.min_x = lo, cv.max_x = hi, cv.min_y = 10 * 256, cv.max_y = 20 * 256;
    cv.common.clip = {0, 0, 64, 64};
    return cv;
}

// lavapipe's line bbox is empty when no pixel boundary lies in (minX, maxX] (x0 = ceil(minX), x1 = ceil(maxX) - 1),
// and u_rect_test_intersection then drops the line although 4x samples lie inside: X in [5*256+70, 5*256+120)
// holds sample 0 (sx 96) of column 5 in every row. The same strip moved to cross X = 6*256 keeps its samples.
TEST(ScissorMsaa, LineWithEmptyBoxIsDropped) {
    for (Method m : kAllExact) {
        {
            Scene s({.width = 64, .height = 64, .samples = 4});
            EXPECT_EQ(s.add_convex(strip(5 * 256 + 70, 5 * 256 + 120)), SetupStatus::kClipped) << to_string(m);
            EXPECT_EQ(covered(s, m), SampleSet{}) << to_string(m);
        }
        {
            Scene s({.width = 64, .height = 64, .samples = 4});
            ASSERT_EQ(s.add_convex(strip(5 * 256 + 200, 6 * 256 + 50)), SetupStatus::kAccepted);
            SampleSet want;  // column 5: sample 1 (sx 224); column 6: sample 2 (sx 32)
            for (int y = 10; y < 20; ++y) want.insert({5, y, 1}), want.insert({6, y, 2});
            EXPECT_EQ(covered(s, m), want) << to_string(m);
        }
    }
}

// Boxes (points, rectangles) clip whole pixels at 4x too (lp_setup_point.c clamps its planes to the clipped bbox).
TEST(ScissorMsaa, BoxesClipWholePixels) {
    BoxInput b;
    b.x0 = 0, b.y0 = 0, b.x1 = 50 * 256, b.y1 = 50 * 256;
    b.common.clip = {5, 3, 12, 12};
    for (Method m : kAllExact) {
        Scene s({.width = 64, .height = 64, .samples = 4});
        ASSERT_EQ(s.add_box(b), SetupStatus::kAccepted);
        EXPECT_EQ(covered(s, m), expected({5, 3, 12, 12}, 4, false, false)) << to_string(m);
    }
}

}  // namespace
}  // namespace tilevk::rast::test
