// Sampling: texelFetch, nearest/linear, address modes, explicit and derivative-based LOD, formats.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "glsl.h"
#include "shader/texture_fixed8.h"

using namespace tilevk::shader;
using tilevk::shader::test::f;
using tilevk::shader::test::make_program;
using tilevk::shader::test::u;

namespace {
// gallivm's UNORM8 -> float: a multiply by fl(1/255), not a division (lp_build_unsigned_norm_to_float).
constexpr float kUnorm8 = float(1.0 / 255.0);
// gallivm's sRGB8 -> linear (lp_build_srgb_to_linear): linear segment below 16, else the cubic
// 0.0023 + 0.0030/255 x + 0.6935/255^2 x^2 + 0.3012/255^3 x^3 evaluated as fmuladd(fmuladd(x2, c3, c1), x,
// fmuladd(x2, c2, c0)); tests/icd/api_breadth_formats_sync_test.cpp (EveryReportedImageFormatWorks) compares sampled
// sRGB texels with lavapipe itself.
float srgb_decode(uint8_t u8) {
    const float x = float(u8), x2 = x * x;
    if (x <= 15.0f) return x * (1.0f / (12.6f * 255.0f));
    return std::fma(std::fma(x2, 0.3012f / (255.0f * 255.0f * 255.0f), 0.0030f / 255.0f), x,
                    std::fma(x2, 0.6935f / (255.0f * 255.0f), 0.0023f));
}

// An RGBA8 image 8x8 with a full mip chain; texel (x, y) of level L = (x*16+L, y*16, 40*L, 255).
struct TestImage {
    std::vector<uint8_t> bytes;
    ImageView view;
    explicit TestImage(Format fmt = Format::R8G8B8A8_UNORM, uint32_t w = 8, uint32_t h = 8) {
        view.format = fmt;
        view.width = w, view.height = h;
        uint32_t lw = w, lh = h, off = 0, level = 0;
        for (;; ++level) {
            view.level[level] = ImageLevel{off, uint64_t(lw) * 4, uint64_t(lw) * lh * 4};
            off += lw * lh * 4;
            if (lw == 1 && lh == 1) break;
            lw = std::max(1u, lw / 2), lh = std::max(1u, lh / 2);
        }
        view.levels = level + 1;
        bytes.resize(off);
        for (uint32_t L = 0; L < view.levels; ++L) {
            uint32_t ww = std::max(1u, w >> L), hh = std::max(1u, h >> L);
            for (uint32_t y = 0; y < hh; ++y)
                for (uint32_t x = 0; x < ww; ++x) {
                    uint8_t* p = bytes.data() + view.level[L].offset + (y * ww + x) * 4;
                    p[0] = uint8_t(x * 16 + L), p[1] = uint8_t(y * 16), p[2] = uint8_t(40 * L), p[3] = 255;
                }
        }
        view.base = bytes.data();
    }
    float texel(uint32_t L, int x, int y, int c) const {
        uint32_t ww = std::max(1u, view.width >> L);
        return float(bytes[view.level[L].offset + (uint32_t(y) * ww + uint32_t(x)) * 4 + uint32_t(c)]) * kUnorm8;
    }
};

struct FsTex {
    std::shared_ptr<const Program> prog;
    FragmentBlock block;
    Scratch scratch;
    Bindings bindings;
    explicit FsTex(const std::string& body,
                   const std::string& decls = "layout(set=0, binding=0) uniform sampler2D tex;\n") {
        prog = make_program(Stage::Fragment,
                            "#version 450\nlayout(location=0) in vec4 v;\n"
                            "layout(location=0) out vec4 color;\n" +
                                decls + "void main() {\n" + body + "\n}\n");
    }
    void run() {
        ASSERT_TRUE(prog);
        prog->run_fragment(bindings, block, scratch);
    }
    float out(int l, int c) const { return f(block.outputs[0][c][l]); }
};

}  // namespace

TEST(ShaderTexture, TexelFetchAndBounds) {
    TestImage img;
    SamplerState smp;
    FsTex r("color = texelFetch(tex, ivec2(v.xy), int(v.z));");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u(float(l % 9));  // x; 8 is out of bounds at level 0
        r.block.inputs[0][1][l] = u(float(l / 4));
        r.block.inputs[0][2][l] = u(float(l % 3));  // level
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int x = l % 9, y = l / 4, L = l % 3;
        int w = 8 >> L;
        bool in = x < w && y < w;
        for (int c = 0; c < 4; ++c) EXPECT_EQ(r.out(l, c), in ? img.texel(uint32_t(L), x, y, c) : 0.0f) << l;
    }
    ASSERT_EQ(r.prog->interface().descriptors.size(), 1u);
    EXPECT_EQ(r.prog->interface().descriptors[0].kind, DescriptorKind::CombinedImageSampler);
}

// texelFetch(sampler2DMS, p, s) reads sample plane s (sample_pitch bytes apart) of level 0; a sample index below 0
// or past the view's count is outside, as a coordinate is (zeros: RGBA8 has alpha); textureSamples is the view's
// count. The expected texels are the test's own bytes.
TEST(ShaderTexture, MultisampledFetchAndSampleCount) {
    constexpr uint32_t kW = 4, kH = 4, kSamples = 4, kPitch = kW * kH * 4 + 64;  // padded planes, as icd/image.cpp
    std::vector<uint8_t> bytes(kPitch * kSamples);
    for (uint32_t s = 0; s < kSamples; ++s)
        for (uint32_t i = 0; i < kW * kH; ++i) {
            uint8_t* p = bytes.data() + s * kPitch + i * 4;
            p[0] = uint8_t(i * 16), p[1] = uint8_t(s * 60), p[2] = uint8_t(200 - s), p[3] = uint8_t(255 - i);
        }
    ImageView view;
    view.format = Format::R8G8B8A8_UNORM;
    view.width = kW, view.height = kH;
    view.samples = kSamples;
    view.sample_pitch = kPitch;
    view.level[0] = ImageLevel{0, kW * 4, uint64_t(kPitch) * kSamples};
    view.base = bytes.data();
    SamplerState smp;
    FsTex r("color = texelFetch(tex, ivec2(v.xy), int(v.z)); if (v.w > 0.0) color = vec4(textureSamples(tex));",
            "layout(set=0, binding=0) uniform sampler2DMS tex;\n");
    r.bindings.set(0, 0, 0, Descriptor{{}, &view, &smp});
    auto sample_of = [](int l) { return l % 6 - 1; };  // -1 .. 4
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u(float(l % 5));  // x; 4 is outside
        r.block.inputs[0][1][l] = u(float(l / 5));
        r.block.inputs[0][2][l] = u(float(sample_of(l)));
        r.block.inputs[0][3][l] = u(l == 15 ? 1.0f : 0.0f);
    }
    r.run();
    for (int l = 0; l < 15; ++l) {
        const int x = l % 5, y = l / 5, s = sample_of(l);
        const bool in = x < int(kW) && s >= 0 && s < int(kSamples);
        for (int c = 0; c < 4; ++c) {
            const float want =
                in ? float(bytes[size_t(s) * kPitch + (size_t(y) * kW + size_t(x)) * 4 + size_t(c)]) * kUnorm8 : 0.0f;
            EXPECT_EQ(r.out(l, c), want) << "lane " << l << " channel " << c;
        }
    }
    for (int c = 0; c < 4; ++c) EXPECT_EQ(r.out(15, c), 4.0f);
}

TEST(ShaderTexture, NearestAddressModes) {
    TestImage img;
    const AddressMode modes[] = {AddressMode::Repeat, AddressMode::MirroredRepeat, AddressMode::ClampToEdge,
                                 AddressMode::ClampToBorder};
    // coordinates in texels (u * 8): expected texel index per mode, computed by hand from the Vulkan rules
    const float coords[] = {1.25f, -0.3f, 0.5f, 9.7f};
    const int expect[4][4] = {
        // u=1.25 -> i=10 ; u=-0.3 -> i=-3 ; u=0.5 -> 4 ; u=9.7 -> i=77
        {2, 5, 4, 5},  // repeat: 10 mod 8 = 2, -3 mod 8 = 5, 77 mod 8 = 5
        // mirrored as lavapipe (lp_build_coord_mirror, then trunc(m * 8)): s = 1.25 mirrors to m = 0.75 exactly, the
        // edge between texels 5 and 6, which truncates to 6 (the Vulkan formula, floor(10) mirrored, gives 5;
        // gallivm's comment owns the difference); -2.4 -> 2; 77.6 -> 2
        {6, 2, 4, 2},
        {7, 0, 4, 7},     // clamp
        {-1, -1, 4, -1},  // border
    };
    for (int m = 0; m < 4; ++m) {
        SamplerState smp;
        smp.address_u = smp.address_v = modes[m];
        smp.border = BorderColor::OpaqueWhite;
        FsTex r("color = textureLod(tex, v.xy, 0.0);");
        r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
        for (int l = 0; l < kLanes; ++l) {
            r.block.inputs[0][0][l] = u(coords[l % 4]);
            r.block.inputs[0][1][l] = u(0.3f);  // y texel 2
        }
        r.run();
        for (int l = 0; l < 4; ++l) {
            int x = expect[m][l];
            for (int c = 0; c < 4; ++c) {
                float e = x < 0 ? 1.0f : img.texel(0, x, 2, c);
                EXPECT_EQ(r.out(l, c), e) << "mode " << m << " lane " << l << " c " << c;
            }
        }
    }
}

TEST(ShaderTexture, BilinearFiltering) {
    TestImage img;
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    // MIRROR_CLAMP_TO_EDGE reads like CLAMP_TO_EDGE for indices >= -1 but takes lavapipe's float filter
    smp.address_u = smp.address_v = AddressMode::MirrorClampToEdge;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u(0.05f + 0.06f * float(l));
        r.block.inputs[0][1][l] = u(0.9f - 0.05f * float(l));
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float s = 0.05f + 0.06f * float(l), t = 0.9f - 0.05f * float(l);
        float uu = s * 8.0f - 0.5f, vv = t * 8.0f - 0.5f;
        int i0 = int(std::floor(uu)), j0 = int(std::floor(vv));
        float a = uu - std::floor(uu), b = vv - std::floor(vv);
        auto cl = [](int i) { return std::min(std::max(i, 0), 7); };
        for (int c = 0; c < 4; ++c) {
            float t00 = img.texel(0, cl(i0), cl(j0), c), t10 = img.texel(0, cl(i0 + 1), cl(j0), c);
            float t01 = img.texel(0, cl(i0), cl(j0 + 1), c), t11 = img.texel(0, cl(i0 + 1), cl(j0 + 1), c);
            // lavapipe's float filter for 8-bit texels: c * float(1/255), fused lerps along x, then y
            auto re = [](float x) { return float(std::lround(x * 255.0f)) * (1.0f / 255.0f); };
            float x0 = std::fma(a, re(t10) - re(t00), re(t00)), x1 = std::fma(a, re(t11) - re(t01), re(t01));
            EXPECT_EQ(r.out(l, c), std::fma(b, x1 - x0, x0)) << l << " " << c;
        }
    }
}

TEST(ShaderTexture, ImplicitLodFromDerivatives) {
    TestImage img;
    SamplerState smp;
    smp.min_filter = Filter::Nearest;
    smp.mipmap_mode = MipmapMode::Nearest;
    // v.xy = pixel * (k / 8): k texels per pixel -> lambda = log2(k)
    FsTex r("color = texture(tex, v.xy);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    for (float k : {1.0f, 2.0f, 4.0f, 8.0f}) {
        for (int l = 0; l < kLanes; ++l) {
            r.block.inputs[0][0][l] = u((float(lane_x(l)) + 0.5f) * k / 8.0f);
            r.block.inputs[0][1][l] = u((float(lane_y(l)) + 0.5f) * k / 8.0f);
        }
        r.run();
        uint32_t level = uint32_t(std::log2(k));
        for (int l = 0; l < kLanes; ++l) EXPECT_EQ(r.out(l, 2), float(40 * level) * kUnorm8) << "k " << k;
    }
    EXPECT_TRUE(r.prog->interface().uses_derivatives);
}

TEST(ShaderTexture, TrilinearBetweenLevels) {
    TestImage img;
    SamplerState smp;
    smp.mipmap_mode = MipmapMode::Linear;
    smp.address_u = smp.address_v = AddressMode::MirroredRepeat;  // float filter (not lavapipe's 8-bit path)
    FsTex r("color = textureLod(tex, vec2(0.01, 0.01), v.x);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    for (int l = 0; l < kLanes; ++l) r.block.inputs[0][0][l] = u(0.25f * float(l));
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float lambda = 0.25f * float(l);
        float e;
        if (lambda <= 0.0f) {
            e = img.texel(0, 0, 0, 2);
        } else {
            int lo = std::min(int(std::floor(lambda)), 3), hi = std::min(lo + 1, 3);
            float fr = lambda - std::floor(lambda);
            float a = img.texel(uint32_t(lo), 0, 0, 2), b = img.texel(uint32_t(hi), 0, 0, 2);
            // lp_build_sample_mipmap: lp_build_lerp(frac, level0, level1) = fmuladd(frac, level1 - level0, level0)
            e = (hi != lo && fr > 0.0f) ? std::fma(fr, b - a, a) : a;
        }
        EXPECT_EQ(r.out(l, 2), e) << l;
    }
}

// gallivm's float filter (lp_bld_sample_soa.c lp_build_sample_mipmap) blends the two levels with lp_build_lerp:
// fmuladd(frac, level1 - level0, level0), fused on FMA hosts. The weighted sum level0 * (1 - frac) + level1 * frac
// differs from it in the last bits for some frac, which float render targets keep (cts random seeds 223 and 720).
TEST(ShaderTexture, MipLinearBlendIsOneFusedLerp) {
    TestImage img;
    SamplerState smp;  // nearest within each level: only the mip blend is under test
    smp.mipmap_mode = MipmapMode::Linear;
    smp.address_u = smp.address_v = AddressMode::MirroredRepeat;  // float filter (not lavapipe's 8-bit path)
    FsTex r("color = textureLod(tex, vec2(0.01, 0.01), v.x);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    int differs = 0;
    for (int base = 0; base < 2; ++base) {
        for (int l = 0; l < kLanes; ++l) r.block.inputs[0][0][l] = u(1.0f + float(base) + float(l + 1) / 17.0f);
        r.run();
        for (int l = 0; l < kLanes; ++l) {
            const float lambda = 1.0f + float(base) + float(l + 1) / 17.0f, fr = lambda - std::floor(lambda);
            const uint32_t lo = uint32_t(std::floor(lambda));
            for (int c : {0, 2}) {  // red = (x*16 + L) / 255, blue = 40 L / 255 at texel (0, 0)
                const float a = img.texel(lo, 0, 0, c), b = img.texel(lo + 1, 0, 0, c);
                EXPECT_EQ(r.out(l, c), std::fma(fr, b - a, a)) << lambda << " " << c;
                differs += std::fma(fr, b - a, a) != a * (1.0f - fr) + b * fr;
            }
        }
    }
    EXPECT_GT(differs, 0) << "no lane tells the fused lerp from the weighted sum";
}

// The float filter lerps every format's texels along x, then y, with fused multiply-adds (lp_build_lerp_2d via
// lp_build_reduce_filter_2d), including 32-bit float texels; not the weighted sum of the four texels.
TEST(ShaderTexture, FloatTexelsBilinearAsTwoFusedLerps) {
    std::vector<float> texels(4 * 4 * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = std::sin(float(i) * 0.7f) * 3.0f + 0.1f * float(i);
    ImageView fv;
    fv.base = reinterpret_cast<const uint8_t*>(texels.data());
    fv.format = Format::R32G32B32A32_SFLOAT;
    fv.width = fv.height = 4;
    fv.level[0] = ImageLevel{0, 64, 256};
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    smp.address_u = smp.address_v = AddressMode::ClampToEdge;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &fv, &smp});
    auto at = [&](int x, int y, int c) { return texels[size_t(y * 16 + x * 4 + c)]; };
    int differs = 0;
    for (int round = 0; round < 4; ++round) {
        auto s_of = [&](int l) { return 0.13f + 0.047f * float(l) + 0.011f * float(round); };
        auto t_of = [&](int l) { return 0.71f - 0.029f * float(l) + 0.017f * float(round); };
        for (int l = 0; l < kLanes; ++l) r.block.inputs[0][0][l] = u(s_of(l)), r.block.inputs[0][1][l] = u(t_of(l));
        r.run();
        for (int l = 0; l < kLanes; ++l) {
            // CLAMP_TO_EDGE in gallivm's float path: u = max(min(s*n, n) - 0.5, 0); i0 = floor(u), i1 = min(i0+1, n-1)
            const float uu = std::max(std::min(s_of(l) * 4.0f, 4.0f) - 0.5f, 0.0f);
            const float vv = std::max(std::min(t_of(l) * 4.0f, 4.0f) - 0.5f, 0.0f);
            const int i0 = int(std::floor(uu)), j0 = int(std::floor(vv));
            const int i1 = std::min(i0 + 1, 3), j1 = std::min(j0 + 1, 3);
            const float a = uu - std::floor(uu), b = vv - std::floor(vv);
            for (int c = 0; c < 4; ++c) {
                const float x0 = std::fma(a, at(i1, j0, c) - at(i0, j0, c), at(i0, j0, c));
                const float x1 = std::fma(a, at(i1, j1, c) - at(i0, j1, c), at(i0, j1, c));
                const float e = std::fma(b, x1 - x0, x0);
                EXPECT_EQ(r.out(l, c), e) << l << " " << c;
                const float sum = (1 - a) * (1 - b) * at(i0, j0, c) + a * (1 - b) * at(i1, j0, c) +
                                  (1 - a) * b * at(i0, j1, c) + a * b * at(i1, j1, c);
                differs += sum != e;
            }
        }
    }
    EXPECT_GT(differs, 0) << "no lane tells the fused lerps from the weighted sum";
}

// MIRROR_CLAMP_TO_EDGE as gallivm's float path computes it (the spec's rule, with these roundings): nearest takes
// trunc(|u|) clamped to n - 1 (u = -1.0 texel 1, a NaN texel n - 1); linear folds u to |u| and then clamps as
// CLAMP_TO_EDGE, so a negative u blends texels (i0, i0 + 1) of |u| with |u|'s weight.
TEST(ShaderTexture, MirrorClampToEdgeFoldsTheCoordinate) {
    TestImage img;
    SamplerState near;
    near.address_u = near.address_v = AddressMode::MirrorClampToEdge;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &near});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float texels_u[] = {-1.0f, -2.5f, 0.25f, -9.5f, nan, 3.0f, -0.0f, 1e10f};
    const int expect[] = {1, 2, 0, 7, 7, 3, 0, 7};
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u(texels_u[l % 8] / 8.0f);
        r.block.inputs[0][1][l] = u(0.3f);  // y texel 2
    }
    r.run();
    for (int l = 0; l < 8; ++l)
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(r.out(l, c), img.texel(0, expect[l], 2, c)) << "u " << texels_u[l] << " c " << c;

    std::vector<float> texels(4 * 4 * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = std::sin(float(i) * 0.9f) * 5.0f + 0.3f * float(i);
    ImageView fv;
    fv.base = reinterpret_cast<const uint8_t*>(texels.data());
    fv.format = Format::R32G32B32A32_SFLOAT;
    fv.width = fv.height = 4;
    fv.level[0] = ImageLevel{0, 64, 256};
    SamplerState lin = near;
    lin.mag_filter = lin.min_filter = Filter::Linear;
    FsTex q("color = textureLod(tex, v.xy, 0.0);");
    q.bindings.set(0, 0, 0, Descriptor{{}, &fv, &lin});
    auto at = [&](int x, int y, int c) { return texels[size_t(y * 16 + x * 4 + c)]; };
    const auto s_of = [](int l) { return -0.93f + 0.061f * float(l); };
    for (int l = 0; l < kLanes; ++l) q.block.inputs[0][0][l] = u(s_of(l)), q.block.inputs[0][1][l] = u(0.375f);
    q.run();
    for (int l = 0; l < kLanes; ++l) {
        const float uu = std::max(std::min(std::fabs(s_of(l) * 4.0f), 4.0f) - 0.5f, 0.0f);
        const int i0 = int(std::floor(uu)), i1 = std::min(i0 + 1, 3);
        const float a = uu - std::floor(uu);
        for (int c = 0; c < 4; ++c) {  // t = 0.375: v = 1.5 - 0.5 = 1.0, row 1 with weight 0
            const float x0 = std::fma(a, at(i1, 1, c) - at(i0, 1, c), at(i0, 1, c));
            const float x1 = std::fma(a, at(i1, 2, c) - at(i0, 2, c), at(i0, 2, c));
            EXPECT_EQ(q.out(l, c), std::fma(0.0f, x1 - x0, x0)) << "s " << s_of(l) << " c " << c;
        }
    }
}

// gallivm turns a NaN texel coordinate into INT_MIN (cvttps2dq in lp_build_ifloor / lp_build_ifloor_fract), which
// CLAMP_TO_BORDER's bounds test sends to the border colour; the linear weight is NaN - floor(NaN) = NaN, carried by
// the fused lerps.
TEST(ShaderTexture, NanCoordinateWithClampToBorderReadsTheBorder) {
    TestImage img;
    SamplerState smp;
    smp.address_u = smp.address_v = AddressMode::ClampToBorder;
    smp.border = BorderColor::OpaqueWhite;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // lanes alternate: NaN in s only, NaN in t only
    for (int l = 0; l < kLanes; ++l)
        r.block.inputs[0][0][l] = u(l % 2 ? 0.3f : nan), r.block.inputs[0][1][l] = u(l % 2 ? nan : 0.3f);
    r.run();
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) EXPECT_EQ(r.out(l, c), 1.0f) << "nearest " << l << " " << c;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    r.run();
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isnan(r.out(l, c))) << "linear " << l << " " << c;
}

TEST(ShaderTexture, SrgbAndFloatFormats) {
    TestImage srgb(Format::R8G8B8A8_SRGB, 4, 4);
    SamplerState smp;
    FsTex r("color = texelFetch(tex, ivec2(v.xy), 0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &srgb.view, &smp});
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u(float(l % 4));
        r.block.inputs[0][1][l] = u(float(l / 4));
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        EXPECT_EQ(r.out(l, 0), srgb_decode(uint8_t((l % 4) * 16)));
        EXPECT_EQ(r.out(l, 3), 1.0f);  // alpha is linear
    }
    // RGBA32F
    std::vector<float> texels(4 * 4 * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = float(i) * 0.125f - 3.0f;
    ImageView fv;
    fv.base = reinterpret_cast<const uint8_t*>(texels.data());
    fv.format = Format::R32G32B32A32_SFLOAT;
    fv.width = fv.height = 4;
    fv.level[0] = ImageLevel{0, 64, 256};
    r.bindings.set(0, 0, 0, Descriptor{{}, &fv, &smp});
    r.run();
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) EXPECT_EQ(r.out(l, c), texels[size_t((l / 4) * 16 + (l % 4) * 4 + c)]);
}

TEST(ShaderTexture, SeparateImageAndSampler) {
    TestImage img;
    SamplerState smp;
    FsTex r("color = textureLod(sampler2D(t, s), v.xy, 0.0) + vec4(float(textureSize(sampler2D(t, s), 1).x));",
            "layout(set=0, binding=0) uniform texture2D t;\nlayout(set=0, binding=1) uniform sampler s;\n");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, nullptr});
    r.bindings.set(0, 1, 0, Descriptor{{}, nullptr, &smp});
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u((float(l % 8) + 0.5f) / 8.0f);
        r.block.inputs[0][1][l] = u(0.5f / 8.0f);
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(r.out(l, 0), img.texel(0, l % 8, 0, 0) + 4.0f);
    const auto& d = r.prog->interface().descriptors;
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].kind, DescriptorKind::SampledImage);
    EXPECT_EQ(d[1].kind, DescriptorKind::Sampler);
}

TEST(ShaderTexture, MissingImageReadsZero) {
    FsTex r("color = texture(tex, v.xy) + vec4(1.0);");
    r.run();
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(r.out(l, 0), 1.0f);
}

TEST(ShaderTexture, ShadowCompareAndOffsets) {
    // 4x4 D32 depth image: depth(x, y) = (x + 4y) / 16
    std::vector<float> depth(16);
    for (int i = 0; i < 16; ++i) depth[size_t(i)] = float(i) / 16.0f;
    ImageView dv;
    dv.base = reinterpret_cast<const uint8_t*>(depth.data());
    dv.format = Format::D32_SFLOAT;
    dv.width = dv.height = 4;
    dv.level[0] = ImageLevel{0, 16, 64};
    SamplerState smp;
    smp.compare_enable = true;
    smp.compare_op = CompareOp::Less;
    smp.address_u = smp.address_v = AddressMode::ClampToEdge;
    FsTex r(
        "color = vec4(textureLod(shadow, vec3(v.xy, v.z), 0.0), texelFetchOffset(plain, ivec2(v.xy * 4.0), 0, "
        "ivec2(1, -1)).x, textureLodOffset(plain, v.xy, 0.0, ivec2(-1, 2)).x, 0.0);",
        "layout(set=0, binding=0) uniform sampler2DShadow shadow;\n"
        "layout(set=0, binding=1) uniform sampler2D plain;\n");
    SamplerState plain_smp;  // nearest, repeat
    r.bindings.set(0, 0, 0, Descriptor{{}, &dv, &smp});
    r.bindings.set(0, 1, 0, Descriptor{{}, &dv, &plain_smp});
    for (int l = 0; l < kLanes; ++l) {
        int x = l % 4, y = l / 4;
        r.block.inputs[0][0][l] = u((float(x) + 0.5f) / 4.0f);
        r.block.inputs[0][1][l] = u((float(y) + 0.5f) / 4.0f);
        r.block.inputs[0][2][l] = u(0.4f);  // reference
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int x = l % 4, y = l / 4;
        float d = float(x + 4 * y) / 16.0f;
        EXPECT_EQ(r.out(l, 0), 0.4f < d ? 1.0f : 0.0f) << l;
        int fx = x + 1, fy = y - 1;
        bool in = fx < 4 && fy >= 0;
        EXPECT_EQ(r.out(l, 1), in ? float(fx + 4 * fy) / 16.0f : 0.0f) << l;
        int ox = (x - 1 + 4) % 4, oy = (y + 2) % 4;  // repeat addressing
        EXPECT_EQ(r.out(l, 2), float(ox + 4 * oy) / 16.0f) << l;
    }
}

// ---- lavapipe's 8-bit fixed-point filter (shader/texture_fixed8.h) ----

namespace {
// Independent model of llvmpipe's 8-bit lerp: a + (w/256)*(b-a) rounded half up.
int lerp_model(int w, int a, int b) {
    return a + int(std::floor(double(w) * double(b - a) / 256.0 + 0.5));
}
// Footprint along one axis for CLAMP_TO_EDGE: u in texels, 8 fraction bits (ties to even), minus half a texel.
struct Axis {
    int i0, i1, w;
};
Axis clamp_axis(float s, int n) {
    long c = std::lrint(double(s) * double(n) * 256.0) - 128;  // default rounding: to nearest even
    long i = c >= 0 ? c / 256 : -((-c + 255) / 256);           // floor division
    int w = int(c - i * 256);
    auto cl = [n](long k) { return int(std::min<long>(std::max<long>(k, 0), n - 1)); };
    return {cl(i), cl(i + 1), w};
}
}  // namespace

TEST(ShaderTextureFixed8, LerpMatchesRoundedModelAndKnownValues) {
    for (int w = 0; w < 256; ++w)
        for (int a = 0; a < 256; a += 5)
            for (int b = 0; b < 256; b += 3) ASSERT_EQ(fixed8::lerp(w, a, b), lerp_model(w, a, b)) << w << a << b;
    EXPECT_EQ(fixed8::lerp(128, 0, 255), 128);  // (128*255 + 128) >> 8 = 32768 >> 8
    EXPECT_EQ(fixed8::lerp(255, 0, 255), 254);  // the largest weight never reaches b
    EXPECT_EQ(fixed8::lerp(1, 200, 0), 199);    // (-200 + 128) >> 8 = -1
}

TEST(ShaderTextureFixed8, FastLog2IsPiecewiseLinear) {
    EXPECT_EQ(fixed8::fast_log2(1.0f), 0.0f);
    EXPECT_EQ(fixed8::fast_log2(8.0f), 3.0f);
    EXPECT_EQ(fixed8::fast_log2(0.25f), -2.0f);
    EXPECT_EQ(fixed8::fast_log2(3.0f), 1.5f);    // 2 * 1.5: 1 + 0.5
    EXPECT_EQ(fixed8::fast_log2(9.0f), 3.125f);  // 8 * 1.125
    EXPECT_EQ(fixed8::fast_log2(0.75f), -0.5f);  // 0.5 * 1.5: -1 + 0.5
    EXPECT_EQ(fixed8::fast_log2(0.0f), -127.0f);
    EXPECT_EQ(fixed8::mip_weight(0.5625f), 144);
    EXPECT_EQ(fixed8::mip_weight(0.999f), 255);
    EXPECT_EQ(fixed8::mip_weight(-0.25f), 0);
    EXPECT_EQ(fixed8::iround(2.5f), 2);
    EXPECT_EQ(fixed8::iround(3.5f), 4);
    EXPECT_EQ(fixed8::iround(NAN), INT32_MIN);
}

TEST(ShaderTextureFixed8, BilinearClampToEdge) {
    TestImage img;
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    smp.address_u = smp.address_v = AddressMode::ClampToEdge;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    auto sx = [](int l) { return 0.05f + 0.0613f * float(l); };
    auto ty = [](int l) { return 0.93f - 0.057f * float(l); };
    for (int l = 0; l < kLanes; ++l) r.block.inputs[0][0][l] = u(sx(l)), r.block.inputs[0][1][l] = u(ty(l));
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        Axis x = clamp_axis(sx(l), 8), y = clamp_axis(ty(l), 8);
        for (int c = 0; c < 4; ++c) {
            auto b = [&](int i, int j) { return int(std::lround(img.texel(0, i, j, c) * 255.0f)); };
            int top = lerp_model(x.w, b(x.i0, y.i0), b(x.i1, y.i0));
            int bottom = lerp_model(x.w, b(x.i0, y.i1), b(x.i1, y.i1));
            EXPECT_EQ(r.out(l, c), float(lerp_model(y.w, top, bottom)) * kUnorm8) << l << " " << c;
        }
    }
}

TEST(ShaderTextureFixed8, RepeatNonPowerOfTwoWrapsFromTheFloatCoordinate) {
    TestImage img(Format::R8G8B8A8_UNORM, 6, 6);
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    // s = 1.02: fract 0.02 -> 0.12 texels -> c = 31 - 128 = -97 -> i0 = -1 -> 5, i1 = 0, w = 159
    // s = -0.5: fract 0.5 -> 3 texels -> c = 768 - 128 = 640 -> i0 = 2, i1 = 3, w = 128
    const float ss[2] = {1.02f, -0.5f};
    const int e[2][3] = {{5, 0, 159}, {2, 3, 128}};
    for (int l = 0; l < kLanes; ++l) r.block.inputs[0][0][l] = u(ss[l % 2]), r.block.inputs[0][1][l] = u(0.5f);
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        // t = 0.5: c = 768 - 128 = 640: rows 2 and 3 with weight 128
        const int* k = e[l % 2];
        int top = lerp_model(k[2], k[0] * 16, k[1] * 16);  // red = x*16 on level 0
        EXPECT_EQ(r.out(l, 0), float(top) * kUnorm8) << l;
        EXPECT_EQ(r.out(l, 1), float(lerp_model(128, 32, 48)) * kUnorm8) << l;  // green = y*16
    }
}

TEST(ShaderTextureFixed8, MipLinearUsesFastLog2AndEightBitWeight) {
    TestImage img;
    SamplerState smp;
    smp.mipmap_mode = MipmapMode::Linear;
    FsTex r("color = texture(tex, v.xy);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    // 3 texels per pixel: rho^2 = 9, lambda = 0.5 * fast_log2(9) = 1.5625 (exact log2 would give 1.585)
    // levels 1 and 2, weight trunc(0.5625 * 256) = 144; blue = 40*L: 40 + ((144*40 + 128) >> 8) = 63
    for (int l = 0; l < kLanes; ++l) {
        r.block.inputs[0][0][l] = u((float(lane_x(l)) + 0.5f) * 3.0f / 8.0f);
        r.block.inputs[0][1][l] = u((float(lane_y(l)) + 0.5f) * 3.0f / 8.0f);
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(r.out(l, 2), 63.0f * kUnorm8) << l;
    // explicit LOD 2.25 on RGBA8 + REPEAT: weight 64; 80 + ((64*40 + 128) >> 8) = 90
    FsTex e("color = textureLod(tex, vec2(0.01, 0.01), 2.25);");
    e.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    e.run();
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(e.out(l, 2), 90.0f * kUnorm8) << l;
}

TEST(ShaderTextureFixed8, SrgbStaysInFloat) {
    // sRGB does not fit 8-bit UNORM after decoding: lavapipe blends the linear floats
    TestImage img(Format::R8G8B8A8_SRGB, 8, 8);
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    smp.address_u = smp.address_v = AddressMode::ClampToEdge;
    FsTex r("color = textureLod(tex, vec2(0.125, 0.0625), 0.0);");  // halfway between texels 0 and 1, row 0
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    r.run();
    float lin1 = srgb_decode(16);
    EXPECT_EQ(r.out(0, 0), 0.5f * 0.0f + 0.5f * lin1);
}

TEST(ShaderTextureFixed8, MirroredRepeatLinearMirrorsTheCoordinateFirst) {
    // float path (MIRRORED_REPEAT is not an 8-bit-path wrap): s = 1.125 -> m = |2(0.5625 - 1)| = 0.875,
    // u = 0.875*8 - 0.5 = 6.5: texels 6 and 7 with weight 0.5; s = -0.0625 -> m = 0.0625, u = 0: texel 0 only
    TestImage img;
    SamplerState smp;
    smp.mag_filter = smp.min_filter = Filter::Linear;
    smp.address_u = AddressMode::MirroredRepeat;
    smp.address_v = AddressMode::ClampToEdge;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    for (int l = 0; l < kLanes; ++l)
        r.block.inputs[0][0][l] = u(l % 2 ? -0.0625f : 1.125f), r.block.inputs[0][1][l] = u(0.0625f);
    r.run();
    const float k = 1.0f / 255.0f;
    for (int l = 0; l < kLanes; ++l)
        EXPECT_EQ(r.out(l, 0), l % 2 ? 0.0f : std::fma(0.5f, 112.0f * k - 96.0f * k, 96.0f * k)) << l;
}

TEST(ShaderTextureFixed8, RepeatNonPowerOfTwoNearestTruncatesTheWrappedFraction) {
    // s = 0x1.2aaaaap+0: s*6 rounds to 7.0 (texel 1 after floor and mod), but lavapipe's 8-bit path takes
    // fract(s) = 0x0.2aaaaap+0 = 0.16666663, times 6 = 0.99999976, truncated: texel 0 (red = x*16 = 0)
    TestImage img(Format::R8G8B8A8_UNORM, 6, 6);
    SamplerState smp;
    FsTex r("color = textureLod(tex, v.xy, 0.0);");
    r.bindings.set(0, 0, 0, Descriptor{{}, &img.view, &smp});
    for (int l = 0; l < kLanes; ++l)
        r.block.inputs[0][0][l] = u(l % 2 ? 0x1.2aaaaap+0f : 0.25f), r.block.inputs[0][1][l] = u(0.5f);
    r.run();
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(r.out(l, 0), l % 2 ? 0.0f : 16.0f * kUnorm8) << l;  // 0.25*6 -> 1
}

// Storage images of the 3D and cube dimensions are not implemented: a module declaring one is refused at
// translation with a message naming the dimension (instead of a program that would touch the wrong texels).
TEST(ShaderTexture, ThreeDimensionalAndCubeStorageImagesAreRefusedByName) {
    const struct {
        const char* decl;
        const char* name;
    } kinds[] = {{"image3D", "Dim3D"}, {"imageCube", "Cube"}};
    for (const auto& k : kinds) {
        const std::string src = std::string("#version 450\nlayout(set = 0, binding = 0, rgba8) uniform readonly ") +
                                k.decl + " img;\nlayout(location = 0) out vec4 o;\nvoid main() { o = imageLoad(img, " +
                                "ivec3(0)); }\n";
        const auto spirv = tilevk::shader::test::compile_glsl(Stage::Fragment, src);
        ASSERT_FALSE(spirv.empty());
        const Result r = Program::create(spirv, Stage::Fragment);
        EXPECT_FALSE(r) << k.decl;
        EXPECT_NE(r.error.find(std::string("unsupported storage image dimension ") + k.name), std::string::npos)
            << r.error;
    }
}

namespace {
// A 2x2 single-level view of `fmt` over `bytes` (texels tight, `texel` bytes each).
ImageView small_view(Format fmt, const std::vector<uint8_t>& bytes, uint32_t texel) {
    ImageView v;
    v.format = fmt;
    v.width = v.height = 2;
    v.levels = 1;
    v.level[0] = ImageLevel{0, 2 * texel, 4 * texel};
    v.base = bytes.data();
    return v;
}
}  // namespace

// samplerFilterMinmax, worked out by hand: at the centre of a 2x2 texture the linear footprint is all four texels
// with weights 0.5, so MIN and MAX are the smallest and largest of them; at texel (0, 0)'s centre both weights are
// 0 and lavapipe keeps the first texel (lp_build_sample_min: a zero weight keeps v0), not the footprint's minimum.
// R32_SFLOAT takes the float filter, R8_UNORM the 8-bit one (CLAMP_TO_EDGE).
TEST(ShaderTexture, MinMaxReductionOfFourTexels) {
    const float fl[4] = {0.75f, 0.25f, -0.5f, 2.0f};
    std::vector<uint8_t> f32(16);
    std::memcpy(f32.data(), fl, 16);
    const std::vector<uint8_t> u8 = {200, 40, 90, 255};
    const ImageView views[2] = {small_view(Format::R32_SFLOAT, f32, 4), small_view(Format::R8_UNORM, u8, 1)};
    const float mins[2] = {-0.5f, 40 * kUnorm8}, maxs[2] = {2.0f, 255 * kUnorm8}, firsts[2] = {0.75f, 200 * kUnorm8};
    for (int v = 0; v < 2; ++v)
        for (Reduction m : {Reduction::Min, Reduction::Max}) {
            SamplerState smp;
            smp.mag_filter = smp.min_filter = Filter::Linear;
            smp.address_u = smp.address_v = AddressMode::ClampToEdge;
            smp.reduction = m;
            FsTex r("color = textureLod(tex, v.xy, 0.0);");
            r.bindings.set(0, 0, 0, Descriptor{{}, &views[v], &smp});
            for (int l = 0; l < kLanes; ++l) {
                const float c = l % 2 ? 0.5f : 0.25f;  // the texture's centre; texel (0, 0)'s centre
                r.block.inputs[0][0][l] = u(c), r.block.inputs[0][1][l] = u(c);
            }
            r.run();
            for (int l = 0; l < kLanes; ++l) {
                const float want = l % 2 ? (m == Reduction::Min ? mins[v] : maxs[v]) : firsts[v];
                EXPECT_EQ(r.out(l, 0), want) << "view " << v << " mode " << int(m) << " lane " << l;
                EXPECT_EQ(r.out(l, 3), 1.0f);  // R formats: alpha 1 in every texel
            }
        }
}

// Custom border colours, worked out by hand from gallivm's rule (lp_build_clamp_border_color,
// lp_build_sample_texel_soa): the colour is clamped to the format's range (UNORM [0, 1], SNORM [-1, 1], UINT8
// [0, 255] unsigned, float not at all) and replaces only the channels the format stores; the others keep 0, and
// alpha 1 (the integer 1 on integer formats).
TEST(ShaderTexture, CustomBorderClampedToTheFormatsChannels) {
    struct Row {
        Format fmt;
        uint32_t texel;
        std::array<uint32_t, 4> border, want;
    };
    const auto F = [](float a, float b, float c, float d) { return std::array<uint32_t, 4>{u(a), u(b), u(c), u(d)}; };
    const Row rows[] = {
        {Format::R8_UNORM, 1, F(0.25f, -0.5f, 2.0f, 0.75f), F(0.25f, 0.0f, 0.0f, 1.0f)},
        {Format::R8G8B8A8_UNORM, 4, F(0.25f, -0.5f, 2.0f, 0.75f), F(0.25f, 0.0f, 1.0f, 0.75f)},
        {Format::B8G8R8A8_UNORM, 4, F(-3.0f, 0.5f, 7.0f, 0.125f), F(0.0f, 0.5f, 1.0f, 0.125f)},
        {Format::R8G8_SNORM, 2, F(0.25f, -1.5f, 2.0f, 0.75f), F(0.25f, -1.0f, 0.0f, 1.0f)},
        {Format::R32_SFLOAT, 4, F(-3.0f, 0.5f, 7.0f, 0.125f), F(-3.0f, 0.0f, 0.0f, 1.0f)},
        {Format::R8_UINT, 1, {300, 7, 9, 11}, {255, 0, 0, 1}},
        {Format::R8G8B8A8_SINT, 4, {uint32_t(-200), 100, 5, uint32_t(-1)}, {uint32_t(-128), 100, 5, uint32_t(-1)}},
    };
    for (const Row& row : rows) {
        const std::vector<uint8_t> bytes(4 * row.texel, 0x5A);
        const ImageView view = small_view(row.fmt, bytes, row.texel);
        SamplerState smp;
        smp.address_u = smp.address_v = AddressMode::ClampToBorder;
        smp.border = BorderColor::Custom;
        smp.custom_border = row.border;
        const bool is_uint = row.fmt == Format::R8_UINT, is_sint = row.fmt == Format::R8G8B8A8_SINT;
        FsTex r(is_uint   ? "color = uintBitsToFloat(textureLod(tex, v.xy, 0.0));"
                : is_sint ? "color = intBitsToFloat(textureLod(tex, v.xy, 0.0));"
                          : "color = textureLod(tex, v.xy, 0.0);",
                std::string("layout(set=0, binding=0) uniform ") +
                    (is_uint   ? "u"
                     : is_sint ? "i"
                               : "") +
                    "sampler2D tex;\n");
        r.bindings.set(0, 0, 0, Descriptor{{}, &view, &smp});
        for (int l = 0; l < kLanes; ++l) r.block.inputs[0][0][l] = u(-0.25f), r.block.inputs[0][1][l] = u(0.5f);
        r.run();
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(u(r.out(5, c)), row.want[size_t(c)]) << "format " << int(row.fmt) << " channel " << c;
    }
}
