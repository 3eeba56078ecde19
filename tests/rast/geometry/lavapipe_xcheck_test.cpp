// End-to-end cross-check with lavapipe: triangles (many clipped, with perspective) are rendered through Vulkan on
// lavapipe into R8G8B8A8_UNORM at 1x, and every pixel is compared with a model made of this folder's
// prepare_vertex / clip_triangle / setup_triangle_planes plus the notes' snap, edge (§2), interpolation (§4) and
// colour (§5) rules written out below. Skips when lavapipe is not available.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <vector>

#include "host/cpu.h"
#include "lavapipe_harness.h"
#include "xcheck_model.h"

using namespace tilevk::rast::geometry;
using namespace xcheck;

TEST(LavapipeCrossCheck, ClippedPerspectiveTrianglesMatchPixelForPixel) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    const bool fma = tilevk::host::has_fma();
    int compared = 0, clipped_scenes = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        for (int mode : {0, 1, 2, 4, 5, 6}) {
            const auto got = lvp.render(scenes[s], mode);
            ASSERT_EQ(got.size(), static_cast<size_t>(kSize * kSize * 4));
            const auto want = model(scenes[s], mode, fma);
            int diff = 0, first = -1;
            for (size_t i = 0; i < got.size(); ++i)
                if (got[i] != want[i]) {
                    if (first < 0) first = static_cast<int>(i);
                    ++diff;
                }
            EXPECT_EQ(diff, 0) << "scene " << s << " mode " << mode << " first diff at pixel " << first / 4
                               << " channel " << first % 4 << ": lavapipe " << int(got[first < 0 ? 0 : first])
                               << " model " << int(want[first < 0 ? 0 : first]);
            int lit = 0;
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            compared += lit;
        }
        (void)clipped_scenes;
    }
    std::printf("compared %zu scenes x 6 modes, %d lit pixels in total\n", scenes.size(), compared);
    EXPECT_GT(compared, 10000);  // the scenes really drew something
}

TEST(LavapipeCrossCheck, WrongRulesAreDetected) {
    // The comparison can fail: deliberately wrong rules (the other FMA choice, a/w for a*(1/w)) must differ.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    int diff_fma = 0, diff_div = 0;
    for (const auto& sc : scenes) {
        for (int mode : {4, 5}) {
            const auto got = lvp.render(sc, mode);
            const auto wrong_fma = model(sc, mode, !tilevk::host::has_fma());
            const auto wrong_div = model(sc, mode, tilevk::host::has_fma(), true);
            for (size_t i = 0; i < got.size(); ++i) {
                diff_fma += got[i] != wrong_fma[i];
                diff_div += got[i] != wrong_div[i];
            }
        }
    }
    std::printf("wrong-rule channel mismatches: other FMA choice %d, a/w %d\n", diff_fma, diff_div);
    EXPECT_GT(diff_fma, 0);
    EXPECT_GT(diff_div, 0);
}

TEST(LavapipeCrossCheck, LinesIncludingClippedAndWide) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = tilevk::host::has_fma();
    int lit = 0;
    for (int s = 0; s < 16; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 2 * 6; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            sc.push_back(iv((u(rng) * 3.0f - 1.5f) * w, (u(rng) * 3.0f - 1.5f) * w, (u(rng) * 1.2f - 0.1f) * w, w,
                            u(rng), u(rng), u(rng), u(rng)));
        }
        for (float width : {1.0f, 3.0f, 2.5f}) {
            for (int mode : {0, 1, 2, 4, 5}) {
                const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, width);
                const auto want = model_lines(sc, mode, fma, width);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "scene " << s << " width " << width << " mode " << mode << " first diff pixel "
                                   << first / 4 << " (x " << (first / 4) % kSize << ", y " << (first / 4) / kSize
                                   << ") lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                                   << int(want[first < 0 ? 0 : first]);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("lines: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, PointsIncludingOffscreenCentres) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = tilevk::host::has_fma();
    int lit = 0;
    for (int s = 0; s < 16; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 24; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            sc.push_back(iv((u(rng) * 2.4f - 1.2f) * w, (u(rng) * 2.4f - 1.2f) * w, (u(rng) * 1.2f - 0.1f) * w, w,
                            u(rng), u(rng), u(rng), u(rng)));
        }
        for (int mode : {0, 1, 2, 4, 5}) {
            const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST);
            const auto want = model_points(sc, mode, fma);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "scene " << s << " mode " << mode << " first diff pixel " << first / 4 << " (x "
                               << (first / 4) % kSize << ", y " << (first / 4) / kSize << ") lavapipe "
                               << int(got[first < 0 ? 0 : first]) << " model " << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
        }
    }
    std::printf("points: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, BresenhamLines) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    if (!lvp.has_line_ext()) GTEST_SKIP() << "no VK_EXT_line_rasterization";
    std::mt19937 rng(78);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = tilevk::host::has_fma();
    int lit = 0, differs_from_rect = 0;
    for (int s = 0; s < 16; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 2 * 6; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            // a quarter of the endpoints on pixel centres / edges, where the diamond rule has its special cases
            float x = u(rng) * 2.4f - 1.2f, y = u(rng) * 2.4f - 1.2f;
            if (k % 4 == 0) x = (std::floor((x + 1) * 32) + 0.5f) / 32 - 1, y = std::floor((y + 1) * 32) / 32 - 1;
            sc.push_back(iv(x * w, y * w, 0.5f * w, w, u(rng), u(rng), u(rng), u(rng)));
        }
        for (float width : {1.0f, 3.0f}) {
            for (int mode : {0, 1, 4}) {
                const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, width, true);
                const auto want = model_lines(sc, mode, fma, width, true);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "scene " << s << " width " << width << " mode " << mode << " first diff pixel "
                                   << first / 4 << " (x " << (first / 4) % kSize << ", y " << (first / 4) / kSize
                                   << ") lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                                   << int(want[first < 0 ? 0 : first]);
                int f2;
                differs_from_rect += count_diff(got, model_lines(sc, mode, fma, width, false), &f2);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("bresenham lines: %d lit pixels compared, %d channels differ from the rectangular model\n", lit,
                differs_from_rect);
    EXPECT_GT(lit, 2000);
    EXPECT_GT(differs_from_rect, 0);  // the two line modes are really different
}

TEST(LavapipeCrossCheck, VertexFormatConversions) {
    // Points with constant colours fetched from each format; the amplified mode (fract(x*65536)) exposes the low
    // bits of every converted value in the u8 output.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const struct {
        VkFormat vk;
        VertexFormat ours;
    } formats[] = {
        {VK_FORMAT_R8G8B8A8_UNORM, VertexFormat::R8G8B8A8_UNORM},
        {VK_FORMAT_R8G8B8A8_SNORM, VertexFormat::R8G8B8A8_SNORM},
        {VK_FORMAT_B8G8R8A8_UNORM, VertexFormat::B8G8R8A8_UNORM},
        {VK_FORMAT_R8G8_UNORM, VertexFormat::R8G8_UNORM},
        {VK_FORMAT_R8G8B8_SNORM, VertexFormat::R8G8B8_SNORM},
        {VK_FORMAT_R16G16B16A16_UNORM, VertexFormat::R16G16B16A16_UNORM},
        {VK_FORMAT_R16G16B16A16_SNORM, VertexFormat::R16G16B16A16_SNORM},
        {VK_FORMAT_R16G16_SNORM, VertexFormat::R16G16_SNORM},
        {VK_FORMAT_R16G16B16A16_SFLOAT, VertexFormat::R16G16B16A16_SFLOAT},
        {VK_FORMAT_R32G32B32_SFLOAT, VertexFormat::R32G32B32_SFLOAT},
        {VK_FORMAT_R32_SFLOAT, VertexFormat::R32_SFLOAT},
    };
    std::mt19937 rng(404);
    const bool fma = tilevk::host::has_fma();
    int lit = 0;
    for (const auto& f : formats) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 64; ++k) {
            InVertex v = iv(((k % 8) + 0.5f) / 4 - 1, ((k / 8) + 0.5f) / 4 - 1, 0.5f, 1, 0, 0, 0);
            uint8_t bytes[16];
            for (auto& b : bytes) b = static_cast<uint8_t>(rng());
            if (k < 4) std::memset(bytes, k == 0 ? 0x00 : k == 1 ? 0xFF : k == 2 ? 0x80 : 0x7F, 16);  // extremes
            if (f.ours == VertexFormat::R16G16B16A16_SFLOAT || f.ours == VertexFormat::R32G32B32_SFLOAT ||
                f.ours == VertexFormat::R32_SFLOAT) {
                // finite values in [0, 1): random mantissa bits
                for (int c = 0; c < 4; ++c) {
                    const float x = static_cast<float>(rng() % 1000000) / 1000000.0f;
                    if (f.ours == VertexFormat::R16G16B16A16_SFLOAT) {
                        const uint16_t h = static_cast<uint16_t>(0x3800 | (rng() & 0x3FF));  // [0.5, 1)
                        std::memcpy(bytes + 2 * c, &h, 2);
                    } else {
                        std::memcpy(bytes + 4 * c, &x, 4);
                    }
                }
            }
            std::memcpy(v.col, bytes, 16);
            sc.push_back(v);
        }
        for (int mode : {1, 5}) {
            const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 1, false, f.vk);
            const auto want = model_points(sc, mode, fma, f.ours);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "format " << f.vk << " mode " << mode << " first diff pixel " << first / 4
                               << " channel " << first % 4 << " lavapipe " << int(got[first < 0 ? 0 : first])
                               << " model " << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
        }
    }
    std::printf("vertex formats: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 500);
}

TEST(LavapipeCrossCheck, DepthPlaneAndDepthBias) {
    // gl_FragCoord.z carries the z plane plus lavapipe's depth offset (unorm24 units without a depth attachment).
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    const bool fma = tilevk::host::has_fma();
    DepthBias cases[4];
    cases[0] = DepthBias{};
    cases[1].constant_factor = 3.0f;
    cases[2].constant_factor = 1.5f, cases[2].slope_factor = 0.75f;
    cases[3].constant_factor = -200.0f, cases[3].slope_factor = -2.0f, cases[3].clamp = -0.0004f;
    int lit = 0, unbiased_diff = 0, no_factor2_diff = 0;
    for (int b = 0; b < 4; ++b) {
        for (size_t s = 0; s < 12; ++s) {
            const auto got = lvp.render(scenes[s], 8, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                        VK_FORMAT_R32G32B32A32_SFLOAT, b == 0 ? nullptr : &cases[b]);
            const auto want = model(scenes[s], 8, fma, false, b == 0 ? nullptr : &cases[b]);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "bias case " << b << " scene " << s << " first diff pixel " << first / 4
                               << " channel " << first % 4 << " lavapipe " << int(got[first < 0 ? 0 : first])
                               << " model " << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            if (b != 0) {
                // negative control: the same scene without the bias (or without the factor 2) must differ
                int f2;
                unbiased_diff += count_diff(got, model(scenes[s], 8, fma), &f2);
                DepthBias half = cases[b];
                half.constant_factor *= 0.5f;
                no_factor2_diff += count_diff(got, model(scenes[s], 8, fma, false, &half), &f2);
            }
        }
    }
    std::printf("depth: %d lit pixels compared; controls differ: no bias %d, no factor 2 %d\n", lit, unbiased_diff,
                no_factor2_diff);
    EXPECT_GT(unbiased_diff, 0);
    EXPECT_GT(no_factor2_diff, 0);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, DepthClampNegativeWAndCulling) {
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    auto scenes = make_scenes();
    std::mt19937 rng(909);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int s = 0; s < 12; ++s) {  // vertices behind the eye (w < 0) and far outside z
        std::vector<InVertex> sc;
        for (int k = 0; k < 3 * 4; ++k) {
            const float w = -1.0f + 4.0f * u(rng);
            sc.push_back(iv((u(rng) * 3 - 1.5f) * 1.5f, (u(rng) * 3 - 1.5f) * 1.5f, (u(rng) * 3 - 1) * 1.5f, w, u(rng),
                            u(rng), u(rng), u(rng)));
        }
        scenes.push_back(sc);
    }
    const bool fma = tilevk::host::has_fma();
    int lit = 0;
    for (int variant = 0; variant < 4; ++variant) {
        Extra x;
        ModelExtra mx;
        x.depth_clamp = variant == 1;
        mx.clip_z = !x.depth_clamp;
        if (variant == 2) x.cull = VK_CULL_MODE_BACK_BIT, mx.cull_back = true;
        if (variant == 3) {
            x.cull = VK_CULL_MODE_FRONT_BIT, mx.cull_front = true;
            x.front = VK_FRONT_FACE_CLOCKWISE, mx.front_ccw = false;
        }
        for (size_t s = 0; s < scenes.size(); ++s) {
            for (int mode : {0, 4}) {
                const auto got = lvp.render(scenes[s], mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                            VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                const auto want = model(scenes[s], mode, fma, false, nullptr, mx);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "variant " << variant << " scene " << s << " mode " << mode
                                   << " first diff pixel " << first / 4 << " lavapipe "
                                   << int(got[first < 0 ? 0 : first]) << " model " << int(want[first < 0 ? 0 : first]);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("depth clamp / w<0 / cull: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 5000);
}

TEST(LavapipeCrossCheck, StripsFansAndRestartOrders) {
    // Indexed strips and fans with primitive restart: assemble_primitives' order (and thus each triangle's plane
    // rounding and provoking vertex) must reproduce lavapipe's pixels, in the amplified and flat modes.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(1717);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = tilevk::host::has_fma();
    int lit = 0, wrong_diff = 0;
    for (int s = 0; s < 12; ++s) {
        std::vector<InVertex> verts;
        for (int k = 0; k < 16; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            verts.push_back(iv((u(rng) * 2.8f - 1.4f) * w, (u(rng) * 2.8f - 1.4f) * w, 0.5f * w, w, u(rng), u(rng),
                               u(rng), u(rng)));
        }
        std::vector<uint32_t> idx;
        for (int k = 0; k < 14; ++k) idx.push_back(rng() % 16);
        idx[6] = 0xFFFFFFFFu;  // restart in the middle
        for (auto topo : {VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN}) {
            IndexSource src;
            src.indices = reinterpret_cast<const uint8_t*>(idx.data());
            src.index_size = 4;
            src.index_count_total = static_cast<uint32_t>(idx.size());
            src.count = src.index_count_total;
            src.primitive_restart = true;
            const Topology t =
                topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP ? Topology::kTriangleStrip : Topology::kTriangleFan;
            std::vector<uint32_t> order(assembled_index_capacity(t, src.count));
            const uint32_t prims = assemble_primitives(src, t, true, order.data(), order.size());
            std::vector<InVertex> list, wrong;
            for (uint32_t i = 0; i < prims * 3; ++i) list.push_back(verts[order[i]]);
            // negative control: the last-vertex-provoking order
            std::vector<uint32_t> order_last(order.size());
            assemble_primitives(src, t, false, order_last.data(), order_last.size());
            for (uint32_t i = 0; i < prims * 3; ++i) wrong.push_back(verts[order_last[i]]);
            Extra x;
            x.restart = true;
            x.indices = &idx;
            for (int mode : {2, 4, 5}) {
                const auto got = lvp.render(verts, mode, topo, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                const auto want = model(list, mode, fma);
                int first;
                const int diff = count_diff(got, want, &first);
                EXPECT_EQ(diff, 0) << "topology " << topo << " scene " << s << " mode " << mode << " first diff pixel "
                                   << first / 4 << " lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                                   << int(want[first < 0 ? 0 : first]);
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
                wrong_diff += count_diff(got, model(wrong, mode, fma), &first);
            }
        }
    }
    std::printf("strips/fans: %d lit pixels compared; last-vertex order differs in %d channels\n", lit, wrong_diff);
    EXPECT_GT(wrong_diff, 0);
    EXPECT_GT(lit, 5000);
}

TEST(LavapipeCrossCheck, FractionalViewportLimitsEveryPrimitive) {
    // A fractional viewport smaller than the target: clipped triangles and lines, and points (never x/y clipped,
    // limited only by the viewport's whole-pixel rectangle).
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = tilevk::host::has_fma();
    const float vps[3][4] = {{10.25f, 5.75f, 40.5f, 30.25f}, {3.6f, 50.4f, 52.3f, -41.7f}, {0.5f, 0.5f, 62, 62}};
    int lit = 0;
    for (const auto& vpv : vps) {
        Extra x;
        ModelExtra mx;
        std::memcpy(x.vp, vpv, sizeof(x.vp));
        std::memcpy(mx.vp, vpv, sizeof(mx.vp));
        for (int s = 0; s < 6; ++s) {
            std::vector<InVertex> sc;
            for (int k = 0; k < 12; ++k) {
                const float w = 0.5f + 2.0f * u(rng);
                sc.push_back(iv((u(rng) * 3.0f - 1.5f) * w, (u(rng) * 3.0f - 1.5f) * w, 0.5f * w, w, u(rng), u(rng),
                                u(rng), u(rng)));
            }
            for (int mode : {0, 4}) {
                int first;
                auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                      VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                EXPECT_EQ(count_diff(got, model(sc, mode, fma, false, nullptr, mx), &first), 0)
                    << "triangles vp " << vpv[0] << " scene " << s << " mode " << mode << " pixel " << first / 4;
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
                got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 2.0f, false, VK_FORMAT_R32G32B32A32_SFLOAT,
                                 nullptr, x);
                EXPECT_EQ(count_diff(got, model_lines(sc, mode, fma, 2.0f, false, mx), &first), 0)
                    << "lines vp " << vpv[0] << " scene " << s << " mode " << mode << " pixel " << first / 4;
                got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT,
                                 nullptr, x);
                EXPECT_EQ(count_diff(got, model_points(sc, mode, fma, VertexFormat::R32G32B32A32_SFLOAT, mx), &first),
                          0)
                    << "points vp " << vpv[0] << " scene " << s << " mode " << mode << " pixel " << first / 4;
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
        }
    }
    std::printf("fractional viewports: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, NineVertexTriangleListQuirk) {
    // lavapipe-rules §8: a non-indexed, unclipped TRIANGLE_LIST draw of exactly 9 vertices without flat inputs whose
    // third triangle has three equal window y values is swallowed by lp_setup_analyse_triangles (unless the first six
    // vertices form its "aero" rectangle). Check what lavapipe really does.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::vector<InVertex> sc = {
        iv(-0.9f, -0.9f, 0.5f, 1, 1, 0, 0), iv(0.5f, -0.8f, 0.5f, 1, 0, 1, 0), iv(-0.7f, 0.6f, 0.5f, 1, 0, 0, 1),
        iv(0.1f, 0.1f, 0.5f, 1, 1, 1, 0),   iv(0.9f, 0.2f, 0.5f, 1, 0, 1, 1),  iv(0.3f, 0.9f, 0.5f, 1, 1, 0, 1),
        iv(-0.5f, 0.5f, 0.5f, 1, 1, 1, 1),  iv(0.0f, 0.5f, 0.5f, 1, 1, 1, 1),  iv(0.5f, 0.5f, 0.5f, 1, 1, 1, 1)};
    Extra x;
    x.no_flat = true;
    auto lit_count = [](const std::vector<uint8_t>& img) {
        int n = 0;
        for (size_t i = 3; i < img.size(); i += 4) n += img[i] != 0;
        return n;
    };
    const auto nine =
        lvp.render(sc, 0, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
    // the same first two triangles with a non-degenerate third: everything drawn
    auto sc2 = sc;
    sc2[8].pos[1] = 0.6f;
    const auto control =
        lvp.render(sc2, 0, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
    // with a flat input in the shader the analysis is off
    const auto flat = lvp.render(sc, 0);
    std::printf("9-vertex quirk: lit pixels %d (quirk case), %d (control), %d (shader with a flat input)\n",
                lit_count(nine), lit_count(control), lit_count(flat));
    EXPECT_EQ(lit_count(nine), 0);
    EXPECT_GT(lit_count(control), 100);
    EXPECT_GT(lit_count(flat), 100);
    EXPECT_EQ(quirk_for(sc), NineVertexQuirk::kSwallowed);
    EXPECT_EQ(quirk_for(sc2), NineVertexQuirk::kNone);
    EXPECT_EQ(quirk_for(sc, false, true), NineVertexQuirk::kNone);
    // 10 vertices: draw trims the incomplete triangle first, so the quirk still applies
    auto ten = sc;
    ten.push_back(iv(0, 0, 0.5f, 1, 1, 1, 1));
    EXPECT_EQ(lit_count(lvp.render(ten, 0, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT,
                                   nullptr, x)),
              0);
    EXPECT_EQ(quirk_for(ten), NineVertexQuirk::kSwallowed);
    // a clipped vertex sends the batch down draw's pipeline path: no analysis, everything drawn
    auto clipped = sc;
    clipped[0].pos[0] = -1.5f;
    EXPECT_GT(lit_count(lvp.render(clipped, 0, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                   VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x)),
              100);
    EXPECT_EQ(quirk_for(clipped), NineVertexQuirk::kNone);
    // indexed draws go through draw_elements: no analysis
    std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    Extra xi = x;
    xi.indices = &idx;
    EXPECT_GT(lit_count(lvp.render(sc, 0, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false, VK_FORMAT_R32G32B32A32_SFLOAT,
                                   nullptr, xi)),
              100);
    EXPECT_EQ(quirk_for(sc, true), NineVertexQuirk::kNone);
}

TEST(LavapipeCrossCheck, Msaa4xClippedTrianglesAfterResolve) {
    // 4x: snap offset 0, per-sample coverage at lavapipe's sample positions, planes from the pixel corner (pc = 0)
    // evaluated at the pixel centre, then the render-pass resolve.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const auto scenes = make_scenes();
    const bool fma = tilevk::host::has_fma();
    Extra x;
    x.samples = 4;
    ModelExtra mx;
    mx.samples = 4;
    int lit = 0, one_x_diff = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        for (int mode : {0, 1, 2, 4, 5}) {
            const auto got = lvp.render(scenes[s], mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                        VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
            const auto want = model(scenes[s], mode, fma, false, nullptr, mx);
            int first;
            const int diff = count_diff(got, want, &first);
            EXPECT_EQ(diff, 0) << "scene " << s << " mode " << mode << " first diff pixel " << first / 4 << " (x "
                               << (first / 4) % kSize << ", y " << (first / 4) / kSize << ") channel " << first % 4
                               << " lavapipe " << int(got[first < 0 ? 0 : first]) << " model "
                               << int(want[first < 0 ? 0 : first]);
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            one_x_diff += count_diff(got, model(scenes[s], mode, fma), &first);
        }
    }
    std::printf("msaa 4x: %d lit pixels compared; the 1x model differs in %d channels\n", lit, one_x_diff);
    EXPECT_GT(lit, 10000);
    EXPECT_GT(one_x_diff, 0);
}

TEST(LavapipeCrossCheck, Msaa4xLinesAndPoints) {
    // 4x lines (rectangular) and points: snap offset 0, but attribute planes keep setup->pixel_offset 0.5 while the
    // shader evaluates at the pixel centre (the half-pixel attribute shift of lavapipe-rules §6).
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    std::mt19937 rng(8080);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const bool fma = tilevk::host::has_fma();
    Extra x;
    x.samples = 4;
    ModelExtra mx;
    mx.samples = 4;
    int lit = 0;
    for (int s = 0; s < 10; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 12; ++k) {
            const float w = 0.5f + 2.0f * u(rng);
            sc.push_back(iv((u(rng) * 2.6f - 1.3f) * w, (u(rng) * 2.6f - 1.3f) * w, 0.5f * w, w, u(rng), u(rng), u(rng),
                            u(rng)));
        }
        for (int mode : {0, 1, 4}) {
            int first;
            for (float width : {1.0f, 2.5f}) {
                const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, width, false,
                                            VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                EXPECT_EQ(count_diff(got, model_lines(sc, mode, fma, width, false, mx), &first), 0)
                    << "lines scene " << s << " width " << width << " mode " << mode << " pixel " << first / 4;
                for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
            }
            const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 1, false,
                                        VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
            EXPECT_EQ(count_diff(got, model_points(sc, mode, fma, VertexFormat::R32G32B32A32_SFLOAT, mx), &first), 0)
                << "points scene " << s << " mode " << mode << " pixel " << first / 4;
            for (size_t i = 3; i < got.size(); i += 4) lit += got[i] != 0;
        }
    }
    std::printf("msaa 4x lines/points: %d lit pixels compared\n", lit);
    EXPECT_GT(lit, 2000);
}

TEST(LavapipeCrossCheck, FloatCullOnlyOnDrawsPipelinePath) {
    // A sliver whose orientation flips when snapped: float det and fixed-point area disagree. draw's float cull
    // only runs when some vertex of the batch is clipped, so the same sliver is kept or culled depending on an
    // unrelated clipped triangle in the same draw.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const bool fma = tilevk::host::has_fma();
    // window = (ndc + 1) * 32; we want window v0 (10.5, 10.5), v1 (30.5, 10.5017), v2 (50.5, 10.503)
    auto ndc = [](float wx) { return wx / 32.0f - 1.0f; };
    const std::vector<InVertex> sliver = {iv(ndc(10.5f), ndc(10.5f), 0.5f, 1, 1, 0, 0),
                                          iv(ndc(30.5f), ndc(10.5017f), 0.5f, 1, 0, 1, 0),
                                          iv(ndc(50.5f), ndc(10.503f), 0.5f, 1, 0, 0, 1)};
    std::vector<InVertex> with_clipped = sliver;
    for (const auto& v :
         {iv(-1.5f, 0.5f, 0.5f, 1, 1, 1, 1), iv(-0.5f, 0.9f, 0.5f, 1, 1, 1, 1), iv(-0.6f, 0.6f, 0.5f, 1, 1, 1, 1)})
        with_clipped.push_back(v);
    int differing_rules = 0;
    for (VkCullModeFlags cull : {VK_CULL_MODE_BACK_BIT, VK_CULL_MODE_FRONT_BIT}) {
        Extra x;
        x.cull = cull;
        ModelExtra mx;
        mx.cull_back = cull == VK_CULL_MODE_BACK_BIT;
        mx.cull_front = cull == VK_CULL_MODE_FRONT_BIT;
        for (const std::vector<InVertex>* sc :
             std::initializer_list<const std::vector<InVertex>*>{&sliver, &with_clipped}) {
            for (int mode : {0, 2}) {
                const auto got = lvp.render(*sc, mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                            VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
                int first;
                EXPECT_EQ(count_diff(got, model(*sc, mode, fma, false, nullptr, mx), &first), 0)
                    << "cull " << cull << " scene with clipped triangle " << (sc == &with_clipped) << " pixel "
                    << first / 4;
            }
        }
        // sanity: does the batch rule matter here at all? compare the model with float cull forced off
        int lit_a = 0, lit_b = 0;
        const auto a = model(sliver, 2, fma, false, nullptr, mx);
        const auto b = model(with_clipped, 2, fma, false, nullptr, mx);
        for (int p = 0; p < 64 * 26; ++p) lit_a += a[p * 4 + 3] != 0, lit_b += b[p * 4 + 3] != 0;  // rows 0..25
        differing_rules += lit_a != lit_b;
        std::printf("cull %u: sliver rows lit alone %d, with a clipped triangle in the draw %d\n", cull, lit_a, lit_b);
    }
    EXPECT_GT(differing_rules, 0) << "the sliver does not exercise the batch rule";
}

TEST(LavapipeCrossCheck, IdentityViewportBypassesTheDivide) {
    // Viewport (-1, -1, 2, 2), depth [0, 1]: scale (1,1,1), translate (0,0,0) -> draw bypasses the viewport and the
    // divide by w. Its pixel rectangle is just pixel (0, 0): (int)(-1 + 0.499) = 0 .. (int)(2 - 1 - 0.501) = 0.
    Lavapipe lvp;
    if (!lvp.init()) GTEST_SKIP() << "lavapipe not available";
    const bool fma = tilevk::host::has_fma();
    Extra x;
    ModelExtra mx;
    const float vp[4] = {-1, -1, 2, 2};
    std::memcpy(x.vp, vp, sizeof(vp));
    std::memcpy(mx.vp, vp, sizeof(vp));
    ASSERT_TRUE(is_identity_viewport(model_viewport(mx)));
    // raw clip (0,0) (2,0) (0,2) covers pixel (0,0)'s centre only without the divide by w = 4
    const std::vector<InVertex> sc = {iv(0, 0, 0.5f, 4, 0.9f, 0.1f, 0.3f), iv(2, 0, 0.5f, 4, 0.2f, 0.8f, 0.5f),
                                      iv(0, 2, 0.5f, 4, 0.4f, 0.4f, 0.9f)};
    for (int mode : {0, 1, 4}) {
        const auto got = lvp.render(sc, mode, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1, false,
                                    VK_FORMAT_R32G32B32A32_SFLOAT, nullptr, x);
        int first;
        EXPECT_EQ(count_diff(got, model(sc, mode, fma, false, nullptr, mx), &first), 0)
            << "mode " << mode << " pixel " << first / 4;
        EXPECT_NE(got[0], 0) << "pixel (0,0) should be drawn when the divide is bypassed";
        // with a viewport transform (divide by w = 4) the triangle would miss pixel (0,0)'s centre
        ModelExtra divided = mx;
        divided.vp[2] = 2.0000002f;  // not identity any more
        EXPECT_EQ(model(sc, mode, fma, false, nullptr, divided)[0], 0);
    }
}
