// draw's batch segmentation (draw_batches.h), the clipper's edge flags (clip.h) and the unfilled-polygon stages
// (unfilled.h). Expectations are worked out by hand from the Mesa rules quoted in the comments, independently
// of the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

#include "rast/geometry/clip.h"
#include "rast/geometry/draw_batches.h"
#include "rast/geometry/unfilled.h"
#include "rast/geometry/viewport.h"

using namespace tilevk::rast::geometry;

namespace {

std::vector<uint32_t> batches(Topology t, bool indexed, uint32_t count) {
    std::vector<uint32_t> out;
    append_run_batches(t, indexed, count, &out);
    return out;
}

TEST(DrawBatches, SmallDrawsAreOneBatch) {
    EXPECT_EQ(batches(Topology::kTriangleList, false, 9), (std::vector<uint32_t>{3}));
    EXPECT_EQ(batches(Topology::kTriangleList, false, 11), (std::vector<uint32_t>{3}));  // trimmed to 9
    EXPECT_EQ(batches(Topology::kTriangleList, false, 2), (std::vector<uint32_t>{}));
    // 4096 vertices: still "no splitting required", fans included
    EXPECT_EQ(batches(Topology::kTriangleFan, false, 4096), (std::vector<uint32_t>{4094}));
    EXPECT_EQ(batches(Topology::kTriangleStrip, false, 4096), (std::vector<uint32_t>{4094}));
    EXPECT_EQ(batches(Topology::kPointList, false, 4096), (std::vector<uint32_t>{4096}));
}

TEST(DrawBatches, NonIndexedListsSplitAt4095Vertices) {
    // seg_max = trim(4096, 3, 3) = 4095 vertices = 1365 triangles; 4104 vertices -> 1365 + 3
    EXPECT_EQ(batches(Topology::kTriangleList, false, 4104), (std::vector<uint32_t>{1365, 3}));
    // lines: trim(4096, 2, 2) = 4096 -> 2048 lines; 5000 vertices = 2500 lines -> 2048 + 452
    EXPECT_EQ(batches(Topology::kLineList, false, 5000), (std::vector<uint32_t>{2048, 452}));
}

TEST(DrawBatches, StripsKeepAnEvenTriangleCountAndOverlapTwoVertices) {
    // seg_max 4096 -> (4096-3) odd, kept: 4094 triangles; next segment starts at vertex 4094: 5000-4094 = 906
    // vertices = 904 triangles
    EXPECT_EQ(batches(Topology::kTriangleStrip, false, 5000), (std::vector<uint32_t>{4094, 904}));
    // indexed: segment 1024 -> 1022 triangles, step 1022
    EXPECT_EQ(batches(Topology::kTriangleStrip, true, 2048), (std::vector<uint32_t>{1022, 1022, 2}));
    // line strip: rollback 1, 4095 lines per 4096-vertex segment
    EXPECT_EQ(batches(Topology::kLineStrip, false, 4100), (std::vector<uint32_t>{4095, 4}));
}

TEST(DrawBatches, LongFansSplitAt1024) {
    // 5000 > 4096: fan segments of 1024 vertices (1022 triangles), 4 of them, then 5000-4088 = 912 -> 910
    EXPECT_EQ(batches(Topology::kTriangleFan, false, 5000), (std::vector<uint32_t>{1022, 1022, 1022, 1022, 910}));
}

TEST(DrawBatches, IndexedListsSplitAt1023Indices) {
    EXPECT_EQ(batches(Topology::kTriangleList, true, 2000), (std::vector<uint32_t>{341, 325}));
    EXPECT_EQ(batches(Topology::kPointList, true, 2049), (std::vector<uint32_t>{1024, 1024, 1}));
}

TEST(DrawBatches, EveryPrimitiveInExactlyOneBatch) {
    for (Topology t : {Topology::kPointList, Topology::kLineList, Topology::kLineStrip, Topology::kTriangleList,
                       Topology::kTriangleStrip, Topology::kTriangleFan})
        for (bool indexed : {false, true})
            for (uint32_t count : {0u, 1u, 3u, 1023u, 1024u, 1025u, 4095u, 4096u, 4097u, 9000u, 20001u}) {
                const auto b = batches(t, indexed, count);
                uint32_t first, incr;
                split_prim(t, &first, &incr);
                const uint32_t prims = count < first ? 0 : (count - first) / incr + 1;
                EXPECT_EQ(std::accumulate(b.begin(), b.end(), 0u), prims)
                    << "topology " << int(t) << " indexed " << indexed << " count " << count;
            }
}

TEST(DrawBatches, RestartRunsAreSeparateDraws) {
    const uint16_t idx[] = {0, 1, 2, 3, 0xFFFF, 4, 5, 6, 0xFFFF, 7, 8};
    IndexSource src;
    src.indices = reinterpret_cast<const uint8_t*>(idx);
    src.index_size = 2;
    src.index_count_total = 11;
    src.count = 11;
    src.primitive_restart = true;
    std::vector<uint32_t> b;
    draw_batches(src, Topology::kTriangleStrip, &b);
    EXPECT_EQ(b, (std::vector<uint32_t>{2, 1}));  // runs of 4, 3, 2 vertices
}

// --- clipper edge flags ---

const Interp kInterp[1] = {Interp::kPerspective};

struct Rec {
    float f[12];
};

Rec rec(float x, float y, float z, float w) {
    Rec r{};
    r.f[0] = x, r.f[1] = y, r.f[2] = z, r.f[3] = w;
    return r;
}

ClipConfig config() {
    ClipConfig c;
    c.layout = {1, kInterp};
    c.vp = make_viewport(0, 0, 64, 64, 0, 1);
    return c;
}

TEST(ClipEdgeFlags, UnclippedTriangleDrawsEverything) {
    Rec a = rec(0, 0, 0.5f, 1), b = rec(0.5f, 0, 0.5f, 1), c = rec(0, 0.5f, 0.5f, 1);
    std::vector<float> scratch(12 * kClipScratchVertices);
    ClippedTriangle out[kMaxClippedTriangles];
    ASSERT_EQ(clip_triangle(config(), a.f, b.f, c.f, 0, 0, 0, scratch.data(), out), 1u);
    EXPECT_EQ(out[0].edges, 7);
}

TEST(ClipEdgeFlags, RightPlaneCut) {
    // v0 inside, v1 right of x = w, v2 inside. Plane 0 turns (v0, v1, v2) into (v0, A, B, v2): A leaves the
    // plane (vertex flag 0), B comes back in (flag of v1 = 1). Fan: (v0, A, B) flags first|middle, then
    // (v0, B, v2) flags middle|last.
    //   tri 0 edges: v0->A yes, A->B no (A's flag), B->v0 is inner (no flag)        -> 0b001
    //   tri 1 edges: v0->B inner, B->v2 yes, v2->v0 yes                             -> 0b110
    // polygonMode LINE; POINT makes no x/y cut (PointModeCutsNoXyPlane).
    Rec v0 = rec(-0.5f, 0, 0.5f, 1), v1 = rec(2, 0.2f, 0.5f, 1), v2 = rec(0, 0.8f, 0.5f, 1);
    std::vector<float> scratch(12 * kClipScratchVertices);
    ClippedTriangle out[kMaxClippedTriangles];
    ASSERT_EQ(clip_triangle(config(), v0.f, v1.f, v2.f, 0, 1, 0, scratch.data(), out), 2u);
    EXPECT_EQ(out[0].v[0], v0.f);
    EXPECT_EQ(out[1].v[2], v2.f);
    EXPECT_EQ(out[0].edges, 0b001);
    EXPECT_EQ(out[1].edges, 0b110);
}

// polygonMode POINT (ClipConfig::cut_xy off): the same triangle is not cut at x = w. It still goes through draw's
// clipper, which re-emits it as a one-triangle fan with every flag, so v1, outside the viewport, stays a corner
// (lavapipe draws the part of its point inside the viewport: cts quirks.unfilled.point_outside_vertex_*). Three
// vertices outside one x/y plane still reject the triangle.
TEST(ClipEdgeFlags, PointModeCutsNoXyPlane) {
    Rec v0 = rec(-0.5f, 0, 0.5f, 1), v1 = rec(2, 0.2f, 0.5f, 1), v2 = rec(0, 0.8f, 0.5f, 1);
    std::vector<float> scratch(12 * kClipScratchVertices);
    ClippedTriangle out[kMaxClippedTriangles];
    ClipConfig c = config();
    c.cut_xy = false;
    ASSERT_EQ(clip_triangle(c, v0.f, v1.f, v2.f, 0, 1, 0, scratch.data(), out), 1u);
    EXPECT_EQ(out[0].v[0], v0.f);
    EXPECT_EQ(out[0].v[1], v1.f);
    EXPECT_EQ(out[0].v[2], v2.f);
    EXPECT_EQ(out[0].edges, 7);
    EXPECT_EQ(clip_triangle(c, v0.f, v1.f, v2.f, 1, 1, 1, scratch.data(), out), 0u);
    // Outside the right and the near plane: only the near plane cuts. The vertex coming back in on v1->v2 lies at
    // z = 0 and x = 1 (window 64: where the x cut would have put a corner too) and is a corner (v1's flag).
    Rec n1 = rec(2, 0.2f, -0.5f, 1);
    ASSERT_EQ(clip_triangle(c, v0.f, n1.f, v2.f, 0, 1 | 16, 0, scratch.data(), out), 2u);
    EXPECT_EQ(out[1].v[0], v0.f);
    EXPECT_EQ(out[1].edges & 0b010, 0b010);
    EXPECT_FLOAT_EQ(out[1].v[1][0], 1.0f);
    EXPECT_FLOAT_EQ(out[1].v[1][2], 0.0f);
}

TEST(ClipEdgeFlags, NearPlaneComingInVertexIsAPoint) {
    // v0 behind z = 0: (v0, v1, v2) -> (B, v1, v2, C), B coming in on the v0->v1 edge (flag of v0 = 1), C going
    // out on v2->v0 (flag 0). Fan around B: (B, v1, v2): first|middle -> B->v1 yes, v1->v2 yes -> 0b011;
    // (B, v2, C): middle|last -> v2->C yes, C->B hidden by C's flag -> 0b010. Corners: the same bits.
    Rec v0 = rec(-0.8f, -0.8f, -0.5f, 1), v1 = rec(0.8f, -0.6f, 0.5f, 1), v2 = rec(0.1f, 0.9f, 0.9f, 1);
    std::vector<float> scratch(12 * kClipScratchVertices);
    ClippedTriangle out[kMaxClippedTriangles];
    ASSERT_EQ(clip_triangle(config(), v0.f, v1.f, v2.f, 16, 0, 0, scratch.data(), out), 2u);
    EXPECT_EQ(out[0].v[1], v1.f);
    EXPECT_EQ(out[0].edges, 0b011);
    EXPECT_EQ(out[1].edges, 0b010);
}

// --- unfilled stages ---

TEST(Unfilled, LinesInDrawOrder) {
    uint8_t l[3][2];
    ASSERT_EQ(unfilled_lines(7, l), 3u);
    EXPECT_EQ(l[0][0], 2);
    EXPECT_EQ(l[0][1], 0);
    EXPECT_EQ(l[1][0], 0);
    EXPECT_EQ(l[1][1], 1);
    EXPECT_EQ(l[2][0], 1);
    EXPECT_EQ(l[2][1], 2);
    ASSERT_EQ(unfilled_lines(0b010, l), 1u);
    EXPECT_EQ(l[0][0], 1);
    EXPECT_EQ(l[0][1], 2);
    EXPECT_EQ(unfilled_lines(0, l), 0u);
}

TEST(Unfilled, DepthOffsetUnorm) {
    // Window triangle (0,0,0.25) (8,0,0.75) (0,4,0.5): e = v0-v2 = (0,-4,-0.25), f = v1-v2 = (8,-4,0.25).
    // det = 0*-4 - (-4*8) = 32; a = ey*fz - ez*fy = -1 - 1 = -2; b = ez*fx - ex*fz = -2 - 0 = -2
    // dzdx = dzdy = 2/32 = 0.0625; slope 2 -> mult 0.125; D16 units: (float)(10 * 2/65535) ; clamp 0.
    const float w0[3] = {0, 0, 0.25f}, w1[3] = {8, 0, 0.75f}, w2[3] = {0, 4, 0.5f};
    DepthBias b;
    b.constant_factor = 10, b.slope_factor = 2, b.unorm_bits = 16;
    const float units = static_cast<float>(10.0 * (1.0 / 65535.0) * 2.0);
    EXPECT_EQ(unfilled_depth_offset(b, w0, w1, w2), units + 0.125f);
    b.clamp = 0.1f;  // positive clamp: MIN2
    EXPECT_EQ(unfilled_depth_offset(b, w0, w1, w2), 0.1f);
    b.clamp = -0.1f;  // negative clamp: MAX2 with a positive offset keeps the offset
    EXPECT_EQ(unfilled_depth_offset(b, w0, w1, w2), units + 0.125f);
}

TEST(Unfilled, DepthOffsetFloatUsesTheLargestExponent) {
    // max |z| = 0.75 (exponent -1): 2^(-1-23) = 2^-24; units 4 -> 2^-22; zero slope.
    const float w0[3] = {0, 0, 0.25f}, w1[3] = {8, 0, 0.75f}, w2[3] = {0, 4, 0.5f};
    DepthBias b;
    b.constant_factor = 4, b.float_depth = true;
    EXPECT_EQ(unfilled_depth_offset(b, w0, w1, w2), std::ldexp(1.0f, -22));
}

TEST(Unfilled, PrepareAppliesOffsetSaturatesAndCopiesFlat) {
    const Interp interp[2] = {Interp::kFlat, Interp::kPerspective};
    auto make = [](float x, float y, float z, float a) {
        std::vector<float> r(16, 0.0f);
        r[4] = x, r[5] = y, r[6] = z, r[7] = 1;
        for (int c = 0; c < 4; ++c) r[8 + c] = a, r[12 + c] = a + 10;
        return r;
    };
    auto v0 = make(0, 0, 0.25f, 1), v1 = make(8, 0, 0.75f, 2), v2 = make(0, 4, 0.99f, 3);
    UnfilledConfig cfg;
    cfg.layout = {2, interp};
    cfg.bias_enable = true;
    cfg.bias.constant_factor = 0.02f;  // float depth: 0.02 * 2^-24 is tiny; use unorm 24 to see it
    cfg.bias.slope_factor = 0.0f;
    cfg.bias.unorm_bits = 24;
    std::vector<float> scratch(3 * 16);
    const float* in[3] = {v0.data(), v1.data(), v2.data()};
    const float* out[3];
    prepare_unfilled_triangle(cfg, in, scratch.data(), out);
    // inv_det finite (area 32), slope 0 -> mult 0; offset = units
    const float units = static_cast<float>(0.02f * (1.0 / 16777215.0) * 2.0);
    EXPECT_EQ(out[0][6], 0.25f + units);
    EXPECT_EQ(out[2][6], std::min(1.0f, 0.99f + units));
    EXPECT_EQ(out[1][8], 1.0f);  // flat attribute from v0
    EXPECT_EQ(out[2][8], 1.0f);
    EXPECT_EQ(out[1][12], 12.0f);  // perspective attribute untouched
    EXPECT_EQ(v1[8], 2.0f);        // inputs untouched
    // nothing to apply: the inputs are passed through
    cfg.bias_enable = false;
    const Interp smooth[1] = {Interp::kPerspective};
    cfg.layout = {1, smooth};
    prepare_unfilled_triangle(cfg, in, scratch.data(), out);
    EXPECT_EQ(out[1], v1.data());
}

TEST(Unfilled, SaturateClampsToOne) {
    const Interp smooth[1] = {Interp::kPerspective};
    std::vector<float> a(12, 0.0f), b(12, 0.0f), c(12, 0.0f);
    a[4] = 0, a[5] = 0, a[6] = 0.9f;
    b[4] = 8, b[5] = 0, b[6] = 0.9f;
    c[4] = 0, c[5] = 4, c[6] = 0.9f;
    UnfilledConfig cfg;
    cfg.layout = {1, smooth};
    cfg.bias_enable = true;
    cfg.bias.constant_factor = 1e7f;  // units = 1e7 * 2 / (2^24 - 1) > 1
    std::vector<float> scratch(36);
    const float* in[3] = {a.data(), b.data(), c.data()};
    const float* out[3];
    prepare_unfilled_triangle(cfg, in, scratch.data(), out);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out[k][6], 1.0f);
}

}  // namespace

namespace {

TEST(Unfilled, FrontFacingFromTheCullDeterminant) {
    // y down: (0,0) (8,0) (0,4) turns clockwise on screen; det = ex*fy - ey*fx with e = v0-v2 = (0,-4),
    // f = v1-v2 = (8,-4): 0*-4 - (-4*8) = 32 > 0, i.e. "cw" for draw: front only with a clockwise front face.
    const float a[2] = {0, 0}, b[2] = {8, 0}, c[2] = {0, 4};
    EXPECT_FALSE(unfilled_front_facing(true, a, b, c));
    EXPECT_TRUE(unfilled_front_facing(false, a, b, c));
    EXPECT_TRUE(unfilled_front_facing(true, a, c, b));
    // zero area: back for both front-face conventions
    const float d[2] = {16, 0};
    EXPECT_FALSE(unfilled_front_facing(true, a, b, d));
    EXPECT_FALSE(unfilled_front_facing(false, a, b, d));
}

}  // namespace
