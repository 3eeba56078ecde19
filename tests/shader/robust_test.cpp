// Bad input never crashes: truncated/garbled SPIR-V and unsupported features fail creation with a message.
#include <gtest/gtest.h>

#include <random>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::compile_glsl;

namespace {
const char* kFs = R"(#version 450
layout(location=0) in vec4 v;
layout(location=0) out vec4 color;
layout(set=0, binding=0) uniform sampler2D tex;
void main() {
    vec4 c = texture(tex, v.xy);
    for (int i = 0; i < 4; ++i) { if (c.x > v.z) break; c += v; }
    color = c;
})";

std::string create_error(const std::vector<uint32_t>& spirv, Stage stage, const char* entry = "main") {
    Result r = Program::create(spirv, stage, entry);
    return r ? std::string() : r.error;
}
}  // namespace

TEST(ShaderRobust, EmptyAndTruncated) {
    EXPECT_NE(create_error({}, Stage::Vertex), "");
    auto spirv = compile_glsl(Stage::Fragment, kFs);
    ASSERT_FALSE(spirv.empty());
    EXPECT_EQ(create_error(spirv, Stage::Fragment), "");
    for (size_t n : {size_t(1), size_t(5), spirv.size() / 2, spirv.size() - 1}) {
        std::vector<uint32_t> cut(spirv.begin(), spirv.begin() + long(n));
        EXPECT_NE(create_error(cut, Stage::Fragment), "") << n;
    }
    std::vector<uint32_t> bad = spirv;
    bad[0] = 0xdeadbeef;
    EXPECT_NE(create_error(bad, Stage::Fragment).find("magic"), std::string::npos);
}

TEST(ShaderRobust, GarbledWordsNeverCrash) {
    auto spirv = compile_glsl(Stage::Fragment, kFs);
    ASSERT_FALSE(spirv.empty());
    std::mt19937 rng(1234);
    int created = 0;
    for (int iter = 0; iter < 300; ++iter) {
        std::vector<uint32_t> m = spirv;
        int edits = 1 + int(rng() % 3);
        for (int e = 0; e < edits; ++e) {
            size_t at = 5 + rng() % (m.size() - 5);
            switch (rng() % 3) {
                case 0:
                    m[at] = rng();
                    break;
                case 1:
                    m[at] ^= 1u << (rng() % 32);
                    break;
                default:
                    m[at] = rng() % 64;
                    break;
            }
        }
        Result r = Program::create(m, Stage::Fragment);
        if (r) {
            ++created;
            // a module that still validates must also run safely
            FragmentBlock fb;
            Scratch s;
            r.program->run_fragment(Bindings{}, fb, s);
        } else {
            EXPECT_FALSE(r.error.empty());
        }
    }
    SUCCEED() << created << " mutated modules were still valid";
}

TEST(ShaderRobust, WrongStageOrEntry) {
    auto spirv = compile_glsl(Stage::Fragment, kFs);
    EXPECT_NE(create_error(spirv, Stage::Vertex).find("no vertex entry point"), std::string::npos);
    EXPECT_NE(create_error(spirv, Stage::Fragment, "other").find("entry point"), std::string::npos);
}

TEST(ShaderRobust, GeometryShaderRejected) {
    // glslang's geometry stage is not our helper's stage enum: compile by hand through a tiny module instead.
    // A vertex shader with a Geometry capability requirement: gl_Layer would need ShaderViewportIndexLayerEXT.
    auto spirv = compile_glsl(Stage::Vertex, R"(#version 450
        void main() { gl_Position = vec4(1.0); })");
    ASSERT_FALSE(spirv.empty());
    // Rewrite the entry point's execution model to Geometry (3): validation or translation must refuse it.
    std::vector<uint32_t> m = spirv;
    for (size_t i = 5; i < m.size();) {
        uint32_t n = m[i] >> 16, op = m[i] & 0xffff;
        if (n == 0) break;
        if (op == 15 /*OpEntryPoint*/) m[i + 1] = 3;
        if (op == 17 /*OpCapability*/ && m[i + 1] == 1 /*Shader*/) m[i + 1] = 2 /*Geometry*/;
        i += n;
    }
    std::string err = create_error(m, Stage::Vertex);
    EXPECT_NE(err, "");
}

TEST(ShaderRobust, UnsupportedFeaturesNamed) {
    struct Case {
        Stage stage;
        const char* src;
        const char* expect;
    };
    const Case cases[] = {
        {Stage::Fragment, R"(#version 450
            layout(location=0) out vec4 c;
            layout(location=0) in vec4 v;
            void main() { double d = double(v.x); c = vec4(float(ldexp(d, 3))); })",
         "Ldexp on 64-bit values"},
        {Stage::Fragment, R"(#version 450
            layout(location=0) out vec4 c;
            layout(set=0,binding=0, rgba8) uniform readonly imageCube t;  // storage cube images: not implemented
            void main() { c = imageLoad(t, ivec3(0)); })",
         "dimension Cube"},
        {Stage::Fragment, R"(#version 450
            layout(location=0) out vec4 c;
            layout(set=0,binding=0, r32ui) uniform uimage2DMS img;  // image atomics: 2D single-sample only
            void main() { c = vec4(float(imageAtomicAdd(img, ivec2(0), 0, 1u))); })",
         "StorageImageMultisample"},
        {Stage::Fragment, R"(#version 450
            layout(location=0) out vec4 c;
            layout(set=0,binding=0, rgba8) uniform readonly image2DMS img;
            void main() { c = imageLoad(img, ivec2(0), 1); })",
         "StorageImageMultisample"},
        {Stage::Fragment, R"(#version 450
            layout(location=0) out vec4 c;
            layout(input_attachment_index=0, set=0, binding=0) uniform subpassInputMS ia;
            void main() { c = subpassLoad(ia, 2); })",
         "subpassInputMS"},
        {Stage::Fragment, R"(#version 450
            layout(location=0) out vec4 c;
            layout(location=0) in vec4 v[2];
            void main() { c = vec4(interpolateAtCentroid(v[int(gl_FragCoord.x) & 1]).x); })",
         "InterpolateAtCentroid on a dynamically indexed input"},
    };
    for (const Case& c : cases) {
        auto spirv = compile_glsl(c.stage, c.src);
        ASSERT_FALSE(spirv.empty());
        std::string err = create_error(spirv, c.stage);
        EXPECT_NE(err, "") << c.src;
        EXPECT_NE(err.find(c.expect), std::string::npos) << err;
    }
}

TEST(ShaderRobust, NanInfAndDivisionByZero) {
    auto spirv = compile_glsl(Stage::Vertex, R"(#version 450
        layout(location=0) in vec4 a;
        layout(location=1) in ivec4 i;
        layout(location=0) flat out ivec4 o;
        void main() {
            o = ivec4(int(a.x), i.x / i.y, i.x % i.y, int(uint(a.y)));
            gl_Position = a / a.z;
        })");
    Result r = Program::create(spirv, Stage::Vertex);
    ASSERT_TRUE(r) << r.error;
    VertexBatch vb;
    const float vals[] = {NAN, INFINITY, -INFINITY, 3e38f, -3e38f, 0.0f, -0.0f, 1e-45f};
    for (int l = 0; l < kLanes; ++l) {
        for (int c = 0; c < 4; ++c) vb.inputs[0][c][l] = std::bit_cast<uint32_t>(vals[(l + c) % 8]);
        vb.inputs[1][0][l] = l == 3 ? 0x80000000u : uint32_t(l);
        vb.inputs[1][1][l] = l % 2 ? 0u : 0xFFFFFFFFu;
    }
    Scratch s;
    r.program->run_vertex(Bindings{}, vb, s);
    // integer division by zero gives 0 (signed), as llvmpipe; INT_MIN / -1 does not trap
    EXPECT_EQ(vb.outputs[0][1][1], 0u);
    EXPECT_EQ(int32_t(vb.outputs[0][1][3]), 0) << "lane 3 divides by zero";
    EXPECT_EQ(vb.outputs[0][1][2], uint32_t(-2));
    // NaN -> int is INT_MIN (cvttps2dq)
    EXPECT_EQ(vb.outputs[0][0][0], 0x80000000u);
}

TEST(ShaderRobust, InfiniteLoopIsCutByTheWatchdog) {
    // valid SPIR-V that never terminates for v.x >= 0: the run must return, and say so
    auto spirv = compile_glsl(Stage::Fragment, R"(#version 450
        layout(location=0) in vec4 v;
        layout(location=0) out vec4 color;
        void main() {
            float c = 0.0;
            while (v.x >= 0.0) { c += 1.0; if (c > 1e30) c = 0.0; }
            color = vec4(c);
        })");
    Result r = Program::create(spirv, Stage::Fragment);
    ASSERT_TRUE(r) << r.error;
    FragmentBlock fb;
    for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = std::bit_cast<uint32_t>(l < 8 ? 1.0f : -1.0f);
    Scratch s;
    EXPECT_EQ(s.loop_limit_hits(), 0u);
    r.program->run_fragment(Bindings{}, fb, s);
    EXPECT_EQ(s.loop_limit_hits(), 1u);
    // a terminating loop on the same scratch does not count
    for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = std::bit_cast<uint32_t>(-1.0f);
    r.program->run_fragment(Bindings{}, fb, s);
    EXPECT_EQ(s.loop_limit_hits(), 1u);
    for (int l = 0; l < kLanes; ++l) EXPECT_EQ(fb.outputs[0][0][l], 0u);
}
