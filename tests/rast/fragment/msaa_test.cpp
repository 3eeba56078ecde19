// Alpha to coverage, sample mask, resolve and clear packing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "rast/core/cpu.h"
#include "rast/fragment/msaa.h"

using namespace tilevk::rast::fragment;
using tilevk::rast::Isa;
using tilevk::rast::kernel_isa;
using tilevk::rast::set_kernel_isa_for_testing;

TEST(FragmentMsaa, AlphaToCoverageThresholds) {
    float alpha[16];
    const float values[16] = {0.0f, 0.2f,  0.25f, 0.26f,    0.5f,    0.51f,   0.75f,      0.76f,
                              1.0f, -1.0f, NAN,   INFINITY, 0.0001f, 0.7499f, 0.2500001f, 2.0f};
    std::memcpy(alpha, values, sizeof alpha);
    uint16_t masks[4] = {0xffff, 0xffff, 0xffff, 0xffff};
    alpha_to_coverage_4x(alpha, masks);
    for (int l = 0; l < 16; ++l)
        for (int s = 0; s < 4; ++s) {
            // sample s survives iff alpha > s/4 (strict; unordered: NaN always survives)
            const bool want = std::isnan(alpha[l]) || alpha[l] > double(s) / 4.0;
            EXPECT_EQ(bool(masks[s] & (1u << l)), want) << "lane " << l << " sample " << s;
        }
    const uint16_t m1 = alpha_to_coverage_1x(alpha, 0xffff);
    for (int l = 0; l < 16; ++l) EXPECT_EQ(bool(m1 & (1u << l)), std::isnan(alpha[l]) || alpha[l] > 0.5) << l;
    // DAZ: a denormal alpha is zero, so it fails even the s = 0 threshold
    float tiny[16];
    for (float& t : tiny) t = 1e-42f;
    uint16_t mt[4] = {0xffff, 0xffff, 0xffff, 0xffff};
    alpha_to_coverage_4x(tiny, mt);
    EXPECT_EQ(mt[0], 0);
    EXPECT_EQ(alpha_to_coverage_1x(alpha, 0), 0);
}

TEST(FragmentMsaa, SampleMask) {
    uint16_t m[4] = {0x1111, 0x2222, 0x4444, 0x8888};
    apply_sample_mask(0x5, 4, m);
    EXPECT_EQ(m[0], 0x1111);
    EXPECT_EQ(m[1], 0);
    EXPECT_EQ(m[2], 0x4444);
    EXPECT_EQ(m[3], 0);
    EXPECT_EQ(any_sample(m), 0x5555);
    uint16_t one[4] = {0xffff, 0, 0, 0};
    apply_sample_mask(0x2, 1, one);  // 1x ignores the mask ...
    EXPECT_EQ(one[0], 0xffff);
    apply_sample_mask(0, 1, one);  // ... unless it is entirely zero
    EXPECT_EQ(one[0], 0);
}

TEST(FragmentMsaa, ResolveUnorm8SumsInSampleOrder) {
    // Exhaustive over pairs of sample values with the other two fixed, plus random quadruples.
    std::mt19937 rng(1);
    const float k = float(1.0 / 255.0);
    auto check = [&](const uint8_t v[4]) {
        uint8_t px[4][4];
        for (int s = 0; s < 4; ++s)
            for (int c = 0; c < 4; ++c) px[s][c] = uint8_t(v[s] ^ (c * 37));
        const uint8_t* p[4] = {px[0], px[1], px[2], px[3]};
        uint8_t out[4];
        ASSERT_TRUE(resolve_pixel(ColorFormat::R8G8B8A8_UNORM, p, out, true));
        for (int c = 0; c < 4; ++c) {
            volatile float sum = 0.0f;
            for (int s = 0; s < 4; ++s) {
                volatile float t = float(px[s][c]) * k;
                sum = sum + t;
            }
            volatile float avg = sum * 0.25f;
            volatile float sc = avg * 255.0f;
            ASSERT_EQ(out[c], uint8_t(std::nearbyint(sc))) << int(v[0]) << " " << int(v[1]);
            // and it is the integer average to within one code (it differs from (sum+2)/4 sometimes)
            const int isum = px[0][c] + px[1][c] + px[2][c] + px[3][c];
            ASSERT_LE(std::abs(int(out[c]) * 4 - isum), 4);
        }
    };
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; ++b) {
            const uint8_t v[4] = {uint8_t(a), uint8_t(b), 17, 200};
            check(v);
        }
    for (int i = 0; i < 100000; ++i) {
        const uint8_t v[4] = {uint8_t(rng()), uint8_t(rng()), uint8_t(rng()), uint8_t(rng())};
        check(v);
    }
}

// resolve_rect copies a UNORM8 pixel whose four samples are equal (msaa.cpp): that is only right because the
// resolve of four equal bytes u, computed as lavapipe does, is u for every u.
TEST(FragmentMsaa, ResolveOfEqualSamplesIsTheSample) {
    const float k = float(1.0 / 255.0);
    for (int u = 0; u < 256; ++u) {
        volatile float sum = 0.0f;
        for (int s = 0; s < 4; ++s) {
            volatile float t = float(u) * k;
            sum = sum + t;
        }
        volatile float avg = std::min(1.0f, sum * 0.25f);
        volatile float sc = avg * 255.0f;
        ASSERT_EQ(int(std::nearbyint(sc)), u);
        const uint8_t px[4] = {uint8_t(u), uint8_t(u), uint8_t(u), uint8_t(u)};
        const uint8_t* p[4] = {px, px, px, px};
        uint8_t out[4];
        ASSERT_TRUE(resolve_pixel(ColorFormat::R8G8B8A8_UNORM, p, out, true));
        ASSERT_EQ(out[0], u);
    }
}

// resolve_rect's row path for formats made of UNORM8 bytes is a twin of resolve_pixel: equal on every pixel, in
// the icd/ layout (a pixel's samples adjacent) and in sample planes, with padding between rows.
TEST(FragmentMsaa, ResolveRectEqualsResolvePixel) {
    const Isa before = kernel_isa();
    std::mt19937 rng(7);
    const ColorFormat formats[] = {ColorFormat::R8G8B8A8_UNORM,     ColorFormat::B8G8R8A8_UNORM,
                                   ColorFormat::R8_UNORM,           ColorFormat::R8G8_UNORM,
                                   ColorFormat::R8G8B8_UNORM,       ColorFormat::R8G8B8A8_SRGB,
                                   ColorFormat::R16G16B16A16_SFLOAT};
    const int w = 37, h = 5;
    for (ColorFormat f : formats) {
        const size_t bpp = format_info(f).bytes;
        for (bool adjacent : {true, false}) {
            const size_t sample_stride = adjacent ? bpp : size_t(h) * (w * bpp + 3);
            const size_t pitch = adjacent ? w * 4 * bpp + 5 : w * bpp + 3;
            const size_t pixel_stride = adjacent ? 4 * bpp : 0;
            std::vector<uint8_t> src(4 * size_t(h) * (w * 4 * bpp + 5));
            for (uint8_t& b : src) b = uint8_t(rng() % 4 == 0 ? 255 * (rng() & 1) : rng());
            if (f == ColorFormat::R16G16B16A16_SFLOAT)  // finite halves only: keep NaN payloads out of the compare
                for (size_t i = 1; i < src.size(); i += 2) src[i] &= 0x7b;
            // Pixels whose four samples are equal (the copy shortcut), in whole runs of four (one compare), mixed
            // with pixels where only samples 0..m (m = 0..3) are equal.
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const int m = (x / 4 + y) % 3 != 0 ? 3 : int(rng() % 4);
                    uint8_t* s0 = src.data() + y * pitch + x * (adjacent ? pixel_stride : bpp);
                    for (int s = 1; s <= m; ++s) std::memcpy(s0 + s * sample_stride, s0, bpp);
                }
            const size_t dst_pitch = w * bpp + 7;
            std::vector<uint8_t> want(size_t(h) * dst_pitch, 0xcd);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const uint8_t* base = src.data() + y * pitch + x * (adjacent ? pixel_stride : bpp);
                    const uint8_t* p[4] = {base, base + sample_stride, base + 2 * sample_stride,
                                           base + 3 * sample_stride};
                    resolve_pixel(f, p, want.data() + y * dst_pitch + x * bpp, true);
                }
            // Both builds of the eight-pixel step (rast/fragment/resolve_rows.h) and the rows' SSE2 remainder.
            for (const Isa isa : {Isa::kAvx2, Isa::kPortable}) {
                if (!set_kernel_isa_for_testing(isa)) continue;
                std::vector<uint8_t> got(want.size(), 0xcd);
                resolve_rect(f, src.data(), sample_stride, pitch, got.data(), dst_pitch, w, h, true, pixel_stride);
                EXPECT_EQ(got, want) << "format " << int(f) << (adjacent ? " adjacent samples" : " sample planes")
                                     << (isa == Isa::kAvx2 ? " avx2" : " portable");
            }
            set_kernel_isa_for_testing(before);
        }
    }
}

TEST(FragmentMsaa, ResolveFloatFormats) {
    const float s[4] = {1.0f, 2.0f, 1e-8f, 3.0f};
    const uint8_t* p[4];
    float px[4];
    std::memcpy(px, s, sizeof px);
    for (int i = 0; i < 4; ++i) p[i] = reinterpret_cast<const uint8_t*>(&px[i]);
    float out;
    ASSERT_TRUE(resolve_pixel(ColorFormat::R32_SFLOAT, p, reinterpret_cast<uint8_t*>(&out), true));
    volatile float sum = 0.0f;
    for (float v : s) sum = sum + v;
    EXPECT_EQ(out, sum * 0.25f);
    // rect walker uses the sample stride
    float img[4][2] = {{1, 2}, {3, 4}, {5, 6}, {7, 8}};
    float dst[2];
    resolve_rect(ColorFormat::R32_SFLOAT, reinterpret_cast<const uint8_t*>(img), 8, 8, reinterpret_cast<uint8_t*>(dst),
                 8, 2, 1, true);
    EXPECT_EQ(dst[0], 4.0f);
    EXPECT_EQ(dst[1], 5.0f);
}

TEST(FragmentMsaa, ClearColorPacking) {
    uint8_t out[16];
    const float c[4] = {0.5f, 1.0f, -0.2f, 0.25f};
    ASSERT_TRUE(pack_clear_color(ColorFormat::B8G8R8A8_UNORM, c, out));
    EXPECT_EQ(out[0], 0);    // B
    EXPECT_EQ(out[1], 255);  // G
    EXPECT_EQ(out[2], float_to_ubyte(0.5f));
    EXPECT_EQ(out[3], float_to_ubyte(0.25f));
    ASSERT_TRUE(pack_clear_color(ColorFormat::R32G32_SFLOAT, c, out));
    float f[2];
    std::memcpy(f, out, 8);
    EXPECT_EQ(f[0], 0.5f);
    EXPECT_EQ(f[1], 1.0f);
    ASSERT_TRUE(pack_clear_color(ColorFormat::R8G8B8A8_SRGB, c, out));
    EXPECT_EQ(out[1], 255);
    EXPECT_EQ(out[2], 0);
    EXPECT_EQ(out[3], float_to_ubyte(0.25f));  // alpha is linear
}

TEST(FragmentMsaa, SrgbClearEncoderAccuracy) {
    // The table encoder (rygorous' fp32 -> sRGB8) is within 0.6 of the exact curve for every float in [0, 1],
    // and clamps NaN / negatives to 0 and >= 1 to 255.
    for (uint32_t u = 0; u <= 0x3f800000u; u += 37) {
        float x;
        std::memcpy(&x, &u, 4);
        const double e = (x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(double(x), 1 / 2.4) - 0.055) * 255.0;
        ASSERT_LE(std::fabs(linear_to_srgb8_table(x) - e), 0.6) << x;
    }
    EXPECT_EQ(linear_to_srgb8_table(NAN), 0);
    EXPECT_EQ(linear_to_srgb8_table(-1.0f), 0);
    EXPECT_EQ(linear_to_srgb8_table(1.0f), 255);
    EXPECT_EQ(linear_to_srgb8_table(5.0f), 255);
}

TEST(FragmentMsaa, ClearDepthPacking) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> d(0.0, 1.0);
    for (int i = 0; i < 100000; ++i) {
        const double z = d(rng);
        // lrint(z * 65535) in double: nearest, ties to even
        const double t = z * 65535.0;
        const double fl = std::floor(t);
        const double want = (t - fl > 0.5 || (t - fl == 0.5 && std::fmod(fl, 2.0) != 0.0)) ? fl + 1 : fl;
        ASSERT_EQ(pack_clear_depth(DepthFormat::D16, z), uint32_t(want));
    }
    EXPECT_EQ(pack_clear_depth(DepthFormat::D16, 1.0), 0xffffu);
    EXPECT_EQ(pack_clear_depth(DepthFormat::D16, 2.0), 0xffffu);
    EXPECT_EQ(pack_clear_depth(DepthFormat::D16, -1.0), 0u);
    EXPECT_EQ(pack_clear_depth(DepthFormat::X8D24, 1.0), 0xffffffu);
    EXPECT_EQ(pack_clear_depth(DepthFormat::X8D24, 0.5), 8388608u);  // 8388607.5 -> even
    float h = 0.3f;
    uint32_t hb;
    std::memcpy(&hb, &h, 4);
    EXPECT_EQ(pack_clear_depth(DepthFormat::D32F, 0.3), hb);
}
