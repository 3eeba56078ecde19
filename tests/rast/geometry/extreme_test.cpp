// Extreme clip-space coordinates, class by class (rast/geometry/README.md "Extreme coordinates"), with
// expectations worked out by hand: lavapipe's float environment where its result stands (DAZ on inputs), and the
// exact projection where the named difference keeps it (a flushed intersection parameter, an overflowed plane
// distance, cancellation), next to what draw's float clipper alone computes.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/fp_env.h"
#include "rast/geometry/viewport.h"

namespace tilevk::rast::geometry {
namespace {

constexpr Interp kSmooth[1] = {Interp::kPerspective};
const VertexLayout kLayout{1, kSmooth};

// Vertex records of one triangle on a 256x256 viewport, window positions from the (fused) viewport transform as the
// vertex stage computes them, and the clip masks.
struct Tri {
    std::vector<float> rec;
    uint32_t mask[3];
    Viewport vp = make_viewport(0, 0, 256, 256, 0, 1);
    const float* v(int i) const { return rec.data() + size_t(i) * vertex_floats(kLayout); }
    explicit Tri(const float (&p)[3][4]) : rec(3 * vertex_floats(kLayout), 0.0f) {
        ViewportConfig vc;
        vc.vp = vp;
        for (int i = 0; i < 3; ++i) {
            float* r = rec.data() + size_t(i) * vertex_floats(kLayout);
            for (int c = 0; c < 4; ++c) r[kClipPosOffset + c] = p[i][c];
            r[kAttribOffset] = float(i);  // an attribute that tells the vertices apart
            mask[i] = compute_clipmask({}, r + kClipPosOffset);
            viewport_transform(vc, r + kClipPosOffset, r + kWinPosOffset);
        }
    }
    uint32_t clip(bool precise, std::vector<float>* scratch, ClippedTriangle* out,
                  HiddenDepth hidden = HiddenDepth::kNone) const {
        ClipConfig cc;
        cc.layout = kLayout;
        cc.vp = vp;
        cc.precise_fallback = precise;
        cc.hidden_depth = hidden;
        scratch->assign(size_t(kClipScratchVertices) * vertex_floats(kLayout), 0.0f);
        return clip_triangle(cc, v(0), v(1), v(2), mask[0], mask[1], mask[2], scratch->data(), out);
    }
};

// Whether some output vertex lies at window (x, y) to within `tol` px.
bool has_vertex(const ClippedTriangle* out, uint32_t n, float x, float y, float tol) {
    for (uint32_t t = 0; t < n; ++t)
        for (const float* r : out[t].v)
            if (std::fabs(win_pos(r)[0] - x) <= tol && std::fabs(win_pos(r)[1] - y) <= tol) return true;
    return false;
}

uint64_t covered_pixels(const ClippedTriangle* out, uint32_t n, int samples = 1) {
    Scene scene({.width = 256, .height = 256, .samples = samples, .method = Method::kReference});
    for (uint32_t t = 0; t < n; ++t) {
        TriangleInput in;
        for (int k = 0; k < 3; ++k) in.x[k] = win_pos(out[t].v[k])[0], in.y[k] = win_pos(out[t].v[k])[1];
        in.common.clip = {0, 0, 256, 256};
        scene.add_triangle(in);
    }
    struct Count final : CoverageConsumer {
        uint64_t n = 0;
        void begin_tile(unsigned, const TileInfo&) override {}
        void end_tile(unsigned, const TileInfo&) override {}
        void primitive(unsigned, const TileInfo&, const PrimCoverage& c) override {
            for_each_block4(c,
                            [&](int32_t, int32_t, const uint16_t masks[4]) { n += std::popcount(uint32_t(masks[0])); });
            for (size_t i = 0; i < c.num_full; ++i) n += uint64_t(c.full[i].size) * c.full[i].size;
        }
    } count;
    ThreadPool pool(1);
    scene.rasterize(count, pool);
    return count.n;
}

float bits(uint32_t b) {
    return std::bit_cast<float>(b);
}

// The triangle (y = -1e10 with w = 1e-7, y = +1e10): draw's float clip cancels 1e10 - 1e10 into a vertex
// at y = 22493 px instead of 256, on the same vertical line x = 22.87 as the true corner, so the visible region
// stays right. lavapipe rasterizes it (its setup holds 22493 px: 5.76e6 fixed < 2^31, edges < 2^23) and draws
// the exact 14 080 pixel centres; tilevk keeps draw's result (the region is the same) and draws the same.
TEST(Extreme, HugeYTinyWKeepsLavapipesClipAndItsPixels) {
    const ScopedFlushDenormals ftz;
    const Tri tri({{bits(0xbeb69e15), bits(0x3f265ecf), bits(0x3b6d059e), bits(0x3f6a91ca)},
                   {bits(0xbf2f9c14), bits(0xd01502f9), bits(0x3d8c1320), bits(0x33d6bf95)},
                   {bits(0xbf046fad), bits(0x501502f9), bits(0x3ddcca1b), bits(0x3fbb898d)}});
    std::vector<float> scratch;
    ClippedTriangle out[kMaxClippedTriangles];
    const uint32_t n_float = tri.clip(false, &scratch, out);
    ASSERT_EQ(n_float, 3u);
    EXPECT_TRUE(has_vertex(out, n_float, 22.8745804f, 22493.1699f, 0.01f));  // the cancelled corner
    EXPECT_EQ(covered_pixels(out, n_float), 14080u);
    const uint32_t n = tri.clip(true, &scratch, out);
    ASSERT_EQ(n, 3u);
    EXPECT_TRUE(has_vertex(out, n, 22.8745804f, 22493.1699f, 0.01f));  // kept: same visible region
    EXPECT_EQ(covered_pixels(out, n), 14080u);
}

// x = 3e38 at w = 1 (from v0 at x = -0.6): the intersection with x = w is at t = 1.6 / (3e38 + 0.6) = 5.3e-39,
// below FLT_MIN, which FTZ flushes to 0: draw's new vertex is v0 itself and the triangle collapses to the sliver
// between v0 and v2. The exact corner is on x/w = 1 (window x 256) at y/w = -0.5 + 5.3e-39 * 0.1 = -0.5
// (window y 64); the precise fallback puts it there.
TEST(Extreme, FlushedIntersectionParameterIsRecomputed) {
    const ScopedFlushDenormals ftz;
    const Tri tri({{-0.6f, -0.5f, 0.3f, 1.0f}, {3e38f, -0.4f, 0.5f, 1.0f}, {0.1f, 0.7f, 0.6f, 1.0f}});
    EXPECT_EQ(tri.mask[1], kClipRight);
    std::vector<float> scratch;
    ClippedTriangle out[kMaxClippedTriangles];
    const uint32_t n_float = tri.clip(false, &scratch, out);
    EXPECT_FALSE(has_vertex(out, n_float, 256.0f, 64.0f, 0.01f));
    const uint32_t n = tri.clip(true, &scratch, out);
    ASSERT_GT(n, 0u);
    EXPECT_TRUE(has_vertex(out, n, 256.0f, 64.0f, 1.0f / 256));
    // The other new corner: edge v1 -> v2 meets x = w at t = (3e38 - 1) / (3e38 - 1 + 0.9) ~ 1 - 3e-39, i.e. at v2's
    // side: y/w = 0.7 - 3e-39 * 1.1 = 0.7, window (256, 217.6).
    EXPECT_TRUE(has_vertex(out, n, 256.0f, 217.6f, 1.0f / 256));
}

// w = 1e37 beside w = 0 (cts extreme.regression.w_zero_far_plane). Draw cuts the edge v2 -> v0 at x = -w first,
// t = 0.466 / 1e37 = 4.7e-38 from v2: the corner (-0.466, -0.137, 0.508, 0.466), window (0, 90.33), lies past the
// far plane (z > w). Its cut at z = w is 0.042 / 1e37 = 4.2e-39 from it, which FTZ flushes to 0, so draw keeps it.
// The exact corner lies on v2 -> v0 where z = w, i.e. at w = 0.508 to float precision (the v0 - v2 terms are 1e-38
// of it): window 128 + 128 (x, y) / z of v2 = (10.55, 93.44). What draw's polygon adds beyond the far plane has
// depth >= 1: with LESS it is never drawn and draw's polygon stands; with GREATER it is drawn and the precise one
// is taken.
TEST(Extreme, FlushedFarPlaneCutStandsWhereTheDepthTestHidesIt) {
    const ScopedFlushDenormals ftz;
    const float p[3][4] = {{bits(0xbf7769a1), bits(0x3f2860da), bits(0x3f75b2c8), bits(0x7cf0bdc2)},
                           {bits(0x3fb8ea4b), bits(0xbf65f060), bits(0x3f173249), bits(0x3f90119c)},
                           {bits(0xbeeeb050), bits(0xbe0c790f), bits(0x3f0211b2), 0.0f}};
    const Tri tri(p);
    EXPECT_EQ(tri.mask[0], 0u);
    EXPECT_EQ(tri.mask[2], kClipLeft | kClipTop | kClipFar);
    const float exact_x = float(128 + 128 * double(p[2][0]) / p[2][2]);
    const float exact_y = float(128 + 128 * double(p[2][1]) / p[2][2]);
    const float draw_y = float(128 + 128 * double(p[2][1]) / -double(p[2][0]));  // on x = -w
    EXPECT_NEAR(exact_x, 10.554f, 1e-3f);
    std::vector<float> scratch;
    ClippedTriangle out[kMaxClippedTriangles];
    uint32_t n = tri.clip(false, &scratch, out);
    EXPECT_TRUE(has_vertex(out, n, 0.0f, draw_y, 1.0f / 256));
    EXPECT_FALSE(has_vertex(out, n, exact_x, exact_y, 0.5f));
    for (const HiddenDepth visible_far : {HiddenDepth::kNone, HiddenDepth::kUpToZero}) {
        n = tri.clip(true, &scratch, out, visible_far);
        EXPECT_TRUE(has_vertex(out, n, exact_x, exact_y, 1.0f / 256));
        EXPECT_FALSE(has_vertex(out, n, 0.0f, draw_y, 0.5f));
    }
    n = tri.clip(true, &scratch, out, HiddenDepth::kFromOne);
    EXPECT_TRUE(has_vertex(out, n, 0.0f, draw_y, 1.0f / 256));
    EXPECT_FALSE(has_vertex(out, n, exact_x, exact_y, 0.5f));
}

// Pixel centres of a 256x256 viewport that a clip-space triangle covers by homogeneous edge functions in long
// double (64-bit mantissa, exponent range far past float's: no overflow, and relative error 1e-19), counting only
// centres farther than 1/64 px from every edge; those within are returned in *near. The depth range clips too:
// z/w = sum(z_i E_i) / sum(w_i E_i) must lie in [0, 1] (exact_coverage.hpp in cts_subset derives it).
uint64_t homogeneous_count(const float (&p)[3][4], uint64_t* near) {
    using L = long double;
    L c[3][3];
    for (int i = 0; i < 3; ++i) {
        const float *a = p[(i + 1) % 3], *b = p[(i + 2) % 3];
        c[i][0] = L(a[1]) * b[3] - L(a[3]) * b[1];
        c[i][1] = L(a[3]) * b[0] - L(a[0]) * b[3];
        c[i][2] = L(a[0]) * b[1] - L(a[1]) * b[0];
    }
    const L d = L(p[0][0]) * c[0][0] + L(p[0][1]) * c[0][1] + L(p[0][3]) * c[0][2];
    uint64_t n = 0;
    *near = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const L X = (x + 0.5L) / 128 - 1, Y = (y + 0.5L) / 128 - 1;
            bool inside = true, close = false;
            L num = 0, den = 0;
            for (int i = 0; i < 3; ++i) {
                const L* e = c[i];
                const L f = (e[0] * X + e[1] * Y + e[2]) * (d > 0 ? 1 : -1);
                const L dist = std::fabs(f) / std::hypot(e[0], e[1]) * 128;  // window pixels
                if (dist <= 1.0L / 64) close = true;
                inside &= f > 0;
                num += L(p[i][2]) * f;
                den += L(p[i][3]) * f;
            }
            const L depth = num / den;
            if (std::fabs(depth) < 1e-6L || std::fabs(depth - 1) < 1e-6L) close = true;
            inside &= depth >= 0 && depth <= 1;
            if (close)
                ++*near;
            else
                n += inside;
        }
    return n;
}

// (FLT_MAX, 0, 0.5, -8e37) is outside x <= w by w - x = -4.2e38 = -Inf in float: draw discards the whole triangle
// (util_is_inf_or_nan). It is a point behind the eye (|w| < 2^126, so its projection is representable); the visible
// part of the triangle is what homogeneous edge functions say. The precise fallback draws it: its pixels agree
// with them (up to 1/64 px of an edge).
TEST(Extreme, OverflowedPlaneDistanceIsRecomputed) {
    const ScopedFlushDenormals ftz;
    const float max = std::numeric_limits<float>::max();
    const float p[3][4] = {{-0.6f, -0.5f, 0.3f, 1.0f}, {max, 0.0f, 0.5f, -8e37f}, {0.1f, 0.7f, 0.6f, 1.0f}};
    const Tri tri(p);
    EXPECT_NE(tri.mask[1] & kClipRight, 0u);
    std::vector<float> scratch;
    ClippedTriangle out[kMaxClippedTriangles];
    EXPECT_EQ(tri.clip(false, &scratch, out), 0u);
    const uint32_t n = tri.clip(true, &scratch, out);
    ASSERT_GT(n, 0u);
    uint64_t near = 0;
    const uint64_t expect = homogeneous_count(p, &near);
    const uint64_t got = covered_pixels(out, n);
    EXPECT_GT(expect, 1000u);
    EXPECT_LE(got, expect + near);
    EXPECT_GE(got, expect);
}

// A vertex at w = FLT_MAX with x, y, z near 1 (at most 2^-64 w) projects to the viewport's centre exactly as FTZ
// puts it, so the triangle has an exact answer. The edge from the w = 1e-20 vertex (past the right, bottom and far
// planes) back to it is cut at t = 0.986 / FLT_MAX, which FTZ flushes to 0: draw keeps the w = 1e-20 vertex, 4e21 px
// away, past llvmpipe's snap range (cts extreme.regression.w_flt_max_flushed_t, seed 6638). The precise fallback
// draws what homogeneous edge functions say.
TEST(Extreme, FlushedCutToAFltMaxWVertexIsRecomputed) {
    const ScopedFlushDenormals ftz;
    const float max = std::numeric_limits<float>::max();
    const float p[3][4] = {{2.70247436f, 1.28784764f, 0.352528572f, max},
                           {-0.251885474f, 1.88253736f, 0.797676623f, 1.30979061f},
                           {0.985703468f, 1.13436317f, 0.278056145f, 1e-20f}};
    const Tri tri(p);
    std::vector<float> scratch;
    ClippedTriangle out[kMaxClippedTriangles];
    const uint32_t n_float = tri.clip(false, &scratch, out);
    bool far_vertex = false;  // draw's polygon keeps a vertex lavapipe's setup snaps to INT_MIN
    for (uint32_t t = 0; t < n_float; ++t)
        for (const float* r : out[t].v) far_vertex |= std::fabs(win_pos(r)[0]) > 1e20f;
    EXPECT_TRUE(far_vertex);
    const uint32_t n = tri.clip(true, &scratch, out);
    ASSERT_GT(n, 0u);
    uint64_t near = 0;
    const uint64_t expect = homogeneous_count(p, &near);
    const uint64_t got = covered_pixels(out, n);
    EXPECT_GT(expect, 1000u);
    EXPECT_LE(got, expect + near);
    EXPECT_GE(got, expect);
}

// |w| >= 2^126: 1/w is subnormal and lavapipe's FTZ flushes it to 0, so the viewport transform puts the vertex on
// the viewport's centre with depth = translate, whatever its x/w, y/w, z/w: tilevk follows that float environment
// ((5e37, -2.5e37, 5e37, 1e38) is NDC (0.5, -0.25, 0.5) but lands on (128, 128, 0) on 256x256).
TEST(Extreme, SubnormalOneOverWFollowsLavapipe) {
    ViewportConfig vc;
    vc.vp = make_viewport(0, 0, 256, 256, 0, 1);
    const float clip[4] = {5e37f, -2.5e37f, 5e37f, 1e38f};
    float win[4];
    {
        const ScopedFlushDenormals ftz;
        viewport_transform(vc, clip, win);
    }
    EXPECT_EQ(win[0], 128.0f);
    EXPECT_EQ(win[1], 128.0f);
    EXPECT_EQ(win[2], 0.0f);
    EXPECT_EQ(win[3], 0.0f);
    viewport_transform(vc, clip, win);  // without FTZ: the exact projection (what lavapipe does not compute)
    EXPECT_NEAR(win[0], 192.0f, 1e-3f);
    EXPECT_NEAR(win[1], 96.0f, 1e-3f);
}

// Subnormal inputs follow lavapipe's DAZ: z = -1e-40 reads as -0, inside the near plane z >= 0 (lavapipe draws the
// triangle; without DAZ it would be clipped). z = +1e-40 likewise.
TEST(Extreme, SubnormalZReadsAsZero) {
    const float p[4] = {0.5f, -0.4f, -1e-40f, 1.0f};
    EXPECT_EQ(compute_clipmask({}, p), kClipNear);  // the default environment: outside
    const ScopedFlushDenormals ftz;
    EXPECT_EQ(compute_clipmask({}, p), 0u);
}

// Non-finite inputs have no exact answer: lavapipe's result stands (NaN plane distances discard the triangle, also
// with the precise fallback on).
TEST(Extreme, NonFiniteInputsKeepDrawsResult) {
    const ScopedFlushDenormals ftz;
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const float bad : {nan, inf, -inf}) {
        const Tri tri({{-0.6f, -0.5f, 0.3f, 1.0f}, {bad, -0.4f, 0.5f, 1.0f}, {0.1f, 0.7f, 0.6f, 1.0f}});
        std::vector<float> scratch;
        ClippedTriangle out[kMaxClippedTriangles];
        const uint32_t n_float = tri.clip(false, &scratch, out);
        std::vector<float> keep(scratch);
        EXPECT_EQ(tri.clip(true, &scratch, out), n_float) << bad;
    }
}

}  // namespace
}  // namespace tilevk::rast::geometry
