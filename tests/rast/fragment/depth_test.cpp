// Depth conversion, compares, stencil ops and the combined test, against independent references.
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstring>
#include <random>

#include "rast/fragment/depth_stencil.h"

using namespace tilevk::rast::fragment;

static float bits_to_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Round half to even of a double (exact rational input), computed with floor.
static double rne(double v) {
    const double f = std::floor(v);
    const double r = v - f;
    if (r > 0.5) return f + 1;
    if (r < 0.5) return f;
    return std::fmod(f, 2.0) == 0.0 ? f : f + 1;
}

TEST(FragmentDepth, D16IsRneOfScaledZ) {
    // Every 61st float in [0, 1] plus all floats near the rounding midpoints of the first codes.
    int checked = 0;
    for (uint32_t u = 0; u <= 0x3f800000u; u += 61) {
        const float z = bits_to_float(u);
        const double t = double(float(double(z) * (65535.0 / 65536.0)));  // fl(z * (1 - 2^-16)), exact product
        const uint32_t expect = uint32_t(rne(t * 65536.0));
        ASSERT_EQ(depth_to_stored(z, DepthFormat::D16), expect) << z;
        ++checked;
    }
    EXPECT_EQ(depth_to_stored(1.0f, DepthFormat::D16), 0xffffu);
    EXPECT_EQ(depth_to_stored(0.0f, DepthFormat::D16), 0u);
    EXPECT_GT(checked, 1000000);
}

TEST(FragmentDepth, D24IsRneOfZTimes2To24Minus1) {
    for (uint32_t u = 0; u <= 0x3f800000u; u += 61) {
        const float z = bits_to_float(u);
        const double p = double(float(double(z) * 16777215.0));
        ASSERT_EQ(depth_to_stored(z, DepthFormat::X8D24), uint32_t(rne(p))) << z;
    }
    EXPECT_EQ(depth_to_stored(1.0f, DepthFormat::X8D24), 0xffffffu);
}

TEST(FragmentDepth, ClampRestrictsAndClampsWithSseNanRule) {
    DepthStencilState s;
    EXPECT_EQ(clamp_depth(-0.5f, s, DepthFormat::D16), 0.0f);
    EXPECT_EQ(clamp_depth(1.5f, s, DepthFormat::D32F), 1.0f);
    EXPECT_EQ(clamp_depth(NAN, s, DepthFormat::D32F), 1.0f);  // min(NaN, 1) returns 1
    s.unrestricted_depth = true;
    EXPECT_EQ(clamp_depth(1.5f, s, DepthFormat::D32F), 1.5f);
    EXPECT_EQ(clamp_depth(1.5f, s, DepthFormat::D16), 1.0f);  // only D32F is unrestricted
    s.depth_clamp = true;
    s.min_depth = 0.25f;
    s.max_depth = 0.75f;
    EXPECT_EQ(clamp_depth(1.5f, s, DepthFormat::D32F), 0.75f);
    EXPECT_EQ(clamp_depth(0.1f, s, DepthFormat::D16), 0.25f);
    EXPECT_EQ(clamp_depth(0.5f, s, DepthFormat::D16), 0.5f);
}

TEST(FragmentDepth, CompareOpsTruthTable) {
    // expected[op][a<b, a==b, a>b]
    const bool expected[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    for (int op = 0; op < 8; ++op) {
        EXPECT_EQ(compare(CompareOp(op), 1, 2), expected[op][0]);
        EXPECT_EQ(compare(CompareOp(op), 2, 2), expected[op][1]);
        EXPECT_EQ(compare(CompareOp(op), 3, 2), expected[op][2]);
        EXPECT_EQ(compare_float(CompareOp(op), 0.1f, 0.2f), expected[op][0]);
        EXPECT_EQ(compare_float(CompareOp(op), 0.2f, 0.2f), expected[op][1]);
        EXPECT_EQ(compare_float(CompareOp(op), 0.3f, 0.2f), expected[op][2]);
    }
    // NaN: lavapipe's compares are unordered (fcmp ult/ueq/...), so everything but NEVER is true
    for (int op = 0; op < 8; ++op) {
        const bool want = CompareOp(op) != CompareOp::Never;
        EXPECT_EQ(compare_float(CompareOp(op), NAN, 0.5f), want) << op;
        EXPECT_EQ(compare_float(CompareOp(op), 0.5f, NAN), want) << op;
    }
    // DAZ: a denormal equals zero
    EXPECT_TRUE(compare_float(CompareOp::Equal, 1e-40f, 0.0f));
    EXPECT_FALSE(compare_float(CompareOp::Greater, 1e-40f, 0.0f));
}

TEST(FragmentStencil, AllOpsAllValues) {
    for (int v = 0; v < 256; ++v) {
        const uint8_t ref = 77;
        EXPECT_EQ(apply_stencil_op(StencilOp::Keep, v, ref), v);
        EXPECT_EQ(apply_stencil_op(StencilOp::Zero, v, ref), 0);
        EXPECT_EQ(apply_stencil_op(StencilOp::Replace, v, ref), ref);
        EXPECT_EQ(apply_stencil_op(StencilOp::IncrementAndClamp, v, ref), std::min(v + 1, 255));
        EXPECT_EQ(apply_stencil_op(StencilOp::DecrementAndClamp, v, ref), std::max(v - 1, 0));
        EXPECT_EQ(apply_stencil_op(StencilOp::Invert, v, ref), 255 - v);
        EXPECT_EQ(apply_stencil_op(StencilOp::IncrementAndWrap, v, ref), (v + 1) % 256);
        EXPECT_EQ(apply_stencil_op(StencilOp::DecrementAndWrap, v, ref), (v + 255) % 256);
    }
}

// Independent per-lane model of the Vulkan depth/stencil algorithm (spec order), for D32F values in [0,1].
TEST(FragmentStencil, CombinedTestMatchesSpecModel) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> b(0, 255), op8(0, 7), coin(0, 1);
    std::uniform_real_distribution<float> zd(0.0f, 1.0f);
    for (int iter = 0; iter < 20000; ++iter) {
        DepthStencilState s;
        s.depth_test = coin(rng);
        s.depth_write = coin(rng);
        s.depth_compare = CompareOp(op8(rng));
        s.stencil_test = coin(rng);
        for (StencilFace* f : {&s.front, &s.back}) {
            f->fail_op = StencilOp(op8(rng));
            f->pass_op = StencilOp(op8(rng));
            f->depth_fail_op = StencilOp(op8(rng));
            f->compare_op = CompareOp(op8(rng));
            f->compare_mask = uint8_t(b(rng));
            f->write_mask = uint8_t(b(rng));
            f->reference = uint8_t(b(rng) & 7);
        }
        const bool front = coin(rng);
        const DepthFormat fmt = coin(rng) ? DepthFormat::D32F : DepthFormat::D16;
        DepthStencilBlock zs;
        float z[16];
        for (int l = 0; l < 16; ++l) {
            z[l] = zd(rng);
            const float stored = zd(rng);
            zs.depth[l] = fmt == DepthFormat::D32F ? depth_to_stored(stored, fmt) : uint32_t(b(rng) * 257);
            zs.stencil[l] = uint8_t(b(rng) & 7);
        }
        const uint16_t mask = uint16_t(rng());
        DepthStencilBlock before = zs;
        const uint16_t pass = depth_stencil_test(s, fmt, front, z, mask, zs);
        const StencilFace& f = front ? s.front : s.back;
        for (int l = 0; l < 16; ++l) {
            const bool live = mask & (1u << l);
            uint8_t sv = before.stencil[l];
            bool sp = !s.stencil_test || compare(f.compare_op, f.reference & f.compare_mask, sv & f.compare_mask);
            const uint32_t zsrc = depth_to_stored(z[l], fmt);
            bool zp = true;
            if (s.depth_test) {
                if (fmt == DepthFormat::D32F)
                    zp = compare_float(s.depth_compare, z[l], bits_to_float(before.depth[l]));
                else
                    zp = compare(s.depth_compare, zsrc, before.depth[l]);
            }
            uint32_t want_z = before.depth[l];
            uint8_t want_s = sv;
            if (live) {
                if (s.stencil_test) {
                    StencilOp o = !sp ? f.fail_op : (!zp ? f.depth_fail_op : f.pass_op);
                    uint8_t r = apply_stencil_op(o, sv, f.reference);
                    want_s = uint8_t((sv & ~f.write_mask) | (r & f.write_mask));
                }
                if (sp && zp && s.depth_test && s.depth_write) want_z = zsrc;
            }
            ASSERT_EQ(bool(pass & (1u << l)), live && sp && zp);
            ASSERT_EQ(zs.depth[l], want_z);
            ASSERT_EQ(zs.stencil[l], want_s);
        }
    }
}

TEST(FragmentDepth, DepthModeFollowsLavapipe) {
    DepthStencilState s;
    ShaderDepthTraits t;
    EXPECT_EQ(choose_depth_mode(s, t, false), 0);
    s.depth_test = true;
    s.depth_write = true;
    EXPECT_EQ(choose_depth_mode(s, t, false), kEarlyDepthTest | kEarlyDepthWrite | kEarlyDepthTestInferred);
    t.uses_discard = true;
    EXPECT_EQ(choose_depth_mode(s, t, false), kEarlyDepthTest | kLateDepthWrite | kEarlyDepthTestInferred);
    s.stencil_test = true;  // stencil writes (write masks 0xff) force late tests with discard
    EXPECT_EQ(choose_depth_mode(s, t, false), kLateDepthTest | kLateDepthWrite);
    t.uses_discard = false;
    t.writes_depth = true;
    EXPECT_EQ(choose_depth_mode(s, t, false), kLateDepthTest | kLateDepthWrite);
    s.depth_write = false;
    s.front.write_mask = s.back.write_mask = 0;
    EXPECT_EQ(choose_depth_mode(s, t, false), kLateDepthTest);
    t = {};
    t.early_fragment_tests = true;
    EXPECT_EQ(choose_depth_mode(s, t, false), kEarlyDepthTest);
}
