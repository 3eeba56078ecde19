// InterpolateAtCentroid / AtSample / AtOffset (shader/interpolate.cpp) on hand-made attribute planes whose values
// are exact in float (dyadic planes and positions), so the expected value a0 + dadx * x + dady * y is computed here
// independently, per lane, in both tiers (interpreter and compiled).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <string>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::compile_glsl;
using tilevk::shader::test::make_program;

namespace {

constexpr float kPos[4][2] = {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};

// Location 1: a = 1 + 2x + 4y (noperspective); location 2: the same plane, perspective; location 3: flat 7.5.
InputPlanes planes(int samples) {
    InputPlanes ip;
    for (int loc = 1; loc <= 3; ++loc)
        for (int c = 0; c < 4; ++c) {
            ip.a0[loc][c] = 1.0f + float(c);
            ip.dadx[loc][c] = 2.0f;
            ip.dady[loc][c] = 4.0f;
        }
    ip.kind[1] = InputPlanes::Kind::NoPerspective;
    ip.kind[2] = InputPlanes::Kind::Perspective;
    ip.kind[3] = InputPlanes::Kind::Flat;
    ip.a0[3][0] = 7.5f;
    for (int l = 0; l < kLanes; ++l) ip.w[l] = l % 2 ? 2.0f : 0.5f;  // 1/w: 0.5 or 2, exact
    ip.x = 8;
    ip.y = 4;
    ip.samples = samples;
    std::memcpy(ip.sample_pos, kPos, sizeof kPos);
    // centroid: lane 0 all samples, lane 1 sample 2 only, lane 2 samples 1 and 3, lane 3 none; others all
    ip.masks[0] = uint16_t(0xfff1);
    ip.masks[1] = uint16_t(0xfff5);
    ip.masks[2] = uint16_t(0xfff3);
    ip.masks[3] = uint16_t(0xfff5);
    return ip;
}

// The plane's value at offset (ox, oy) from lane l's pixel corner (4x) or pixel centre (1x): exact here.
float expected(int c, int lane, float ox, float oy) {
    const double x = 8 + lane_x(lane) + double(ox), y = 4 + lane_y(lane) + double(oy);
    return float(1.0 + c + 2.0 * x + 4.0 * y);
}

float out(const FragmentBlock& fb, int comp, int lane) {
    return std::bit_cast<float>(fb.outputs[0][comp][lane]);
}

// Runs `body` (GLSL) on one block in both tiers; the two must agree bit for bit.
FragmentBlock run(const std::string& body, const InputPlanes* ip) {
    const std::string src =
        "#version 450\nlayout(location=1) noperspective in vec4 a;\nlayout(location=2) in vec4 p;\n"
        "layout(location=3) flat in float f;\nlayout(location=0) out vec4 o;\nvoid main() {\n" +
        body + "\n}\n";
    FragmentBlock result[2];
    for (int jit = 0; jit < 2; ++jit) {
        set_jit_enabled(jit == 1);
        auto prog = make_program(Stage::Fragment, src);
        set_jit_enabled(true);
        if (!prog) return {};
        EXPECT_TRUE(prog->interface().interpolates_at);
        result[jit].input_planes = ip;
        for (int l = 0; l < kLanes; ++l) {  // FragCoord: the pixel centre
            result[jit].frag_coord[0][l] = std::bit_cast<uint32_t>(8.5f + float(lane_x(l)));
            result[jit].frag_coord[1][l] = std::bit_cast<uint32_t>(4.5f + float(lane_y(l)));
        }
        Scratch s;
        prog->run_fragment(Bindings{}, result[jit], s);
    }
    EXPECT_EQ(std::memcmp(result[0].outputs, result[1].outputs, sizeof result[0].outputs), 0) << "tiers differ";
    return result[0];
}

TEST(InterpolateAt, OffsetFromThePixelCentre) {
    for (int samples : {1, 4}) {
        const InputPlanes ip = planes(samples);
        FragmentBlock fb =
            run("o = vec4(interpolateAtOffset(a.xy, vec2(0.25, -0.125)), "
                "interpolateAtOffset(a.w, vec2(-1.5, 1.75)), 0.0);",
                &ip);
        const float c = samples > 1 ? 0.5f : 0.0f;  // 4x planes start at the pixel corner
        for (int l = 0; l < kLanes; ++l) {
            EXPECT_EQ(out(fb, 0, l), expected(0, l, c + 0.25f, c - 0.125f)) << samples << "x lane " << l;
            EXPECT_EQ(out(fb, 1, l), expected(1, l, c + 0.25f, c - 0.125f)) << samples << "x lane " << l;
            // unclamped, outside [minInterpolationOffset, maxInterpolationOffset]
            EXPECT_EQ(out(fb, 2, l), expected(3, l, c - 1.5f, c + 1.75f)) << samples << "x lane " << l;
        }
    }
}

TEST(InterpolateAt, VaryingOffsetAndSampleIndex) {
    const InputPlanes ip = planes(4);
    FragmentBlock fb =
        run("vec2 off = vec2(gl_FragCoord.x - 8.5, 0.0) * 0.0625;\n"
            "int k = int(gl_FragCoord.x) & 3;\n"
            "o = vec4(interpolateAtOffset(a.x, off), interpolateAtSample(a.y, k), 0.0, 0.0);",
            &ip);
    for (int l = 0; l < kLanes; ++l) {
        const float off = float(lane_x(l)) * 0.0625f;
        const int k = (8 + lane_x(l)) & 3;
        EXPECT_EQ(out(fb, 0, l), expected(0, l, 0.5f + off, 0.5f)) << "lane " << l;
        EXPECT_EQ(out(fb, 1, l), expected(1, l, kPos[k][0], kPos[k][1])) << "lane " << l;
    }
}

TEST(InterpolateAt, SampleAndCentroidPositions) {
    for (int samples : {1, 4}) {
        const InputPlanes ip = planes(samples);
        FragmentBlock fb =
            run("o = vec4(interpolateAtSample(a.x, 3), interpolateAtCentroid(a.z), "
                "interpolateAtSample(a.y, 1), 0.0);",
                &ip);
        for (int l = 0; l < kLanes; ++l) {
            if (samples == 1) {  // at 1x every position is the centre, the planes' origin
                EXPECT_EQ(out(fb, 0, l), expected(0, l, 0, 0)) << l;
                EXPECT_EQ(out(fb, 1, l), expected(2, l, 0, 0)) << l;
                continue;
            }
            EXPECT_EQ(out(fb, 0, l), expected(0, l, kPos[3][0], kPos[3][1])) << l;
            EXPECT_EQ(out(fb, 2, l), expected(1, l, kPos[1][0], kPos[1][1])) << l;
            // centroid: the centre when all or no samples are covered, else the lowest covered sample
            const int site = l == 1 ? 2 : l == 2 ? 1 : -1;
            const float cx = site < 0 ? 0.5f : kPos[site][0], cy = site < 0 ? 0.5f : kPos[site][1];
            EXPECT_EQ(out(fb, 1, l), expected(2, l, cx, cy)) << "centroid lane " << l;
        }
    }
}

TEST(InterpolateAt, PerspectiveFlatAndMissingPlanes) {
    const InputPlanes ip = planes(4);
    FragmentBlock fb =
        run("o = vec4(interpolateAtOffset(p.y, vec2(0.125)), interpolateAtSample(f, 2), "
            "interpolateAtCentroid(f), 1.0);",
            &ip);
    for (int l = 0; l < kLanes; ++l) {
        // a * fl(1 / w): both exact here
        EXPECT_EQ(out(fb, 0, l), expected(1, l, 0.625f, 0.625f) * (1.0f / ip.w[l])) << l;
        EXPECT_EQ(out(fb, 1, l), 7.5f) << l;
        EXPECT_EQ(out(fb, 2, l), 7.5f) << l;
    }
    // No planes (a caller that does not fill them): 0.0, no crash.
    FragmentBlock none = run("o = vec4(interpolateAtOffset(a.x, vec2(0.125)), 1.0, 1.0, 1.0);", nullptr);
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(out(none, 0, l), 0.0f);
}

TEST(InterpolateAt, RefusedWhereItCannotWork) {
    // Outside a fragment shader glslang itself refuses interpolateAt*; a dynamically indexed input is refused by
    // name (tests/shader/robust_test.cpp); a flat integer input is not a float interpolant (glslang refuses it).
    auto spirv = compile_glsl(Stage::Fragment, R"(#version 450
        layout(location=0) in vec4 v[2];
        layout(location=0) out vec4 o;
        void main() { o = interpolateAtOffset(v[int(gl_FragCoord.x) & 1], vec2(0.0)); })");
    ASSERT_FALSE(spirv.empty());
    Result r = Program::create(spirv, Stage::Fragment);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error.find("InterpolateAtOffset on a dynamically indexed input"), std::string::npos) << r.error;
    // A constant index into an input array is fine.
    auto ok = make_program(Stage::Fragment, R"(#version 450
        layout(location=0) in vec4 v[2];
        layout(location=0) out vec4 o;
        void main() { o = interpolateAtOffset(v[1], vec2(0.0)); })");
    EXPECT_TRUE(ok);
}

}  // namespace
