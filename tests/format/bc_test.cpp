// format/texel_bc.h: BC1-BC5 blocks decoded texel by texel against values worked out by hand from llvmpipe's integer
// arithmetic (lp_bld_format_s3tc.c), each also checked to lie within one step of the ideal interpolation (the
// spec's 1/3, 2/3, k/7 and k/5 weights), and the float conversions against their definitions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "format/format.h"
#include "format/texel_bc.h"
#include "format/texel_codec.h"

namespace tilevk::format {
namespace {

struct Rgba {
    int r, g, b, a;
};

Rgba texel(Format f, const uint8_t* block, int i, int j) {
    uint8_t c[4];
    decode_bc_rgba8(format_info(f), block, i, j, c);
    return {c[0], c[1], c[2], c[3]};
}

// A BC1 colour half: endpoints c0, c1 and codes 0, 1, 2, 3 along every row.
void bc1_block(uint8_t* p, uint16_t c0, uint16_t c1) {
    const uint32_t w = uint32_t(c0) | uint32_t(c1) << 16, codes = 0xe4e4e4e4u;
    std::memcpy(p, &w, 4);
    std::memcpy(p + 4, &codes, 4);
}

// A BC3-alpha / BC4 channel: endpoints a0, a1 and codes 0..7 then 0..7 again.
void alpha_block(uint8_t* p, uint8_t a0, uint8_t a1) {
    const uint64_t v = uint64_t(a0) | uint64_t(a1) << 8 | 0xfac688fac688ull << 16;
    std::memcpy(p, &v, 8);
}

void expect_rgba(Rgba got, Rgba want, const char* what) {
    EXPECT_EQ(got.r, want.r) << what;
    EXPECT_EQ(got.g, want.g) << what;
    EXPECT_EQ(got.b, want.b) << what;
    EXPECT_EQ(got.a, want.a) << what;
}

// Four-colour mode, red (0xf800) to blue (0x001f): colours 2 and 3 are 1/3 and 2/3 of the way. lp_build_lerp23:
// red 255 -> 0: 85 * -255 = -21675 = 0xab55 as 16 bits; >> 8 = 171, 255 + 171 = 170 (mod 256); >> 7 & 255 = 86,
// 255 + 86 = 85. Blue 0 -> 255: 21675 >> 8 = 84, 21675 >> 7 = 169. (Ideal: 170, 85 and 85, 170.)
TEST(BcDecode, Bc1FourColourMode) {
    uint8_t b[8];
    bc1_block(b, 0xf800, 0x001f);
    expect_rgba(texel(Format::BC1_RGB_UNORM_BLOCK, b, 0, 0), {255, 0, 0, 255}, "code 0");
    expect_rgba(texel(Format::BC1_RGB_UNORM_BLOCK, b, 1, 2), {0, 0, 255, 255}, "code 1");
    expect_rgba(texel(Format::BC1_RGB_UNORM_BLOCK, b, 2, 1), {170, 0, 84, 255}, "code 2");
    expect_rgba(texel(Format::BC1_RGBA_UNORM_BLOCK, b, 3, 3), {85, 0, 169, 255}, "code 3");
    for (int code = 2; code <= 3; ++code) {
        const Rgba t = texel(Format::BC1_RGB_UNORM_BLOCK, b, code, 0);
        const double k = code == 2 ? 1.0 / 3.0 : 2.0 / 3.0;
        EXPECT_LE(std::fabs(t.r - 255 * (1 - k)), 1.0);
        EXPECT_LE(std::fabs(t.b - 255 * k), 1.0);
    }
}

// Three-colour mode (c0 <= c1): colour 2 the average rounded up (pavgb), colour 3 black, transparent for BC1_RGBA
// only. 565 widening by bit replication: 0x8410 = (16, 32, 16) -> (132, 130, 132).
TEST(BcDecode, Bc1ThreeColourMode) {
    uint8_t b[8];
    bc1_block(b, 0x001f, 0xf800);
    expect_rgba(texel(Format::BC1_RGB_UNORM_BLOCK, b, 2, 0), {128, 0, 128, 255}, "average");
    expect_rgba(texel(Format::BC1_RGB_UNORM_BLOCK, b, 3, 0), {0, 0, 0, 255}, "black, RGB");
    expect_rgba(texel(Format::BC1_RGBA_UNORM_BLOCK, b, 3, 0), {0, 0, 0, 0}, "black, RGBA");
    expect_rgba(texel(Format::BC1_RGBA_UNORM_BLOCK, b, 2, 0), {128, 0, 128, 255}, "average, RGBA");
    bc1_block(b, 0x8410, 0x8410);  // equal endpoints: three-colour mode too
    expect_rgba(texel(Format::BC1_RGBA_SRGB_BLOCK, b, 0, 0), {132, 130, 132, 255}, "565 widening");
    expect_rgba(texel(Format::BC1_RGBA_SRGB_BLOCK, b, 2, 0), {132, 130, 132, 255}, "average of equals");
    expect_rgba(texel(Format::BC1_RGBA_SRGB_BLOCK, b, 3, 0), {0, 0, 0, 0}, "transparent");
}

// BC2: explicit 4-bit alpha times 17; BC2/BC3 colour is always four-colour (c0 < c1 here).
TEST(BcDecode, Bc2ExplicitAlpha) {
    uint8_t b[16];
    const uint64_t a = 0xfedcba9876543210ull;
    std::memcpy(b, &a, 8);
    bc1_block(b + 8, 0x001f, 0xf800);
    for (int t = 0; t < 16; ++t) EXPECT_EQ(texel(Format::BC2_UNORM_BLOCK, b, t % 4, t / 4).a, t * 17) << t;
    // c0 < c1 (blue to red) still takes four colours: code 3 is 2/3 of the way, red 169 (ideal 170), blue 85
    expect_rgba(texel(Format::BC2_UNORM_BLOCK, b, 3, 0), {169, 0, 85, 3 * 17}, "four colours, code 3");
}

// BC3 alpha, eight-value mode (a0 > a1): 255 -> 0 with weights lo16(2331 * (code - 1)) >> 6 = 36, 72, 109, 145,
// 182, 218: 255 + (lo16(0xff01 * w) >> 8) mod 256 = 219, 183, 146, 110, 73, 37 (ideal 218.6, 182.1, 145.7, 109.3,
// 72.9, 36.4). Six-value mode 0 -> 255: 50, 101, 152, 203 (ideal 51, 102, 153, 204), code 6 = 0, code 7 = 255.
TEST(BcDecode, Bc3InterpolatedAlpha) {
    uint8_t b[16];
    alpha_block(b, 255, 0);
    bc1_block(b + 8, 0xffff, 0x0000);
    const int eight[8] = {255, 0, 219, 183, 146, 110, 73, 37};
    for (int t = 0; t < 16; ++t) {
        const int got = texel(Format::BC3_UNORM_BLOCK, b, t % 4, t / 4).a, code = t % 8;
        EXPECT_EQ(got, eight[code]) << "code " << code;
        if (code >= 2) {
            EXPECT_LE(std::fabs(got - 255.0 * (8 - code) / 7), 1.0) << code;
        }
    }
    alpha_block(b, 0, 255);
    const int six[8] = {0, 255, 50, 101, 152, 203, 0, 255};
    for (int t = 0; t < 8; ++t) {
        const int got = texel(Format::BC3_SRGB_BLOCK, b, t % 4, t / 4).a;
        EXPECT_EQ(got, six[t]) << "code " << t;
        if (t >= 2 && t <= 5) {
            EXPECT_LE(std::fabs(got - 255.0 * (t - 1) / 5), 1.0) << t;
        }
    }
}

// BC4/BC5 SNORM: signed endpoints (-128 < 127: six-value mode, codes 6 and 7 give -127 and 127), the same 16-bit
// lerp on the signed values: -78, -27, 24, 75 (ideal -77, -26, 25, 76); 127 -> -128 in eight-value mode: 91, 55,
// 18, -18, -55, -91.
TEST(BcDecode, Bc4Bc5Signed) {
    uint8_t b[16];
    alpha_block(b, 0x80, 0x7f);
    alpha_block(b + 8, 0x7f, 0x80);
    const int six[8] = {-128, 127, -78, -27, 24, 75, -127, 127};
    const int eight[8] = {127, -128, 91, 55, 18, -18, -55, -91};
    for (int t = 0; t < 8; ++t) {
        const Rgba r4 = texel(Format::BC4_SNORM_BLOCK, b, t % 4, t / 4);
        EXPECT_EQ(int8_t(r4.r), six[t]) << t;
        EXPECT_EQ(r4.a, 127);
        const Rgba r5 = texel(Format::BC5_SNORM_BLOCK, b, t % 4, t / 4);
        EXPECT_EQ(int8_t(r5.r), six[t]) << t;
        EXPECT_EQ(int8_t(r5.g), eight[t]) << t;
    }
    // unsigned, the same bytes: 128 > 127, eight-value mode: 128 + (lo16(0xffff * 36) >> 8) = 128 + 255 = 127
    // (mod 256; ideal 127.9)
    const Rgba u = texel(Format::BC4_UNORM_BLOCK, b, 2, 0);
    EXPECT_EQ(u.r, 127);
    EXPECT_EQ(u.a, 255);
}

// The float conversions: UNORM bytes * fl(1/255), SNORM max(c * fl(1/127), -1), sRGB colour through the sRGB8 decode
// (alpha linear); BC4 gives (r, 0, 0, 1).
TEST(BcDecode, FloatConversions) {
    uint8_t b[16];
    bc1_block(b, 0xf800, 0x001f);
    float f[4];
    decode_bc_color(format_info(Format::BC1_RGB_UNORM_BLOCK), b, 2, 0, f, true);
    EXPECT_EQ(f[0], 170.0f * (1.0f / 255.0f));
    EXPECT_EQ(f[2], 84.0f * (1.0f / 255.0f));
    EXPECT_EQ(f[3], 1.0f);
    decode_bc_color(format_info(Format::BC1_RGB_SRGB_BLOCK), b, 2, 0, f, true);
    EXPECT_EQ(f[0], srgb8_to_linear(170, true));
    EXPECT_EQ(f[2], srgb8_to_linear(84, true));
    EXPECT_EQ(f[3], 1.0f);
    alpha_block(b, 0x80, 0x7f);
    decode_bc_color(format_info(Format::BC4_SNORM_BLOCK), b, 0, 0, f, true);
    EXPECT_EQ(f[0], -1.0f);
    EXPECT_EQ(f[1], 0.0f);
    EXPECT_EQ(f[3], 1.0f);
    decode_bc_color(format_info(Format::BC4_SNORM_BLOCK), b, 1, 0, f, true);
    EXPECT_EQ(f[0], 127.0f * (1.0f / 127.0f));
    EXPECT_TRUE(is_bc_decoded(format_info(Format::BC5_SNORM_BLOCK)));
    EXPECT_FALSE(is_bc_decoded(format_info(Format::BC6H_UFLOAT_BLOCK)));
    EXPECT_FALSE(is_bc_decoded(format_info(Format::R8G8B8A8_UNORM)));
}

}  // namespace
}  // namespace tilevk::format
