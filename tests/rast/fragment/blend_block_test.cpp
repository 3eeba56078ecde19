// blend_block (state prepared once per block, opaque RGBA8/BGRA8 fast path) must write exactly the bytes that
// blend_pixel writes lane by lane, for every format, random blend states, write masks, lane masks and sources
// (including NaN, +-Inf, denormals and out-of-range values).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rast/fragment/blend.h"

using namespace tilevk::rast::fragment;

namespace {

constexpr ColorFormat kFormats[] = {
    ColorFormat::R8G8B8A8_UNORM,      ColorFormat::B8G8R8A8_UNORM, ColorFormat::R8G8B8A8_SRGB,
    ColorFormat::B8G8R8A8_SRGB,       ColorFormat::R8_UNORM,       ColorFormat::R8G8_UNORM,
    ColorFormat::R16G16B16A16_SFLOAT, ColorFormat::R32_SFLOAT,     ColorFormat::R32G32_SFLOAT,
    ColorFormat::R32G32B32A32_SFLOAT,
};

float random_src(std::mt19937& rng) {
    switch (rng() % 10) {
        case 0:
            return std::numeric_limits<float>::quiet_NaN();
        case 1:
            return (rng() & 1) ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
        case 2:
            return 1e-40f;  // denormal
        case 3:
            return std::uniform_real_distribution<float>(-3.0f, 3.0f)(rng);
        default:
            return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
    }
}

}  // namespace

TEST(FragmentBlendBlock, MatchesPerPixelForAllFormatsAndStates) {
    std::mt19937 rng(1234);
    int fast_cases = 0;
    for (ColorFormat f : kFormats) {
        const size_t bytes = format_info(f).bytes;
        const size_t pitch = 4 * bytes + 8;  // padding between rows must stay untouched
        for (int iter = 0; iter < 400; ++iter) {
            BlendAttachment a;
            a.blend_enable = (iter % 3) != 0;
            auto factor = [&] { return BlendFactor(rng() % 15); };  // Zero..SrcAlphaSaturate (no dual source)
            a.src_color = factor();
            a.dst_color = factor();
            a.src_alpha = factor();
            a.dst_alpha = factor();
            a.color_op = BlendOp(rng() % 5);
            a.alpha_op = BlendOp(rng() % 5);
            a.write_mask = (iter % 2) ? 0xf : uint8_t(rng() % 16);
            float k[4];
            for (float& c : k) c = random_src(rng);
            float src[4][kBlockLanes];
            for (auto& ch : src)
                for (float& v : ch) v = random_src(rng);
            const uint16_t lanes = (iter % 4 == 0) ? 0xffff : uint16_t(rng());
            BlendOptions opt;
            opt.fused = (iter % 5) != 0;
            opt.unorm_path = (iter % 7 == 0) ? UnormPath::Sse4 : UnormPath::Avx8;

            std::vector<uint8_t> dst(pitch * 4);
            for (auto& b : dst) b = uint8_t(rng());
            if (format_info(f).kind == ChannelKind::Float32 || format_info(f).kind == ChannelKind::Half)
                for (auto& b : dst) b &= 0x3f;  // mostly finite stored floats
            std::vector<uint8_t> expect = dst;
            for (int l = 0; l < kBlockLanes; ++l) {
                if (!(lanes & (1u << l))) continue;
                const float s[4] = {src[0][l], src[1][l], src[2][l], src[3][l]};
                blend_pixel(a, f, k, s, expect.data() + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * bytes, opt);
            }
            blend_block(a, f, k, src, lanes, dst.data(), pitch, opt);
            ASSERT_EQ(dst, expect) << "format " << int(f) << " iter " << iter;
            if (!a.blend_enable && a.write_mask == 0xf && bytes == 4 && format_info(f).kind == ChannelKind::Unorm8)
                ++fast_cases;
        }
    }
    EXPECT_GT(fast_cases, 100);  // the opaque RGBA8/BGRA8 fast path was exercised
}

TEST(FragmentBlendBlock, OpaqueRgba8WritesConvertedSourceInMemoryOrder) {
    // independent expectation: u8 = sat(rne(min(1,x)*255)), B8G8R8A8 stores B first
    const float src[4][kBlockLanes] = {{0.0f}, {0.5f}, {1.0f}, {0.25f}};
    uint8_t px[64] = {};
    BlendAttachment a;
    blend_block(a, ColorFormat::B8G8R8A8_UNORM, src[0], src, 1, px, 16);
    EXPECT_EQ(px[0], 255);  // B
    EXPECT_EQ(px[1], 128);  // G: rne(127.5) = 128
    EXPECT_EQ(px[2], 0);    // R
    EXPECT_EQ(px[3], 64);   // A: rne(63.75)
    EXPECT_EQ(px[4], 0);    // lane 1 untouched
}
