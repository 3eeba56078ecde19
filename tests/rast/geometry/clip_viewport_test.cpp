// Clip mask, viewport transform, draw's clipper and float cull. Expected values are derived by hand in the
// comments, or step by step with explicit float roundings, or from a double-precision reference clipper.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rast/geometry/clip.h"
#include "rast/geometry/fp_env.h"
#include "rast/geometry/viewport.h"

using namespace tilevk::rast::geometry;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Vtx {
    float f[8 + 4 * 3];
};

const Interp kInterp[3] = {Interp::kPerspective, Interp::kNoPerspective, Interp::kFlat};

ClipConfig config(bool flat_first = true) {
    ClipConfig c;
    c.layout = {3, kInterp};
    c.vp = make_viewport(0, 0, 100, 100, 0, 1);
    c.clip_halfz = true;
    c.flatshade_first = flat_first;
    return c;
}

Vtx vert(float x, float y, float z, float w, float a = 0) {
    Vtx v{};
    v.f[0] = x, v.f[1] = y, v.f[2] = z, v.f[3] = w;
    viewport_transform_c(config().vp, v.f, v.f + 4);
    for (int i = 0; i < 12; ++i) v.f[8 + i] = a + static_cast<float>(i);
    return v;
}

uint32_t mask(const Vtx& v) {
    return compute_clipmask(ClipMaskConfig{}, v.f);
}

}  // namespace

TEST(ClipMask, PlanesNaNAndDepthClipSwitch) {
    const ClipMaskConfig all{};
    const float inside[4] = {0.5f, -0.5f, 0.5f, 1};
    EXPECT_EQ(compute_clipmask(all, inside), 0u);
    const float right[4] = {2, 0, 0.5f, 1}, left[4] = {-2, 0, 0.5f, 1};
    const float bottom[4] = {0, 2, 0.5f, 1}, top[4] = {0, -2, 0.5f, 1};
    const float nearp[4] = {0, 0, -0.1f, 1}, farp[4] = {0, 0, 1.5f, 1};
    EXPECT_EQ(compute_clipmask(all, right), kClipRight);
    EXPECT_EQ(compute_clipmask(all, left), kClipLeft);
    EXPECT_EQ(compute_clipmask(all, bottom), kClipBottom);
    EXPECT_EQ(compute_clipmask(all, top), kClipTop);
    EXPECT_EQ(compute_clipmask(all, nearp), kClipNear);
    EXPECT_EQ(compute_clipmask(all, farp), kClipFar);
    // boundary: x == w is inside (strict >)
    const float edge[4] = {1, -1, 0, 1};
    EXPECT_EQ(compute_clipmask(all, edge), 0u);
    // depth clamp on (clip_z off): z planes never set
    ClipMaskConfig noz{true, false, true};
    EXPECT_EQ(compute_clipmask(noz, farp), 0u);
    // -1..1 depth: near is z + w < 0
    ClipMaskConfig gl{true, true, false};
    const float zneg[4] = {0, 0, -0.5f, 1};
    EXPECT_EQ(compute_clipmask(gl, zneg), 0u);
    EXPECT_EQ(compute_clipmask(all, zneg), kClipNear);
    // NaN: unordered compares set every plane it takes part in
    const float nanx[4] = {kNaN, 0, 0.5f, 1};
    EXPECT_EQ(compute_clipmask(all, nanx), kClipRight | kClipLeft);
    const float nanw[4] = {0, 0, 0.5f, kNaN};
    EXPECT_EQ(compute_clipmask(all, nanw), 0x3Fu & ~kClipNear);
    // x = +Inf, w = +Inf: x > w false, x + w = Inf -> no bit at all (lavapipe passes it on unclipped)
    const float infs[4] = {kInf, 0, 0.5f, kInf};
    EXPECT_EQ(compute_clipmask(all, infs) & (kClipRight | kClipLeft), 0u);
    // x = -Inf, w = +Inf: x + w = NaN -> left bit
    const float ninf[4] = {-kInf, 0, 0.5f, kInf};
    EXPECT_EQ(compute_clipmask(all, ninf) & (kClipRight | kClipLeft), kClipLeft);
}

TEST(Viewport, LavapipeValues) {
    const Viewport v = make_viewport(10.0f, 20.0f, 101.0f, -50.0f, 0.25f, 0.75f);
    EXPECT_EQ(v.scale[0], 50.5f);
    EXPECT_EQ(v.translate[0], 60.5f);
    EXPECT_EQ(v.scale[1], -25.0f);
    EXPECT_EQ(v.translate[1], -5.0f);
    EXPECT_EQ(v.scale[2], 0.5f);
    EXPECT_EQ(v.translate[2], 0.25f);
    // z scale computed in double: f - n of 0.1f and 0.3f in double, then rounded once
    const Viewport d = make_viewport(0, 0, 1, 1, 0.1f, 0.3f);
    EXPECT_EQ(d.scale[2], static_cast<float>(static_cast<double>(0.3f) - static_cast<double>(0.1f)));
    EXPECT_EQ(d.translate[2], 0.1f);
    EXPECT_FALSE(is_identity_viewport(v));
    Viewport id{{1, 1, 1}, {0, 0, 0}};
    EXPECT_TRUE(is_identity_viewport(id));
}

TEST(Viewport, FusedAndUnfusedDifferWhereExpected) {
    // x = 1 + 2^-12, w = 1 (oow = 1, p = x), scale = 1 + 2^-12, translate = -1.
    // exact p*s = 1 + 2^-11 + 2^-24; float rounding is a tie (2^-24 = half an ulp of 1) to even: 1 + 2^-11.
    // unfused: fl(1 + 2^-11 - 1) = 2^-11;  fused: 2^-11 + 2^-24.
    const float x = 1.0f + std::ldexp(1.0f, -12);
    ViewportConfig cfg;
    cfg.vp = Viewport{{x, x, 1}, {-1, -1, 0}};
    const float clip[4] = {x, x, 0.5f, 1.0f};
    float win[4];
    cfg.fused = true;
    viewport_transform(cfg, clip, win);
    EXPECT_EQ(win[0], std::ldexp(1.0f, -11) + std::ldexp(1.0f, -24));
    EXPECT_EQ(win[3], 1.0f);
    cfg.fused = false;
    viewport_transform(cfg, clip, win);
    EXPECT_EQ(win[0], std::ldexp(1.0f, -11));
    viewport_transform_c(cfg.vp, clip, win);  // the clipper's C path never fuses
    EXPECT_EQ(win[0], std::ldexp(1.0f, -11));
    // oow = 1/w once, then x*oow (not x/w): w = 3, x = 1 -> fl(1/3)*1 ; with x = 3: fl(3*fl(1/3)) = 1
    const float c3[4] = {3, 0, 0, 3};
    viewport_transform(ViewportConfig{Viewport{{1, 1, 1}, {0.5f, 0, 0}}, true, false}, c3, win);
    EXPECT_EQ(win[3], 1.0f / 3.0f);
    EXPECT_EQ(win[0], std::fma(3.0f * (1.0f / 3.0f), 1.0f, 0.5f));
    // bypass: raw clip coordinates, w not inverted
    ViewportConfig by;
    by.bypass = true;
    const float raw[4] = {2, 3, 4, 5};
    viewport_transform(by, raw, win);
    EXPECT_EQ(win[0], 2.0f);
    EXPECT_EQ(win[3], 5.0f);
}

TEST(Clipper, UntouchedWhenAllMasksZeroAndRejectWhenAllOutside) {
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    Vtx a = vert(0, 0, 0.5f, 1), b = vert(0.5f, 0, 0.5f, 1), c = vert(0, 0.5f, 0.5f, 1);
    ASSERT_EQ(clip_triangle(config(), a.f, b.f, c.f, 0, 0, 0, scratch.data(), out), 1u);
    EXPECT_EQ(out[0].v[0], a.f);
    EXPECT_EQ(out[0].v[1], b.f);
    EXPECT_EQ(out[0].v[2], c.f);
    Vtx d = vert(2, 0, 0.5f, 1), e = vert(3, 0, 0.5f, 1), f = vert(2, 1, 0.5f, 1);
    EXPECT_EQ(clip_triangle(config(), d.f, e.f, f.f, mask(d), mask(e), mask(f), scratch.data(), out), 0u);
}

TEST(Clipper, RightPlaneQuadByHand) {
    // v0 (0,0), v1 (2,0), v2 (0,1), w = 1. Plane 0: dp = w - x -> 1, -1, 1.
    // v0->v1 going out: -dp (1) < dp_prev (1) false -> t = -1/(-2) = 0.5 from v0: A = (1, 0)
    // v1->v2 coming in: -dp_prev (1) < dp (1) false -> t = 1/2 from v2 towards v1: B = (1, 0.5)
    // polygon (v0, A, B, v2) -> fan (v0, A, B), (v0, B, v2)
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    Vtx v0 = vert(0, 0, 0.5f, 1, 0), v1 = vert(2, 0, 0.5f, 1, 10), v2 = vert(0, 1, 0.5f, 1, 20);
    ASSERT_EQ(clip_triangle(config(), v0.f, v1.f, v2.f, mask(v0), mask(v1), mask(v2), scratch.data(), out), 2u);
    EXPECT_EQ(out[0].v[0], v0.f);
    EXPECT_EQ(out[1].v[0], v0.f);
    EXPECT_EQ(out[1].v[2], v2.f);
    const float* A = out[0].v[1];
    const float* B = out[0].v[2];
    EXPECT_EQ(out[1].v[1], B);
    EXPECT_EQ(A[0], 1.0f);
    EXPECT_EQ(A[1], 0.0f);
    EXPECT_EQ(B[0], 1.0f);
    EXPECT_EQ(B[1], 0.5f);
    EXPECT_EQ(A[3], 1.0f);
    // window: x = (1*1)*50 + 50 = 100, y of B = 0.5*50 + 50 = 75, 1/w = 1
    EXPECT_EQ(A[4], 100.0f);
    EXPECT_EQ(B[5], 75.0f);
    EXPECT_EQ(B[7], 1.0f);
    // perspective attribute 0 of B: v2 + 0.5*(v1 - v2) = 20 + 0.5*(10-20) = 15
    EXPECT_EQ(B[8], 15.0f);
    // flat attribute of the emitted first vertex is v0's (v0 survived, nothing copied)
    EXPECT_EQ(out[0].v[0][16], 8.0f);
}

TEST(Clipper, InterpolatesFromTheVertexNearerThePlane) {
    // v0 x = -0.3 (dp = 1.3), v1 x = 1.9 (dp = fl(1 - 1.9) < 0), both w = 1.
    // -dp < dp_prev -> t = dp/(dp - dp_prev) measured from the outside vertex v1.
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    Vtx v0 = vert(-0.3f, 0.1f, 0.5f, 1, 0.3f), v1 = vert(1.9f, 0.7f, 0.5f, 1, 7.1f), v2 = vert(-0.3f, 0.9f, 0.5f, 1);
    const uint32_t n = clip_triangle(config(), v0.f, v1.f, v2.f, mask(v0), mask(v1), mask(v2), scratch.data(), out);
    ASSERT_EQ(n, 2u);
    const float dp_prev = 1.0f - (-0.3f);  // dot4: ((0.3 + 0) + 0) + 1*1
    const float dp = (-1.9f + 0.0f + 0.0f) + 1.0f;
    ASSERT_LT(-dp, dp_prev);
    const float t = dp / (dp - dp_prev);
    const float* A = out[0].v[1];
    auto lin = [&](float o, float i) { return o + t * (i - o); };  // out = v1, in = v0
    EXPECT_EQ(A[0], lin(1.9f, -0.3f));
    EXPECT_EQ(A[1], lin(0.7f, 0.1f));
    EXPECT_EQ(A[8], lin(7.1f, 0.3f));
    // the other direction gives a different float here, so the branch is observable
    const float t2 = -dp_prev / (dp - dp_prev);
    const float other = -0.3f + t2 * (1.9f - (-0.3f));
    EXPECT_NE(A[0], other) << "pick another example: both branches agree";
    // window x in C: fl(fl(fl(x*oow)*50)+50), oow = fl(1/w)
    const float oow = 1.0f / A[3];
    const float wx = (A[0] * oow) * 50.0f;
    EXPECT_EQ(A[4], wx + 50.0f);
}

TEST(Clipper, NoPerspectiveUsesScreenSpaceT) {
    // Edge from v0 (x=0, w=1) to v1 (x=3, w=2) (x/w = 1.5) crossing x = w.
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    Vtx v0 = vert(0, 0, 0.5f, 1, 0), v1 = vert(3, 0, 0.5f, 2, 100), v2 = vert(0, 0.5f, 0.5f, 1, 0);
    ASSERT_GE(clip_triangle(config(), v0.f, v1.f, v2.f, mask(v0), mask(v1), mask(v2), scratch.data(), out), 1u);
    const float* A = out[0].v[1];
    // dp0 = 1, dp1 = 2 - 3 = -1: -dp < dp_prev false -> t = -1/(-2) = 0.5 from v0: clip (1.5, 0, 0.5, 1.5)
    EXPECT_EQ(A[0], 1.5f);
    EXPECT_EQ(A[3], 1.5f);
    EXPECT_EQ(A[8], 50.0f);  // perspective: 0 + 0.5*100
    // screen: in (v1) 3/2 = 1.5, out (v0) 0, dst 1.5/1.5 = 1 -> t' = (1 - 0)/(1.5 - 0) = fl(2/3)
    const float tn = 1.0f / 1.5f;
    EXPECT_EQ(A[12], 4.0f + tn * (104.0f - 4.0f));  // noperspective attribute 1, component 0 = a + 4
}

TEST(Clipper, FlatAttributesComeFromTheProvokingVertex) {
    // v0 outside: the polygon starts with a new vertex, which gets v0's flat attribute (attrib 2).
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    Vtx v0 = vert(3, 0, 0.5f, 1, 1000), v1 = vert(0, 0, 0.5f, 1, 0), v2 = vert(0, 0.5f, 0.5f, 1, 0);
    const uint32_t n = clip_triangle(config(), v0.f, v1.f, v2.f, mask(v0), mask(v1), mask(v2), scratch.data(), out);
    ASSERT_EQ(n, 2u);
    for (uint32_t i = 0; i < n; ++i) {
        EXPECT_NE(out[i].v[0], v0.f);
        EXPECT_EQ(out[i].v[0][16], 1008.0f);  // attrib 2 component 0 = a + 8
    }
    // last-vertex convention: fan emitted (p[i-1], p[i], p0), p0's flat copied from v2
    Vtx w0 = vert(0, 0, 0.5f, 1, 0), w1 = vert(0, 0.5f, 0.5f, 1, 0), w2 = vert(3, 0, 0.5f, 1, 500);
    const uint32_t m =
        clip_triangle(config(false), w0.f, w1.f, w2.f, mask(w0), mask(w1), mask(w2), scratch.data(), out);
    ASSERT_EQ(m, 2u);
    // p0 = w0 (inside) is emitted last; it is not the provoking vertex w2, so it is a copy with w2's flat value
    EXPECT_NE(out[0].v[2], w0.f);
    EXPECT_EQ(std::memcmp(out[0].v[2], w0.f, 16 * sizeof(float)), 0);
    EXPECT_EQ(out[0].v[2][16], 508.0f);
}

TEST(Clipper, ReordersEvenWhenNothingIsCut) {
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    // A mask bit whose plane cuts nothing (as with lavapipe's guard band): the fan is still re-emitted.
    Vtx v0 = vert(0, 0, 0.5f, 1), v1 = vert(0.5f, 0, 0.5f, 1), v2 = vert(0, 0.5f, 0.5f, 1);
    ASSERT_EQ(clip_triangle(config(false), v0.f, v1.f, v2.f, kClipRight, 0, 0, scratch.data(), out), 1u);
    // last-vertex emit order (in[i-1], in[i], in[0]) = (v1, v2, v0): rotated
    EXPECT_EQ(out[0].v[0], v1.f);
    EXPECT_EQ(out[0].v[1], v2.f);
    EXPECT_EQ(std::memcmp(out[0].v[2], v0.f, 16 * sizeof(float)), 0);  // v0 copied: flat attribs from v2
    EXPECT_EQ(out[0].v[2][16], v2.f[16]);
}

TEST(Clipper, GuardBandCutsOnlyBeyondTwiceTheViewport) {
    // llvmpipe's linear mode: the clip mask still tests the viewport (x > w), the clipper uses x <= 2w.
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    ClipConfig gb = config();
    gb.guard_band_xy = true;
    // v1 at x = 1.5 w: outside the viewport (mask bit 0), inside the guard band -> one triangle, the input
    // vertices in the fan order (in[0], in[1], in[2]); without the guard band it is cut into two.
    Vtx v0 = vert(0, 0, 0.5f, 1, 0), v1 = vert(1.5f, 0, 0.5f, 1, 10), v2 = vert(0, 1, 0.5f, 1, 20);
    ASSERT_EQ(mask(v1), kClipRight);
    ASSERT_EQ(clip_triangle(gb, v0.f, v1.f, v2.f, mask(v0), mask(v1), mask(v2), scratch.data(), out), 1u);
    EXPECT_EQ(out[0].v[0], v0.f);
    EXPECT_EQ(out[0].v[1], v1.f);
    EXPECT_EQ(out[0].v[2], v2.f);
    EXPECT_EQ(clip_triangle(config(), v0.f, v1.f, v2.f, mask(v0), mask(v1), mask(v2), scratch.data(), out), 2u);
    // v1 at x = 4: plane 0 of the guard band (-0.5, 0, 0, 1): dp0 = 1, dp1 = fl(-2 + 0) + 0 + 1 = -1.
    // v0->v1 going out: -dp (1) < dp_prev (1) false -> t = -dp_prev/(dp - dp_prev) = 0.5 from v0: A = (2, 0)
    // v1->v2 coming in: dp_prev = -1, dp (v2) = 1 -> t = 0.5 from v2 towards v1: B = (2, 0.5), attrib 15.
    Vtx u1 = vert(4, 0, 0.5f, 1, 10);
    ASSERT_EQ(clip_triangle(gb, v0.f, u1.f, v2.f, mask(v0), mask(u1), mask(v2), scratch.data(), out), 2u);
    const float* A = out[0].v[1];
    const float* B = out[0].v[2];
    EXPECT_EQ(A[0], 2.0f);
    EXPECT_EQ(A[1], 0.0f);
    EXPECT_EQ(B[0], 2.0f);
    EXPECT_EQ(B[1], 0.5f);
    EXPECT_EQ(B[8], 15.0f);
    // window x of the cut vertex: fl(fl(2*1)*50) + 50 = 150, past the 100-px viewport
    EXPECT_EQ(A[4], 150.0f);
    // the guard-band plane distance: dot4 with -0.5, left to right
    const float c[4] = {3, -5, 0.25f, 1};
    EXPECT_EQ(clip_plane_distance(c, 0, true, true), -0.5f);
    EXPECT_EQ(clip_plane_distance(c, 1, true, true), 2.5f);
    EXPECT_EQ(clip_plane_distance(c, 2, true, true), 3.5f);
    EXPECT_EQ(clip_plane_distance(c, 3, true, true), -1.5f);
    EXPECT_EQ(clip_plane_distance(c, 5, true, true), clip_plane_distance(c, 5, true, false));  // z planes as before
}

TEST(LineClip, GuardBand) {
    // v0 x = -3, v1 x = 1.5 (w = 1): guard-band left plane dp = 0.5x + w -> -0.5, 1.75 -> t0 = 0.5/2.25;
    // the right plane (mask bit set by x > w) cuts nothing (dp1 = -0.75 + 1 = 0.25).
    std::vector<float> scratch(2 * 20);
    ClipConfig gb = config();
    gb.guard_band_xy = true;
    Vtx v0 = vert(-3, 0, 0.5f, 1, 0), v1 = vert(1.5f, 0, 0.5f, 1, 8);
    const float* a;
    const float* b;
    ASSERT_TRUE(clip_line(gb, v0.f, v1.f, mask(v0), mask(v1), scratch.data(), &a, &b));
    // v1 has a mask bit, so draw re-makes it with t1 = 0 (same clip position, window coordinates in C)
    EXPECT_NE(b, v1.f);
    EXPECT_EQ(b[0], 1.5f);
    const float t0 = -0.5f / (-0.5f - 1.75f);
    EXPECT_EQ(a[0], -3.0f + t0 * (1.5f - -3.0f));
    EXPECT_NEAR(a[0], -2.0f, 1e-6f);
}

TEST(Clipper, NaNAndInfDiscardHugeSurvives) {
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    Vtx a = vert(0, 0, 0.5f, 1), b = vert(kNaN, 0, 0.5f, 1), c = vert(0, 0.5f, 0.5f, 1);
    EXPECT_EQ(clip_triangle(config(), a.f, b.f, c.f, mask(a), mask(b), mask(c), scratch.data(), out), 0u);
    Vtx d = vert(kInf, 0, 0.5f, 1);
    EXPECT_EQ(clip_triangle(config(), a.f, d.f, c.f, mask(a), mask(d), mask(c), scratch.data(), out), 0u);
    Vtx e = vert(1e30f, 0, 0.5f, 1);
    const uint32_t n = clip_triangle(config(), a.f, e.f, c.f, mask(a), mask(e), mask(c), scratch.data(), out);
    ASSERT_GE(n, 1u);
    for (uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(out[i].v[k][4]));
}

namespace {

// Double-precision Sutherland-Hodgman against x<=w, -x<=w, y<=w, -y<=w, 0<=z<=w.
std::vector<std::array<double, 4>> ref_clip(std::vector<std::array<double, 4>> poly) {
    const double planes[6][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 0}, {0, 0, -1, 1}};
    for (const auto& p : planes) {
        std::vector<std::array<double, 4>> out;
        for (size_t i = 0; i < poly.size(); ++i) {
            const auto& s = poly[i];
            const auto& e = poly[(i + 1) % poly.size()];
            const double ds = s[0] * p[0] + s[1] * p[1] + s[2] * p[2] + s[3] * p[3];
            const double de = e[0] * p[0] + e[1] * p[1] + e[2] * p[2] + e[3] * p[3];
            if (ds >= 0) out.push_back(s);
            if ((ds >= 0) != (de >= 0)) {
                const double t = ds / (ds - de);
                std::array<double, 4> q;
                for (int k = 0; k < 4; ++k) q[k] = s[k] + t * (e[k] - s[k]);
                out.push_back(q);
            }
        }
        poly = out;
        if (poly.size() < 3) return {};
    }
    return poly;
}

}  // namespace

TEST(Clipper, AgreesWithDoubleReferenceOnRandomTriangles) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> pos(-3.0f, 3.0f), wd(0.2f, 2.0f);
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    int clipped = 0;
    for (int iter = 0; iter < 2000; ++iter) {
        Vtx v[3];
        std::vector<std::array<double, 4>> poly;
        for (auto& x : v) {
            x = vert(pos(rng), pos(rng), pos(rng) * 0.5f + 0.5f, wd(rng));
            poly.push_back({x.f[0], x.f[1], x.f[2], x.f[3]});
        }
        const uint32_t n =
            clip_triangle(config(), v[0].f, v[1].f, v[2].f, mask(v[0]), mask(v[1]), mask(v[2]), scratch.data(), out);
        const auto ref = ref_clip(poly);
        if (mask(v[0]) | mask(v[1]) | mask(v[2])) ++clipped;
        // Same polygon: same vertex count (fan of n-2 triangles), and every float vertex within float rounding
        // (a few ulps of the coordinate range 3) of a reference vertex. Degenerate slivers can gain/lose a vertex.
        if (ref.size() >= 3 && n >= 1) {
            for (uint32_t i = 0; i < n; ++i)
                for (int k = 0; k < 3; ++k) {
                    double best = 1e9;
                    for (const auto& q : ref) {
                        double d = 0;
                        for (int c = 0; c < 4; ++c) d = std::max(d, std::fabs(q[c] - out[i].v[k][c]));
                        best = std::min(best, d);
                    }
                    EXPECT_LT(best, 1e-5) << iter;
                }
            if (n + 2 != ref.size()) {
                // allowed only for near-degenerate cuts; count them
            }
        }
        if (ref.empty()) {
            // reference says empty: the float clipper may keep only a sliver of zero or tiny area
            for (uint32_t i = 0; i < n; ++i) {
                for (int k = 0; k < 3; ++k) {
                    const float* c = out[i].v[k];
                    EXPECT_LE(c[0], c[3] * (1 + 1e-5f) + 1e-6f);
                }
            }
        }
    }
    EXPECT_GT(clipped, 500);
}

TEST(Clipper, GarbageNeverCrashes) {
    std::mt19937 rng(99);
    const float specials[] = {kNaN, kInf, -kInf, 0.0f, -0.0f, 1e38f, -1e38f, 1e-38f, 1.0f, -1.0f};
    std::vector<float> scratch(kClipScratchVertices * 20);
    ClippedTriangle out[kMaxClippedTriangles];
    for (int iter = 0; iter < 5000; ++iter) {
        Vtx v[3];
        for (auto& x : v) {
            x = vert(0, 0, 0, 1);
            for (int c = 0; c < 4; ++c) x.f[c] = specials[rng() % 10];
        }
        const uint32_t n =
            clip_triangle(config(), v[0].f, v[1].f, v[2].f, mask(v[0]), mask(v[1]), mask(v[2]), scratch.data(), out);
        EXPECT_LE(n, kMaxClippedTriangles);
        const float* e0;
        const float* e1;
        (void)clip_line(config(), v[0].f, v[1].f, mask(v[0]), mask(v[1]), scratch.data(), &e0, &e1);
    }
}

TEST(LineClip, ParametricEndsByHand) {
    // v0 x = -2 (left plane dp = x + w = -1), v1 x = 2 (right plane dp = w - x = -1), w = 1.
    // left: dp0 = -1, dp1 = 3 -> t0 = -1/(-1-3) = 0.25; right: dp0 = 3, dp1 = -1 -> t1 = 0.25.
    std::vector<float> scratch(2 * 20);
    Vtx v0 = vert(-2, 0, 0.5f, 1, 0), v1 = vert(2, 0, 0.5f, 1, 8);
    const float* a;
    const float* b;
    ASSERT_TRUE(clip_line(config(), v0.f, v1.f, mask(v0), mask(v1), scratch.data(), &a, &b));
    EXPECT_EQ(a[0], -1.0f);  // -2 + 0.25*4
    EXPECT_EQ(b[0], 1.0f);
    EXPECT_EQ(a[8], 2.0f);
    EXPECT_EQ(b[8], 6.0f);
    EXPECT_EQ(b[16], v0.f[16]);  // flat from provoking v0
    // t0 + t1 >= 1 discards: both ends beyond the same side after accumulation
    Vtx w0 = vert(-3, 0, 0.5f, 1), w1 = vert(-1.5f, 0, 0.5f, 1);
    EXPECT_FALSE(clip_line(config(), w0.f, w1.f, mask(w0), mask(w1), scratch.data(), &a, &b));
    Vtx u0 = vert(0, 0, 0.5f, 1), u1 = vert(0.5f, 0, 0.5f, 1);
    ASSERT_TRUE(clip_line(config(), u0.f, u1.f, 0, 0, scratch.data(), &a, &b));
    EXPECT_EQ(a, u0.f);
    EXPECT_EQ(b, u1.f);
}

TEST(PointClip, OnlyWAndNonFiniteXYDrop) {
    const ClipMaskConfig cm{};
    const float far_x[4] = {50, 0, 0.5f, 1};  // way outside x: points are not x/y clipped
    EXPECT_TRUE(clip_point_keep(far_x, compute_clipmask(cm, far_x)));
    const float neg_w[4] = {0, 0, 0.5f, -1};
    EXPECT_FALSE(clip_point_keep(neg_w, compute_clipmask(cm, neg_w)));  // also sets z bits: dropped
    ClipMaskConfig noz{true, false, true};
    EXPECT_FALSE(clip_point_keep(neg_w, compute_clipmask(noz, neg_w)));  // w <= 0
    const float inf_y[4] = {0, kInf, 0.5f, 1};
    EXPECT_FALSE(clip_point_keep(inf_y, compute_clipmask(cm, inf_y)));
    const float deep[4] = {0, 0, 2, 1};
    EXPECT_FALSE(clip_point_keep(deep, compute_clipmask(cm, deep)));  // z clip drops points
}

TEST(FloatCull, DeterminantSignAndZero) {
    // window y down: (0,0) (0,10) (10,0): e = v0-v2 = (-10, 0), f = v1-v2 = (-10, 10): det = -100 -> ccw
    const float a[2] = {0, 0}, b[2] = {0, 10}, c[2] = {10, 0};
    FloatCull back{false, true, true};
    EXPECT_TRUE(float_cull_keep(back, a, b, c));   // ccw = front with front_ccw
    EXPECT_FALSE(float_cull_keep(back, a, c, b));  // cw = back
    FloatCull front{true, false, true};
    EXPECT_FALSE(float_cull_keep(front, a, b, c));
    // zero determinant is back-facing
    const float d[2] = {20, 0};
    EXPECT_FALSE(float_cull_keep(back, a, c, d));
    EXPECT_TRUE(float_cull_keep(front, a, c, d));
    FloatCull none{};
    EXPECT_TRUE(float_cull_keep(none, a, c, d));
}

TEST(Viewport, PixelRectRounding) {
    // full 64x64: x0 = (int)(0 + 0.499) = 0, x1 = (int)(64 - 0.501) = 63 inclusive -> [0, 64)
    PixelRect r = viewport_pixel_rect(make_viewport(0, 0, 64, 64, 0, 1));
    EXPECT_EQ(r.x0, 0);
    EXPECT_EQ(r.x1, 64);
    EXPECT_EQ(r.y1, 64);
    // x = 10.5, width 20: tx - sx = 10.5 -> (int)10.999 = 10; 20 + 10.5 - 0.501 = 29.999 -> 29 -> [10, 30)
    // y = 5.6, height 10.2: ty - sy = 5.6 -> (int)6.099 = 6; 10.2 + 5.6 - 0.501 = 15.299 -> 15 -> [6, 16)
    r = viewport_pixel_rect(make_viewport(10.5f, 5.6f, 20.0f, 10.2f, 0, 1));
    EXPECT_EQ(r.x0, 10);
    EXPECT_EQ(r.x1, 30);
    EXPECT_EQ(r.y0, 6);
    EXPECT_EQ(r.y1, 16);
    // negative height (flipped): |sy| is used, y0 = ty - |sy|: y = 20, height -10 -> sy = -5, ty = 15 -> 10..19
    r = viewport_pixel_rect(make_viewport(0, 20.0f, 8.0f, -10.0f, 0, 1));
    EXPECT_EQ(r.y0, 10);
    EXPECT_EQ(r.y1, 20);
    // garbage never traps
    r = viewport_pixel_rect(Viewport{{NAN, 1e30f, 1}, {0, 0, 0}});
    EXPECT_EQ(r.x0, INT32_MIN);
}

TEST(FpEnv, FlushesDenormalsInsideTheGuardOnly) {
    volatile float tiny = 1e-38f;  // normal
    volatile float sub = 1e-40f;   // subnormal
    volatile float scale = 1e-3f;
    EXPECT_NE(tiny * scale, 0.0f);  // default environment: a subnormal result
    {
        ScopedFlushDenormals guard;
        EXPECT_EQ(tiny * scale, 0.0f);  // FTZ: subnormal results flush to zero
        EXPECT_EQ(sub + 0.0f, 0.0f);    // DAZ: subnormal inputs read as zero
        // the clipper under FTZ: a plane distance that would be subnormal is 0 (inside), as in lavapipe
        // (w - x with both normal but a subnormal difference)
        const float c[4] = {2e-38f, 0.0f, 0.5f, 2.1e-38f};
        EXPECT_EQ(clip_plane_distance(c, 0, true), 0.0f);
    }
    const float c[4] = {2e-38f, 0.0f, 0.5f, 2.1e-38f};
    EXPECT_GT(clip_plane_distance(c, 0, true), 0.0f);
    EXPECT_NE(sub + 0.0f, 0.0f);
}
