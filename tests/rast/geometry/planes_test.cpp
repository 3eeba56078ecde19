// Attribute plane setup and depth bias, against hand-derived exact cases and a double-precision plane fit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rast/geometry/planes.h"

using namespace tilevk::rast::geometry;

namespace {

struct V {
    float f[8 + 4 * 3];
};

const Interp kModes[3] = {Interp::kPerspective, Interp::kNoPerspective, Interp::kFlat};

V make(float x, float y, float z, float oow, float a) {
    V v{};
    v.f[4] = x, v.f[5] = y, v.f[6] = z, v.f[7] = oow;
    for (int i = 0; i < 12; ++i) v.f[8 + i] = a * static_cast<float>(i + 1);
    return v;
}

PlaneSetupConfig cfg(bool msaa = false) {
    PlaneSetupConfig c;
    c.layout = {3, kModes};
    c.multisample = msaa;
    return c;
}

}  // namespace

TEST(Planes, ExactLinearAttributeAtPixelCentreOrigin) {
    // a(x, y) = 2x + 3y + 1 sampled at v0 (8.5, 8.5), v1 (24.5, 8.5), v2 (8.5, 24.5): area terms
    // dx01 = -16, dy20 = 16, dy01 = dx20 = 0 -> ooa = -1/256, every step exact.
    auto a = [](float x, float y) { return 2 * x + 3 * y + 1; };
    V v0 = make(8.5f, 8.5f, 0.25f, 1, 0), v1 = make(24.5f, 8.5f, 0.5f, 1, 0), v2 = make(8.5f, 24.5f, 0.75f, 1, 0);
    v0.f[12] = a(8.5f, 8.5f), v1.f[12] = a(24.5f, 8.5f), v2.f[12] = a(8.5f, 24.5f);  // noperspective attrib 1.x
    TrianglePlanes t;
    AttribPlane p[3];
    setup_triangle_planes(cfg(), v0.f, v1.f, v2.f, &t, p);
    EXPECT_EQ(t.one_over_area, -1.0f / 256.0f);
    EXPECT_EQ(p[1].dadx[0], 2.0f);
    EXPECT_EQ(p[1].dady[0], 3.0f);
    // origin = pixel (0,0)'s centre (0.5, 0.5): 2*0.5 + 3*0.5 + 1
    EXPECT_EQ(p[1].a0[0], 3.5f);
    // z plane: z = 0.25 + (x-8.5)/64 + (y-8.5)/32 -> dzdx = 1/64, dzdy = 1/32, z at (0.5,0.5) = 0.25 - 8/64 - 8/32
    EXPECT_EQ(t.pos.dadx[2], 1.0f / 64);
    EXPECT_EQ(t.pos.dady[2], 1.0f / 32);
    EXPECT_EQ(t.pos.a0[2], 0.25f - 0.125f - 0.25f);
    EXPECT_EQ(t.pos.a0[0], 0.0f);  // depth offset slot, no bias
    // 1/w plane constant 1
    EXPECT_EQ(t.pos.a0[3], 1.0f);
    EXPECT_EQ(t.pos.dadx[3], 0.0f);
    // MSAA: origin is the framebuffer corner
    setup_triangle_planes(cfg(true), v0.f, v1.f, v2.f, &t, p);
    EXPECT_EQ(p[1].a0[0], 1.0f);
}

TEST(Planes, PerspectivePremultipliesAndFlatTakesProvoking) {
    V v0 = make(8.5f, 8.5f, 0, 0.5f, 4), v1 = make(24.5f, 8.5f, 0, 0.25f, 8), v2 = make(8.5f, 24.5f, 0, 1, 16);
    TrianglePlanes t;
    AttribPlane p[3];
    setup_triangle_planes(cfg(), v0.f, v1.f, v2.f, &t, p);
    // attrib 0 component 0 premultiplied: 4*0.5 = 2, 8*0.25 = 2, 16*1 = 16 -> dadx = 0, dady = 14/16
    EXPECT_EQ(p[0].dadx[0], 0.0f);
    EXPECT_EQ(p[0].dady[0], 14.0f / 16.0f);
    EXPECT_EQ(p[0].a0[0], 2.0f - 14.0f / 16.0f * 8.0f);
    // flat attrib 2 from v0 (flatshade_first) or v2
    EXPECT_EQ(p[2].a0[0], 4.0f * 9);
    EXPECT_EQ(p[2].dadx[0], 0.0f);
    PlaneSetupConfig last = cfg();
    last.flatshade_first = false;
    setup_triangle_planes(last, v0.f, v1.f, v2.f, &t, p);
    EXPECT_EQ(p[2].a0[3], 16.0f * 12);
}

TEST(Planes, MatchDoublePlaneFitOnRandomTriangles) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> c(0.0f, 200.0f), av(-1.0f, 1.0f);
    for (int iter = 0; iter < 1000; ++iter) {
        V v[3];
        for (auto& x : v) x = make(c(rng), c(rng), av(rng) * 0.5f + 0.5f, 1.0f, av(rng));
        TrianglePlanes t;
        AttribPlane p[3];
        setup_triangle_planes(cfg(), v[0].f, v[1].f, v[2].f, &t, p);
        const double area = (double(v[0].f[4]) - v[1].f[4]) * (double(v[2].f[5]) - v[0].f[5]) -
                            (double(v[0].f[5]) - v[1].f[5]) * (double(v[2].f[4]) - v[0].f[4]);
        if (std::fabs(area) < 100) continue;  // slivers amplify float rounding; the exact tests cover the order
        // the plane reproduces the vertex values of noperspective attrib 1.x within float rounding of the fit
        for (int k = 0; k < 3; ++k) {
            const double px = double(v[k].f[4]) - 0.5, py = double(v[k].f[5]) - 0.5;
            const double val = p[1].a0[0] + p[1].dadx[0] * px + p[1].dady[0] * py;
            EXPECT_NEAR(val, v[k].f[12], 1e-3) << iter;
        }
    }
}

TEST(DepthBias, UnormUnitsHaveTheFactorTwo) {
    DepthBias b;
    b.constant_factor = 1.0f;
    b.unorm_bits = 24;
    EXPECT_EQ(depth_bias_units(b), static_cast<float>(2.0 / 16777215.0));
    b.unorm_bits = 16;
    EXPECT_EQ(depth_bias_units(b), static_cast<float>(2.0 / 65535.0));
    b.float_depth = true;
    EXPECT_EQ(depth_bias_units(b), 1.0f);
}

TEST(DepthBias, SlopeConstantFloatExponentAndClamp) {
    // z = 0.25 + (x-8.5)/64 + (y-8.5)/32 (as above): dzdx = 1/64, dzdy = 1/32 -> max = 1/32
    const float w0[3] = {8.5f, 8.5f, 0.25f}, w1[3] = {24.5f, 8.5f, 0.5f}, w2[3] = {8.5f, 24.5f, 0.75f};
    const float ooa = -1.0f / 256;
    DepthBias b;
    b.slope_factor = 2.0f;
    b.constant_factor = 3.0f;
    b.unorm_bits = 16;
    EXPECT_EQ(triangle_depth_offset(b, w0, w1, w2, ooa), static_cast<float>(6.0 / 65535.0) + 1.0f / 16);
    // float depth: max |z| = 0.75 has exponent -1 -> 2^(-1-23) * 3
    b.float_depth = true;
    EXPECT_EQ(triangle_depth_offset(b, w0, w1, w2, ooa), std::ldexp(3.0f, -24) + 1.0f / 16);
    // tiny z: exponent field <= 23 gives a 0 scale
    const float t0[3] = {8.5f, 8.5f, 1e-37f}, t1[3] = {24.5f, 8.5f, 1e-37f}, t2[3] = {8.5f, 24.5f, 1e-37f};
    EXPECT_EQ(triangle_depth_offset(b, t0, t1, t2, ooa), 0.0f);
    // clamp > 0 limits from above, < 0 from below
    b.clamp = 0.01f;
    EXPECT_EQ(triangle_depth_offset(b, w0, w1, w2, ooa), 0.01f);
    b.clamp = -0.5f;
    b.slope_factor = -100.0f;
    b.constant_factor = 0;
    EXPECT_EQ(triangle_depth_offset(b, w0, w1, w2, ooa), -0.5f);
    // disabled bias: exactly 0 even for huge slopes
    DepthBias none;
    EXPECT_EQ(triangle_depth_offset(none, w0, w1, w2, 1e30f), 0.0f);
}
