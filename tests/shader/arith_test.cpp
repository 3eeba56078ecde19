// Arithmetic, conversions, composites, matrices, GLSL.std.450 — checked against C++ computed independently.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::f;
using tilevk::shader::test::make_program;
using tilevk::shader::test::u;

namespace {

// Runs a vertex shader with inputs a (location 0, vec4) and b (location 1, vec4) per lane.
struct VsRun {
    std::shared_ptr<const Program> prog;
    VertexBatch batch;
    Scratch scratch;
    Bindings bindings;
    explicit VsRun(const std::string& body, const std::string& decls = "") {
        prog = make_program(Stage::Vertex,
                            "#version 450\n"
                            "layout(location=0) in vec4 a;\n"
                            "layout(location=1) in vec4 b;\n"
                            "layout(location=2) in ivec4 ia;\n"
                            "layout(location=0) out vec4 o0;\n"
                            "layout(location=1) flat out ivec4 o1;\n" +
                                decls + "void main() {\n" + body + "\n}\n");
    }
    void set_a(int lane, float x, float y, float z, float w) {
        float v[4] = {x, y, z, w};
        for (int c = 0; c < 4; ++c) batch.inputs[0][c][lane] = u(v[c]);
    }
    void set_b(int lane, float x, float y, float z, float w) {
        float v[4] = {x, y, z, w};
        for (int c = 0; c < 4; ++c) batch.inputs[1][c][lane] = u(v[c]);
    }
    void set_ia(int lane, int32_t x, int32_t y, int32_t z, int32_t w) {
        int32_t v[4] = {x, y, z, w};
        for (int c = 0; c < 4; ++c) batch.inputs[2][c][lane] = uint32_t(v[c]);
    }
    void run() {
        ASSERT_TRUE(prog);
        prog->run_vertex(bindings, batch, scratch);
    }
    float o0(int lane, int c) const { return f(batch.outputs[0][c][lane]); }
    int32_t o1(int lane, int c) const { return int32_t(batch.outputs[1][c][lane]); }
};

float lane_val(int l, int k) {
    return float(l) * 0.37f - 2.5f + float(k) * 1.25f;
}

}  // namespace

TEST(ShaderArith, PassThroughPositionAndVaryings) {
    VsRun r("gl_Position = a; o0 = b; o1 = ia;");
    for (int l = 0; l < kLanes; ++l) {
        r.set_a(l, float(l), 2.0f * l, 3.0f, 1.0f);
        r.set_b(l, 0.5f, float(-l), 7.0f, 9.0f);
        r.set_ia(l, l, -l, 100 + l, 7);
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        EXPECT_EQ(f(r.batch.position[0][l]), float(l));
        EXPECT_EQ(f(r.batch.position[1][l]), 2.0f * l);
        EXPECT_EQ(r.o0(l, 1), float(-l));
        EXPECT_EQ(r.o1(l, 2), 100 + l);
    }
    const auto& io = r.prog->interface();
    EXPECT_TRUE(io.builtins_written & bit(BuiltIn::Position));
    ASSERT_EQ(io.inputs.size(), 3u);
    EXPECT_EQ(io.inputs[2].type, ScalarType::Int);
    ASSERT_EQ(io.outputs.size(), 2u);
    EXPECT_EQ(io.outputs[1].interpolation, Interpolation::Flat);
    EXPECT_EQ(io.outputs[0].interpolation, Interpolation::Smooth);
}

TEST(ShaderArith, FloatOpsMatchCpp) {
    VsRun r(
        "o0 = vec4(a.x + b.x, a.y * b.y - a.z, a.z / b.z, -a.w);"
        "gl_Position = vec4(min(a.x, b.x), max(a.y, b.y), clamp(a.z, -1.0, 1.0), abs(b.w));");
    for (int l = 0; l < kLanes; ++l) {
        r.set_a(l, lane_val(l, 0), lane_val(l, 1), lane_val(l, 2), lane_val(l, 3));
        r.set_b(l, lane_val(l, 4), lane_val(l, 5), lane_val(l, 6) + 0.1f, -lane_val(l, 7));
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float ax = lane_val(l, 0), ay = lane_val(l, 1), az = lane_val(l, 2), aw = lane_val(l, 3);
        float bx = lane_val(l, 4), by = lane_val(l, 5), bz = lane_val(l, 6) + 0.1f, bw = -lane_val(l, 7);
        EXPECT_EQ(r.o0(l, 0), ax + bx);
        EXPECT_EQ(r.o0(l, 1), ay * by - az);
        EXPECT_EQ(r.o0(l, 2), az / bz);
        EXPECT_EQ(r.o0(l, 3), -aw);
        EXPECT_EQ(f(r.batch.position[0][l]), std::fmin(ax, bx));
        EXPECT_EQ(f(r.batch.position[1][l]), std::fmax(ay, by));
        EXPECT_EQ(f(r.batch.position[2][l]), std::fmin(std::fmax(az, -1.0f), 1.0f));
        EXPECT_EQ(f(r.batch.position[3][l]), std::fabs(bw));
    }
}

// NIR's rules for pow with a constant operand, which lavapipe applies before gallivm (translate_glsl.cpp): exact
// products, where gallivm's exp2(log2(a)·2) would round differently and be NaN for negative a.
TEST(ShaderArith, PowWithConstantOperandsIsRewrittenAsNir) {
    VsRun r("gl_Position = vec4(pow(a.x, 1.0), pow(a.y, 2.0), pow(a.z, 4.0), pow(2.0, a.w));");
    for (int l = 0; l < kLanes; ++l) r.set_a(l, lane_val(l, 0), lane_val(l, 1), lane_val(l, 2), float(l - 8));
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        const float ax = lane_val(l, 0), ay = lane_val(l, 1), az = lane_val(l, 2);
        EXPECT_EQ(f(r.batch.position[0][l]), ax);
        EXPECT_EQ(f(r.batch.position[1][l]), ay * ay);
        EXPECT_EQ(f(r.batch.position[2][l]), (az * az) * (az * az));
        EXPECT_EQ(f(r.batch.position[3][l]), std::ldexp(1.0f, l - 8));
    }
}

TEST(ShaderArith, GlslStd450Functions) {
    VsRun r(
        "o0 = vec4(sqrt(abs(a.x)), inversesqrt(abs(a.y) + 1.0), floor(a.z), fract(a.w));"
        "gl_Position = vec4(sin(a.x), exp2(a.y), pow(abs(a.z) + 1.0, 1.5), fma(a.x, a.y, a.z));"
        "o1 = ivec4(sign(ia.x), abs(ia.y), ia.z / 3, ia.w % 5);");
    for (int l = 0; l < kLanes; ++l) {
        r.set_a(l, lane_val(l, 0), lane_val(l, 1), lane_val(l, 2), lane_val(l, 3));
        r.set_ia(l, l - 8, 3 - l, 7 * l - 40, 3 * l + 1);
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float ax = lane_val(l, 0), ay = lane_val(l, 1), az = lane_val(l, 2), aw = lane_val(l, 3);
        EXPECT_EQ(r.o0(l, 0), std::sqrt(std::fabs(ax)));
        EXPECT_EQ(r.o0(l, 1), 1.0f / std::sqrt(std::fabs(ay) + 1.0f));
        EXPECT_EQ(r.o0(l, 2), std::floor(az));
        EXPECT_EQ(r.o0(l, 3), aw - std::floor(aw));
        // gallivm's approximations (shader/gallivm_math.h; their bits are tests/shader/gallivm_math_test.cpp's and
        // cts quirks.transcendental.*'s): close to the true values
        EXPECT_NEAR(f(r.batch.position[0][l]), std::sin(double(ax)), 1e-6);
        EXPECT_NEAR(f(r.batch.position[1][l]), std::exp2(double(ay)), 1e-6 * std::exp2(double(ay)));
        const double p = std::pow(std::fabs(double(az)) + 1.0, 1.5);
        EXPECT_NEAR(f(r.batch.position[2][l]), p, 2e-6 * p);
        // GLSL fma = mul then add, as lavapipe (not fused)
        EXPECT_EQ(f(r.batch.position[3][l]), ax * ay + az);
        int x = l - 8, y = 3 - l, z = 7 * l - 40, w = 3 * l + 1;
        EXPECT_EQ(r.o1(l, 0), (x > 0) - (x < 0));
        EXPECT_EQ(r.o1(l, 1), std::abs(y));
        EXPECT_EQ(r.o1(l, 2), z / 3);
        EXPECT_EQ(r.o1(l, 3), w % 5);
    }
}

TEST(ShaderArith, VectorsMatricesAndGeometry) {
    VsRun r(R"(
        mat4 m = mat4(a, b, a.wzyx, b.yxwz);
        vec4 v = m * vec4(1.0, 2.0, -1.0, 0.5);
        vec4 w = vec4(1.0, 2.0, -1.0, 0.5) * m;
        o0 = vec4(dot(a.xyz, b.xyz), length(a.xy), cross(a.xyz, b.xyz).y, normalize(b.xyz).z);
        gl_Position = v + transpose(m)[1] + w.zzzz;
        o1 = ivec4(a.xxyy.zwxy * 4.0);
    )");
    for (int l = 0; l < kLanes; ++l) {
        r.set_a(l, lane_val(l, 0), lane_val(l, 1), lane_val(l, 2), lane_val(l, 3));
        r.set_b(l, lane_val(l, 4), lane_val(l, 5), lane_val(l, 6), lane_val(l, 7));
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float a[4], b[4];
        for (int c = 0; c < 4; ++c) a[c] = lane_val(l, c), b[c] = lane_val(l, 4 + c);
        float m[4][4];  // m[col][row]
        for (int c = 0; c < 4; ++c) {
            m[0][c] = a[c];
            m[1][c] = b[c];
            m[2][c] = a[3 - c];
        }
        m[3][0] = b[1], m[3][1] = b[0], m[3][2] = b[3], m[3][3] = b[2];
        float vin[4] = {1.0f, 2.0f, -1.0f, 0.5f};
        float v[4], w[4];
        for (int row = 0; row < 4; ++row) {  // last column first, as Mesa's vtn matrix_multiply
            float s = m[3][row] * vin[3];
            for (int c = 2; c >= 0; --c) s = m[c][row] * vin[c] + s;
            v[row] = s;
        }
        for (int c = 0; c < 4; ++c) {
            float s = vin[0] * m[c][0];
            for (int k = 1; k < 4; ++k) s = s + vin[k] * m[c][k];
            w[c] = s;
        }
        for (int row = 0; row < 4; ++row)
            EXPECT_EQ(f(r.batch.position[row][l]), v[row] + m[row][1] + w[2]) << "lane " << l << " row " << row;
        float d3 = (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
        EXPECT_EQ(r.o0(l, 0), d3);
        EXPECT_EQ(r.o0(l, 1), std::sqrt(a[0] * a[0] + a[1] * a[1]));
        EXPECT_EQ(r.o0(l, 2), a[2] * b[0] - a[0] * b[2]);
        float bl = (b[0] * b[0] + b[1] * b[1]) + b[2] * b[2];
        // normalize divides by the length (Mesa's vtn_glsl450.c: nir_fast_normalize), not v * inversesqrt
        EXPECT_EQ(r.o0(l, 3), b[2] / std::sqrt(bl));
        float sw[4] = {a[1], a[1], a[0], a[0]};
        for (int c = 0; c < 4; ++c) EXPECT_EQ(r.o1(l, c), int32_t(sw[c] * 4.0f));
    }
}

// lavapipe sums M*v from the last column to the first (Mesa's spirv/vtn_alu.c matrix_multiply): with the terms
// 1, 2^-24, 2^-24, -1 the two orders give 2^-23 and 0. M*M takes each result column the same way.
TEST(ShaderArith, MatrixProductsSumFromTheLastColumn) {
    VsRun r(R"(
        mat4 m = mat4(vec4(a.x), vec4(a.y), vec4(a.z), vec4(a.w));
        gl_Position = m * vec4(1.0);
        o0 = (m * mat4(1.0, 1.0, 1.0, 1.0,  0.0, 0.0, 0.0, 0.0,  0.0, 0.0, 0.0, 0.0,  0.0, 0.0, 0.0, 0.0))[0];
    )");
    const float tiny = std::ldexp(1.0f, -24);
    for (int l = 0; l < kLanes; ++l) r.set_a(l, 1.0f, tiny, tiny, -1.0f);
    r.run();
    const float last_first = ((-1.0f + tiny) + tiny) + 1.0f;
    ASSERT_EQ(last_first, std::ldexp(1.0f, -23));
    ASSERT_NE(last_first, ((1.0f + tiny) + tiny) + -1.0f);  // the first-column order: 0
    for (int l = 0; l < kLanes; ++l) {
        for (int c = 0; c < 4; ++c) {
            EXPECT_EQ(f(r.batch.position[c][l]), last_first) << "M*v lane " << l;
            EXPECT_EQ(r.o0(l, c), last_first) << "M*M lane " << l;
        }
    }
}

TEST(ShaderArith, IntegerBitOpsAndConversions) {
    VsRun r(R"(
        uint x = uint(ia.x);
        o1 = ivec4(int(bitCount(x)), findMSB(ia.y), int(x >> 3u) ^ ia.z, bitfieldExtract(ia.w, 2, 5));
        o0 = vec4(float(ia.x), float(uint(ia.y)), intBitsToFloat(ia.z), float(ia.w < ia.x ? 1 : 0));
    )");
    for (int l = 0; l < kLanes; ++l) r.set_ia(l, l * 977 + 5, -l * 33 + 100, l * 0x01010101, l * 37 - 200);
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int32_t x = l * 977 + 5, y = -l * 33 + 100, z = l * 0x01010101, w = l * 37 - 200;
        EXPECT_EQ(r.o1(l, 0), std::popcount(uint32_t(x)));
        uint32_t ym = y < 0 ? ~uint32_t(y) : uint32_t(y);
        EXPECT_EQ(r.o1(l, 1), ym ? 31 - std::countl_zero(ym) : -1);
        EXPECT_EQ(r.o1(l, 2), int32_t(uint32_t(x) >> 3) ^ z);
        int32_t bf = int32_t(uint32_t(w) << (32 - 7)) >> (32 - 5);
        EXPECT_EQ(r.o1(l, 3), bf);
        EXPECT_EQ(r.o0(l, 0), float(x));
        EXPECT_EQ(r.o0(l, 1), float(uint32_t(y)));
        EXPECT_EQ(u(r.o0(l, 2)), uint32_t(z));
        EXPECT_EQ(r.o0(l, 3), w < x ? 1.0f : 0.0f);
    }
}

TEST(ShaderArith, VertexIndexAndPartialBatch) {
    VsRun r("gl_Position = vec4(float(gl_VertexIndex), float(gl_InstanceIndex), 0.0, 1.0); gl_PointSize = 3.0;");
    r.batch.count = 5;
    for (int l = 0; l < kLanes; ++l) r.batch.vertex_index[l] = 1000 + l, r.batch.instance_index[l] = 7;
    r.run();
    for (int l = 0; l < 5; ++l) {
        EXPECT_EQ(f(r.batch.position[0][l]), float(1000 + l));
        EXPECT_EQ(f(r.batch.position[1][l]), 7.0f);
        EXPECT_EQ(f(r.batch.point_size[l]), 3.0f);
    }
    EXPECT_TRUE(r.prog->interface().builtins_read & bit(BuiltIn::VertexIndex));
}

TEST(ShaderArith, SpecializationConstants) {
    auto spirv = tilevk::shader::test::compile_glsl(Stage::Vertex,
                                                    "#version 450\nlayout(constant_id=3) const float K = 2.0;\n"
                                                    "layout(constant_id=4) const int N = 1;\n"
                                                    "void main() { gl_Position = vec4(K, float(N * 2), 0.0, 1.0); }\n");
    SpecConstants spec{{3, {u(5.5f)}}, {4, {uint32_t(21)}}};
    Result res = Program::create(spirv, Stage::Vertex, "main", spec);
    ASSERT_TRUE(res) << res.error;
    VertexBatch vb;
    Scratch s;
    res.program->run_vertex(Bindings{}, vb, s);
    EXPECT_EQ(f(vb.position[0][3]), 5.5f);
    EXPECT_EQ(f(vb.position[1][3]), 42.0f);
    Result def = Program::create(spirv, Stage::Vertex);
    ASSERT_TRUE(def) << def.error;
    def.program->run_vertex(Bindings{}, vb, s);
    EXPECT_EQ(f(vb.position[0][0]), 2.0f);
    EXPECT_EQ(f(vb.position[1][0]), 2.0f);
}

TEST(ShaderArith, InterfaceBlocksArraysAndClipDistance) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(location=0) in vec2 p;
        layout(location=3) in mat2 m;                 // locations 3, 4
        layout(location=1) out Block { vec3 n; flat int id; } ob;   // locations 1, 2
        layout(location=5) out float arr[2];          // locations 5, 6
        layout(location=7, component=2) out vec2 zw;
        out gl_PerVertex { vec4 gl_Position; float gl_ClipDistance[2]; };
        void main() {
            gl_Position = vec4(p, 0.0, 1.0);
            gl_ClipDistance[0] = p.x; gl_ClipDistance[1] = -p.y;
            ob.n = vec3(m[0], m[1].y); ob.id = gl_VertexIndex * 2;
            arr[0] = m[1].x; arr[1] = 4.0;
            zw = p.yx;
        })");
    ASSERT_TRUE(prog);
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l) {
        vb.inputs[0][0][l] = u(float(l)), vb.inputs[0][1][l] = u(float(-l) * 0.5f);
        for (int c = 0; c < 2; ++c) {
            vb.inputs[3][c][l] = u(float(l * 10 + c));
            vb.inputs[4][c][l] = u(float(l * 100 + c));
        }
        vb.vertex_index[l] = uint32_t(l + 3);
    }
    Scratch s;
    prog->run_vertex(Bindings{}, vb, s);
    for (int l = 0; l < kLanes; ++l) {
        EXPECT_EQ(f(vb.clip_distance[0][l]), float(l));
        EXPECT_EQ(f(vb.clip_distance[1][l]), float(l) * 0.5f);
        EXPECT_EQ(f(vb.outputs[1][0][l]), float(l * 10));
        EXPECT_EQ(f(vb.outputs[1][1][l]), float(l * 10 + 1));
        EXPECT_EQ(f(vb.outputs[1][2][l]), float(l * 100 + 1));
        EXPECT_EQ(vb.outputs[2][0][l], uint32_t((l + 3) * 2));
        EXPECT_EQ(f(vb.outputs[5][0][l]), float(l * 100));
        EXPECT_EQ(f(vb.outputs[6][0][l]), 4.0f);
        EXPECT_EQ(f(vb.outputs[7][2][l]), float(-l) * 0.5f);
        EXPECT_EQ(f(vb.outputs[7][3][l]), float(l));
    }
    const auto& io = prog->interface();
    EXPECT_EQ(io.clip_distances, 2u);
    EXPECT_TRUE(io.builtins_written & bit(BuiltIn::ClipDistance));
    ASSERT_EQ(io.outputs.size(), 5u);
    EXPECT_EQ(io.outputs[1].location, 2u);
    EXPECT_EQ(io.outputs[1].interpolation, Interpolation::Flat);
    EXPECT_EQ(io.outputs[4].location, 7u);
    EXPECT_EQ(io.outputs[4].component, 2u);
    ASSERT_EQ(io.inputs.size(), 3u);  // p, m column 0, m column 1
}

TEST(ShaderArith, MultipleFragmentOutputsAndSampleMask) {
    auto prog = make_program(Stage::Fragment, R"(#version 450
        layout(location=0) in vec4 v;
        layout(location=0) out vec4 c0;
        layout(location=2) out uvec2 c2;
        void main() { c0 = v * 2.0; c2 = uvec2(7u, uint(v.x)); gl_SampleMask[0] = 5; })");
    ASSERT_TRUE(prog);
    FragmentBlock fb;
    for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = u(float(l));
    Scratch s;
    prog->run_fragment(Bindings{}, fb, s);
    for (int l = 0; l < kLanes; ++l) {
        EXPECT_EQ(f(fb.outputs[0][0][l]), 2.0f * float(l));
        EXPECT_EQ(fb.outputs[2][0][l], 7u);
        EXPECT_EQ(fb.outputs[2][1][l], uint32_t(l));
        EXPECT_EQ(fb.sample_mask[l], 5u);
    }
    EXPECT_EQ(prog->interface().outputs[1].type, ScalarType::Uint);
}
