// GLSL.std.450 coverage: every extended instruction is either translated or rejected with its name; the ones
// with a lavapipe construction (determinant, inverse, modf, frexp) and the extended-arithmetic / array-length core
// opcodes against values computed here in C++ (lavapipe's operation order, see shader/README.md).
#include <gtest/gtest.h>

#include <spirv-tools/libspirv.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::f;
using tilevk::shader::test::make_program;
using tilevk::shader::test::u;

namespace {

// One OpExtInst case: the instruction's name as the assembler spells it, its result type and operands (ids of
// the template below), and where the result goes.
struct ExtCase {
    const char* name;
    const char* type;
    const char* args;
    const char* store;  // assembly that consumes %r
};

const char* kHeader = R"(
OpCapability Shader
OpCapability InterpolationFunction
%glsl = OpExtInstImport "GLSL.std.450"
OpMemoryModel Logical GLSL450
OpEntryPoint Fragment %main "main" %in %o_f %o_i %o_u %o_v2 %o_v3 %o_v4 %o_f2
OpExecutionMode %main OriginUpperLeft
OpDecorate %in Location 0
OpDecorate %o_f Location 0
OpDecorate %o_i Location 1
OpDecorate %o_u Location 2
OpDecorate %o_v2 Location 3
OpDecorate %o_v3 Location 4
OpDecorate %o_v4 Location 5
OpDecorate %o_f2 Location 6
%void = OpTypeVoid
%fn = OpTypeFunction %void
%float = OpTypeFloat 32
%int = OpTypeInt 32 1
%uint = OpTypeInt 32 0
%v2f = OpTypeVector %float 2
%v3f = OpTypeVector %float 3
%v4f = OpTypeVector %float 4
%v2u = OpTypeVector %uint 2
%m2 = OpTypeMatrix %v2f 2
%m3 = OpTypeMatrix %v3f 3
%m4 = OpTypeMatrix %v4f 4
%sff = OpTypeStruct %float %float
%sfi = OpTypeStruct %float %int
%p_in = OpTypePointer Input %v4f
%p_f = OpTypePointer Output %float
%p_i = OpTypePointer Output %int
%p_u = OpTypePointer Output %uint
%p_v2 = OpTypePointer Output %v2f
%p_v3 = OpTypePointer Output %v3f
%p_v4 = OpTypePointer Output %v4f
%pf_f = OpTypePointer Function %float
%pf_i = OpTypePointer Function %int
%in = OpVariable %p_in Input
%o_f = OpVariable %p_f Output
%o_i = OpVariable %p_i Output
%o_u = OpVariable %p_u Output
%o_v2 = OpVariable %p_v2 Output
%o_v3 = OpVariable %p_v3 Output
%o_v4 = OpVariable %p_v4 Output
%o_f2 = OpVariable %p_f Output
%main = OpFunction %void None %fn
%entry = OpLabel
%vf = OpVariable %pf_f Function
%vi = OpVariable %pf_i Function
%v = OpLoad %v4f %in
%x = OpCompositeExtract %float %v 0
%y = OpCompositeExtract %float %v 1
%z = OpCompositeExtract %float %v 2
%i = OpConvertFToS %int %x
%j = OpConvertFToS %int %y
%k = OpConvertFToS %int %z
%a = OpConvertFToU %uint %x
%b = OpConvertFToU %uint %y
%c = OpConvertFToU %uint %z
%v2 = OpVectorShuffle %v2f %v %v 0 1
%v3 = OpVectorShuffle %v3f %v %v 0 1 2
%w3 = OpVectorShuffle %v3f %v %v 3 2 1
%u3 = OpVectorShuffle %v3f %v %v 1 3 0
%mat2 = OpCompositeConstruct %m2 %v2 %v2
%mat3 = OpCompositeConstruct %m3 %v3 %w3 %u3
%mat4 = OpCompositeConstruct %m4 %v %v %v %v
)";

const char* kFloat = "OpStore %o_f %r";
const char* kInt = "OpStore %o_i %r";
const char* kUint = "OpStore %o_u %r";
const char* kV2 = "OpStore %o_v2 %r";
const char* kV3 = "OpStore %o_v3 %r";
const char* kV4 = "OpStore %o_v4 %r";

std::vector<ExtCase> ext_cases() {
    std::vector<ExtCase> c;
    for (const char* n :
         {"Round", "RoundEven", "Trunc", "FAbs", "FSign", "Floor", "Ceil", "Fract",      "Radians", "Degrees",
          "Sin",   "Cos",       "Tan",   "Asin", "Acos",  "Atan",  "Sinh", "Cosh",       "Tanh",    "Asinh",
          "Acosh", "Atanh",     "Exp",   "Log",  "Exp2",  "Log2",  "Sqrt", "InverseSqrt"})
        c.push_back({n, "%float", "%x", kFloat});
    for (const char* n : {"SAbs", "SSign", "FindILsb", "FindSMsb"}) c.push_back({n, "%int", "%i", kInt});
    c.push_back({"FindUMsb", "%uint", "%a", kUint});
    for (const char* n : {"Atan2", "Pow", "FMin", "FMax", "Step", "NMin", "NMax"})
        c.push_back({n, "%float", "%x %y", kFloat});
    for (const char* n : {"FClamp", "FMix", "SmoothStep", "Fma", "NClamp"})
        c.push_back({n, "%float", "%x %y %z", kFloat});
    for (const char* n : {"UMin", "UMax"}) c.push_back({n, "%uint", "%a %b", kUint});
    for (const char* n : {"SMin", "SMax"}) c.push_back({n, "%int", "%i %j", kInt});
    c.push_back({"UClamp", "%uint", "%a %b %c", kUint});
    c.push_back({"SClamp", "%int", "%i %j %k", kInt});
    c.push_back({"Determinant", "%float", "%mat2", kFloat});
    c.push_back({"Determinant", "%float", "%mat3", kFloat});
    c.push_back({"Determinant", "%float", "%mat4", kFloat});
    c.push_back({"MatrixInverse", "%m2", "%mat2", "%r0 = OpCompositeExtract %v2f %r 1\nOpStore %o_v2 %r0"});
    c.push_back({"MatrixInverse", "%m3", "%mat3", "%r0 = OpCompositeExtract %v3f %r 2\nOpStore %o_v3 %r0"});
    c.push_back({"MatrixInverse", "%m4", "%mat4", "%r0 = OpCompositeExtract %v4f %r 3\nOpStore %o_v4 %r0"});
    c.push_back({"Modf", "%float", "%x %vf", "OpStore %o_f %r\n%r1 = OpLoad %float %vf\nOpStore %o_f2 %r1"});
    c.push_back({"ModfStruct", "%sff", "%x",
                 "%r0 = OpCompositeExtract %float %r 0\n%r1 = OpCompositeExtract %float %r 1\n"
                 "OpStore %o_f %r0\nOpStore %o_f2 %r1"});
    c.push_back({"Frexp", "%float", "%x %vi", "OpStore %o_f %r\n%r1 = OpLoad %int %vi\nOpStore %o_i %r1"});
    c.push_back({"FrexpStruct", "%sfi", "%x",
                 "%r0 = OpCompositeExtract %float %r 0\n%r1 = OpCompositeExtract %int %r 1\n"
                 "OpStore %o_f %r0\nOpStore %o_i %r1"});
    c.push_back({"Ldexp", "%float", "%x %i", kFloat});
    c.push_back({"PackSnorm4x8", "%uint", "%v", kUint});
    c.push_back({"PackUnorm4x8", "%uint", "%v", kUint});
    for (const char* n : {"PackSnorm2x16", "PackUnorm2x16", "PackHalf2x16"}) c.push_back({n, "%uint", "%v2", kUint});
    for (const char* n : {"UnpackSnorm2x16", "UnpackUnorm2x16", "UnpackHalf2x16"}) c.push_back({n, "%v2f", "%a", kV2});
    for (const char* n : {"UnpackSnorm4x8", "UnpackUnorm4x8"}) c.push_back({n, "%v4f", "%a", kV4});
    c.push_back({"Length", "%float", "%v3", kFloat});
    c.push_back({"Distance", "%float", "%v3 %w3", kFloat});
    c.push_back({"Cross", "%v3f", "%v3 %w3", kV3});
    c.push_back({"Normalize", "%v3f", "%v3", kV3});
    c.push_back({"FaceForward", "%v3f", "%v3 %w3 %u3", kV3});
    c.push_back({"Reflect", "%v3f", "%v3 %w3", kV3});
    c.push_back({"Refract", "%v3f", "%v3 %w3 %x", kV3});
    c.push_back({"InterpolateAtCentroid", "%v4f", "%in", kV4});
    c.push_back({"InterpolateAtSample", "%v4f", "%in %i", kV4});
    c.push_back({"InterpolateAtOffset", "%v4f", "%in %v2", kV4});
    return c;
}

Result create_from_assembly(const std::string& text, std::string* asm_error) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string msg;
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { msg += m; });
    std::vector<uint32_t> words;
    if (!tools.Assemble(text, &words)) {
        *asm_error = msg;
        return Result{};
    }
    return Program::create(words, Stage::Fragment);
}

}  // namespace

TEST(ShaderGlsl450, EveryInstructionTranslatedOrRejectedByName) {
    int translated = 0, rejected = 0;
    std::string rejected_names;
    for (const ExtCase& c : ext_cases()) {
        std::string text = std::string(kHeader) + "%r = OpExtInst " + c.type + " %glsl " + c.name + " " + c.args +
                           "\n" + c.store + "\nOpReturn\nOpFunctionEnd\n";
        std::string asm_error;
        Result r = create_from_assembly(text, &asm_error);
        ASSERT_TRUE(asm_error.empty()) << c.name << ": " << asm_error;
        if (r) {
            ++translated;
            // and it runs
            FragmentBlock fb;
            for (int l = 0; l < kLanes; ++l)
                for (int k = 0; k < 4; ++k) fb.inputs[0][k][l] = u(0.25f * float(l + k) + 0.5f);
            Scratch s;
            r.program->run_fragment(Bindings{}, fb, s);
        } else {
            ++rejected;
            rejected_names += std::string(c.name) + " ";
            EXPECT_NE(r.error.find(std::string("GLSL.std.450 instruction ") + c.name), std::string::npos)
                << c.name << ": " << r.error;
        }
    }
    // The two 64-bit instructions (Float64 capability): the uvec2 (low, high) and the double are the same registers.
    for (const char* dbl :
         {"%d = OpExtInst %double %glsl PackDouble2x32 %uv\n", "%d = OpExtInst %v2u %glsl UnpackDouble2x32 %dc\n"}) {
        std::string text =
            std::string(kHeader) + "%uv = OpCompositeConstruct %v2u %a %b\n" + dbl + "OpReturn\nOpFunctionEnd\n";
        text.insert(text.find("OpCapability InterpolationFunction"), "OpCapability Float64\n");
        text.insert(text.find("%v2u = OpTypeVector"), "%double = OpTypeFloat 64\n%dc = OpConstant %double 1.5\n");
        std::string asm_error;
        Result r = create_from_assembly(text, &asm_error);
        ASSERT_TRUE(asm_error.empty()) << asm_error;
        EXPECT_TRUE(r) << r.error;
        ++translated;
    }
    // IMix (47) is reserved: not even the assembler knows it; a hand-made instruction is refused (validation).
    {
        std::string text = std::string(kHeader) + "%r = OpExtInst %float %glsl Round %x\nOpStore %o_f %r\n" +
                           "OpReturn\nOpFunctionEnd\n";
        spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
        std::vector<uint32_t> words;
        ASSERT_TRUE(tools.Assemble(text, &words));
        bool patched = false;
        for (size_t at = 5; at < words.size();) {
            uint32_t n = words[at] >> 16;
            if ((words[at] & 0xffff) == 12 /*OpExtInst*/ && words[at + 4] == 1 /*Round*/) {
                words[at + 4] = 47;
                patched = true;
            }
            at += n ? n : 1;
        }
        ASSERT_TRUE(patched);
        Result r = Program::create(words, Stage::Fragment);
        ASSERT_FALSE(r);
        EXPECT_FALSE(r.error.empty());
        ++rejected;
    }
    // 81 instructions (Determinant and MatrixInverse are tried at 2x2, 3x3 and 4x4: +4 cases)
    EXPECT_EQ(translated + rejected, 81 + 4);
    EXPECT_EQ(rejected, 1) << rejected_names;  // IMix
    std::printf("GLSL.std.450: %d cases translated, %d rejected by name (%s+ IMix)\n", translated, rejected,
                rejected_names.c_str());
}

namespace {

using Mat = std::vector<std::vector<float>>;  // [column][row]

// lavapipe's determinant (vtn build_det), written out independently: expand along column 0,
// prod_i = m[0][i] * minor(i, 0), det = (prod_0 - prod_1) + (prod_2 - prod_3); a 2x2 minor is one element.
float model_det(const Mat& m);
float model_minor(const Mat& m, size_t row, size_t col) {
    size_t n = m.size();
    if (n == 2) return m[1 - col][1 - row];
    Mat s;
    for (size_t c = 0; c < n; ++c) {
        if (c == col) continue;
        std::vector<float> v;
        for (size_t r = 0; r < n; ++r)
            if (r != row) v.push_back(m[c][r]);
        s.push_back(v);
    }
    return model_det(s);
}
float model_det(const Mat& m) {
    size_t n = m.size();
    float p[4];
    for (size_t i = 0; i < n; ++i) p[i] = m[0][i] * model_minor(m, i, 0);
    float acc = p[0] - p[1];
    if (n == 3) acc = acc + p[2];
    if (n == 4) acc = acc + (p[2] - p[3]);
    return acc;
}

}  // namespace

TEST(ShaderGlsl450, DeterminantAndInverse) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(location=0) in vec4 c0;
        layout(location=1) in vec4 c1;
        layout(location=2) in vec4 c2;
        layout(location=3) in vec4 c3;
        layout(location=0) out vec4 dets;
        layout(location=1) out vec4 i2;
        layout(location=2) out vec3 i3a;
        layout(location=3) out vec3 i3b;
        layout(location=4) out vec3 i3c;
        layout(location=5) out vec4 i4[4];
        void main() {
            mat2 m2 = mat2(c0.xy, c1.xy);
            mat3 m3 = mat3(c0.xyz, c1.xyz, c2.xyz);
            mat4 m4 = mat4(c0, c1, c2, c3);
            dets = vec4(determinant(m2), determinant(m3), determinant(m4), 0.0);
            mat2 a = inverse(m2);
            i2 = vec4(a[0], a[1]);
            mat3 b = inverse(m3);
            i3a = b[0]; i3b = b[1]; i3c = b[2];
            mat4 d = inverse(m4);
            for (int k = 0; k < 4; ++k) i4[k] = d[k];
            gl_Position = vec4(0.0);
        })");
    ASSERT_TRUE(prog);
    VertexBatch vb;
    auto value = [](int l, int c, int r) {
        // varied, well-conditioned-ish entries with inexact products
        return float((l * 7 + c * 13 + r * 5 + c * r * 3) % 17) * 0.37f - 2.9f + (c == r ? 4.1f : 0.0f) +
               float(l) * 0.013f;
    };
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) vb.inputs[c][r][l] = u(value(l, c, r));
    Scratch s;
    prog->run_vertex(Bindings{}, vb, s);
    int checked_identity = 0;
    for (int l = 0; l < kLanes; ++l) {
        for (size_t n = 2; n <= 4; ++n) {
            Mat m(n, std::vector<float>(n));
            for (size_t c = 0; c < n; ++c)
                for (size_t r = 0; r < n; ++r) m[c][r] = value(l, int(c), int(r));
            float det = model_det(m);
            EXPECT_EQ(f(vb.outputs[0][n - 2][l]), det) << "lane " << l << " det" << n;
            // inverse: adj[c][r] = (-1)^(r+c) minor(row c, column r), times 1/det
            float inv = 1.0f / det;
            for (size_t c = 0; c < n; ++c)
                for (size_t r = 0; r < n; ++r) {
                    float a = model_minor(m, c, r);
                    if ((r + c) % 2) a = -a;
                    float e = a * inv;
                    uint32_t got = n == 2   ? vb.outputs[1][c * 2 + r][l]
                                   : n == 3 ? vb.outputs[2 + c][r][l]
                                            : vb.outputs[5 + c][r][l];
                    EXPECT_EQ(f(got), e) << "lane " << l << " inverse" << n << " [" << c << "][" << r << "]";
                }
            // and it is an inverse: M * inv(M) ~ I in double maths (a sanity check on the formula, not on bits)
            if (std::fabs(det) > 0.5f) {
                for (size_t r = 0; r < n; ++r)
                    for (size_t c = 0; c < n; ++c) {
                        double acc = 0;
                        for (size_t k = 0; k < n; ++k) {
                            uint32_t ik = n == 2   ? vb.outputs[1][c * 2 + k][l]
                                          : n == 3 ? vb.outputs[2 + c][k][l]
                                                   : vb.outputs[5 + c][k][l];
                            acc += double(m[k][r]) * double(f(ik));
                        }
                        EXPECT_NEAR(acc, r == c ? 1.0 : 0.0, 1e-4) << l << " " << n;
                    }
                ++checked_identity;
            }
        }
    }
    EXPECT_GT(checked_identity, 20);
}

TEST(ShaderGlsl450, ModfAndFrexp) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(location=0) in vec4 x;
        layout(location=0) out vec4 fr;
        layout(location=1) out vec4 wh;
        layout(location=2) out vec4 sig;
        layout(location=3) flat out ivec4 ex;
        void main() {
            vec4 w;
            fr = modf(x, w);
            wh = w;
            ivec4 e;
            sig = frexp(x, e);
            ex = e;
            gl_Position = vec4(0.0);
        })");
    ASSERT_TRUE(prog);
    const float vals[] = {2.75f,    -2.75f,    0.0f, -0.0f, 1.0f,  -0.5f, 1e-40f /*denormal: DAZ*/,
                          INFINITY, -INFINITY, NAN,  3e38f, -7.0f, 0.3f,  1234.5678f,
                          1.5e-38f, -6e-39f};
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) vb.inputs[0][c][l] = u(vals[(l + c * 5) % 16]);
    Scratch s;
    prog->run_vertex(Bindings{}, vb, s);
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) {
            float x = vals[(l + c * 5) % 16];
            uint32_t xb = u(x);
            bool denormal = (xb & 0x7f800000u) == 0 && (xb & 0x7fffffu) != 0;
            float xd = denormal ? 0.0f * (x < 0 ? -1.0f : 1.0f) : x;  // what DAZ makes of it in arithmetic
            // modf as lavapipe: sign(x) * fract(|x|), +-0 (x's sign) for +-inf; whole = sign(x) * floor(|x|)
            float sg = xd > 0 ? 1.0f : xd < 0 ? -1.0f : xd * 0.0f;
            float ax = std::fabs(xd);
            float efr = std::isinf(x) ? std::bit_cast<float>(xb & 0x80000000u) : sg * (ax - std::floor(ax));
            float ewh = sg * std::floor(ax);
            uint32_t gfr = vb.outputs[0][c][l], gwh = vb.outputs[1][c][l];
            if (std::isnan(x)) {
                EXPECT_TRUE(std::isnan(f(gfr))) << l;
                EXPECT_TRUE(std::isnan(f(gwh))) << l;
            } else {
                EXPECT_EQ(gfr, u(efr)) << "modf fract of " << x;
                EXPECT_EQ(gwh, u(ewh)) << "modf whole of " << x;
            }
            // frexp (nir_lower_frexp): finite non-zero -> mantissa with exponent field 126; exponent = field - 126;
            // zero (and denormals under DAZ): x itself and 0; inf/NaN: x itself and 129
            uint32_t field = (xb >> 23) & 0xff;
            bool nonzero_finite = !denormal && x != 0.0f && std::isfinite(x);
            uint32_t esig = nonzero_finite ? (xb & 0x807fffffu) | 0x3f000000u : xb;
            int32_t eexp = (denormal || x == 0.0f) ? 0 : int32_t(field) - 126;
            EXPECT_EQ(vb.outputs[2][c][l], esig) << "frexp significand of " << x;
            EXPECT_EQ(int32_t(vb.outputs[3][c][l]), eexp) << "frexp exponent of " << x;
            if (nonzero_finite) {
                EXPECT_EQ(std::ldexp(f(esig), eexp), x);
            }
        }
}

TEST(ShaderGlsl450, ExtendedIntegerArithmeticAndArrayLength) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(set=0, binding=0, std430) readonly buffer B { uvec2 head; vec3 items[]; } b;
        layout(set=0, binding=1, std430) readonly buffer C { float xs[]; } cs[2];
        layout(location=0) in uvec2 ab;
        layout(location=0) flat out uvec4 o0;
        layout(location=1) flat out uvec4 o1;
        layout(location=2) flat out ivec4 o2;
        void main() {
            uint carry, borrow, hi, lo;
            uint s = uaddCarry(ab.x, ab.y, carry);
            uint d = usubBorrow(ab.x, ab.y, borrow);
            umulExtended(ab.x, ab.y, hi, lo);
            int shi, slo;
            imulExtended(int(ab.x), int(ab.y), shi, slo);
            o0 = uvec4(s, carry, d, borrow);
            o1 = uvec4(hi, lo, uint(shi), uint(slo));
            o2 = ivec4(b.items.length(), cs[0].xs.length(), cs[1].xs.length(), 0);
            gl_Position = vec4(0.0);
        })");
    ASSERT_TRUE(prog);
    VertexBatch vb;
    const uint32_t vals[] = {0u, 1u, 0xFFFFFFFFu, 0x80000000u, 0x7FFFFFFFu, 12345u, 0xDEADBEEFu, 3u};
    for (int l = 0; l < kLanes; ++l) {
        vb.inputs[0][0][l] = vals[l % 8];
        vb.inputs[0][1][l] = vals[(l * 3 + 1) % 8];
    }
    // B: head (8 bytes) then vec3 items at stride 16 from offset 16: size 16 + 5*16 + 12 -> 5 whole items
    std::vector<uint8_t> bb(16 + 5 * 16 + 12), c0(4 * 7 + 3);
    Bindings bind;
    bind.set(0, 0, 0, Descriptor{BufferView{bb.data(), nullptr, bb.size()}});
    bind.set(0, 1, 0, Descriptor{BufferView{c0.data(), nullptr, c0.size()}});  // element 1 missing
    Scratch s;
    prog->run_vertex(bind, vb, s);
    for (int l = 0; l < kLanes; ++l) {
        uint32_t a = vals[l % 8], b = vals[(l * 3 + 1) % 8];
        uint64_t up = uint64_t(a) * b;
        int64_t sp = int64_t(int32_t(a)) * int32_t(b);
        EXPECT_EQ(vb.outputs[0][0][l], a + b);
        EXPECT_EQ(vb.outputs[0][1][l], (uint64_t(a) + b) >> 32);
        EXPECT_EQ(vb.outputs[0][2][l], a - b);
        EXPECT_EQ(vb.outputs[0][3][l], a < b ? 1u : 0u);
        EXPECT_EQ(vb.outputs[1][0][l], uint32_t(up >> 32));
        EXPECT_EQ(vb.outputs[1][1][l], uint32_t(up));
        EXPECT_EQ(vb.outputs[1][2][l], uint32_t(uint64_t(sp) >> 32));
        EXPECT_EQ(vb.outputs[1][3][l], uint32_t(uint64_t(sp)));
        // lavapipe (nir_lower_explicit_io): usub_sat(size, offset) / stride, rounded down: (108 - 16) / 16 = 5
        // even though a sixth vec3 (12 bytes at 96) would fit
        EXPECT_EQ(vb.outputs[2][0][l], 5u);
        EXPECT_EQ(vb.outputs[2][1][l], 7u);
        EXPECT_EQ(vb.outputs[2][2][l], 0u) << "missing descriptor: length 0";
    }
}
