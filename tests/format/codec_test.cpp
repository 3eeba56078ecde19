// The texel codec and the format table (format/): the clear packers against their definitions and the CPU's own
// F16C conversion, and the table's rows against the registry's format descriptions and tilevk's support rules.
#include <gtest/gtest.h>
#include <immintrin.h>

#include <cmath>
#include <cstring>

#include "format/format.h"
#include "format/texel_bc.h"
#include "format/texel_codec.h"

namespace tilevk::format {
namespace {

float from_bits(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// float_to_ubyte: the low byte of fl(f*fl(255/256)) + 32768 is round-half-even(x * 256) for x = fl(f*fl(255/256)),
// because the ulp of 32768.0f is exactly 1/256. Expected value computed in double from that statement.
TEST(ClearPack, FloatToUbyteMatchesItsDefinition) {
    const float k = 255.0f / 256.0f;
    for (uint32_t u = 0; u <= 0x3f800000u; u += 61) {
        float f = from_bits(u);
        float x = f * k;
        int expected = f >= 1.0f ? 255 : f > 0.0f ? int(std::nearbyint(double(x) * 256.0)) & 0xff : 0;
        ASSERT_EQ(float_to_ubyte(f), expected) << "f = " << f;
    }
    EXPECT_EQ(float_to_ubyte(-1.0f), 0);
    EXPECT_EQ(float_to_ubyte(NAN), 0);
    EXPECT_EQ(float_to_ubyte(INFINITY), 255);
    EXPECT_EQ(float_to_ubyte(2.0f), 255);
    EXPECT_EQ(float_to_ubyte(0.5f), 128);  // fl(0.5*255/256)*256 = 127.5 -> 128 (half to even)
}

// Against the CPU's own F16C conversion in round-toward-zero mode (the instruction Mesa uses) as the reference.
__attribute__((target("f16c"))) uint16_t f16c_rtz(float f) {
    return uint16_t(_cvtss_sh(f, _MM_FROUND_TO_ZERO));
}

TEST(ClearPack, HalfConversionRoundsTowardZeroLikeF16c) {
    if (!__builtin_cpu_supports("f16c")) GTEST_SKIP() << "no F16C on this CPU: no hardware reference";
    for (uint64_t u = 0; u <= 0xffffffffull; u += 9973) {
        float f = from_bits(uint32_t(u));
        ASSERT_EQ(float_to_half_rtz(f), f16c_rtz(f)) << std::hexfloat << f << " bits " << std::hex << u;
    }
    for (float f : {65504.0f, 65519.0f, 65520.0f, 1e9f, -1e9f, INFINITY, -INFINITY, NAN, 5.9604645e-08f, 1e-9f}) {
        EXPECT_EQ(float_to_half_rtz(f), f16c_rtz(f)) << f;
    }
    for (uint32_t h = 0; h < 0x10000; ++h) {
        _Float16 v;
        uint16_t b = uint16_t(h);
        std::memcpy(&v, &b, 2);
        float want = static_cast<float>(v);  // half -> float is exact
        if (std::isnan(want)) {
            EXPECT_TRUE(std::isnan(half_to_float(b)));
            continue;
        }
        ASSERT_EQ(half_to_float(b), want) << h;
    }
}

// The bucketed sRGB encoder stays within one step of the exact curve, and hits the ends exactly.
TEST(ClearPack, SrgbEncodeCloseToExactCurve) {
    EXPECT_EQ(linear_to_srgb8_table(0.0f), 0);
    EXPECT_EQ(linear_to_srgb8_table(1.0f), 255);
    EXPECT_EQ(linear_to_srgb8_table(-3.0f), 0);
    EXPECT_EQ(linear_to_srgb8_table(7.0f), 255);
    EXPECT_EQ(linear_to_srgb8_table(NAN), 0);
    for (int i = 0; i <= 10000; ++i) {
        double x = i / 10000.0;
        double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
        int exact = int(std::floor(s * 255.0 + 0.5));
        ASSERT_LE(std::abs(int(linear_to_srgb8_table(float(x))) - exact), 1) << x;
    }
}

TEST(ClearPack, DepthPacking) {
    struct Case {
        float z;
        uint16_t want;
    } cases[] = {{0.0f, 0}, {-1.0f, 0}, {1.0f, 65535}, {2.0f, 65535}, {0.5f, 32768}, {0.25f, 16384}};
    // 0.5*65535 = 32767.5 -> lrint (half to even) = 32768; 0.25*65535 = 16383.75 -> 16384.
    for (const Case& c : cases) {
        const uint32_t v = pack_clear_depth(DepthFormat::D16, c.z);
        EXPECT_EQ(v, c.want) << c.z;
    }
}

TEST(ClearPack, ColorChannelOrder) {
    float c[4] = {};
    c[0] = 1.0f;  // red
    c[3] = 1.0f;
    uint8_t t[16] = {};
    pack_clear_color(Format::B8G8R8A8_UNORM, c, t);
    EXPECT_EQ(t[0], 0);  // blue first in memory
    EXPECT_EQ(t[2], 255);
    EXPECT_EQ(t[3], 255);
    pack_clear_color(Format::R32G32_SFLOAT, c, t);
    float g;
    std::memcpy(&g, t + 4, 4);
    EXPECT_EQ(g, 0.0f);
}

// Spot checks of where the registry puts each channel (the spec's "Identification of Formats": array formats from
// the lowest address, packed formats from the top bit of the word), written out here by hand.
TEST(FormatTable, ChannelPlacementFollowsTheSpec) {
    struct Want {
        Format f;
        uint8_t bytes;
        Component c[4];
        uint8_t bits[4], shift[4];
    } cases[] = {
        {Format::R8G8B8A8_UNORM,
         4,
         {Component::kR, Component::kG, Component::kB, Component::kA},
         {8, 8, 8, 8},
         {0, 8, 16, 24}},
        {Format::B8G8R8A8_SRGB,
         4,
         {Component::kB, Component::kG, Component::kR, Component::kA},
         {8, 8, 8, 8},
         {0, 8, 16, 24}},
        {Format::R5G6B5_UNORM_PACK16, 2, {Component::kR, Component::kG, Component::kB}, {5, 6, 5}, {11, 5, 0}},
        {Format::B5G5R5A1_UNORM_PACK16,
         2,
         {Component::kB, Component::kG, Component::kR, Component::kA},
         {5, 5, 5, 1},
         {11, 6, 1, 0}},
        {Format::A2B10G10R10_UINT_PACK32,
         4,
         {Component::kA, Component::kB, Component::kG, Component::kR},
         {2, 10, 10, 10},
         {30, 20, 10, 0}},
        {Format::B10G11R11_UFLOAT_PACK32, 4, {Component::kB, Component::kG, Component::kR}, {10, 11, 11}, {22, 11, 0}},
        {Format::E5B9G9R9_UFLOAT_PACK32,
         4,
         {Component::kE, Component::kB, Component::kG, Component::kR},
         {5, 9, 9, 9},
         {27, 18, 9, 0}},
        {Format::R64G64_SFLOAT, 16, {Component::kR, Component::kG}, {64, 64}, {0, 64}},
        {Format::D24_UNORM_S8_UINT, 4, {Component::kD, Component::kS}, {24, 8}, {0, 24}},
        {Format::X8_D24_UNORM_PACK32, 4, {Component::kD}, {24}, {0}},
        {Format::D32_SFLOAT_S8_UINT, 8, {Component::kD, Component::kS}, {32, 8}, {0, 32}},
        {Format::R10X6G10X6_UNORM_2PACK16, 4, {Component::kR, Component::kG}, {10, 10}, {6, 22}},
    };
    for (const Want& w : cases) {
        const FormatInfo& f = format_info(w.f);
        EXPECT_EQ(f.bytes, w.bytes) << f.name;
        for (int i = 0; i < f.channels; ++i) {
            EXPECT_EQ(f.channel[i].component, w.c[i]) << f.name << " channel " << i;
            EXPECT_EQ(f.channel[i].bits, w.bits[i]) << f.name << " channel " << i;
            EXPECT_EQ(f.channel[i].shift, w.shift[i]) << f.name << " channel " << i;
        }
    }
    EXPECT_EQ(format_info(Format::R8G8B8A8_SRGB).channel[3].numeric, Numeric::kUnorm);  // sRGB alpha is linear
    EXPECT_EQ(format_info(Format::BC1_RGB_UNORM_BLOCK).layout, Layout::kCompressed);
    EXPECT_EQ(format_info(Format::BC1_RGB_UNORM_BLOCK).block_width, 4);
    EXPECT_EQ(format_info(Format::BC7_SRGB_BLOCK).block_bytes, 16);
    EXPECT_EQ(format_info(Format::G8_B8R8_2PLANE_420_UNORM).layout, Layout::kMultiPlanar);
}

// Support is reported only where a codec implements it: attachments and sampling need a texel codec, vertex and
// texel-buffer formats channels fetch_words converts, 4 samples a resolvable colour codec or depth.
// store_image_texel (imageStore) against hand values of texel_codec.h's rules: UNORM8 rne(x * 255) with NaN at the
// upper bound (0.5 -> 127.5 -> 128), SNORM8 rne(x * 127) (0.5 -> 63.5 -> 64, NaN -> 127, -inf -> -127), 16-bit
// integers saturated, halves toward zero (0.1 -> 0x2e66, 70000 -> 65504 = 0x7bff), 32-bit channels as they are.
TEST(ImageStore, ChannelsFollowTheStoreRules) {
    const uint32_t nan = 0x7fc00000u, ninf = 0xff800000u;
    const auto word = [](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    uint8_t t[16] = {};
    const uint32_t unorm[4] = {word(0.5f), nan, word(-3.0f), word(1.0f / 255.0f)};
    store_image_texel(format_info(Format::R8G8B8A8_UNORM), unorm, t);
    EXPECT_EQ(t[0], 128);
    EXPECT_EQ(t[1], 255);
    EXPECT_EQ(t[2], 0);
    EXPECT_EQ(t[3], 1);
    const uint32_t snorm[4] = {word(0.5f), nan, ninf, word(-0.5f)};
    store_image_texel(format_info(Format::R8G8B8A8_SNORM), snorm, t);
    EXPECT_EQ(int8_t(t[0]), 64);
    EXPECT_EQ(int8_t(t[1]), 127);
    EXPECT_EQ(int8_t(t[2]), -127);
    EXPECT_EQ(int8_t(t[3]), -64);
    const uint32_t ints[4] = {70000u, 0xffffffffu, 5u, 65535u};
    uint16_t h[4];
    store_image_texel(format_info(Format::R16G16B16A16_UINT), ints, t);
    std::memcpy(h, t, 8);
    EXPECT_EQ(h[0], 65535);
    EXPECT_EQ(h[1], 65535);
    EXPECT_EQ(h[2], 5);
    store_image_texel(format_info(Format::R16G16B16A16_SINT), ints, t);
    std::memcpy(h, t, 8);
    EXPECT_EQ(int16_t(h[0]), 32767);
    EXPECT_EQ(int16_t(h[1]), -1);
    const uint32_t halves[4] = {word(0.1f), word(70000.0f), word(-2.25f), word(0.0f)};
    store_image_texel(format_info(Format::R16G16B16A16_SFLOAT), halves, t);
    std::memcpy(h, t, 8);
    EXPECT_EQ(h[0], 0x2e66);
    EXPECT_EQ(h[1], 0x7bff);
    EXPECT_EQ(h[2], 0xc080);
    store_image_texel(format_info(Format::R32G32_SINT), ints, t);
    uint32_t w[2];
    std::memcpy(w, t, 8);
    EXPECT_EQ(w[0], 70000u);
    EXPECT_EQ(w[1], 0xffffffffu);
    EXPECT_TRUE(can_store_image(format_info(Format::R32G32B32A32_SFLOAT)));
    EXPECT_FALSE(can_store_image(format_info(Format::R8G8B8A8_SRGB)));
    EXPECT_FALSE(can_store_image(format_info(Format::D32_SFLOAT)));
}

// The packed extended storage formats by hand: A2B10G10R10 UNORM rne(x * 1023) in floats (0.5 -> 511.5 -> 512, NaN
// -> 1023) and alpha rne(0.4 * 3) = 1; B10G11R11 1.0 = 2^0 -> exponent 15, 0.5 -> 14, 70000 past 64512 -> the
// largest 10-bit value (30 << 5 | 31), each field in its place (R bits 0-10, G 11-21, B 22-31).
TEST(ImageStore, PackedExtendedFormats) {
    const auto word = [](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    uint8_t bytes[4] = {};
    const auto texel = [&] {
        uint32_t t;
        std::memcpy(&t, bytes, 4);
        return t;
    };
    const uint32_t a2b10[4] = {word(1.0f), word(0.5f), 0x7fc00000u, word(0.4f)};
    store_image_texel(format_info(Format::A2B10G10R10_UNORM_PACK32), a2b10, bytes);
    EXPECT_EQ(texel(), 1023u | 512u << 10 | 1023u << 20 | 1u << 30);
    const uint32_t uf[4] = {word(1.0f), word(0.5f), word(70000.0f), word(9.0f)};
    store_image_texel(format_info(Format::B10G11R11_UFLOAT_PACK32), uf, bytes);
    EXPECT_EQ(texel(), (15u << 6) | (14u << 6) << 11 | (30u << 5 | 31u) << 22);
    EXPECT_TRUE(can_store_image(format_info(Format::B10G11R11_UFLOAT_PACK32)));
}

TEST(FormatTable, SupportNeedsTheCodec) {
    int supported = 0;
    for (size_t i = 0; i < size_t(Format::kCount); ++i) {
        const FormatInfo& f = format_info(Format(i));
        const uint32_t image = f.optimal | f.linear;
        if (image | f.buffer) ++supported;
        if (image & (kColorAttachment | kColorAttachmentBlend)) {
            EXPECT_NE(f.kind, ChannelKind::None) << f.name;
        }
        if (image & kDepthStencilAttachment) {
            EXPECT_TRUE(f.depth != DepthFormat::None || f.aspects == kStencil) << f.name;  // S8_UINT: stencil only
        }
        if (image & kBlitDst) {
            EXPECT_TRUE(can_decode_color(f)) << f.name;
        }
        if (image & kBlitSrc) {
            EXPECT_TRUE(can_decode_color(f) || is_bc_decoded(f)) << f.name;  // the blitter samples BC sources
        }
        if (image & kSampledImage) {
            EXPECT_TRUE(can_decode_color(f) || is_bc_decoded(f)) << f.name;  // texel_bc.h: BC blocks
        }
        if (image & kStorageImage) {
            EXPECT_TRUE(can_store_image(f) && can_decode_color(f)) << f.name;  // imageStore / imageLoad
        }
        if (f.buffer & kUniformTexelBuffer) {
            EXPECT_NE(f.kind, ChannelKind::None) << f.name;
        }
        if (f.buffer & kVertexBuffer) {
            EXPECT_TRUE(f.layout == Layout::kArray || f.layout == Layout::kPacked || f.kind == ChannelKind::SharedExp)
                << f.name;
            for (int c = 0; c < f.channels; ++c) {
                EXPECT_LE(f.channel[c].bits, 32) << f.name;
                if (f.channel[c].numeric == Numeric::kUfloat) {
                    EXPECT_TRUE(f.kind == ChannelKind::Ufloat11 || f.kind == ChannelKind::SharedExp) << f.name;
                }
                EXPECT_NE(f.channel[c].numeric, Numeric::kSrgb) << f.name;
            }
        }
        if (f.sample_counts & 4) {
            EXPECT_TRUE((f.kind != ChannelKind::None && (image & kColorAttachment)) || f.depth != DepthFormat::None ||
                        f.aspects == kStencil)
                << f.name;
        }
        if (f.linear) {
            EXPECT_EQ(f.linear & ~f.optimal, 0u) << f.name;  // linear images are the same layout
        }
    }
    EXPECT_EQ(supported, 129);  // the rows of support.txt that support something
}

}  // namespace
}  // namespace tilevk::format
