// The strongest evidence: render on lavapipe itself and compare bit for bit with the kernels: blending (full-screen
// triangle per blend state over random destination bytes), depth conversion/clamping (gl_FragDepth from a buffer)
// and 4x resolves (per-sample colours via sample shading, render-pass resolve). For blending: read the image back
// and compare every pixel with blend_pixel() fed the same source colours, destination bytes and constants.
// Skips (not fails) when no lavapipe device can be created.
#include "lvp_harness.h"

using F = BlendFactor;
using O = BlendOp;

TEST(FragmentLavapipe, BlendMatchesLavapipeBitForBit) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    BlendAttachment off;
    const Case cases[] = {
        {"rgba8 no blend", ColorFormat::R8G8B8A8_UNORM, off},
        {"rgba8 alpha", ColorFormat::R8G8B8A8_UNORM,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::OneMinusSrcAlpha, O::Add)},
        {"rgba8 additive", ColorFormat::R8G8B8A8_UNORM, ba(F::One, F::One, O::Add, F::One, F::One, O::Add)},
        {"rgba8 modulate", ColorFormat::R8G8B8A8_UNORM,
         ba(F::DstColor, F::Zero, O::Add, F::DstAlpha, F::SrcColor, O::Subtract)},
        {"rgba8 const", ColorFormat::R8G8B8A8_UNORM,
         ba(F::ConstantColor, F::OneMinusConstantAlpha, O::ReverseSubtract, F::ConstantAlpha, F::OneMinusDstAlpha,
            O::Add, kWriteR | kWriteB | kWriteA)},
        {"rgba8 min max", ColorFormat::R8G8B8A8_UNORM, ba(F::SrcAlpha, F::DstColor, O::Min, F::Zero, F::Zero, O::Max)},
        {"rgba8 saturate", ColorFormat::R8G8B8A8_UNORM,
         ba(F::SrcAlphaSaturate, F::OneMinusSrcColor, O::Add, F::SrcAlphaSaturate, F::OneMinusDstColor, O::Add)},
        {"bgra8 alpha", ColorFormat::B8G8R8A8_UNORM,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Subtract, F::OneMinusDstAlpha, F::One, O::ReverseSubtract)},
        {"r8 lerp quirk", ColorFormat::R8_UNORM,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::SrcAlpha, F::OneMinusSrcAlpha, O::Add)},
        {"r8 dst alpha", ColorFormat::R8_UNORM, ba(F::DstAlpha, F::OneMinusDstColor, O::Add, F::One, F::Zero, O::Add)},
        {"rg8 const", ColorFormat::R8G8_UNORM, ba(F::ConstantAlpha, F::SrcColor, O::Subtract, F::One, F::Zero, O::Add)},
        {"rgba16f alpha", ColorFormat::R16G16B16A16_SFLOAT,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::OneMinusSrcAlpha, O::Add)},
        {"rgba16f shared", ColorFormat::R16G16B16A16_SFLOAT,
         ba(F::ConstantColor, F::ConstantColor, O::Subtract, F::ConstantColor, F::ConstantColor, O::Subtract)},
        {"r32f lerp", ColorFormat::R32_SFLOAT, ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::Zero, O::Add)},
        {"r32f complementary sub", ColorFormat::R32_SFLOAT,
         ba(F::OneMinusSrcColor, F::SrcColor, O::ReverseSubtract, F::One, F::Zero, O::Add)},
        {"rg32f general", ColorFormat::R32G32_SFLOAT,
         ba(F::DstColor, F::ConstantColor, O::Add, F::One, F::Zero, O::Add)},
        {"rgba32f shared", ColorFormat::R32G32B32A32_SFLOAT,
         ba(F::SrcAlpha, F::SrcAlpha, O::Add, F::SrcAlpha, F::SrcAlpha, O::Add)},
        {"rgba32f min", ColorFormat::R32G32B32A32_SFLOAT, ba(F::SrcColor, F::SrcAlpha, O::Min, F::One, F::One, O::Max)},
        {"srgb alpha", ColorFormat::R8G8B8A8_SRGB,
         ba(F::SrcAlpha, F::OneMinusSrcAlpha, O::Add, F::One, F::OneMinusSrcAlpha, O::Add)},
        {"srgb no blend", ColorFormat::B8G8R8A8_SRGB, off},
    };
    std::mt19937 rng(42);
    for (const Case& c : cases) {
        const FormatInfo fi = format_info(c.format);
        std::vector<float> src(size_t(kW) * kH * 4);
        std::vector<uint8_t> dst(size_t(kW) * kH * fi.bytes);
        for (float& s : src) s = random_src(rng, fi.kind);
        for (size_t p = 0; p < size_t(kW) * kH; ++p) random_dst(rng, c.format, &dst[p * fi.bytes]);
        const float consts[4] = {0.2f, 0.71f, 1.0f, 0.4f};
        const std::vector<uint8_t> got = render(v, c.format, c.a, consts, src, dst);
        int bad = 0, changed = 0;
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            changed += std::memcmp(&dst[p * fi.bytes], &got[p * fi.bytes], fi.bytes) != 0;
            uint8_t want[16];
            std::memcpy(want, &dst[p * fi.bytes], fi.bytes);
            blend_pixel(c.a, c.format, consts, &src[p * 4], want);
            if (std::memcmp(want, &got[p * fi.bytes], fi.bytes) != 0) {
                if (bad++ < 3) {
                    std::string w, g;
                    for (int i = 0; i < fi.bytes; ++i) {
                        w += std::to_string(want[i]) + " ";
                        g += std::to_string(got[p * fi.bytes + i]) + " ";
                    }
                    ADD_FAILURE() << c.name << " pixel " << p << " src " << src[p * 4] << "," << src[p * 4 + 1] << ","
                                  << src[p * 4 + 2] << "," << src[p * 4 + 3] << " want " << w << " lavapipe " << g;
                }
            }
        }
        EXPECT_EQ(bad, 0) << c.name;
        // The draw really happened: most pixels changed.
        EXPECT_GT(changed, int(kW * kH) / 2) << c.name;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Depth conversion and clamping, and MSAA resolve, against lavapipe.

TEST(FragmentLavapipe, DepthConversionAndClampMatchLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(77);
    std::vector<float> z(size_t(kW) * kH);
    for (size_t i = 0; i < z.size(); ++i) {
        const uint32_t r = rng() % 100;
        if (r < 3)
            z[i] = -0.5f;
        else if (r < 6)
            z[i] = 1.75f;
        else if (r < 8)
            z[i] = NAN;
        else if (r < 40)
            z[i] = float(rng() % 65536) / 65535.0f + float(int(rng() % 3) - 1) * 0x1p-18f;  // near codes
        else
            z[i] = bits_f(rng() % 0x3f800001u);  // any float in [0, 1]
    }
    struct DCase {
        VkFormat vf;
        DepthFormat df;
        uint32_t bpp;
        bool clamp;
    } cases[] = {{VK_FORMAT_D16_UNORM, DepthFormat::D16, 2, false},
                 {VK_FORMAT_D32_SFLOAT, DepthFormat::D32F, 4, false},
                 {VK_FORMAT_X8_D24_UNORM_PACK32, DepthFormat::X8D24, 4, false},
                 {VK_FORMAT_D16_UNORM, DepthFormat::D16, 2, true},
                 {VK_FORMAT_D32_SFLOAT, DepthFormat::D32F, 4, true}};
    for (const DCase& c : cases) {
        PassSpec spec;
        spec.depth = true;
        spec.format = c.vf;
        spec.depth_clamp = c.clamp;
        if (c.clamp) {
            spec.min_depth = 0.8f;  // reversed range: the clamp uses min/max of the two
            spec.max_depth = 0.3f;
        }
        const std::vector<uint8_t> got = run_pass(v, spec, z, c.bpp);
        DepthStencilState s;
        s.depth_test = s.depth_write = true;
        s.depth_compare = CompareOp::Always;
        s.depth_clamp = c.clamp;
        s.min_depth = 0.3f;
        s.max_depth = 0.8f;
        int bad = 0;
        for (size_t i = 0; i < z.size(); ++i) {
            uint32_t g = 0;
            std::memcpy(&g, &got[i * c.bpp], c.bpp);
            if (c.df == DepthFormat::X8D24) g &= 0xffffffu;
            const uint32_t want = depth_to_stored(clamp_depth(z[i], s, c.df), c.df);
            if (g != want && bad++ < 3)
                ADD_FAILURE() << "format " << c.vf << " clamp " << c.clamp << " z " << z[i] << " want " << want
                              << " lavapipe " << g;
        }
        EXPECT_EQ(bad, 0) << c.vf;
    }
}

TEST(FragmentLavapipe, ResolveMatchesLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(9);
    const ColorFormat formats[] = {ColorFormat::R8G8B8A8_UNORM, ColorFormat::R8_UNORM,
                                   ColorFormat::B8G8R8A8_UNORM, ColorFormat::R16G16B16A16_SFLOAT,
                                   ColorFormat::R32_SFLOAT,     ColorFormat::R8G8B8A8_SRGB};
    for (ColorFormat f : formats) {
        const FormatInfo fi = format_info(f);
        std::vector<float> c(size_t(kW) * kH * 4 * 4);
        for (float& x : c)
            x = fi.kind == ChannelKind::Float32 || fi.kind == ChannelKind::Half
                    ? float(int(rng() % 40001) - 20000) / 7919.0f
                    : float(rng() % 1000001) / 1000000.0f;
        PassSpec spec;
        spec.format = to_vk(f);
        const std::vector<uint8_t> got = run_pass(v, spec, c, fi.bytes);
        // Each sample's stored value is the shader colour through the format's output conversion, a pixel's
        // samples adjacent as icd/ images keep them; resolve_rect is what the driver resolves them with.
        const size_t bpp = fi.bytes;
        std::vector<uint8_t> samples(size_t(kW) * kH * 4 * bpp);
        const BlendAttachment off;
        const float k[4] = {};
        for (size_t p = 0; p < size_t(kW) * kH; ++p)
            for (int s = 0; s < 4; ++s) blend_pixel(off, f, k, &c[(p * 4 + s) * 4], &samples[(p * 4 + s) * bpp]);
        std::vector<uint8_t> resolved(size_t(kW) * kH * bpp);
        resolve_rect(f, samples.data(), bpp, size_t(kW) * 4 * bpp, resolved.data(), size_t(kW) * bpp, kW, kH, true,
                     4 * bpp);
        int bad = 0;
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            const uint8_t* want = &resolved[p * bpp];
            if (std::memcmp(want, &got[p * fi.bytes], fi.bytes) != 0 && bad++ < 3)
                ADD_FAILURE() << "format " << int(f) << " pixel " << p << " want " << int(want[0]) << " lavapipe "
                              << int(got[p * fi.bytes]);
        }
        EXPECT_EQ(bad, 0) << int(f);
    }
}

TEST(FragmentLavapipe, AlphaToCoverageAndSampleMaskMatchLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(21);
    std::vector<float> c(size_t(kW) * kH * 4);
    for (size_t p = 0; p < size_t(kW) * kH; ++p) {
        for (int ch = 0; ch < 3; ++ch) c[p * 4 + ch] = float(rng() % 1000001) / 1000000.0f;
        const uint32_t r = rng() % 100;
        // alphas on and around the thresholds 0, 0.25, 0.5, 0.75, plus NaN and out-of-range values
        const float th[4] = {0.0f, 0.25f, 0.5f, 0.75f};
        if (r < 40)
            c[p * 4 + 3] = std::nextafter(th[r % 4], (r & 4) ? 2.0f : -2.0f);
        else if (r < 60)
            c[p * 4 + 3] = th[r % 4];
        else if (r < 63)
            c[p * 4 + 3] = NAN;
        else if (r < 66)
            c[p * 4 + 3] = 1.5f;
        else
            c[p * 4 + 3] = float(rng() % 1001) / 1000.0f;
    }
    for (uint32_t smask : {0xfu, 0xbu}) {
        for (bool a2c : {true, false}) {
            PassSpec spec;
            spec.format = VK_FORMAT_R8G8B8A8_UNORM;
            spec.per_pixel_color = true;
            spec.alpha_to_coverage = a2c;
            spec.sample_mask = smask;
            const std::vector<uint8_t> got = run_pass(v, spec, c, 4);
            int bad = 0;
            for (size_t p = 0; p < size_t(kW) * kH; ++p) {
                // model: every sample covered; sample mask; alpha to coverage on the raw alpha; the covered samples
                // store the pixel's colour, the others keep the clear value 0; then resolve.
                float alpha[16] = {};
                alpha[0] = c[p * 4 + 3];
                uint16_t m[4] = {1, 1, 1, 1};
                apply_sample_mask(smask, 4, m);
                if (a2c) alpha_to_coverage_4x(alpha, m);
                uint8_t sp[4][4] = {};
                const BlendAttachment off;
                const float k[4] = {};
                for (int s = 0; s < 4; ++s)
                    if (m[s] & 1) blend_pixel(off, ColorFormat::R8G8B8A8_UNORM, k, &c[p * 4], sp[s]);
                const uint8_t* ptr[4] = {sp[0], sp[1], sp[2], sp[3]};
                uint8_t want[4];
                resolve_pixel(ColorFormat::R8G8B8A8_UNORM, ptr, want, true);
                if (std::memcmp(want, &got[p * 4], 4) != 0 && bad++ < 3)
                    ADD_FAILURE() << "smask " << smask << " a2c " << a2c << " alpha " << c[p * 4 + 3] << " want "
                                  << int(want[0]) << "," << int(want[3]) << " lavapipe " << int(got[p * 4]) << ","
                                  << int(got[p * 4 + 3]);
            }
            EXPECT_EQ(bad, 0) << smask << " " << a2c;
        }
    }
}

TEST(FragmentLavapipe, StencilAndDepthTestMatchLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(5150);
    const size_t n = size_t(kW) * kH;
    int total_bad = 0, depth_changed = 0, stencil_changed = 0;
    for (int iter = 0; iter < 24; ++iter) {
        DepthStencilState st;
        st.depth_test = iter % 4 != 3;
        st.depth_write = iter % 3 != 2;
        st.depth_compare = CompareOp(rng() % 8);
        st.stencil_test = iter % 6 != 5;
        for (StencilFace* f : {&st.front, &st.back}) {
            f->fail_op = StencilOp(rng() % 8);
            f->pass_op = StencilOp(rng() % 8);
            f->depth_fail_op = StencilOp(rng() % 8);
            f->compare_op = CompareOp(rng() % 8);
            f->compare_mask = uint8_t(rng());
            f->write_mask = uint8_t(rng());
            f->reference = uint8_t(rng() % 4 == 0 ? 0 : (rng() % 4 == 0 ? 255 : rng()));
        }
        const bool front = iter % 2 == 0;
        std::vector<uint32_t> d0(n), d1;
        std::vector<uint8_t> s0(n), s1;
        std::vector<float> z(n);
        for (size_t i = 0; i < n; ++i) {
            d0[i] = uint32_t(rng() % 0x1000000u);
            // stencil near the 0/255 edges and the reference, so clamps and wraps happen
            const uint32_t r = rng() % 4;
            s0[i] = uint8_t(r == 0 ? rng() % 3 : r == 1 ? 253 + rng() % 3 : r == 2 ? st.front.reference : rng());
            // depth equal to the stored value a quarter of the time
            z[i] = rng() % 4 == 0 ? float(double(d0[i]) / 16777215.0) : float(rng() % 1000001) / 1000000.0f;
        }
        run_stencil_pass(v, st, front, d0, s0, z, d1, s1);
        int bad = 0;
        for (size_t i = 0; i < n; ++i) {
            DepthStencilBlock b{};
            b.depth[0] = d0[i];
            b.stencil[0] = s0[i];
            float zz[16] = {z[i]};
            depth_stencil_test(st, DepthFormat::X8D24, front, zz, 1, b);
            depth_changed += (d1[i] & 0xffffffu) != d0[i];
            stencil_changed += s1[i] != s0[i];
            if (((d1[i] & 0xffffffu) != b.depth[0] || s1[i] != b.stencil[0]) && bad++ < 3)
                ADD_FAILURE() << "iter " << iter << " px " << i << " z " << z[i] << " d0 " << d0[i] << " s0 "
                              << int(s0[i]) << " want " << b.depth[0] << "/" << int(b.stencil[0]) << " lavapipe "
                              << (d1[i] & 0xffffffu) << "/" << int(s1[i]);
        }
        total_bad += bad;
    }
    EXPECT_EQ(total_bad, 0);
    // the draws did something
    EXPECT_GT(depth_changed, 5000);
    EXPECT_GT(stencil_changed, 5000);
}

// Interpolation: a triangle inside the viewport (no clipping), planes set up with the notes' §4 formulas in the
// test, evaluated by eval_plane / perspective_divide, compared with lavapipe's RGBA32F output at 1x and 4x.

TEST(FragmentLavapipe, InterpolationMatchesLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(31337);
    int fused_only = 0;
    for (int iter = 0; iter < 6; ++iter) {
        const bool msaa = iter % 2 == 1;
        // NDC corners of the lower-left half of the viewport: window (0,0), (64,0), (0,64) exactly.
        const float ndc[3][2] = {{-1, -1}, {1, -1}, {-1, 1}};
        const float ws[3] = {float(1 << (rng() % 3)), float(1 << (rng() % 3)), float(1 << (rng() % 3))};
        float attr_s[3][2], attr_l[3][2];
        std::vector<float> data;
        for (int i = 0; i < 3; ++i) {
            for (int c = 0; c < 2; ++c) {
                attr_s[i][c] = float(int(rng() % 20001) - 10000) / 997.0f;
                attr_l[i][c] = float(int(rng() % 20001) - 10000) / 991.0f;
            }
            const float w = ws[i];
            const float pos[4] = {ndc[i][0] * w, ndc[i][1] * w, 0.5f * w, w};
            data.insert(data.end(), pos, pos + 4);
            data.insert(data.end(), {attr_s[i][0], attr_s[i][1], 0.0f, 0.0f});
            data.insert(data.end(), {attr_l[i][0], attr_l[i][1], 0.0f, 0.0f});
        }
        PassSpec spec;
        spec.interp = true;
        spec.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        spec.samples = msaa ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
        const std::vector<uint8_t> got = run_pass(v, spec, data, 16);

        // Setup model: window coords are exact; the triangle is clockwise in lavapipe's fixed-point test, so the
        // flatshade_first re-order (v0, v2, v1) applies.
        const int order[3] = {0, 2, 1};
        float vx[3], vy[3], oow[3], as[2][3], al[2][3];
        for (int k = 0; k < 3; ++k) {
            const int i = order[k];
            vx[k] = (ndc[i][0] + 1.0f) * 32.0f;
            vy[k] = (ndc[i][1] + 1.0f) * 32.0f;
            oow[k] = 1.0f / ws[i];
            for (int c = 0; c < 2; ++c) {
                volatile float pa = attr_s[i][c] * oow[k];  // perspective inputs are pre-multiplied by 1/w
                as[c][k] = pa;
                al[c][k] = attr_l[i][c];
            }
        }
        const float pc = msaa ? 0.0f : 0.5f;
        const Plane pw = SetupPlane::make(vx, vy, oow, pc);
        Plane ps[2], plin[2];
        for (int c = 0; c < 2; ++c) {
            ps[c] = SetupPlane::make(vx, vy, as[c], pc);
            plin[c] = SetupPlane::make(vx, vy, al[c], pc);
        }
        int bad = 0, compared = 0;
        for (int by = 0; by < int(kH); by += 4)
            for (int bx = 0; bx < int(kW); bx += 4) {
                float want[2][4][16];  // [fused?][channel][lane]
                for (int f = 0; f < 2; ++f) {
                    const EvalOffset off = plane_offset(msaa ? 4 : 1, -1);
                    float w[16], a[16];
                    eval_plane(pw, bx, by, off, f == 0, w);
                    for (int c = 0; c < 2; ++c) {
                        eval_plane(ps[c], bx, by, off, f == 0, a);
                        perspective_divide(a, w, want[f][c]);
                        eval_plane(plin[c], bx, by, off, f == 0, want[f][2 + c]);
                    }
                }
                for (int l = 0; l < 16; ++l) {
                    const int x = bx + lane_x(l), y = by + lane_y(l);
                    if (x + y + 2 > 62) continue;  // strictly inside the triangle: every sample covered
                    ++compared;
                    const float* g = reinterpret_cast<const float*>(&got[(size_t(y) * kW + x) * 16]);
                    for (int c = 0; c < 4; ++c) {
                        float e[2];
                        for (int f = 0; f < 2; ++f) {
                            e[f] = want[f][c][l];
                            if (msaa) {  // four identical samples through the resolve shader
                                volatile float s = 0.0f;
                                for (int k = 0; k < 4; ++k) s = s + e[f];
                                e[f] = s * 0.25f;
                            }
                        }
                        fused_only += e[0] != e[1];
                        if (std::memcmp(&g[c], &e[0], 4) != 0 && bad++ < 3)
                            ADD_FAILURE() << "iter " << iter << " (" << x << "," << y << ") c" << c << " want " << e[0]
                                          << " lavapipe " << g[c];
                    }
                }
            }
        EXPECT_EQ(bad, 0) << iter;
        EXPECT_GT(compared, 1500);
    }
    EXPECT_GT(fused_only, 0);  // the data distinguishes fused from unfused evaluation
}

TEST(FragmentLavapipe, ClearPackingMatchesLavapipe) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(606);
    const ColorFormat formats[] = {ColorFormat::R8G8B8A8_UNORM, ColorFormat::B8G8R8A8_SRGB, ColorFormat::R8G8B8A8_SRGB,
                                   ColorFormat::R16G16B16A16_SFLOAT};
    for (ColorFormat f : formats) {
        const FormatInfo fi = format_info(f);
        for (int iter = 0; iter < 8; ++iter) {
            PassSpec spec;
            spec.format = to_vk(f);
            spec.samples = VK_SAMPLE_COUNT_1_BIT;
            spec.per_pixel_color = true;
            spec.no_draw = true;
            for (float& c : spec.clear) c = float(int(rng() % 1200001) - 100000) / 1000000.0f;
            if (iter == 0) {
                spec.clear[0] = 0.0031308f;
                spec.clear[1] = 0.5f / 255.0f;
                spec.clear[2] = 1e-5f;
                spec.clear[3] = 127.5f / 255.0f;
            }
            const std::vector<float> dummy(4, 0.0f);
            const std::vector<uint8_t> got = run_pass(v, spec, dummy, fi.bytes);
            uint8_t want[16];
            ASSERT_TRUE(pack_clear_color(f, spec.clear, want));
            EXPECT_EQ(std::memcmp(want, got.data(), fi.bytes), 0)
                << "format " << int(f) << " clear " << spec.clear[0] << "," << spec.clear[1] << "," << spec.clear[2]
                << "," << spec.clear[3] << " want " << int(want[0]) << "," << int(want[1]) << "," << int(want[2]) << ","
                << int(want[3]) << " lavapipe " << int(got[0]) << "," << int(got[1]) << "," << int(got[2]) << ","
                << int(got[3]);
        }
    }
}

TEST(FragmentLavapipe, SingleSampleMaskAndHalfAlphaThreshold) {
    Lvp v;
    if (!v.init()) GTEST_SKIP() << "lavapipe not available (set VK_ICD_FILENAMES)";
    std::mt19937 rng(8);
    std::vector<float> c(size_t(kW) * kH * 4);
    for (size_t p = 0; p < size_t(kW) * kH; ++p) {
        for (int ch = 0; ch < 3; ++ch) c[p * 4 + ch] = float(rng() % 1000) / 999.0f;
        const uint32_t r = rng() % 10;
        c[p * 4 + 3] = r == 0   ? 0.5f
                       : r == 1 ? std::nextafter(0.5f, 1.0f)
                       : r == 2 ? NAN
                                : float(rng() % 1001) / 1000.0f;
    }
    for (int variant = 0; variant < 6; ++variant) {
        const bool a2c = variant & 1;
        // bit 0 clear still draws at 1x; only an all-zero mask discards
        const uint32_t smask = variant < 2 ? 1u : variant < 4 ? 0xfffffffeu : 0u;
        PassSpec spec;
        spec.format = VK_FORMAT_R8G8B8A8_UNORM;
        spec.samples = VK_SAMPLE_COUNT_1_BIT;
        spec.per_pixel_color = true;
        spec.alpha_to_coverage = a2c;
        spec.sample_mask = smask;
        const std::vector<uint8_t> got = run_pass(v, spec, c, 4);
        int bad = 0;
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            float alpha[16] = {c[p * 4 + 3]};
            uint16_t m[4] = {1, 0, 0, 0};
            apply_sample_mask(smask, 1, m);
            const bool live = m[0] && (!a2c || (alpha_to_coverage_1x(alpha, 1) & 1));
            uint8_t want[4] = {0, 0, 0, 0};
            const BlendAttachment off;
            const float k[4] = {};
            if (live) blend_pixel(off, ColorFormat::R8G8B8A8_UNORM, k, &c[p * 4], want);
            if (std::memcmp(want, &got[p * 4], 4) != 0 && bad++ < 3)
                ADD_FAILURE() << "a2c " << a2c << " alpha " << c[p * 4 + 3] << " want " << int(want[0]) << " lavapipe "
                              << int(got[p * 4]);
        }
        EXPECT_EQ(bad, 0) << a2c;
    }
}
