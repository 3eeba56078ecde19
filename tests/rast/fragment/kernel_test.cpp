// The fragment stage's block kernels (block_kernels.h): each AVX2 kernel must give exactly the bytes of its scalar
// twin, and each scalar twin exactly the bytes of the per-lane reference it replaces (interp.h eval_plane /
// perspective_divide, depth_stencil_test, blend_block), on random inputs with NaN, +-Inf, denormals, -0 and
// out-of-range values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rast/core/cpu.h"
#include "rast/fragment/blend.h"
#include "rast/fragment/blend_rgba8.h"
#include "rast/fragment/block_kernels.h"

#if TILEVK_SIMD_AVX2
// Built with the AVX2/FMA translation units' flags: on a CPU without them every test here is skipped.
class RequireAvx2 : public ::testing::Environment {
  public:
    void SetUp() override {
        if (!tilevk::rast::cpu_has_avx2_kernels()) GTEST_SKIP() << "this CPU cannot run the AVX2/FMA kernels";
    }
};
[[maybe_unused]] const auto* const kRequireAvx2 = ::testing::AddGlobalTestEnvironment(new RequireAvx2);
#endif

using namespace tilevk::rast::fragment;

namespace {

float nasty(std::mt19937& rng, float lo, float hi) {
    switch (rng() % 12) {
        case 0: {
            // NaNs of both signs and different payloads: which operand's NaN survives must match too
            uint32_t u = 0x7fc00000u | (rng() & 0x3fffffu) | ((rng() & 1u) << 31);
            float f;
            std::memcpy(&f, &u, 4);
            return f;
        }
        case 1:
            return (rng() & 1) ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
        case 2:
            return (rng() & 1) ? 1e-40f : -1e-40f;  // denormals
        case 3:
            return (rng() & 1) ? 0.0f : -0.0f;
        case 4:
            return std::uniform_real_distribution<float>(-3.0f, 3.0f)(rng);
        case 5:
            return 1.0f;
        default:
            return std::uniform_real_distribution<float>(lo, hi)(rng);
    }
}

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// Bits, except that every NaN reads as one value: when several operands of an operation are NaN, which payload
// survives depends on the instruction form the compiler picked (operand order of VMULSS, VFMADD132/213/231) — in
// the reference loops as much as in the kernels (and in lavapipe's JIT) — so only "NaN" is part of the contract.
uint32_t canonical(float f) {
    return std::isnan(f) ? 0x7fc00000u : bits(f);
}

void expect_same_bits(const float* a, const float* b, const char* what, int iter) {
    for (int l = 0; l < kBlockLanes; ++l)
        ASSERT_EQ(canonical(a[l]), canonical(b[l])) << what << " lane " << l << " iter " << iter;
}

}  // namespace

TEST(FragmentKernels, MaskConversionIsTheLaneOrderPermutation) {
    for (uint32_t m = 0; m < 65536; ++m) {
        uint16_t lanes = 0;  // independent: bit y*4+x -> bit lane_of(x, y)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x)
                if (m & (1u << (y * 4 + x))) lanes |= uint16_t(1u << lane_of(x, y));
        ASSERT_EQ(raster_to_lanes(uint16_t(m)), lanes) << m;
        ASSERT_EQ(lanes_to_raster(lanes), m) << m;
    }
}

TEST(FragmentKernels, PlaneEvaluationMatchesInterp) {
    std::mt19937 rng(11);
    for (int iter = 0; iter < 20000; ++iter) {
        Plane p{nasty(rng, -4, 4), nasty(rng, -4, 4), nasty(rng, -100, 100)};
        if (iter % 3 == 0) p = {std::uniform_real_distribution<float>(-1e-3f, 1e-3f)(rng), 1e-7f, 0.5f};
        const int bx = int(rng() % 4096) * 4, by = int(rng() % 4096) * 4;
        const int samples = (iter & 1) ? 4 : 1, sample = int(rng() % 5) - 1;
        const EvalOffset off = plane_offset(samples, sample);
        const bool fused = (iter % 4) != 0;
        float expect[kBlockLanes], scalar[kBlockLanes];
        eval_plane(p, bx, by, off, fused, expect);
        LaneCoords c;
        make_lane_coords(bx, by, off, c);
        eval_plane_scalar(p, c, fused, scalar);
        expect_same_bits(scalar, expect, "scalar", iter);
#if TILEVK_SIMD_AVX2
        float simd[kBlockLanes];
        eval_plane_avx2(p, c, fused, simd);
        expect_same_bits(simd, expect, "avx2", iter);
#endif
    }
}

TEST(FragmentKernels, HoistedReciprocalMatchesPerspectiveDivide) {
    std::mt19937 rng(12);
    for (int iter = 0; iter < 20000; ++iter) {
        float a[kBlockLanes], w[kBlockLanes];
        for (int l = 0; l < kBlockLanes; ++l) {
            a[l] = nasty(rng, -50, 50);
            w[l] = nasty(rng, 1e-3f, 10);
        }
        float expect[kBlockLanes];
        perspective_divide(a, w, expect);
        float oow[kBlockLanes], scalar[kBlockLanes];
        std::memcpy(scalar, a, sizeof a);
        reciprocal_scalar(w, oow);
        mul_lanes_scalar(scalar, oow);
        expect_same_bits(scalar, expect, "scalar", iter);
#if TILEVK_SIMD_AVX2
        float oow2[kBlockLanes], simd[kBlockLanes];
        std::memcpy(simd, a, sizeof a);
        reciprocal_avx2(w, oow2);
        mul_lanes_avx2(simd, oow2);
        expect_same_bits(simd, expect, "avx2", iter);
#endif
    }
}

TEST(FragmentKernels, InterpolateInputMatchesEvalPlaneAndPerspectiveDivide) {
    std::mt19937 rng(16);
    for (int iter = 0; iter < 20000; ++iter) {
        const Plane p{nasty(rng, -4, 4), nasty(rng, -4, 4), nasty(rng, -100, 100)};
        const Plane wp{std::uniform_real_distribution<float>(-1e-3f, 1e-3f)(rng), 1e-4f, nasty(rng, 0.1f, 4)};
        const int bx = int(rng() % 4096) * 4, by = int(rng() % 4096) * 4;
        const EvalOffset off = plane_offset((iter & 1) ? 4 : 1, -1);
        const bool fused = (iter % 4) != 0, perspective = (iter % 3) != 0;
        float a[kBlockLanes], w[kBlockLanes], expect[kBlockLanes];
        eval_plane(p, bx, by, off, fused, a);
        eval_plane(wp, bx, by, off, fused, w);
        if (perspective)
            perspective_divide(a, w, expect);
        else
            std::memcpy(expect, a, sizeof a);
        LaneCoords c;
        make_lane_coords(bx, by, off, c);
        alignas(32) float oow[kBlockLanes];
        reciprocal_fast(w, oow);
        uint32_t got[kBlockLanes];
        interpolate_input(p, c, fused, perspective ? oow : nullptr, got);
        for (int l = 0; l < kBlockLanes; ++l) {
            float g;
            std::memcpy(&g, &got[l], 4);
            ASSERT_EQ(canonical(g), canonical(expect[l])) << "lane " << l << " iter " << iter;
        }
    }
}

TEST(FragmentKernels, DepthBlockMatchesDepthStencilTest) {
    std::mt19937 rng(13);
    const DepthFormat formats[] = {DepthFormat::D16, DepthFormat::D32F};
    int passed_some = 0;
    for (int iter = 0; iter < 30000; ++iter) {
        const DepthFormat f = formats[iter & 1];
        const size_t bytes = f == DepthFormat::D16 ? 2 : 4;
        DepthStencilState s;
        s.depth_test = true;
        s.depth_write = (iter % 3) != 0;
        s.depth_compare = CompareOp(rng() % 8);
        s.depth_clamp = (iter % 5) == 0;
        s.min_depth = std::uniform_real_distribution<float>(0.0f, 0.5f)(rng);
        s.max_depth = std::uniform_real_distribution<float>(0.5f, 1.0f)(rng);
        if (iter % 17 == 0) s.min_depth = -0.0f;
        if (iter % 23 == 0) s.min_depth = 0x1p-140f;  // a denormal bound: the clamped z needs the compare's DAZ
        s.unrestricted_depth = (iter % 7) == 0;
        ASSERT_TRUE(depth_fast_supported(s, f));
        const DepthFast d = make_depth_fast(s, f);

        float z[kBlockLanes];
        for (float& v : z) v = nasty(rng, -0.2f, 1.2f);
        // stored texels: random, with some equal to the incoming value so EQUAL / LEQUAL ties are exercised
        const size_t pitch = 4 * bytes + 6;  // bytes between rows stay untouched
        std::vector<uint8_t> mem(pitch * 4);
        for (auto& b : mem) b = uint8_t(rng());
        DepthStencilBlock zs{};
        for (int l = 0; l < kBlockLanes; ++l) {
            uint8_t* t = mem.data() + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * bytes;
            if (rng() % 3 == 0) {
                const uint32_t v = depth_to_stored(clamp_depth(z[l], s, f), f);
                std::memcpy(t, &v, bytes);
            } else if (f == DepthFormat::D32F && rng() % 2) {
                const float v = nasty(rng, 0.0f, 1.0f);
                std::memcpy(t, &v, 4);
            }
            std::memcpy(&zs.depth[l], t, bytes);
        }
        const uint16_t mask = (iter % 4 == 0) ? 0xffff : uint16_t(rng());
        const bool write = (iter % 6) != 0;

        // Reference: depth_stencil_test on the loaded lanes, then the written lanes stored back.
        std::vector<uint8_t> expect = mem;
        const uint16_t expect_pass = depth_stencil_test(s, f, true, z, mask, zs, write);
        for (int l = 0; l < kBlockLanes; ++l)
            if (mask & (1u << l))
                std::memcpy(expect.data() + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * bytes, &zs.depth[l], bytes);
        passed_some += expect_pass != 0;

        std::vector<uint8_t> scalar = mem;
        ASSERT_EQ(depth_block_scalar(d, z, mask, scalar.data(), pitch, write), expect_pass) << iter;
        ASSERT_EQ(scalar, expect) << iter;
#if TILEVK_SIMD_AVX2
        std::vector<uint8_t> simd = mem;
        ASSERT_EQ(depth_block_avx2(d, z, mask, simd.data(), pitch, write), expect_pass) << iter;
        ASSERT_EQ(simd, expect) << iter;
#endif
    }
    EXPECT_GT(passed_some, 10000);
}

TEST(FragmentKernels, DepthFastRejectsStencilAndOtherFormats) {
    DepthStencilState s;
    s.depth_test = true;
    EXPECT_TRUE(depth_fast_supported(s, DepthFormat::D32F));
    EXPECT_FALSE(depth_fast_supported(s, DepthFormat::X8D24));
    EXPECT_FALSE(depth_fast_supported(s, DepthFormat::None));
    s.stencil_test = true;
    EXPECT_FALSE(depth_fast_supported(s, DepthFormat::D16));
    s.stencil_test = false;
    s.depth_test = false;
    EXPECT_FALSE(depth_fast_supported(s, DepthFormat::D16));
}

TEST(FragmentKernels, OpaqueStoreMatchesBlendBlock) {
    std::mt19937 rng(14);
    for (int iter = 0; iter < 20000; ++iter) {
        const bool bgra = iter & 1;
        const UnormPath path = (iter % 9 == 0) ? UnormPath::Sse4 : UnormPath::Avx8;
        float src[4][kBlockLanes];
        for (auto& ch : src)
            for (float& v : ch) v = nasty(rng, 0.0f, 1.0f);
        const size_t pitch = 16 + 12;
        std::vector<uint8_t> mem(pitch * 4);
        for (auto& b : mem) b = uint8_t(rng());
        const uint16_t mask = (iter % 4 == 0) ? 0xffff : uint16_t(rng());

        std::vector<uint8_t> expect = mem;
        BlendAttachment a;  // blend off, all channels
        BlendOptions opt;
        opt.unorm_path = path;
        const float k[4] = {0, 0, 0, 0};
        blend_block(a, bgra ? ColorFormat::B8G8R8A8_UNORM : ColorFormat::R8G8B8A8_UNORM, k, src, mask, expect.data(),
                    pitch, opt);

        std::vector<uint8_t> scalar = mem;
        store_rgba8_scalar(bgra, src, mask, scalar.data(), pitch, path);
        ASSERT_EQ(scalar, expect) << iter;
        for (bool inside : {false, true}) {
            std::vector<uint8_t> fast = mem;
            store_rgba8_fast(bgra, src, mask, fast.data(), pitch, path, inside);
            ASSERT_EQ(fast, expect) << iter;
#if TILEVK_SIMD_AVX2
            if (path == UnormPath::Avx8) {
                std::vector<uint8_t> simd = mem;
                store_rgba8_avx2(bgra, src, mask, simd.data(), pitch, inside);
                ASSERT_EQ(simd, expect) << iter;
                if (inside) {  // the branch-free block store of the 4x uniform path (inside blocks only)
                    __m128i rows[4];
                    detail::pack_rgba8_rows(bgra, src, rows);
                    std::vector<uint8_t> block = mem;
                    store_rgba8_raster_block_avx2(rows, lanes_to_raster(mask), block.data(), pitch);
                    ASSERT_EQ(block, expect) << iter;
                }
            }
#endif
        }
    }
}

TEST(FragmentKernels, Rgba8BlendMatchesBlendBlock) {
    std::mt19937 rng(15);
    int fast = 0;
    for (int iter = 0; iter < 40000; ++iter) {
        const ColorFormat f = (iter & 1) ? ColorFormat::B8G8R8A8_UNORM : ColorFormat::R8G8B8A8_UNORM;
        BlendAttachment a;
        a.blend_enable = (iter % 5) != 0;
        auto factor = [&] { return BlendFactor(rng() % 15); };  // Zero..SrcAlphaSaturate
        a.src_color = factor();
        a.dst_color = factor();
        a.src_alpha = factor();
        a.dst_alpha = factor();
        a.color_op = BlendOp(rng() % 5);
        a.alpha_op = BlendOp(rng() % 5);
        if (iter % 3 == 0) {  // the common state: standard alpha blending
            a.src_color = BlendFactor::SrcAlpha;
            a.dst_color = BlendFactor::OneMinusSrcAlpha;
            a.color_op = a.alpha_op = BlendOp::Add;
        }
        a.write_mask = (iter % 2) ? 0xf : uint8_t(rng() % 16);
        float k[4], src[4][kBlockLanes];
        for (float& v : k) v = nasty(rng, 0.0f, 1.0f);
        for (auto& ch : src)
            for (float& v : ch) v = nasty(rng, 0.0f, 1.0f);
        const size_t pitch = 16 + 20;
        std::vector<uint8_t> mem(pitch * 4);
        for (auto& b : mem) b = uint8_t(rng());
        if (iter % 7 == 0)
            for (size_t i = 0; i < mem.size(); ++i) mem[i] = (i % 4 == 3) ? 255 : uint8_t(rng());  // opaque dst
        const uint16_t mask = (iter % 4 == 0) ? 0xffff : uint16_t(rng());

        std::vector<uint8_t> expect = mem;
        blend_block(a, f, k, src, mask, expect.data(), pitch);
        const Rgba8Blend b = prepare_rgba8_blend(a, f, k);
        ASSERT_TRUE(b.ok);
        std::vector<uint8_t> got = mem;
        if (blend_rgba8_block(b, src, mask, got.data(), pitch)) {
            ++fast;
            ASSERT_EQ(got, expect) << "iter " << iter;
        }
    }
#if TILEVK_SIMD_AVX2
    EXPECT_EQ(fast, 40000);
#else
    EXPECT_EQ(fast, 0);
#endif
}

TEST(FragmentKernels, Rgba8BlendDeclinesWhatItDoesNotCover) {
    BlendAttachment a;
    const float k[4] = {0, 0, 0, 0};
    EXPECT_TRUE(prepare_rgba8_blend(a, ColorFormat::R8G8B8A8_UNORM, k).ok);
    EXPECT_FALSE(prepare_rgba8_blend(a, ColorFormat::R8G8B8A8_SRGB, k).ok);
    EXPECT_FALSE(prepare_rgba8_blend(a, ColorFormat::R8_UNORM, k).ok);
    BlendOptions sse;
    sse.unorm_path = UnormPath::Sse4;
    EXPECT_FALSE(prepare_rgba8_blend(a, ColorFormat::R8G8B8A8_UNORM, k, sse).ok);
    a.blend_enable = true;
    a.src_color = BlendFactor::Src1Color;
    EXPECT_FALSE(prepare_rgba8_blend(a, ColorFormat::R8G8B8A8_UNORM, k).ok);
}

// The standard alpha-blending state: prepare_rgba8_blend marks it `over` exactly when every lowered factor and op is
// SRC_ALPHA / ONE_MINUS_SRC_ALPHA / ADD, whatever the write mask.
TEST(FragmentKernels, Rgba8OverIsTheStandardStateOnly) {
    const float k[4] = {0, 0, 0, 0};
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = a.src_alpha = BlendFactor::SrcAlpha;
    a.dst_color = a.dst_alpha = BlendFactor::OneMinusSrcAlpha;
    a.color_op = a.alpha_op = BlendOp::Add;
    for (ColorFormat f : {ColorFormat::R8G8B8A8_UNORM, ColorFormat::B8G8R8A8_UNORM}) {
        a.write_mask = 0xf;
        EXPECT_TRUE(prepare_rgba8_blend(a, f, k).over);
        a.write_mask = 0x5;
        EXPECT_TRUE(prepare_rgba8_blend(a, f, k).over);
    }
    BlendAttachment b = a;
    b.src_alpha = BlendFactor::One;
    EXPECT_FALSE(prepare_rgba8_blend(b, ColorFormat::R8G8B8A8_UNORM, k).over);
    b = a;
    b.dst_color = BlendFactor::OneMinusDstAlpha;
    EXPECT_FALSE(prepare_rgba8_blend(b, ColorFormat::R8G8B8A8_UNORM, k).over);
    b = a;
    b.alpha_op = BlendOp::Subtract;
    EXPECT_FALSE(prepare_rgba8_blend(b, ColorFormat::R8G8B8A8_UNORM, k).over);
    b = a;
    b.blend_enable = false;
    EXPECT_FALSE(prepare_rgba8_blend(b, ColorFormat::R8G8B8A8_UNORM, k).over);
}

// blend_rgba8_block's `over` specialisation (blend_rgba8.cpp blend_over) against its general kernel (the same state
// with `over` cleared) and the scalar blend_block: every (source channel, source alpha, destination) byte triple
// exhaustively, then random float colours (NaN, Inf, out of range), coverage, write masks and both formats.
TEST(FragmentKernels, Rgba8OverMatchesGeneralKernel) {
    const float k[4] = {0, 0, 0, 0};
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = a.src_alpha = BlendFactor::SrcAlpha;
    a.dst_color = a.dst_alpha = BlendFactor::OneMinusSrcAlpha;
    a.color_op = a.alpha_op = BlendOp::Add;
    const size_t pitch = 16 + 12;
    auto check = [&](ColorFormat f, const float src[4][kBlockLanes], uint16_t mask, const std::vector<uint8_t>& mem,
                     const char* what, int iter) {
        const Rgba8Blend over = prepare_rgba8_blend(a, f, k);
        ASSERT_TRUE(over.over);
        Rgba8Blend general = over;
        general.over = false;
        std::vector<uint8_t> expect = mem, got = mem, got_general = mem;
        if (!blend_rgba8_block(over, src, mask, got.data(), pitch)) return;  // the portable build has no kernel
        blend_block(a, f, k, src, mask, expect.data(), pitch);
        ASSERT_TRUE(blend_rgba8_block(general, src, mask, got_general.data(), pitch));
        ASSERT_EQ(got_general, expect) << what << " general kernel, iter " << iter;
        ASSERT_EQ(got, expect) << what << " over kernel, iter " << iter;
    };
    // Exhaustive bytes: pixel p of block c16 has source code 16*c16 + p in R, G and B, source alpha sa, and every
    // destination byte d; the source codes are exact floats code/255 (rne(code/255 * 255) = code).
    float src[4][kBlockLanes];
    std::vector<uint8_t> mem(pitch * 4);
    for (int sa = 0; sa < 256; ++sa) {
        for (int d = 0; d < 256; ++d) {
            for (size_t i = 0; i < mem.size(); ++i) mem[i] = uint8_t(d);
            for (int c16 = 0; c16 < 16; ++c16) {
                for (int l = 0; l < kBlockLanes; ++l) {
                    const float code = float(16 * c16 + lane_x(l) + 4 * lane_y(l)) / 255.0f;
                    src[0][l] = src[1][l] = src[2][l] = code;
                    src[3][l] = float(sa) / 255.0f;
                }
                check(ColorFormat::R8G8B8A8_UNORM, src, 0xffff, mem, "exhaustive", sa * 256 + d);
            }
        }
    }
    std::mt19937 rng(11);
    for (int iter = 0; iter < 40000; ++iter) {
        const ColorFormat f = (iter & 1) ? ColorFormat::B8G8R8A8_UNORM : ColorFormat::R8G8B8A8_UNORM;
        a.write_mask = (iter % 3) ? 0xf : uint8_t(rng() % 16);
        for (auto& ch : src)
            for (float& v : ch)
                v = (iter % 4) ? std::uniform_real_distribution<float>(0.0f, 1.0f)(rng) : nasty(rng, 0, 1);
        for (auto& b : mem) b = uint8_t(rng());
        const uint16_t mask = (iter % 2) ? 0xffff : uint16_t(rng());
        check(f, src, mask, mem, "random", iter);
    }
}
