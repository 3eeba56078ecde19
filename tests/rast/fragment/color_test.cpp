// Colour conversions against independent definitions (double arithmetic) and the CPU's own F16C instructions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "rast/fragment/color.h"

using namespace tilevk::rast::fragment;

static float bf(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
static double rne(double v) {
    const double f = std::floor(v);
    const double r = v - f;
    if (r > 0.5) return f + 1;
    if (r < 0.5) return f;
    return std::fmod(f, 2.0) == 0.0 ? f : f + 1;
}

// The rule: u8 = sat(rne(fl(min(1,x) * 255))), NaN -> 0; Sse4 path: no min, fl(x*255) >= 2^31 -> 0.
static int expect_unorm8(float x, UnormPath path) {
    if (std::isnan(x)) return 0;
    double a = x;
    if (path == UnormPath::Avx8 && a > 1.0) a = 1.0;
    const double p = double(float(a * 255.0));  // a*255 is exact in double; one float rounding
    if (p >= 2147483648.0) return 0;
    const double r = rne(p);
    return r < 0 ? 0 : r > 255 ? 255 : int(r);
}

TEST(FragmentColor, FloatToUnorm8AllPaths) {
    for (uint64_t u = 0; u <= 0xffffffffull; u += 997) {
        const float x = bf(uint32_t(u));
        ASSERT_EQ(float_to_unorm8(x, UnormPath::Avx8), expect_unorm8(x, UnormPath::Avx8)) << x;
        ASSERT_EQ(float_to_unorm8(x, UnormPath::Sse4), expect_unorm8(x, UnormPath::Sse4)) << x;
    }
    // Midpoints: 0.5/255 scaled gives exactly 0.5 -> 0; 1.5/255 -> 2 (ties to even)
    EXPECT_EQ(float_to_unorm8(INFINITY, UnormPath::Avx8), 255);
    EXPECT_EQ(float_to_unorm8(INFINITY, UnormPath::Sse4), 0);
    EXPECT_EQ(float_to_unorm8(-INFINITY), 0);
    EXPECT_EQ(float_to_unorm8(NAN), 0);
    EXPECT_EQ(float_to_unorm8(0.5f), 128);  // 127.5 -> 128 (even)
    EXPECT_EQ(float_to_unorm8(2.5f / 255.0f), expect_unorm8(2.5f / 255.0f, UnormPath::Avx8));
}

TEST(FragmentColor, Unorm8ToFloatMultipliesByRoundedReciprocal) {
    const double k = double(float(1.0 / 255.0));
    int differs_from_division = 0;
    for (int u = 0; u < 256; ++u) {
        ASSERT_EQ(unorm8_to_float(uint8_t(u)), float(u * k));
        differs_from_division += unorm8_to_float(uint8_t(u)) != float(u) / 255.0f;
    }
    EXPECT_GT(differs_from_division, 0);  // the multiply is observably not a division
    EXPECT_EQ(unorm8_to_float(0), 0.0f);
}

TEST(FragmentColor, ClearFloatToUbyte) {
    for (uint32_t u = 0; u < 0x3f800000u; u += 13) {
        const float f = bf(u);
        const double t = double(float(double(f) * (255.0 / 256.0)));  // exact product, one rounding
        // adding 32768 rounds t to a multiple of 2^-8: the low byte is rne(t*256)
        ASSERT_EQ(float_to_ubyte(f), int(rne(t * 256.0)) & 0xff) << f;
    }
    EXPECT_EQ(float_to_ubyte(1.0f), 255);
    EXPECT_EQ(float_to_ubyte(7.0f), 255);
    EXPECT_EQ(float_to_ubyte(-1.0f), 0);
    EXPECT_EQ(float_to_ubyte(NAN), 0);
    EXPECT_EQ(float_to_ubyte(0.5f), 128);
}

static double exact_srgb_encode(double x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

TEST(FragmentColor, SrgbRoundTripAndAccuracyOnThisCpu) {
    for (bool fused : {true, false}) {
        float prev = -1.0f;
        for (int u = 0; u < 256; ++u) {
            const float lin = srgb8_to_linear(uint8_t(u), fused);
            ASSERT_GT(lin, prev);  // strictly increasing
            prev = lin;
            // Mesa requires every sRGB value to map back to itself through its two approximations.
            ASSERT_EQ(linear_to_srgb8(lin, fused), u) << "fused=" << fused;
        }
        // Encode error: Mesa states +-0.17 before rounding, so the rounded code is within 0.67 of exact.
        for (int i = 0; i <= 100000; ++i) {
            const float x = float(i) / 100000.0f;
            const double exact = exact_srgb_encode(x) * 255.0;
            ASSERT_LE(std::fabs(linear_to_srgb8(x, fused) - exact), 0.67) << x;
        }
    }
    EXPECT_EQ(linear_to_srgb8(NAN, true), 255);  // clamp: min(NaN, 1) -> 1
    EXPECT_EQ(linear_to_srgb8(-3.0f, true), 0);
    EXPECT_EQ(srgb_alpha_to_u8(NAN), 0);
    EXPECT_EQ(srgb_alpha_to_u8(0.5f), 128);
    EXPECT_EQ(srgb_alpha_to_u8(2.0f), 255);
}

TEST(FragmentColor, HwRsqrtIsTheApproximation) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> d(1e-6f, 1e6f);
    int inexact = 0;
    for (int i = 0; i < 100000; ++i) {
        const float x = d(rng);
        const double exact = 1.0 / std::sqrt(double(x));
        const double rel = std::fabs(hw_rsqrt(x) - exact) / exact;
        ASSERT_LE(rel, 1.5 * 0x1p-12);  // Intel/AMD documented bound for RSQRTSS
        inexact += float(exact) != hw_rsqrt(x);
    }
    EXPECT_GT(inexact, 0);
}

#if defined(__x86_64__)
__attribute__((target("f16c"))) static uint16_t hw_half(float f, bool rz) {
    const __m128i r =
        rz ? _mm_cvtps_ph(_mm_set_ss(f), _MM_FROUND_TO_ZERO) : _mm_cvtps_ph(_mm_set_ss(f), _MM_FROUND_TO_NEAREST_INT);
    return uint16_t(_mm_extract_epi16(r, 0));
}
__attribute__((target("f16c"))) static float hw_float(uint16_t h) {
    return _mm_cvtss_f32(_mm_cvtph_ps(_mm_cvtsi32_si128(h)));
}

TEST(FragmentColor, HalfConversionsMatchF16c) {
    if (!__builtin_cpu_supports("f16c")) GTEST_SKIP() << "no F16C on this CPU";
    for (uint64_t u = 0; u <= 0xffffffffull; u += 251) {
        const float f = bf(uint32_t(u));
        ASSERT_EQ(float_to_half_rtz(f), hw_half(f, true)) << std::hex << u;
    }
    for (uint32_t h = 0; h < 65536; ++h) {
        const float a = half_to_float(uint16_t(h)), b = hw_float(uint16_t(h));
        ASSERT_EQ(std::memcmp(&a, &b, 4), 0) << std::hex << h;
    }
}
#endif
