// format/texel_bptc.cpp: BC7 and BC6H blocks written bit by bit from the spec's layouts (Khronos Data Format
// Specification, BPTC) and decoded texel by texel against values worked out by hand: the spec's interpolation
// ((64 - w) * e0 + w * e1 + 32) >> 6, BC7's endpoint widening, p-bits, rotation, index selector and anchor texels;
// BC6H's unquantization, deltas, bit-reversed fields and 31/64 (31/32 signed) half scaling; and the reserved modes
// as Mesa's decoder (the one lavapipe calls) answers them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "format/format.h"
#include "format/texel_bc.h"

namespace tilevk::format {
namespace {

// Appends fields to a 128-bit block from bit 0 up, each value's lowest bit first.
struct BitWriter {
    uint8_t block[16] = {};
    int at = 0;
    void put(uint32_t value, int bits) {
        for (int b = 0; b < bits; ++b, ++at)
            if (value >> b & 1) block[at / 8] |= uint8_t(1u << (at % 8));
    }
};

struct Rgba8 {
    int r, g, b, a;
};
Rgba8 bc7(Format f, const uint8_t* block, int t) {
    uint8_t c[4];
    decode_bc_rgba8(format_info(f), block, t % 4, t / 4, c);
    return {c[0], c[1], c[2], c[3]};
}
void expect_rgba8(Rgba8 got, Rgba8 want, int t) {
    EXPECT_EQ(got.r, want.r) << "texel " << t;
    EXPECT_EQ(got.g, want.g) << "texel " << t;
    EXPECT_EQ(got.b, want.b) << "texel " << t;
    EXPECT_EQ(got.a, want.a) << "texel " << t;
}

// Mode 6: one subset, 7-bit RGBA endpoints with a p-bit each (8 bits, no widening), 4-bit indices; texel t gets
// index t. e0 = (10, 20, 30, 40) << 1 | 1 = (21, 41, 61, 81), e1 = (100, 110, 120, 127) << 1 = (200, 220, 240, 254).
// Texel 5, w = 21: r = (43 * 21 + 21 * 200 + 32) >> 6 = 5135 >> 6 = 80, g = 6415 >> 6 = 100, b = 7695 >> 6 = 120,
// a = 8849 >> 6 = 138.
TEST(BptcDecode, Bc7Mode6PBitsAndFourBitIndices) {
    BitWriter w;
    w.put(1u << 6, 7);
    const uint32_t e[2][4] = {{10, 20, 30, 40}, {100, 110, 120, 127}};
    for (int c = 0; c < 4; ++c)
        for (const auto& ep : e) w.put(ep[c], 7);
    w.put(1, 1), w.put(0, 1);  // p-bits of e0, e1
    w.put(0, 3);               // texel 0: the anchor, 3 bits
    for (uint32_t t = 1; t < 16; ++t) w.put(t, 4);
    ASSERT_EQ(w.at, 128);
    expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, w.block, 0), {21, 41, 61, 81}, 0);
    expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, w.block, 5), {80, 100, 120, 138}, 5);
    expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, w.block, 15), {200, 220, 240, 254}, 15);
    // the float the sampler sees: the byte times fl(1/255); sRGB through Mesa's table of the exact curve
    float f[4];
    decode_bc_color(format_info(Format::BC7_UNORM_BLOCK), w.block, 1, 1, f, true);
    EXPECT_EQ(f[0], 80.0f * float(1.0 / 255.0));
    EXPECT_EQ(f[3], 138.0f * float(1.0 / 255.0));
    decode_bc_color(format_info(Format::BC7_SRGB_BLOCK), w.block, 1, 1, f, true);
    const double x = 80.0 / 255.0, exact = std::pow((x + 0.055) / 1.055, 2.4);  // 0.0802
    EXPECT_NEAR(f[0], exact, exact * 1.2e-7);
    EXPECT_EQ(f[3], 138.0f * float(1.0 / 255.0));  // alpha stays linear
}

// The interpolation's rounding: e0 = 0, e1 = 32 (mode 6: 7-bit 16, p-bit 0), index 5 of 16 (w = 21):
// 21 * 32 = 672 = 10.5 * 64, and + 32 rounds the half up: 11.
TEST(BptcDecode, Bc7InterpolationRoundsHalvesUp) {
    BitWriter w;
    w.put(1u << 6, 7);
    for (int c = 0; c < 4; ++c) w.put(0, 7), w.put(16, 7);
    w.put(0, 2);
    w.put(5, 3);
    for (int t = 1; t < 16; ++t) w.put(5, 4);
    ASSERT_EQ(w.at, 128);
    for (int t : {0, 9}) expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, w.block, t), {11, 11, 11, 11}, t);
}

// Mode 4: rotation 1 (R <-> A), index selector 1 (colour from the 3-bit indices, alpha from the 2-bit ones).
// Endpoints r 0 -> 31, g 31 -> 0, b 16 -> 16 (5 bits: 0, 255, 132), a 0 -> 63 (6 bits: 0, 255). Every 2-bit index
// 1 (w = 21), every 3-bit index 2 (w = 18): r = (18 * 255 + 32) >> 6 = 72, g = (46 * 255 + 32) >> 6 = 183, b = 132,
// a = (21 * 255 + 32) >> 6 = 84; rotated: (84, 183, 132, 72).
TEST(BptcDecode, Bc7Mode4RotationAndIndexSelector) {
    BitWriter w;
    w.put(1u << 4, 5);
    w.put(1, 2);  // rotation
    w.put(1, 1);  // index selector
    w.put(0, 5), w.put(31, 5), w.put(31, 5), w.put(0, 5), w.put(16, 5), w.put(16, 5);
    w.put(0, 6), w.put(63, 6);
    w.put(1, 1);
    for (int t = 1; t < 16; ++t) w.put(1, 2);
    w.put(2, 2);
    for (int t = 1; t < 16; ++t) w.put(2, 3);
    ASSERT_EQ(w.at, 128);
    for (int t : {0, 7, 15}) expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, w.block, t), {84, 183, 132, 72}, t);
}

// Mode 2, partition 0 (subsets 0011 0011 0221 2222, anchors texel 0, 3 and 15): subset 0 from 0 to 255, subset 1
// from 255 to 0, subset 2 at 8 (5 bits: 66). Every index 3, the anchors' 1 (w = 21 for 1 -> 84, 255 -> 171).
TEST(BptcDecode, Bc7Mode2ThreeSubsetsAndAnchors) {
    BitWriter w;
    w.put(1u << 2, 3);
    w.put(0, 6);
    for (int c = 0; c < 3; ++c) w.put(0, 5), w.put(31, 5), w.put(31, 5), w.put(0, 5), w.put(8, 5), w.put(8, 5);
    for (int t = 0; t < 16; ++t) {
        const bool anchor = t == 0 || t == 3 || t == 15;
        w.put(anchor ? 1 : 3, anchor ? 1 : 2);
    }
    ASSERT_EQ(w.at, 128);
    const int want[16] = {84, 255, 0, 171, 255, 255, 0, 0, 255, 66, 66, 0, 66, 66, 66, 66};
    for (int t = 0; t < 16; ++t)
        expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, w.block, t), {want[t], want[t], want[t], 255}, t);
}

// A block whose byte 0 has no bit set names no mode: Mesa's decoder returns (0, 0, 0, 0), alpha included.
TEST(BptcDecode, Bc7ReservedModeIsTransparentBlack) {
    uint8_t block[16];
    std::memset(block, 0xff, 16);
    block[0] = 0;
    expect_rgba8(bc7(Format::BC7_UNORM_BLOCK, block, 6), {0, 0, 0, 0}, 6);
    float f[4];
    decode_bc_color(format_info(Format::BC7_SRGB_BLOCK), block, 2, 1, f, true);
    EXPECT_EQ(f[0], 0.0f);
    EXPECT_EQ(f[3], 0.0f);
}

void bc6(Format f, const uint8_t* block, int t, float out[4]) {
    decode_bc_color(format_info(f), block, t % 4, t / 4, out, true);
}

// Mode 00011: one region, 10-bit endpoints stored whole, 4-bit indices (texel t: index t).
// r 0 -> 1023, g 512 -> 512, b 1 -> 0. The returned halves, worked by hand:
//   UFLOAT: 1023 -> 0xffff, 512 -> ((512 << 15) + 0x4000) >> 9 = 32800, 1 -> 96. Texel 0: g = 32800 * 31 / 64 =
//     15887 = 0x3e0f = 1 + 527/1024; b = 96 * 31 / 64 = 46 (a denormal, 46 * 2^-24). Texel 15: r = 65535 * 31 / 64
//     = 31743 = 0x7bff = 65504. Texel 5 (w = 21): r = (21 * 65535 + 32) >> 6 = 21504, * 31 / 64 = 10416 = 0x28b0 =
//     2^-5 * (1 + 176/1024); b = (43 * 96 + 32) >> 6 = 65, * 31 / 64 = 31.
//   SFLOAT: the endpoints are 10-bit two's complement: 1023 = -1 -> -96, 512 = -512 -> -0x7fff, 1 -> 96. Texel 0:
//     g = 0x8000 | 32767 * 31 / 32 = 0xfbff = -65504, b = 96 * 31 / 32 = 93. Texel 15: r = 0x8000 | 93.
TEST(BptcDecode, Bc6hOneRegionUnsignedAndSigned) {
    BitWriter w;
    w.put(0x03, 5);
    w.put(0, 10), w.put(512, 10), w.put(1, 10), w.put(1023, 10), w.put(512, 10), w.put(0, 10);
    w.put(0, 3);
    for (uint32_t t = 1; t < 16; ++t) w.put(t, 4);
    ASSERT_EQ(w.at, 128);
    const float denormal = std::ldexp(1.0f, -24);
    float c[4];
    bc6(Format::BC6H_UFLOAT_BLOCK, w.block, 0, c);
    EXPECT_EQ(c[0], 0.0f);
    EXPECT_EQ(c[1], 1.0f + 527.0f / 1024.0f);
    EXPECT_EQ(c[2], 46.0f * denormal);
    EXPECT_EQ(c[3], 1.0f);
    bc6(Format::BC6H_UFLOAT_BLOCK, w.block, 15, c);
    EXPECT_EQ(c[0], 65504.0f);
    EXPECT_EQ(c[1], 1.0f + 527.0f / 1024.0f);
    EXPECT_EQ(c[2], 0.0f);
    bc6(Format::BC6H_UFLOAT_BLOCK, w.block, 5, c);
    EXPECT_EQ(c[0], (1.0f + 176.0f / 1024.0f) / 32.0f);
    EXPECT_EQ(c[2], 31.0f * denormal);
    bc6(Format::BC6H_SFLOAT_BLOCK, w.block, 0, c);
    EXPECT_EQ(c[0], 0.0f);
    EXPECT_EQ(c[1], -65504.0f);
    EXPECT_EQ(c[2], 93.0f * denormal);
    EXPECT_EQ(c[3], 1.0f);
    bc6(Format::BC6H_SFLOAT_BLOCK, w.block, 15, c);
    EXPECT_EQ(c[0], -93.0f * denormal);
    EXPECT_EQ(c[1], -65504.0f);
}

// Mode 01011: 12-bit endpoints, the second as 8-bit deltas, the endpoints' top two bits stored bit-reversed
// ("rw10:11": the field's first bit is bit 11). rw = 0x800 (reversed field 0b01), rx = 0x800 + (-1) = 2047;
// gw = 0, gx = 0 + (-128) wrapped to 12 bits = 3968; b 0. UFLOAT: 2048 -> 32776, 2047 -> 32760, 3968 -> 63496.
// Texel 0: r = 32776 * 31 / 64 = 15875 = 0x3e03 = 1 + 515/1024. Texel 15: r = 32760 * 31 / 64 = 15868 = 1 + 508/1024,
// g = 63496 * 31 / 64 = 30755 = 0x7823 = 2^15 * (1 + 35/1024) = 33888.
TEST(BptcDecode, Bc6hDeltasAndReversedFields) {
    BitWriter w;
    w.put(0x0b, 5);
    w.put(0, 10), w.put(0, 10), w.put(0, 10);  // rw9:0 gw9:0 bw9:0
    w.put(0xff, 8), w.put(1, 2);               // rx7:0, rw10:11 (first bit -> bit 11)
    w.put(0x80, 8), w.put(0, 2);               // gx7:0, gw10:11
    w.put(0, 8), w.put(0, 2);                  // bx7:0, bw10:11
    w.put(0, 3);
    for (int t = 1; t < 16; ++t) w.put(15, 4);
    ASSERT_EQ(w.at, 128);
    float c[4];
    bc6(Format::BC6H_UFLOAT_BLOCK, w.block, 0, c);
    EXPECT_EQ(c[0], 1.0f + 515.0f / 1024.0f);
    EXPECT_EQ(c[1], 0.0f);
    bc6(Format::BC6H_UFLOAT_BLOCK, w.block, 15, c);
    EXPECT_EQ(c[0], 1.0f + 508.0f / 1024.0f);
    EXPECT_EQ(c[1], 33888.0f);
    EXPECT_EQ(c[2], 0.0f);
}

// Mode codes 10011, 10111, 11011 and 11111 are reserved: Mesa's decoder returns (0, 0, 0, 1).
TEST(BptcDecode, Bc6hReservedModes) {
    for (uint8_t mode : {0x13, 0x17, 0x1b, 0x1f}) {
        uint8_t block[16];
        std::memset(block, 0x5a, 16);
        block[0] = uint8_t((block[0] & ~31u) | mode);
        float c[4];
        bc6(Format::BC6H_SFLOAT_BLOCK, block, 9, c);
        EXPECT_EQ(c[0], 0.0f) << int(mode);
        EXPECT_EQ(c[1], 0.0f) << int(mode);
        EXPECT_EQ(c[2], 0.0f) << int(mode);
        EXPECT_EQ(c[3], 1.0f) << int(mode);
    }
}

}  // namespace
}  // namespace tilevk::format
