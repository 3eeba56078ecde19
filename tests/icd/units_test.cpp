// Unit tests of icd/ internals: clear-value packing, the image layout and the generated entry-point table.
#include <gtest/gtest.h>
#include <immintrin.h>

#include <cmath>
#include <cstring>

#include "clear_pack.h"
#include "entrypoints.h"
#include "formats.h"
#include "image.h"

namespace tilevk::icd {
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
    EXPECT_EQ(linear_float_to_srgb8(0.0f), 0);
    EXPECT_EQ(linear_float_to_srgb8(1.0f), 255);
    EXPECT_EQ(linear_float_to_srgb8(-3.0f), 0);
    EXPECT_EQ(linear_float_to_srgb8(7.0f), 255);
    EXPECT_EQ(linear_float_to_srgb8(NAN), 0);
    for (int i = 0; i <= 10000; ++i) {
        double x = i / 10000.0;
        double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
        int exact = int(std::floor(s * 255.0 + 0.5));
        ASSERT_LE(std::abs(int(linear_float_to_srgb8(float(x))) - exact), 1) << x;
    }
}

TEST(ClearPack, DepthPacking) {
    const FormatInfo* d16 = find_format(VK_FORMAT_D16_UNORM);
    ASSERT_NE(d16, nullptr);
    struct Case {
        float z;
        uint16_t want;
    } cases[] = {{0.0f, 0}, {-1.0f, 0}, {1.0f, 65535}, {2.0f, 65535}, {0.5f, 32768}, {0.25f, 16384}};
    // 0.5*65535 = 32767.5 -> lrint (half to even) = 32768; 0.25*65535 = 16383.75 -> 16384.
    for (const Case& c : cases) {
        uint8_t t[4] = {};
        pack_clear_depth(*d16, c.z, t);
        uint16_t v;
        std::memcpy(&v, t, 2);
        EXPECT_EQ(v, c.want) << c.z;
    }
}

TEST(ClearPack, ColorChannelOrder) {
    VkClearColorValue c{};
    c.float32[0] = 1.0f;  // red
    c.float32[3] = 1.0f;
    uint8_t t[16] = {};
    pack_clear_color(*find_format(VK_FORMAT_B8G8R8A8_UNORM), c, t);
    EXPECT_EQ(t[0], 0);  // blue first in memory
    EXPECT_EQ(t[2], 255);
    EXPECT_EQ(t[3], 255);
    pack_clear_color(*find_format(VK_FORMAT_R32G32_SFLOAT), c, t);
    float g;
    std::memcpy(&g, t + 4, 4);
    EXPECT_EQ(g, 0.0f);
}

// Hand-computed: 5x3 RGBA8, 3 levels, 2 layers. Level 0: rows of 20 B, layers of 60 B -> 120 B.
// Level 1 (2x1) at 128: rows 8 B, layers 8 B -> ends at 144. Level 2 (1x1) at 192: 4 B x 2 -> 200 -> size 256.
TEST(ImageLayout, PlainLinearLayout) {
    ImageLayout l = compute_image_layout(*find_format(VK_FORMAT_R8G8B8A8_UNORM), {5, 3, 1}, 3, 2, 1);
    EXPECT_EQ(l.level_offset[0], 0u);
    EXPECT_EQ(l.row_pitch[0], 20u);
    EXPECT_EQ(l.layer_pitch[0], 60u);
    EXPECT_EQ(l.level_offset[1], 128u);
    EXPECT_EQ(l.row_pitch[1], 8u);
    EXPECT_EQ(l.layer_pitch[1], 8u);
    EXPECT_EQ(l.level_offset[2], 192u);
    EXPECT_EQ(l.row_pitch[2], 4u);
    EXPECT_EQ(l.size, 256u);
    // 4 samples: a row of 5 pixels holds 20 texels.
    ImageLayout m = compute_image_layout(*find_format(VK_FORMAT_D32_SFLOAT_S8_UINT), {5, 3, 1}, 1, 1, 4);
    EXPECT_EQ(m.row_pitch[0], 5u * 4u * 8u);
}

TEST(EntryPoints, TableIsSortedAndLevelsFollowTheFirstParameter) {
    size_t n = 0;
    const EntryPoint* e = entry_points(&n);
    ASSERT_GT(n, 100u);
    for (size_t i = 1; i < n; ++i) EXPECT_LT(std::strcmp(e[i - 1].name, e[i].name), 0);
    struct Case {
        const char* name;
        EntryLevel level;
    } cases[] = {{"vkCreateInstance", EntryLevel::kGlobal},
                 {"vkGetInstanceProcAddr", EntryLevel::kGlobal},
                 {"vkEnumerateInstanceExtensionProperties", EntryLevel::kGlobal},
                 {"vkDestroyInstance", EntryLevel::kInstance},
                 {"vkEnumeratePhysicalDevices", EntryLevel::kInstance},
                 {"vkCreateDevice", EntryLevel::kPhysicalDevice},
                 {"vkGetPhysicalDeviceFormatProperties", EntryLevel::kPhysicalDevice},
                 {"vkGetDeviceProcAddr", EntryLevel::kDevice},
                 {"vkQueueSubmit", EntryLevel::kDevice},
                 {"vkCmdCopyBuffer", EntryLevel::kDevice}};
    for (const Case& c : cases) {
        const EntryPoint* p = find_entry_point(c.name);
        ASSERT_NE(p, nullptr) << c.name;
        EXPECT_EQ(p->level, c.level) << c.name;
        EXPECT_EQ(p->core_version, VK_MAKE_API_VERSION(0, 1, 0, 0)) << c.name;
    }
    EXPECT_NE(find_entry_point("vkCmdBlitImage"), nullptr);
    EXPECT_NE(find_entry_point("vkCmdDispatch"), nullptr);  // exists: logs that there is no compute, does nothing
    EXPECT_EQ(find_entry_point("vkCmdDrawIndirectCount"), nullptr);  // Vulkan 1.2: not in the table
    EXPECT_EQ(find_entry_point(nullptr), nullptr);
}

}  // namespace
}  // namespace tilevk::icd
