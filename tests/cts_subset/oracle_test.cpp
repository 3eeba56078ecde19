// The coverage oracle on hand-made scenes and images whose coverage is known analytically: a pixel-aligned
// rectangle (two triangles) covers exactly its pixels, whatever the fill rule.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "oracle.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kWhite = 0xFFFFFFFFu, kClear = 0xFF000000u;

Vertex v(float x, float y) {
    Vertex r;
    r.pos[0] = x, r.pos[1] = y;
    return r;
}

// 32x32, a rectangle from window (8,8) to (24,20): clip x = win/16 - 1, y = win/16 - 1. Clockwise as listed
// (right, then down on screen; Vulkan's a = -1/2 sum(x_i y_i+1 - x_i+1 y_i) = -192 < 0).
Scene rect_scene() {
    Scene s;
    s.target.width = s.target.height = 32;
    s.target.clear_color[3] = 1.0f;
    Draw d;
    const float x0 = 8 / 16.0f - 1, x1 = 24 / 16.0f - 1, y0 = 8 / 16.0f - 1, y1 = 20 / 16.0f - 1;
    d.vertices = {v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y0), v(x1, y1), v(x0, y1)};
    s.draws.push_back(d);
    return s;
}

// The expected image, from the rectangle's bounds (not from the oracle).
std::vector<Plane> rect_image(int x0, int y0, int x1, int y1) {
    Plane p;
    p.name = "color";
    p.format = VK_FORMAT_R8G8B8A8_UNORM;
    p.width = p.height = 32;
    p.texel_bytes = 4;
    p.data.resize(32 * 32 * 4);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            uint32_t c = x >= x0 && x < x1 && y >= y0 && y < y1 ? kWhite : kClear;
            std::memcpy(&p.data[(y * 32 + x) * 4], &c, 4);
        }
    return {p};
}

TEST(CoverageOracle, RectangleAgrees) {
    OracleVerdict r = rast_reference_oracle(rect_scene(), rect_image(8, 8, 24, 20));
    EXPECT_TRUE(r.applies) << r.note;
    EXPECT_EQ(r.error, "");
}

TEST(CoverageOracle, PerturbedPixelsFail) {
    std::vector<Plane> img = rect_image(8, 8, 24, 20);
    img[0].data[(10 * 32 + 10) * 4] = 0;  // a covered pixel loses red
    img[0].data[(0 * 32 + 0) * 4] = 255;  // an uncovered pixel gains red
    OracleVerdict r = rast_reference_oracle(rect_scene(), img);
    ASSERT_TRUE(r.applies);
    EXPECT_EQ(r.error.rfind("2 of 1024 judged pixels disagree", 0), 0u) << r.error;
}

TEST(CoverageOracle, OneColumnTooWideFails) {
    OracleVerdict r = rast_reference_oracle(rect_scene(), rect_image(8, 8, 25, 20));
    ASSERT_TRUE(r.applies);
    EXPECT_EQ(r.error.rfind("12 of 1024", 0), 0u) << r.error;
}

TEST(CoverageOracle, BackFaceCulledCoversNothing) {
    Scene s = rect_scene();
    s.draws[0].cull = VK_CULL_MODE_BACK_BIT;
    s.draws[0].front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;  // the clockwise rectangle is the back
    EXPECT_EQ(rast_reference_oracle(s, rect_image(0, 0, 0, 0)).error, "");
    EXPECT_NE(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).error, "");
    s.draws[0].front_face = VK_FRONT_FACE_CLOCKWISE;
    EXPECT_EQ(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).error, "");
}

TEST(CoverageOracle, ScissorClips) {
    Scene s = rect_scene();
    s.draws[0].scissor = VkRect2D{{12, 0}, {100, 16}};
    EXPECT_EQ(rast_reference_oracle(s, rect_image(12, 8, 24, 16)).error, "");
    EXPECT_NE(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).error, "");
}

TEST(CoverageOracle, FourSamplesFullPixels) {
    Scene s = rect_scene();
    s.target.samples = VK_SAMPLE_COUNT_4_BIT;
    EXPECT_EQ(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).error, "");
    EXPECT_NE(rast_reference_oracle(s, rect_image(9, 8, 24, 20)).error, "");
}

// Two ONE,ONE additive kCount draws of the rectangle: its pixels are clear + 2/255 per channel, the rest clear.
TEST(CoverageOracle, CountingAddsPerTriangle) {
    Scene s = rect_scene();
    s.draws[0].frag = Frag::kCount;
    s.draws[0].blend = {VK_TRUE,
                        VK_BLEND_FACTOR_ONE,
                        VK_BLEND_FACTOR_ONE,
                        VK_BLEND_OP_ADD,
                        VK_BLEND_FACTOR_ONE,
                        VK_BLEND_FACTOR_ONE,
                        VK_BLEND_OP_ADD,
                        0xF};
    s.draws.push_back(s.draws[0]);
    s.target.clear_color[3] = 0.0f;
    std::vector<Plane> img = rect_image(8, 8, 24, 20);
    for (size_t i = 0; i < img[0].data.size(); i += 4) {
        const uint8_t v = img[0].data[i] ? 2 : 0;
        for (int c = 0; c < 4; ++c) img[0].data[i + c] = v;
    }
    OracleVerdict r = rast_reference_oracle(s, img);
    ASSERT_TRUE(r.applies) << r.note;
    EXPECT_EQ(r.error, "");
    img[0].data[(10 * 32 + 10) * 4] = 1;  // counted once: the fill rule would have missed a triangle
    EXPECT_EQ(rast_reference_oracle(s, img).error.rfind("1 of 1024", 0), 0u);
}

TEST(CoverageOracle, OutsideTheDomainIsNotApplicable) {
    Scene s = rect_scene();
    s.draws[0].vertices[0].pos[0] = -1.5f;  // needs clipping
    OracleVerdict r = rast_reference_oracle(s, rect_image(8, 8, 24, 20));
    EXPECT_FALSE(r.applies);
    EXPECT_NE(r.note.find("clipping"), std::string::npos) << r.note;
    s = rect_scene();
    s.draws[0].blend.blendEnable = VK_TRUE;
    EXPECT_FALSE(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).applies);
    s = rect_scene();
    s.draws[0].vertices[2].color[0] = 0.5f;
    EXPECT_FALSE(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).applies);
    s = rect_scene();
    s.draws[0].vertices[2].pos[0] = NAN;
    EXPECT_FALSE(rast_reference_oracle(s, rect_image(8, 8, 24, 20)).applies);
}

}  // namespace
}  // namespace tilevk::cts
