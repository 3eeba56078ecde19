// llvmpipe's linear shading of a region (rast/fragment/linear.h); expectations derived by hand in the comments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rast/fragment/linear.h"

using namespace tilevk::rast::fragment;

namespace {

struct Target {
    std::vector<uint8_t> px = std::vector<uint8_t>(64 * 64 * 4, 0xEE);
    uint8_t* at(int x, int y) { return px.data() + (size_t(y) * 64 + size_t(x)) * 4; }
};

// pos plane with constant 1/w = `oow_plane`, attribute plane a0/dadx/dady the same for all four components
void planes(float pos[12], float in[12], float oow_plane, float a0, float dadx, float dady) {
    for (int c = 0; c < 4; ++c) {
        pos[c] = c == 3 ? oow_plane : 0.0f;
        pos[4 + c] = 0.0f;
        pos[8 + c] = 0.0f;
        in[c] = a0;
        in[4 + c] = dadx;
        in[8 + c] = dady;
    }
}

}  // namespace

TEST(LinearShade, ConstantHalfIs127) {
    // 0.5 * 32767 = 16383.5 -> (unsigned) 16383 -> >> 7 = 127 (the general path gives rne(127.5) = 128)
    float pos[12], in[12];
    planes(pos, in, 1.0f, 0.5f, 0.0f, 0.0f);
    Target t;
    ASSERT_TRUE(linear_shade_copy({3, 5, 7, 2}, pos, in, true, t.px.data(), 64 * 4));
    for (int y = 5; y < 7; ++y)
        for (int x = 3; x < 10; ++x)
            for (int c = 0; c < 4; ++c) EXPECT_EQ(t.at(x, y)[c], 127);
    EXPECT_EQ(t.at(2, 5)[0], 0xEE);  // outside the region: untouched
    EXPECT_EQ(t.at(10, 5)[0], 0xEE);
    EXPECT_EQ(t.at(3, 7)[0], 0xEE);
}

TEST(LinearShade, FixedPointStepsFromTheRegionOrigin) {
    // a0 = 0.25 at pixel (0,0), dadx = 1/64: at region origin x = 8: s0 = 0.25 + 8/64 = 0.375
    // start = (unsigned)(0.375*32767 = 12287.625) = 12287; step = (int)(32767/64 = 511.98) = 511
    // pixel i: (12287 + 511 i) >> 7: i = 0 -> 95, i = 1 -> 12798 >> 7 = 99, i = 5 -> 14842 >> 7 = 115
    float pos[12], in[12];
    planes(pos, in, 1.0f, 0.25f, 1.0f / 64, 0.0f);
    Target t;
    ASSERT_TRUE(linear_shade_copy({8, 0, 6, 1}, pos, in, true, t.px.data(), 64 * 4));
    EXPECT_EQ(t.at(8, 0)[0], 95);
    EXPECT_EQ(t.at(9, 0)[0], 99);
    EXPECT_EQ(t.at(13, 0)[0], 115);
    // BGRA: channel 0 (red) is byte 2; all four components carry the same plane here
    EXPECT_EQ(t.at(9, 0)[2], 99);
}

TEST(LinearShade, PerspectiveScalesByW) {
    // 1/w plane 0.5 -> oow = 2: perspective planes are a*(1/w): a0 0.2 -> 0.4; noperspective ones are not scaled
    float pos[12], in[12];
    planes(pos, in, 0.5f, 0.2f, 0.0f, 0.0f);
    Target t;
    ASSERT_TRUE(linear_shade_copy({0, 0, 1, 1}, pos, in, true, t.px.data(), 64 * 4));
    // fl(0.2f*2) = 0.4f; 0.4f*32767 = 13106.8 -> 13106 >> 7 = 102
    EXPECT_EQ(t.at(0, 0)[0], 102);
    ASSERT_TRUE(linear_shade_copy({0, 0, 1, 1}, pos, in, false, t.px.data(), 64 * 4));
    // 0.2f*32767 = 6553.4 -> 6553 >> 7 = 51
    EXPECT_EQ(t.at(0, 0)[0], 51);
}

TEST(LinearShade, DeclinesVaryingWAndOutOfRangeCorners) {
    float pos[12], in[12];
    Target t;
    planes(pos, in, 1.0f, 0.5f, 0.0f, 0.0f);
    pos[4 + 3] = 1e-6f;  // 1/w varies in x
    EXPECT_FALSE(linear_shade_copy({0, 0, 4, 4}, pos, in, true, t.px.data(), 64 * 4));
    EXPECT_EQ(t.at(0, 0)[0], 0xEE);
    // a0 = 0.9, dadx = 0.05: the right corner of an 8-wide region is 0.9 + 7*0.05 = 1.25 > 1 -> declined;
    // a 3-wide region ends at 1.0 (fl(0.9 + fl(2*0.05)) = 1.0) -> accepted
    planes(pos, in, 1.0f, 0.9f, 0.05f, 0.0f);
    EXPECT_FALSE(linear_shade_copy({0, 0, 8, 1}, pos, in, true, t.px.data(), 64 * 4));
    EXPECT_TRUE(linear_shade_copy({0, 0, 3, 1}, pos, in, true, t.px.data(), 64 * 4));
    planes(pos, in, 1.0f, -0.01f, 0.0f, 0.0f);
    EXPECT_FALSE(linear_shade_copy({0, 0, 1, 1}, pos, in, true, t.px.data(), 64 * 4));
}

TEST(LinearShade, RowsStepByDady) {
    // dady = -1/32 from a0 = 1 at y = 0: start 32767, stepy = (int)(-1023.97) = -1023
    // row 3: 32767 - 3069 = 29698 >> 7 = 232
    float pos[12], in[12];
    planes(pos, in, 1.0f, 1.0f, 0.0f, -1.0f / 32);
    Target t;
    ASSERT_TRUE(linear_shade_copy({0, 0, 2, 4}, pos, in, true, t.px.data(), 64 * 4));
    EXPECT_EQ(t.at(0, 0)[0], 255);
    EXPECT_EQ(t.at(1, 3)[0], 232);
}

TEST(LinearShade, UnormSourceRoundTrips) {
    // the blended path hands blend_pixel u/255: its UNORM8 conversion rne(x*255) must give u back for every u
    for (int u = 0; u < 256; ++u) {
        const float x = unorm8_source(uint8_t(u));
        EXPECT_EQ(static_cast<int>(std::nearbyint(x * 255.0f)), u);
    }
}

TEST(LinearShade, BlendsTheEightBitColour) {
    // constant 0.5 -> 127 in all channels; SRC_ALPHA / ONE_MINUS_SRC_ALPHA over dst 200: mul_norm(127,127) +
    // mul_norm(200, 128) = 63 + 100 = 163 (dst alpha 200: 63 + 100 too)
    float pos[12], in[12];
    planes(pos, in, 1.0f, 0.5f, 0.0f, 0.0f);
    Target t;
    std::fill(t.px.begin(), t.px.end(), uint8_t(200));
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = a.src_alpha = BlendFactor::SrcAlpha;
    a.dst_color = a.dst_alpha = BlendFactor::OneMinusSrcAlpha;
    const float k[4] = {0, 0, 0, 0};
    ASSERT_TRUE(linear_shade_copy({0, 0, 2, 2}, pos, in, true, t.px.data(), 64 * 4, &a, k));
    EXPECT_EQ(mul_norm8(127, 127), 63);
    EXPECT_EQ(mul_norm8(200, 128), 100);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(t.at(1, 1)[c], 163);
    EXPECT_EQ(t.at(2, 1)[0], 200);
}

TEST(LinearShade, ConstantsAreFloatToUbyte) {
    // float_to_ubyte: 0.5 -> fl(0.5*255/256) = 0.498046875; + 32768 keeps 1/256 steps, and 0.498046875*256 =
    // 127.5 is a tie -> even -> 32768 + 128/256: low byte 128
    EXPECT_EQ(float_to_ubyte(0.5f), 128);
    EXPECT_EQ(float_to_ubyte(0.0f), 0);
    EXPECT_EQ(float_to_ubyte(-1.0f), 0);
    EXPECT_EQ(float_to_ubyte(1.0f), 255);
    EXPECT_EQ(float_to_ubyte(1.0f / 255.0f), 1);
    // constant alpha with an interpolated rgb: vec4(v.rgb, 1.0)
    float pos[12], in[12];
    planes(pos, in, 1.0f, 0.5f, 0.0f, 0.0f);
    in[3] = 5.0f;  // alpha component out of range but not read (usage 0x7): not range-checked
    LinearChannels ch;
    ch.source[3] = -1;
    ch.constant[3] = 1.0f;
    ch.usage = 0x7;
    Target t;
    ASSERT_TRUE(linear_shade({0, 0, 2, 2}, pos, in, true, ch, t.px.data(), 64 * 4));
    EXPECT_EQ(t.at(1, 1)[0], 127);
    EXPECT_EQ(t.at(1, 1)[3], 255);
}
