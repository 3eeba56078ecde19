// The judging functions on hand-made planes: the expected counts are constructed here, independently of
// compare_planes and the checks under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "judge.hpp"
#include "png_writer.hpp"
#include "results.hpp"

namespace tilevk::cts {
namespace {

Plane rgba_plane(uint32_t w, uint32_t h, uint8_t fill) {
    Plane p{"color", VK_FORMAT_R8G8B8A8_UNORM, w, h, 4, {}};
    p.data.assign(size_t(w) * h * 4, fill);
    return p;
}

TEST(CompareDetects, KnownDifferingPixelsAndMaxError) {
    Plane ref = rgba_plane(16, 8, 10), ours = ref;
    // Change exactly 5 pixels: one channel each, by 1, 2, 3, 200 and (two channels of one pixel) 7.
    ours.data[(0 * 16 + 0) * 4 + 0] = 11;
    ours.data[(1 * 16 + 3) * 4 + 1] = 12;
    ours.data[(7 * 16 + 15) * 4 + 3] = 13;
    ours.data[(4 * 16 + 9) * 4 + 2] = 210;
    ours.data[(2 * 16 + 2) * 4 + 0] = 17;
    ours.data[(2 * 16 + 2) * 4 + 1] = 3;
    PlaneDiff d = compare_planes(ours, ref);
    EXPECT_TRUE(d.problem.empty());
    EXPECT_EQ(d.total, 128u);
    EXPECT_EQ(d.differing, 5u);
    EXPECT_EQ(d.max_error, 200.0);
    EXPECT_EQ(compare_planes(ref, ref).differing, 0u);
}

TEST(CompareDetects, DepthInFormatUnits) {
    Plane a{"depth", VK_FORMAT_D16_UNORM, 4, 1, 2, {}}, b;
    uint16_t va[4] = {0, 100, 65535, 7}, vb[4] = {0, 103, 65535, 7};
    a.data.resize(8);
    std::memcpy(a.data.data(), va, 8);
    b = a;
    std::memcpy(b.data.data(), vb, 8);
    PlaneDiff d = compare_planes(a, b);
    EXPECT_EQ(d.differing, 1u);
    EXPECT_EQ(d.max_error, 3.0);
    Plane f{"depth", VK_FORMAT_D32_SFLOAT, 2, 1, 4, {}}, g;
    float fa[2] = {0.5f, 0.25f}, fb[2] = {0.5f, 0.75f};
    f.data.resize(8);
    std::memcpy(f.data.data(), fa, 8);
    g = f;
    std::memcpy(g.data.data(), fb, 8);
    EXPECT_EQ(compare_planes(f, g).max_error, 0.5);
}

TEST(CompareDetects, ShapeMismatchIsAProblem) {
    EXPECT_FALSE(compare_planes(rgba_plane(4, 4, 0), rgba_plane(4, 5, 0)).problem.empty());
}

TEST(Checks, ExactlyOnceFindsOverdrawAndHoles) {
    Plane p = rgba_plane(8, 8, 1);
    EXPECT_EQ(exactly_once(0, 0, 0, 8, 8)({p}), "");
    p.data[(3 * 8 + 5) * 4] = 2;
    EXPECT_NE(exactly_once(0)({p}).find("(5,3) covered 2 times"), std::string::npos);
    p.data[(3 * 8 + 5) * 4] = 0;
    EXPECT_EQ(exactly_once(0)({p}), "");  // a hole outside any must-cover rectangle is allowed
    EXPECT_NE(exactly_once(0, 0, 0, 8, 8)({p}).find("(5,3) not covered"), std::string::npos);
}

TEST(Checks, EvenCoverageAndPalette) {
    Plane p = rgba_plane(4, 4, 2);
    EXPECT_EQ(even_coverage(0)({p}), "");
    p.data[(1 * 4 + 2) * 4] = 3;
    EXPECT_NE(even_coverage(0)({p}).find("(2,1)"), std::string::npos);
    Plane q = rgba_plane(2, 2, 0);
    EXPECT_EQ(palette_only({0u})({q}), "");
    q.data[4] = 255;  // pixel (1,0) red
    EXPECT_NE(palette_only({0u})({q}).find("(1,0)"), std::string::npos);
    EXPECT_EQ(pixel_is(1, 0, 0x000000FFu)({q}), "");
    EXPECT_NE(pixel_is(0, 0, 0x000000FFu)({q}), "");
    EXPECT_NE(all_of({palette_only({0u}), pixel_is(0, 0, 0)})({q}), "");
}

TEST(Checks, CoverageBandAgainstAHandDrawnRectangle) {
    // Two triangles covering window x in [2,6), y in [1,5) of an 8x8 target: NDC = window / 4 - 1.
    Scene s;
    s.target.width = s.target.height = 8;
    Draw d;
    auto v = [](float wx, float wy) {
        Vertex r;
        r.pos[0] = wx / 4 - 1;
        r.pos[1] = wy / 4 - 1;
        return r;
    };
    d.vertices = {v(2, 1), v(6, 1), v(6, 5), v(2, 1), v(6, 5), v(2, 5)};
    s.draws.push_back(d);
    Plane p = rgba_plane(8, 8, 0);
    for (int y = 1; y < 5; ++y)
        for (int x = 2; x < 6; ++x) p.data[(y * 8 + x) * 4] = 255;  // pixel centres x+0.5 in [2,6): drawn
    EXPECT_EQ(coverage_band(s, 1.0f / 64)({p}), "");
    Plane hole = p;
    hole.data[(2 * 8 + 4) * 4] = 0;  // centre (4.5,2.5): 0.7 px from the diagonal
    EXPECT_NE(coverage_band(s, 1.0f / 64)({hole}).find("(4,2) lies inside"), std::string::npos);
    Plane extra = p;
    extra.data[(6 * 8 + 1) * 4] = 9;
    EXPECT_NE(coverage_band(s, 1.0f / 64)({extra}).find("(1,6) lies outside"), std::string::npos);
    // A strip of the same four corners covers the same pixels.
    s.draws[0].topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    s.draws[0].vertices = {v(2, 1), v(6, 1), v(2, 5), v(6, 5)};
    EXPECT_EQ(coverage_band(s, 1.0f / 64)({p}), "");
    Plane hole2 = p;  // (4,2) sits on this split's diagonal; (3,2) is 0.7 px inside the first triangle
    hole2.data[(2 * 8 + 3) * 4] = 0;
    EXPECT_NE(coverage_band(s, 1.0f / 64)({hole2}).find("(3,2) lies inside"), std::string::npos);
}

TEST(Writers, PngAndJsonAreWritten) {
    std::string png = ::testing::TempDir() + "/judge_test.png";
    ASSERT_TRUE(write_png(png, 2, 2, std::vector<uint8_t>(16, 128)));
    FILE* f = std::fopen(png.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    unsigned char sig[8];
    ASSERT_EQ(std::fread(sig, 1, 8, f), 8u);
    std::fclose(f);
    EXPECT_EQ(std::memcmp(sig, "\x89PNG\r\n\x1a\n", 8), 0);
    EXPECT_FALSE(write_png(png, 4, 4, std::vector<uint8_t>(16, 0)));  // too little data: refused
    EXPECT_EQ(json_escape("a\"b\\c\n"), "a\\\"b\\\\c\\u000a");
    // A NaN depth difference is reported as infinite error, written in a spelling the report can read.
    Plane a{"depth", VK_FORMAT_D32_SFLOAT, 1, 1, 4, {0, 0, 0xC0, 0x7F}},
        b{"depth", VK_FORMAT_D32_SFLOAT, 1, 1, 4, {0, 0, 0, 0}};
    CaseResult r;
    r.name = "x";
    r.max_error = compare_planes(a, b).max_error;
    EXPECT_TRUE(std::isinf(r.max_error));
    std::string js = ::testing::TempDir() + "/judge_test.json";
    ASSERT_TRUE(write_json(js, RunInfo{}, {r}, ""));
    std::string text;
    for (FILE* f = std::fopen(js.c_str(), "rb"); f; f = nullptr) {
        char buf[4096];
        text.assign(buf, std::fread(buf, 1, sizeof buf, f));
        std::fclose(f);
    }
    EXPECT_NE(text.find("\"max_error\": Infinity"), std::string::npos) << text;
}

}  // namespace
}  // namespace tilevk::cts
