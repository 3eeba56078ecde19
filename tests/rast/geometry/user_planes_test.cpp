// ClipDistance / CullDistance in draw's clipper (draw_pipe_clip.c, user planes = clip-mask bits 6+) and its user
// cull stage (draw_pipe_user_cull.c). Expected values are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "rast/geometry/clip.h"
#include "rast/geometry/viewport.h"

using namespace tilevk::rast::geometry;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Record: clip position, window position, attribute 0 (a colour), attributes 1-2 (the combined distance array).
constexpr uint32_t kFloats = 8 + 4 * 3;
const Interp kInterp[3] = {Interp::kPerspective, Interp::kPerspective, Interp::kPerspective};

struct Vtx {
    float f[kFloats];
};

ClipConfig config(uint32_t clip, uint32_t cull = 0) {
    ClipConfig c;
    c.layout = {3, kInterp};
    c.vp = make_viewport(0, 0, 100, 100, 0, 1);
    c.distance_slot = 1;
    c.num_clip_distances = clip;
    c.num_cull_distances = cull;
    return c;
}

Vtx vert(float x, float y, float a, std::vector<float> d) {
    Vtx v{};
    v.f[0] = x, v.f[1] = y, v.f[2] = 0.5f, v.f[3] = 1;
    viewport_transform_c(config(0).vp, v.f, v.f + 4);
    for (int i = 0; i < 4; ++i) v.f[8 + i] = a;
    for (size_t i = 0; i < d.size(); ++i) v.f[12 + i] = d[i];
    return v;
}

uint32_t mask(const Vtx& v, uint32_t clip) {
    return compute_clipmask(ClipMaskConfig{}, v.f) | clip_distance_mask(v.f + 12, clip);
}

}  // namespace

TEST(UserPlanes, MaskBitsAreUnorderedBelowZeroOrInfinite) {
    // generate_clipmask: bit 6 + i when 0 > d (unordered) or d is infinite; -0 and +0 are inside.
    const float d[8] = {0.5f, -0.5f, -0.0f, kNaN, kInf, -kInf, 0.0f, 3e38f};
    EXPECT_EQ(clip_distance_mask(d, 8), (1u << 7) | (1u << 9) | (1u << 10) | (1u << 11));
    EXPECT_EQ(clip_distance_mask(d, 1), 0u);  // only the written distances count
    EXPECT_EQ(clip_distance_mask(d, 2), 1u << 7);
}

TEST(UserPlanes, TriangleCutByHandKeepsTheEdgeAlongThePlane) {
    // Distances 1, -1, 1 at v0 (0,0), v1 (0.5,0), v2 (0,0.5), inside the frustum.
    // v0->v1 going out: -dp (1) < dp_prev (1) is false -> t = -dp_prev/(dp - dp_prev) = 0.5 from v0: A = (0.25, 0),
    //   distance 1 + 0.5*(-1 - 1) = 0, colour 0 + 0.5*(8 - 0) = 4.
    // v1->v2 coming in: -dp_prev (1) < dp (1) is false -> t = dp/(dp - dp_prev) = 0.5 from v2: B = (0.25, 0.25),
    //   colour 2 + 0.5*(8 - 2) = 5.
    // Fan (v0, A, B), (v0, B, v2). Along a user plane the new edge A->B is drawn (draw sets the going-out
    // vertex's edge flag), unlike a frustum plane's.
    std::vector<float> scratch(kClipScratchVertices * kFloats);
    ClippedTriangle out[kMaxClippedTriangles];
    const ClipConfig cfg = config(1);
    Vtx v0 = vert(0, 0, 0, {1}), v1 = vert(0.5f, 0, 8, {-1}), v2 = vert(0, 0.5f, 2, {1});
    ASSERT_EQ(mask(v1, 1), 1u << kClipUserShift);
    ASSERT_EQ(clip_triangle(cfg, v0.f, v1.f, v2.f, mask(v0, 1), mask(v1, 1), mask(v2, 1), scratch.data(), out), 2u);
    const float* A = out[0].v[1];
    const float* B = out[0].v[2];
    EXPECT_EQ(out[0].v[0], v0.f);
    EXPECT_EQ(out[1].v[1], B);
    EXPECT_EQ(out[1].v[2], v2.f);
    EXPECT_EQ(A[0], 0.25f);
    EXPECT_EQ(A[1], 0.0f);
    EXPECT_EQ(B[0], 0.25f);
    EXPECT_EQ(B[1], 0.25f);
    EXPECT_EQ(A[4], 62.5f);  // window x: 0.25*50 + 50
    EXPECT_EQ(A[8], 4.0f);
    EXPECT_EQ(B[8], 5.0f);
    EXPECT_EQ(A[12], 0.0f);       // the distance is interpolated like any perspective attribute
    EXPECT_EQ(out[0].edges, 3u);  // v0->A and A->B
    EXPECT_EQ(out[1].edges, 6u);  // B->v2 and v2->v0
}

TEST(UserPlanes, SecondPlaneReadsTheInterpolatedDistance) {
    // Plane 6: distances 1, -1, 1 as above makes A (t 0.5 between v0 and v1) and B. Plane 7: distances
    // -3 at v0, 1 at v1 and v2; A's is -3 + 0.5*(1 - -3) = -1 and B's 1. The polygon (v0, A, B, v2) against plane 7:
    // v0 (-3) and A (-1) out, B and v2 in. A->B coming in: t = 1/(1 - -1) = 0.5 from B towards A:
    // C = (0.25, 0.125); v2->v0 going out: -dp (3) < dp_prev (1) is false -> t = -1/(-3 - 1) = 0.25 from v2:
    // D = (0, 0.375). Result (C, B, v2, D): two triangles from C.
    std::vector<float> scratch(kClipScratchVertices * kFloats);
    ClippedTriangle out[kMaxClippedTriangles];
    const ClipConfig cfg = config(2);
    Vtx v0 = vert(0, 0, 0, {1, -3}), v1 = vert(0.5f, 0, 8, {-1, 1}), v2 = vert(0, 0.5f, 2, {1, 1});
    ASSERT_EQ(clip_triangle(cfg, v0.f, v1.f, v2.f, mask(v0, 2), mask(v1, 2), mask(v2, 2), scratch.data(), out), 2u);
    const float* C = out[0].v[0];
    EXPECT_EQ(C[0], 0.25f);
    EXPECT_EQ(C[1], 0.125f);
    EXPECT_EQ(out[0].v[1][1], 0.25f);  // B
    EXPECT_EQ(out[0].v[2], v2.f);
    const float* D = out[1].v[2];
    EXPECT_EQ(D[0], 0.0f);
    EXPECT_EQ(D[1], 0.375f);
    // Without the user planes counted (num_clip_distances 0) the same masks cut nothing: the fan re-emission only.
    ASSERT_EQ(clip_triangle(config(0), v0.f, v1.f, v2.f, mask(v0, 2), mask(v1, 2), mask(v2, 2), scratch.data(), out),
              1u);
    EXPECT_EQ(out[0].v[1], v1.f);
}

TEST(UserPlanes, NonFiniteDistanceDropsTheTriangle) {
    std::vector<float> scratch(kClipScratchVertices * kFloats);
    ClippedTriangle out[kMaxClippedTriangles];
    const ClipConfig cfg = config(1);
    Vtx v0 = vert(0, 0, 0, {kNaN}), v1 = vert(0.5f, 0, 8, {1}), v2 = vert(0, 0.5f, 2, {1});
    EXPECT_EQ(clip_triangle(cfg, v0.f, v1.f, v2.f, mask(v0, 1), mask(v1, 1), mask(v2, 1), scratch.data(), out), 0u);
    Vtx w0 = vert(0, 0, 0, {-1}), w1 = vert(0.5f, 0, 8, {-2}), w2 = vert(0, 0.5f, 2, {-0.5f});
    EXPECT_EQ(clip_triangle(cfg, w0.f, w1.f, w2.f, mask(w0, 1), mask(w1, 1), mask(w2, 1), scratch.data(), out), 0u);
}

TEST(UserPlanes, LinesAndPoints) {
    // do_clip_line: distances -1 and 3 -> t0 = -1/(-1 - 3) = 0.25 from v0: x = 0 + 0.25*0.8 = 0.2, colour 1.
    std::vector<float> scratch(2 * kFloats);
    const ClipConfig cfg = config(1);
    Vtx v0 = vert(0, 0, 0, {-1}), v1 = vert(0.8f, 0, 4, {3});
    const float* a;
    const float* b;
    ASSERT_TRUE(clip_line(cfg, v0.f, v1.f, mask(v0, 1), mask(v1, 1), scratch.data(), &a, &b));
    EXPECT_FLOAT_EQ(a[0], 0.2f);
    EXPECT_EQ(a[8], 1.0f);
    EXPECT_EQ(a[12], 0.0f);
    EXPECT_EQ(b, v1.f);
    Vtx u0 = vert(0, 0, 0, {-1}), u1 = vert(0.8f, 0, 4, {-3});
    EXPECT_FALSE(clip_line(cfg, u0.f, u1.f, mask(u0, 1), mask(u1, 1), scratch.data(), &a, &b));
    // clip_point_guard_xy: any bit above the x/y planes drops the point, so a negative distance does.
    EXPECT_FALSE(clip_point_keep(v0.f, mask(v0, 1)));
    EXPECT_TRUE(clip_point_keep(v1.f, mask(v1, 1)));
}

TEST(UserPlanes, CullDistanceNeedsEveryVertexOutForOneDistance) {
    // Two clip distances then two cull distances: elements 2 and 3 are the cull distances.
    const ClipConfig cfg = config(2, 2);
    Vtx a = vert(0, 0, 0, {-5, -5, -1, 1}), b = vert(0, 0, 0, {-5, -5, -2, -1}), c = vert(0, 0, 0, {-5, -5, 1, -1});
    const float* tri[3] = {a.f, b.f, c.f};
    EXPECT_TRUE(cull_distance_keep(cfg, tri, 3));  // each cull distance has a vertex inside; clip distances ignored
    c.f[14] = -0.25f;                              // element 2 now out everywhere
    EXPECT_FALSE(cull_distance_keep(cfg, tri, 3));
    c.f[14] = -0.0f;  // -0 is inside
    EXPECT_TRUE(cull_distance_keep(cfg, tri, 3));
    c.f[14] = kNaN;  // NaN and infinities are out (util_is_inf_or_nan)
    EXPECT_FALSE(cull_distance_keep(cfg, tri, 3));
    c.f[14] = kInf;
    EXPECT_FALSE(cull_distance_keep(cfg, tri, 3));
    EXPECT_FALSE(cull_distance_keep(cfg, tri, 2));  // a line a-b: element 2 out at both
    const float* pt[1] = {a.f};
    EXPECT_FALSE(cull_distance_keep(cfg, pt, 1));
    EXPECT_TRUE(cull_distance_keep(config(2, 0), tri, 3));  // no cull distances: nothing culled
}

TEST(UserPlanes, PointModeCutsTheUserPlaneOnly) {
    // v0 (0, -2) is above the top plane (y + w < 0), v1 (0.5, 0.5), v2 (-0.5, 0.5); distances 0.1, -0.4, 0.6. In
    // polygonMode POINT (cut_xy off) the top plane cuts nothing, so the user plane cuts the whole triangle: A going
    // out on v0->v1 at t = 0.2 (0.1, -1.5), drawn as a point (a user plane sets the going-out flags), B coming in on
    // v1->v2 at t = 0.4 (0.1, 0.5) with v1's flag. Fan (v0, A, B), (v0, B, v2); v0 stays a corner above the viewport.
    std::vector<float> scratch(kClipScratchVertices * kFloats);
    ClippedTriangle out[kMaxClippedTriangles];
    ClipConfig cfg = config(1);
    cfg.cut_xy = false;
    Vtx v0 = vert(0, -2, 0, {0.1f}), v1 = vert(0.5f, 0.5f, 0, {-0.4f}), v2 = vert(-0.5f, 0.5f, 0, {0.6f});
    ASSERT_EQ(mask(v0, 1), kClipTop);
    ASSERT_EQ(clip_triangle(cfg, v0.f, v1.f, v2.f, mask(v0, 1), mask(v1, 1), mask(v2, 1), scratch.data(), out), 2u);
    EXPECT_EQ(out[0].v[0], v0.f);
    const float* A = out[0].v[1];
    const float* B = out[0].v[2];
    EXPECT_NEAR(A[0], 0.1f, 1e-6f);
    EXPECT_NEAR(A[1], -1.5f, 1e-6f);
    EXPECT_NEAR(B[0], 0.1f, 1e-6f);
    EXPECT_NEAR(B[1], 0.5f, 1e-6f);
    EXPECT_EQ(out[0].edges, 3u);  // v0 and A
    EXPECT_EQ(out[1].v[2], v2.f);
    EXPECT_EQ(out[1].edges, 6u);  // B and v2
}
