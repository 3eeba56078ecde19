// Blending: 8-bit arithmetic against exact rationals, the R8 lerp against the CPU's PMULHRSW, every factor/op
// against a spec-style reference that applies lavapipe's documented rewrites, float shortcuts, masks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "rast/fragment/blend.h"

using namespace tilevk::rast::fragment;

TEST(FragmentBlend, MulNormExhaustive) {
    int near_half = 0;
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; ++b) {
            const uint32_t p = uint32_t(a * b);
            // defining formula (lp_build_mul_norm with 16-bit lanes)
            uint32_t q = p + (p >> 8);
            q += 0x80;
            ASSERT_EQ(mul_norm8(uint8_t(a), uint8_t(b)), uint8_t(q >> 8));
            // exact rational: round(a*b/255) to nearest, except sometimes when the fraction is 128/255 (just
            // above 1/2), where mul_norm may round down (24 ordered pairs).
            const uint32_t fl = p / 255, rem = p % 255;
            const uint32_t nearest = rem * 2 > 255 ? fl + 1 : fl;
            if (rem == 128) {
                const uint8_t m = mul_norm8(uint8_t(a), uint8_t(b));
                ASSERT_TRUE(m == fl || m == fl + 1) << a << "*" << b;
                near_half += m == fl;
            } else {
                ASSERT_EQ(mul_norm8(uint8_t(a), uint8_t(b)), nearest) << a << "*" << b;
            }
        }
    EXPECT_EQ(near_half, 24);
    for (int a = 0; a < 256; ++a) {
        EXPECT_EQ(mul_norm8(uint8_t(a), 255), a);  // ONE is exact, so the ONE shortcut is invisible in 8 bits
        EXPECT_EQ(mul_norm8(uint8_t(a), 0), 0);
    }
}

#if defined(__x86_64__)
__attribute__((target("ssse3"))) static uint8_t lerp_hw(uint8_t x, uint8_t v0, uint8_t v1) {
    // lavapipe: x16 = x + (x >> 7); delta = v1 - v0 (16-bit); res = pmulhrsw(x16, delta << 7) & 0xff; (v0 + res) & 0xff
    const int16_t x16 = int16_t(x + (x >> 7));
    const int16_t delta = int16_t(v1 - v0);
    const __m128i r = _mm_mulhrs_epi16(_mm_set1_epi16(x16), _mm_set1_epi16(int16_t(delta << 7)));
    const int16_t res = int16_t(_mm_extract_epi16(r, 0)) & 0xff;
    return uint8_t((v0 + res) & 0xff);
}

TEST(FragmentBlend, Lerp8MatchesPmulhrswExhaustive) {
    for (int x = 0; x < 256; ++x)
        for (int v0 = 0; v0 < 256; ++v0)
            for (int v1 = 0; v1 < 256; ++v1)
                ASSERT_EQ(lerp8(uint8_t(x), uint8_t(v0), uint8_t(v1)), lerp_hw(uint8_t(x), uint8_t(v0), uint8_t(v1)))
                    << x << " " << v0 << " " << v1;
}
#endif

TEST(FragmentBlend, Lerp8EndpointsAndDifferenceFromMulNorm) {
    int differs = 0;
    for (int v0 = 0; v0 < 256; ++v0)
        for (int v1 = 0; v1 < 256; ++v1) {
            ASSERT_EQ(lerp8(255, uint8_t(v0), uint8_t(v1)), v1);
            ASSERT_EQ(lerp8(0, uint8_t(v0), uint8_t(v1)), v0);
            for (int x = 1; x < 255; x += 17) {
                const int generic =
                    std::min(255, mul_norm8(uint8_t(v1), uint8_t(x)) + mul_norm8(uint8_t(v0), uint8_t(255 - x)));
                differs += lerp8(uint8_t(x), uint8_t(v0), uint8_t(v1)) != generic;
            }
        }
    EXPECT_GT(differs, 0);  // the R8 quirk is observable
}

// ---------------------------------------------------------------------------------------------------------------
// Spec-style UNORM8 reference with lavapipe's rewrites, written independently of blend.cpp.

static int u8(float x) {  // the documented conversion (AVX path)
    if (std::isnan(x)) return 0;
    double a = std::min(double(x), 1.0);
    double p = double(float(a * 255.0));
    double r = std::nearbyint(p);
    return int(std::clamp(r, 0.0, 255.0));
}
static int mn(int a, int b) {  // exact rational nearest; fraction 128/255 falls back to the formula (tested above)
    const int p = a * b, q = p / 255, r = p % 255;
    if (r == 128) return (p + (p >> 8) + 0x80) >> 8;
    return r * 2 > 255 ? q + 1 : q;
}

struct RefPixel {
    int s[4], d[4], k[4];
};

static int ref_factor(BlendFactor f, int c, bool alpha_chan, bool has_alpha, const RefPixel& p) {
    const int sa = p.s[3], da = has_alpha ? p.d[3] : 255, ka = p.k[3];
    switch (f) {
        case BlendFactor::Zero:
            return 0;
        case BlendFactor::One:
            return 255;
        case BlendFactor::SrcColor:
            return p.s[c];
        case BlendFactor::OneMinusSrcColor:
            return 255 - p.s[c];
        case BlendFactor::DstColor:
            return p.d[c];
        case BlendFactor::OneMinusDstColor:
            return 255 - p.d[c];
        case BlendFactor::SrcAlpha:
            return sa;
        case BlendFactor::OneMinusSrcAlpha:
            return 255 - sa;
        case BlendFactor::DstAlpha:
            return da;
        case BlendFactor::OneMinusDstAlpha:
            return 255 - da;
        case BlendFactor::ConstantColor:
            return p.k[c];
        case BlendFactor::OneMinusConstantColor:
            return 255 - p.k[c];
        case BlendFactor::ConstantAlpha:
            return ka;
        case BlendFactor::OneMinusConstantAlpha:
            return 255 - ka;
        case BlendFactor::SrcAlphaSaturate:
            return alpha_chan ? 255 : std::min(sa, 255 - da);
        default:
            return -1;
    }
}

static int ref_op(BlendOp op, int s, int d) {
    switch (op) {
        case BlendOp::Add:
            return std::min(255, s + d);
        case BlendOp::Subtract:
            return std::max(0, s - d);
        case BlendOp::ReverseSubtract:
            return std::max(0, d - s);
        case BlendOp::Min:
            return std::min(s, d);
        case BlendOp::Max:
            return std::max(s, d);
    }
    return -1;
}

static bool complementary(BlendFactor a, BlendFactor b) {
    // Zero<->One, X <-> OneMinusX (VkBlendFactor pairs), except the pair (Zero, One) ordering is symmetric
    auto inv = [](BlendFactor f) -> int {
        switch (f) {
            case BlendFactor::Zero:
                return int(BlendFactor::One);
            case BlendFactor::One:
                return int(BlendFactor::Zero);
            case BlendFactor::SrcColor:
                return int(BlendFactor::OneMinusSrcColor);
            case BlendFactor::SrcAlpha:
                return int(BlendFactor::OneMinusSrcAlpha);
            case BlendFactor::DstColor:
                return int(BlendFactor::OneMinusDstColor);
            case BlendFactor::DstAlpha:
                return int(BlendFactor::OneMinusDstAlpha);
            case BlendFactor::ConstantColor:
                return int(BlendFactor::OneMinusConstantColor);
            case BlendFactor::ConstantAlpha:
                return int(BlendFactor::OneMinusConstantAlpha);
            default:
                return -1;
        }
    };
    return inv(a) == int(b) || inv(b) == int(a);
}

static bool is_inverse(BlendFactor f) {
    return f == BlendFactor::Zero || f == BlendFactor::OneMinusSrcColor || f == BlendFactor::OneMinusSrcAlpha ||
           f == BlendFactor::OneMinusDstColor || f == BlendFactor::OneMinusDstAlpha ||
           f == BlendFactor::OneMinusConstantColor || f == BlendFactor::OneMinusConstantAlpha;
}

static void ref_blend_unorm8(const BlendAttachment& a0, const FormatInfo& fi, const RefPixel& p, int out[4]) {
    BlendAttachment a = a0;
    const int n = fi.channels;
    if (!fi.has_alpha) {
        auto fix = [](BlendFactor f) {
            if (f == BlendFactor::DstAlpha) return BlendFactor::One;
            if (f == BlendFactor::OneMinusDstAlpha) return BlendFactor::Zero;
            if (f == BlendFactor::SrcAlphaSaturate) return BlendFactor::Zero;
            return f;
        };
        a.src_color = fix(a.src_color);
        a.dst_color = fix(a.dst_color);
    }
    for (int c = 0; c < 4; ++c) out[c] = p.s[c];
    if (!a.blend_enable) return;
    if (n == 1 && a.color_op == BlendOp::Add && complementary(a.src_color, a.dst_color)) {
        // lerp toward the non-inverse factor's operand
        if (!is_inverse(a.src_color))
            out[0] = lerp8(uint8_t(ref_factor(a.src_color, 0, false, false, p)), uint8_t(p.d[0]), uint8_t(p.s[0]));
        else
            out[0] = lerp8(uint8_t(ref_factor(a.dst_color, 0, false, false, p)), uint8_t(p.s[0]), uint8_t(p.d[0]));
        return;
    }
    for (int c = 0; c < n; ++c) {
        const bool ac = fi.has_alpha && c == 3;
        const BlendOp op = ac ? a.alpha_op : a.color_op;
        if (op == BlendOp::Min || op == BlendOp::Max) {
            out[c] = ref_op(op, p.s[c], p.d[c]);  // factors ignored
            continue;
        }
        const int sf = ref_factor(ac ? a.src_alpha : a.src_color, c, ac, fi.has_alpha, p);
        const int df = ref_factor(ac ? a.dst_alpha : a.dst_color, c, ac, fi.has_alpha, p);
        out[c] = ref_op(op, mn(p.s[c], sf), mn(p.d[c], df));
    }
}

static int mem_index(const FormatInfo& fi, int c) {
    return (fi.bgra && c < 3) ? 2 - c : c;
}

TEST(FragmentBlend, Unorm8EveryFactorAndOpAgainstReference) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> d01(-0.1f, 1.1f);
    const ColorFormat formats[] = {ColorFormat::R8G8B8A8_UNORM, ColorFormat::B8G8R8A8_UNORM, ColorFormat::R8G8_UNORM,
                                   ColorFormat::R8_UNORM};
    long checked = 0;
    for (ColorFormat f : formats) {
        const FormatInfo fi = format_info(f);
        for (int sf = 0; sf <= int(BlendFactor::SrcAlphaSaturate); ++sf)
            for (int df = 0; df <= int(BlendFactor::SrcAlphaSaturate); ++df)
                for (int op = 0; op < 5; ++op)
                    for (int rep = 0; rep < 6; ++rep) {
                        BlendAttachment a;
                        a.blend_enable = true;
                        a.src_color = BlendFactor(sf);
                        a.dst_color = BlendFactor(df);
                        a.color_op = BlendOp(op);
                        a.src_alpha = BlendFactor((sf + rep) % 15);
                        a.dst_alpha = BlendFactor((df + 3 * rep) % 15);
                        a.alpha_op = BlendOp((op + rep) % 5);
                        if (!fi.has_alpha) {  // lavapipe uses the colour equation for alpha-less formats
                            a.src_alpha = a.src_color;
                            a.dst_alpha = a.dst_color;
                            a.alpha_op = a.color_op;
                        }
                        float src[4], k[4];
                        RefPixel p;
                        uint8_t px[4];
                        for (int c = 0; c < 4; ++c) {
                            src[c] = d01(rng);
                            k[c] = d01(rng);
                            p.s[c] = u8(src[c]);
                            p.k[c] = u8(k[c]);
                            p.d[c] = int(rng() & 255);
                        }
                        for (int c = 0; c < fi.channels; ++c) px[mem_index(fi, c)] = uint8_t(p.d[c]);
                        int want[4];
                        ref_blend_unorm8(a, fi, p, want);
                        blend_pixel(a, f, k, src, px);
                        for (int c = 0; c < fi.channels; ++c)
                            ASSERT_EQ(px[mem_index(fi, c)], want[c])
                                << "fmt " << int(f) << " sf " << sf << " df " << df << " op " << op << " c " << c;
                        ++checked;
                    }
    }
    EXPECT_GT(checked, 20000);
}

TEST(FragmentBlend, WriteMaskAndLaneMask) {
    BlendAttachment a;  // blending off: plain conversion
    a.write_mask = kWriteR | kWriteA;
    float src[4][16];
    for (int c = 0; c < 4; ++c)
        for (int l = 0; l < 16; ++l) src[c][l] = 0.5f;
    uint8_t img[4 * 16 * 4];
    std::memset(img, 7, sizeof img);
    const float k[4] = {};
    const uint16_t lanes = uint16_t(1u << lane_of(2, 1));
    blend_block(a, ColorFormat::R8G8B8A8_UNORM, k, src, lanes, img, 16, {});
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 4; ++c) {
                const bool written = x == 2 && y == 1 && (c == 0 || c == 3);
                EXPECT_EQ(img[y * 16 + x * 4 + c], written ? 128 : 7);
            }
}

// Dual-source blending on a UNORM8 target: ONE * src + SRC1_COLOR * dst per channel, computed here with the
// defining 8-bit formulas (sources converted to bytes first; ADD saturates); alpha with ONE_MINUS_SRC1_ALPHA.
TEST(FragmentBlend, SecondSourceFactorsUnorm8) {
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = BlendFactor::One;
    a.dst_color = BlendFactor::Src1Color;
    a.src_alpha = BlendFactor::One;
    a.dst_alpha = BlendFactor::OneMinusSrc1Alpha;
    auto mul = [](uint32_t x, uint32_t y) {
        uint32_t p = x * y;
        p += p >> 8;
        return (p + 0x80) >> 8;
    };
    const float constants[4] = {};
    float src[4][kBlockLanes] = {}, src1[4][kBlockLanes] = {};
    uint8_t img[4 * 16] = {};
    for (int l = 0; l < kBlockLanes; ++l)
        for (int c = 0; c < 4; ++c) {
            src[c][l] = float(l * 4 + c) / 255.0f;          // converts to exactly l*4+c
            src1[c][l] = float(255 - 13 * l - c) / 255.0f;  // exactly 255-13l-c
            img[lane_y(l) * 16 + lane_x(l) * 4 + c] = uint8_t(200 - 7 * l + c);
        }
    uint8_t before[sizeof img];
    std::memcpy(before, img, sizeof img);
    blend_block(a, ColorFormat::R8G8B8A8_UNORM, constants, src, 0xffff, img, 16, {}, src1);
    for (int l = 0; l < kBlockLanes; ++l)
        for (int c = 0; c < 4; ++c) {
            const uint32_t s = uint32_t(l * 4 + c), s1 = uint32_t(255 - 13 * l - c);
            const uint32_t d = before[lane_y(l) * 16 + lane_x(l) * 4 + c];
            const uint32_t dst_factor = c < 3 ? s1 : 255 - uint32_t(255 - 13 * l - 3);
            const uint32_t want = std::min<uint32_t>(255, mul(s, 255) + mul(d, dst_factor));
            ASSERT_EQ(img[lane_y(l) * 16 + lane_x(l) * 4 + c], want) << "lane " << l << " channel " << c;
        }
    // Without the second source the factor reads zeros: only the source term remains.
    std::memcpy(img, before, sizeof img);
    blend_block(a, ColorFormat::R8G8B8A8_UNORM, constants, src, 0xffff, img, 16);
    for (int l = 0; l < kBlockLanes; ++l) EXPECT_EQ(img[lane_y(l) * 16 + lane_x(l) * 4], l * 4) << "lane " << l;
}

TEST(FragmentBlend, SecondSourceOnlyWhenBlending) {
    BlendAttachment a;
    a.blend_enable = true;
    EXPECT_FALSE(uses_second_source(a));
    a.dst_alpha = BlendFactor::OneMinusSrc1Alpha;
    EXPECT_TRUE(uses_second_source(a));
    a.logic_op_enable = true;  // a logic op replaces blending
    EXPECT_FALSE(uses_second_source(a));
    a.logic_op_enable = false;
    a.blend_enable = false;
    EXPECT_FALSE(uses_second_source(a));
}

// ---------------------------------------------------------------------------------------------------------------
// Float targets

static float fl_mul(float a, float b) {
    volatile float r = a * b;
    return r;
}
static float fl_add(float a, float b) {
    volatile float r = a + b;
    return r;
}

TEST(FragmentBlend, Float32GeneralAndSharedFactorShapes) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> d(-2.0f, 2.0f);
    int shared_differs = 0;
    for (int i = 0; i < 20000; ++i) {
        float src[4], dst[4], k[4] = {0.3f, 0.6f, 0.9f, 0.45f};
        for (int c = 0; c < 4; ++c) {
            src[c] = d(rng);
            dst[c] = d(rng);
        }
        // General: SRC_ALPHA, ONE_MINUS_SRC_ALPHA, ADD -> fl(fl(s*a) + fl(d*fl(1-a)))
        {
            BlendAttachment a;
            a.blend_enable = true;
            a.src_color = a.src_alpha = BlendFactor::SrcAlpha;
            a.dst_color = a.dst_alpha = BlendFactor::OneMinusSrcAlpha;
            uint8_t px[16];
            std::memcpy(px, dst, 16);
            blend_pixel(a, ColorFormat::R32G32B32A32_SFLOAT, k, src, px);
            float out[4];
            std::memcpy(out, px, 16);
            const float inv = fl_add(1.0f, -src[3]);
            for (int c = 0; c < 4; ++c) ASSERT_EQ(out[c], fl_add(fl_mul(src[c], src[3]), fl_mul(dst[c], inv)));
        }
        // Shared factor (src == dst factor): lavapipe computes fl(fl(s + d) * f)
        {
            BlendAttachment a;
            a.blend_enable = true;
            a.src_color = a.dst_color = a.src_alpha = a.dst_alpha = BlendFactor::ConstantColor;
            uint8_t px[16];
            std::memcpy(px, dst, 16);
            blend_pixel(a, ColorFormat::R32G32B32A32_SFLOAT, k, src, px);
            float out[4];
            std::memcpy(out, px, 16);
            for (int c = 0; c < 4; ++c) {
                ASSERT_EQ(out[c], fl_mul(fl_add(src[c], dst[c]), k[c]));
                shared_differs += out[c] != fl_add(fl_mul(src[c], k[c]), fl_mul(dst[c], k[c]));
            }
        }
    }
    EXPECT_GT(shared_differs, 0);
}

TEST(FragmentBlend, Float32SingleChannelComplementaryLerp) {
    // R32F, SRC_ALPHA / ONE_MINUS_SRC_ALPHA, ADD -> fmuladd(a, fl(s - d), d) (fused on FMA CPUs)
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> d(-2.0f, 2.0f);
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = a.src_alpha = BlendFactor::SrcAlpha;
    a.dst_color = a.dst_alpha = BlendFactor::OneMinusSrcAlpha;
    const float k[4] = {};
    for (int i = 0; i < 20000; ++i) {
        const float s[4] = {d(rng), 0, 0, d(rng)};
        const float dv = d(rng);
        for (bool fused : {true, false}) {
            uint8_t px[4];
            std::memcpy(px, &dv, 4);
            BlendOptions o;
            o.fused = fused;
            blend_pixel(a, ColorFormat::R32_SFLOAT, k, s, px, o);
            float out;
            std::memcpy(&out, px, 4);
            const float delta = fl_add(s[0], -dv);
            const float want = fused ? std::fma(s[3], delta, dv) : fl_add(fl_mul(s[3], delta), dv);
            ASSERT_EQ(out, want);
        }
    }
    // ONE/ZERO on R32F goes through the lerp too: fl(fl(s - d) + d), which is not always s
    a.src_color = BlendFactor::One;
    a.dst_color = BlendFactor::Zero;
    const float s[4] = {1e-8f, 0, 0, 1};
    const float dv = 1.0f;
    uint8_t px[4];
    std::memcpy(px, &dv, 4);
    blend_pixel(a, ColorFormat::R32_SFLOAT, k, s, px);
    float out;
    std::memcpy(&out, px, 4);
    EXPECT_EQ(out, 0.0f);
}

TEST(FragmentBlend, FloatZeroFactorShortcutAvoidsNan) {
    // ONE/ZERO on RGBA32F: the ZERO vector skips the multiply, so an Inf destination does not produce NaN.
    BlendAttachment a;
    a.blend_enable = true;
    const float k[4] = {};
    const float src[4] = {0.25f, 0.5f, 0.75f, 1.0f};
    float dst[4] = {INFINITY, -INFINITY, NAN, 1.0f};
    uint8_t px[16];
    std::memcpy(px, dst, 16);
    blend_pixel(a, ColorFormat::R32G32B32A32_SFLOAT, k, src, px);
    float out[4];
    std::memcpy(out, px, 16);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(out[c], src[c]);
}

TEST(FragmentBlend, HalfStoresRoundTowardZero) {
    BlendAttachment a;  // no blending
    const float k[4] = {};
    const float src[4] = {1.0f + 0x1p-11f + 0x1p-13f, 70000.0f, -1.0f - 0x1p-11f - 0x1p-13f, 0.5f};
    uint16_t px[4];
    blend_pixel(a, ColorFormat::R16G16B16A16_SFLOAT, k, src, reinterpret_cast<uint8_t*>(px));
    EXPECT_EQ(px[0], 0x3c00u);  // 1 + 1.25 ulp(half) truncates to 1.0
    EXPECT_EQ(px[1], 0x7bffu);  // overflow -> max finite toward zero
    EXPECT_EQ(px[2], 0xbc00u);
    EXPECT_EQ(px[3], 0x3800u);
}

TEST(FragmentBlend, SrgbBlendsInLinearFloat) {
    // SRC_ALPHA / ONE_MINUS_SRC_ALPHA on sRGB: decode dst, blend in float, encode with the rsqrt approximation.
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = a.src_alpha = BlendFactor::SrcAlpha;
    a.dst_color = a.dst_alpha = BlendFactor::OneMinusSrcAlpha;
    const float k[4] = {};
    std::mt19937 rng(8);
    for (int i = 0; i < 5000; ++i) {
        float src[4];
        for (float& v : src) v = float(rng() % 1000) / 999.0f;
        uint8_t px[4];
        for (uint8_t& v : px) v = uint8_t(rng());
        float d[4];
        for (int c = 0; c < 3; ++c) d[c] = srgb8_to_linear(px[c], true);
        d[3] = unorm8_to_float(px[3]);
        const float inv = fl_add(1.0f, -src[3]);
        blend_pixel(a, ColorFormat::R8G8B8A8_SRGB, k, src, px);
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(px[c], linear_to_srgb8(fl_add(fl_mul(src[c], src[3]), fl_mul(d[c], inv)), true));
        ASSERT_EQ(px[3], srgb_alpha_to_u8(fl_add(fl_mul(src[3], src[3]), fl_mul(d[3], inv))));
    }
}
