// llvmpipe's rectangle test and box (lp_setup_rect.c), with expectations derived by hand in the comments.
#include <gtest/gtest.h>

#include <climits>
#include <vector>

#include "rast/geometry/rect_detect.h"

using namespace tilevk::rast::geometry;

namespace {

const Interp kInterp[1] = {Interp::kPerspective};

// Records with window position (x, y, 0.5, 1/w) and one attribute (a, a, a, a).
struct Rec {
    float f[12];
};
Rec rec(float x, float y, float a, float oow = 1.0f) {
    return {{0, 0, 0, 1, x, y, 0.5f, oow, a, a, a, a}};
}

RectPairConfig config(bool cull_front = false, bool cull_back = false, bool front_ccw = true) {
    RectPairConfig c;
    c.layout = {1, kInterp};
    c.cull_front = cull_front;
    c.cull_back = cull_back;
    c.front_ccw = front_ccw;
    return c;
}

}  // namespace

TEST(RectDetect, WindingSign) {
    // (0,0) (1,0) (1,1) in y-down window space: e = (-1,-1), f = (0,-1): det = 1 -> cw; reversed -> ccw.
    const float a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {1, 1};
    EXPECT_EQ(float_winding(a, b, c), Winding::kCw);
    EXPECT_EQ(float_winding(a, c, b), Winding::kCcw);
    EXPECT_EQ(float_winding(a, b, b), Winding::kNone);
}

TEST(RectDetect, CwPairBecomesRectFromCornersV2V0V1OfTheBlitterFan) {
    // The fan (v0, v1, v2), (v0, v2, v3) of the rectangle (10,20)-(30,40), both cw: do_rect_ccw(v0, v2, v1,
    // v0, v3, v2) matches SAME_POS(v0, v3') and SAME_POS(v2', v4') -> rv = (v3, v0, v2, v1) ... rotated when
    // rv0-rv1 is horizontal; the corners handed to lp_rect_cw are (rv0, rv2, rv1).
    Rec v0 = rec(10, 20, 0.25f), v1 = rec(30, 20, 0.5f), v2 = rec(30, 40, 0.75f), v3 = rec(10, 40, 0.5f);
    const float* t0[3] = {v0.f, v1.f, v2.f};
    const float* t1[3] = {v0.f, v2.f, v3.f};
    const RectDecision d = decide_rect_pair(config(), t0, t1);
    ASSERT_EQ(d.kind, RectDecision::kRect);
    EXPECT_FALSE(d.front);  // two cw triangles with front = ccw
    // do_rect_ccw(v0, v2, v1, v0, v3, v2): v0 == v3' (v0), then v2' (v1) vs v4' (v3): no; v1' (v2) == v5' (v2):
    // rv0 = v4' = v3, rv1 = v1' = v2, rv2 = v2' = v1, rv3 = v0' = v0. SAME_Y(rv0 = v3, rv1 = v2): 40 == 40 ->
    // rotate: rv = (v2, v1, v0, v3). Corners (rv0, rv2, rv1) = (v2, v0, v1).
    EXPECT_EQ(d.corner[0], v2.f);
    EXPECT_EQ(d.corner[1], v0.f);
    EXPECT_EQ(d.corner[2], v1.f);
}

TEST(RectDetect, RejectsNonCoplanarUnequalWAndNonRectangles) {
    Rec v0 = rec(10, 20, 0.25f), v1 = rec(30, 20, 0.5f), v2 = rec(30, 40, 0.75f), v3 = rec(10, 40, 0.5f);
    const float* t0[3] = {v0.f, v1.f, v2.f};
    const float* t1[3] = {v0.f, v2.f, v3.f};
    // attribute not coplanar: a3 moved by 1/1024, so fl(a0 - a3) != fl(a1 - a2)
    Rec w3 = rec(10, 40, 0.5f + 1.0f / 1024);
    const float* u1[3] = {v0.f, v2.f, w3.f};
    EXPECT_EQ(decide_rect_pair(config(), t0, u1).kind, RectDecision::kTriangles);
    // unequal 1/w at one corner: SAME_POS still matches (it compares 1/w too, on the shared diagonal only)
    Rec o3 = rec(10, 40, 0.5f, 0.5f);
    const float* o1[3] = {v0.f, v2.f, o3.f};
    EXPECT_EQ(decide_rect_pair(config(), t0, o1).kind, RectDecision::kTriangles);
    EXPECT_EQ(decide_rect_pair(config(), t0, t1).kind, RectDecision::kRect);
    // a parallelogram: shares the diagonal but v3 is shifted in x
    Rec p3 = rec(11, 40, 0.5f);
    const float* p1[3] = {v0.f, v2.f, p3.f};
    EXPECT_EQ(decide_rect_pair(config(), t0, p1).kind, RectDecision::kTriangles);
    // mixed windings with no culling: setup_rect_both declines
    const float* m1[3] = {v0.f, v3.f, v2.f};
    EXPECT_EQ(decide_rect_pair(config(), t0, m1).kind, RectDecision::kTriangles);
}

TEST(RectDetect, CullModesPickTheSetupRectVariant) {
    Rec v0 = rec(10, 20, 0.25f), v1 = rec(30, 20, 0.5f), v2 = rec(30, 40, 0.75f), v3 = rec(10, 40, 0.5f);
    const float* cw0[3] = {v0.f, v1.f, v2.f};
    const float* cw1[3] = {v0.f, v2.f, v3.f};
    const float* ccw0[3] = {v0.f, v2.f, v1.f};
    const float* ccw1[3] = {v0.f, v3.f, v2.f};
    // cull back, front ccw -> setup_rect_ccw: two cw -> nothing; ccw then cw -> first only; cw then ccw -> FALSE
    EXPECT_EQ(decide_rect_pair(config(false, true), cw0, cw1).kind, RectDecision::kNothing);
    EXPECT_EQ(decide_rect_pair(config(false, true), ccw0, cw1).kind, RectDecision::kFirstTriangle);
    EXPECT_EQ(decide_rect_pair(config(false, true), cw0, ccw1).kind, RectDecision::kTriangles);
    const RectDecision r = decide_rect_pair(config(false, true), ccw0, ccw1);
    ASSERT_EQ(r.kind, RectDecision::kRect);
    EXPECT_TRUE(r.front);
    // cull front, front ccw -> setup_rect_cw: first cw -> first only; only the second cw -> second only
    EXPECT_EQ(decide_rect_pair(config(true, false), cw0, ccw1).kind, RectDecision::kFirstTriangle);
    EXPECT_EQ(decide_rect_pair(config(true, false), ccw0, cw1).kind, RectDecision::kSecondTriangle);
    EXPECT_EQ(decide_rect_pair(config(true, false), ccw0, ccw1).kind, RectDecision::kNothing);
    EXPECT_EQ(decide_rect_pair(config(true, false), cw0, cw1).kind, RectDecision::kRect);
    // front and back: setup_rect_noop
    EXPECT_EQ(decide_rect_pair(config(true, true), ccw0, ccw1).kind, RectDecision::kNothing);
    // zero-area pair with no culling: setup_rect_both returns TRUE, nothing drawn
    const float* z0[3] = {v0.f, v0.f, v1.f};
    EXPECT_EQ(decide_rect_pair(config(), z0, z0).kind, RectDecision::kNothing);
}

TEST(RectDetect, IroundSnapAndBox) {
    // util_iround(256 * fl(x - 0.5)): x = 10.5 + 1/512 -> 2560.5 -> half away -> 2561 (rne would give 2560)
    EXPECT_EQ(subpixel_snap_iround(10.0f + 1.0f / 512.0f), 2561);
    EXPECT_EQ(subpixel_snap_iround(-(10.0f + 1.0f / 512.0f)), -2561);
    // f + 0.5f rounds in float: 256 * a = 0.5 - 2^-25, + 0.5 = 1 - 2^-25 is a tie between 1 - 2^-24 and 1 ->
    // even -> 1.0 -> 1 (a correctly rounded round() gives 0); 8388607.5 + 0.5 is exact
    EXPECT_EQ(subpixel_snap_iround(0.49999997f / 256.0f), 1);
    EXPECT_EQ(subpixel_snap_iround(8388607.5f / 256.0f), 8388608);
    EXPECT_EQ(subpixel_snap_iround(1e30f), INT_MIN);
    // corners (v0, v1, v2) = (x0,y1), (x1,y0)... as lp_rect_cw receives them from the fan: (v2, v0, v1) of
    // (10.5+1/512, 20.5)-(30.5, 40.5+1/512): snapped x 2561 / 7680, y 5120 / 10241
    const float c0[2] = {30.5f, 40.5f + 1.0f / 512}, c1[2] = {10.5f + 1.0f / 512, 20.5f}, c2[2] = {30.5f, 20.5f};
    const RectBox b = rect_box(c0, c1, c2, 0.5f);
    ASSERT_FALSE(b.culled);
    // x0 = (2561 + 255) >> 8 = 11, x1 = ((7680 + 255) >> 8) - 1 = 29; y0 = 20, y1 = ((10241 + 255) >> 8) - 1 = 40
    EXPECT_EQ(b.x0, 11);
    EXPECT_EQ(b.x1, 29);
    EXPECT_EQ(b.y0, 20);
    EXPECT_EQ(b.y1, 40);
    // (c0, c2, c1): x2 = 2561 < x1 = 7680, y0 = 10241 < y2 = 5120 is false -> a "cw rect", culled
    EXPECT_TRUE(rect_box(c0, c2, c1, 0.5f).culled);
    // negative coordinates: arithmetic shift, x = -3 -> fl(-3.5) * 256 = -896 -> (-896 + 255) >> 8 = -3
    const float n0[2] = {4.5f, 3.5f}, n1[2] = {-3.0f, 0.5f}, n2[2] = {4.5f, 0.5f};
    const RectBox nb = rect_box(n0, n1, n2, 0.5f);
    ASSERT_FALSE(nb.culled);
    EXPECT_EQ(nb.x0, -3);
    EXPECT_EQ(nb.x1, 3);
}
