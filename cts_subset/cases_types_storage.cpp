// types.storage.*, types.fragment.int16_int8, types.convert.f2u: 8- and 16-bit values in memory — a std140 uniform
// buffer and push constants with members at odd offsets, std430 stores of bytes and halves that share words with
// other invocations' stores, 16-bit floats converted to and from 32-bit floats (LLVM's fpext / fptrunc) — in compute
// and fragment shaders, and float -> uint conversions of values outside the uint range, compared byte for byte with
// the reference (cases_types_narrow.cpp has the arithmetic). The stored integers are also checked against the
// offsets the layout rules give them, the halves against a round-to-nearest-even written here.
#include <bit>
#include <cmath>
#include <limits>

#include "compute_case.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

uint8_t byte_at(const std::vector<uint32_t>& w, size_t b) {
    return b / 4 < w.size() ? uint8_t(w[b / 4] >> (b % 4 * 8)) : 0;
}
uint32_t half_at(const std::vector<uint32_t>& w, size_t b) {
    return byte_at(w, b) | uint32_t(byte_at(w, b + 1)) << 8;
}

// The IEEE half nearest to a finite float (ties to even), in double arithmetic: an independent model of fptrunc.
uint32_t half_rne(float f) {
    const uint32_t s = std::signbit(f) ? 0x8000u : 0;
    const double a = std::fabs(double(f));
    if (a >= 65520.0) return s | 0x7c00u;
    const int e = std::max(int(std::floor(std::log2(a > 0 ? a : 1.0))), -14);
    const double q = std::ldexp(1.0, e - 10), m = std::nearbyint(a / q);  // the default rounding: to even
    if (a == 0) return s;
    return s | uint32_t(e == -14 && m < 1024 ? m : (uint32_t(e + 15) << 10) + (uint32_t(m) - 1024));
}
float half_value(uint32_t h) {  // finite halves
    const double m = (h & 0x3ff),
                 v = (h >> 10 & 31) ? std::ldexp(1024 + m, int(h >> 10 & 31) - 25) : std::ldexp(m, -24);
    return float(h & 0x8000 ? -v : v);
}

// std140 U (offsets by the rules): a@0 u8, b@2 u16, c@4 u8, d@8 u8vec3, e@12 i16, f@16 i16vec3, h@22 f16,
// hv@24 f16vec2, g@32 int8_t[4] (stride 16); 96 bytes. Push constants (std430): pa@0 u8, pb@1 i8, pc@2 u16,
// pd@4 u8vec2, pe@6 f16, pf@8 i16. Out (std430) T: a@0, b@2, c@4, d@8, e@12, f@16, h@24 float, hv@32 vec2,
// g@40 int8_t[4], odd@44, size 48.
const char* kLayoutShader =
    "#version 450\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int16 : require\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int8 : require\n"
    "#extension GL_EXT_shader_16bit_storage : require\n"
    "#extension GL_EXT_shader_8bit_storage : require\n"
    "layout(local_size_x=16) in;\n"
    "layout(std140, binding=0) uniform U { uint8_t a; uint16_t b; uint8_t c; u8vec3 d; int16_t e; i16vec3 f;\n"
    "  float16_t h; f16vec2 hv; int8_t g[4]; } u;\n"
    "struct T { uint8_t a; uint16_t b; uint8_t c; u8vec3 d; int16_t e; i16vec3 f; float h; vec2 hv; int8_t g[4];\n"
    "  uint8_t odd; };\n"
    "layout(std430, binding=1) buffer O { T t[]; } o;\n"
    "layout(std430, binding=2) readonly buffer F { float fin[]; } fb;\n"
    "layout(std430, binding=3) buffer H { uint w[128]; float16_t hs[]; } hb;\n"
    "layout(std430, binding=4) buffer B { uint8_t bytes[]; } bb;\n"
    "layout(push_constant) uniform P { uint8_t pa; int8_t pb; uint16_t pc; u8vec2 pd; float16_t pe; int16_t pf; } p;\n"
    "void main() {\n"
    "  uint i = gl_GlobalInvocationID.x;\n"
    "  uint8_t i8 = uint8_t(i); int16_t i16 = int16_t(i);\n"
    "  o.t[i].a = u.a + i8; o.t[i].b = u.b ^ uint16_t(i); o.t[i].c = u.c; o.t[i].d = u.d + u8vec3(i8);\n"
    "  o.t[i].e = u.e - i16; o.t[i].f = u.f * i16; o.t[i].h = float(u.h); o.t[i].hv = vec2(u.hv);\n"
    "  for (int j = 0; j < 4; ++j) o.t[i].g[j] = u.g[j] + int8_t(i8);\n"
    "  o.t[i].odd = uint8_t(i * 37u);\n"
    "  hb.hs[i] = float16_t(fb.fin[i]);\n"
    "  bb.bytes[3u * i + 1u] = p.pa + i8; bb.bytes[3u * i + 2u] = uint8_t(p.pb * int8_t(i8));\n"
    "  hb.w[2u * i] = uint(p.pc) + uint(p.pd.x) * 65536u + uint(p.pd.y) * 16777216u;\n"
    "  hb.w[2u * i + 1u] = floatBitsToUint(float(p.pe) * float(p.pf));\n"
    "}\n";

std::vector<float> half_inputs() {
    std::vector<float> v = {0.0f,
                            -0.0f,
                            1.0f,
                            -1.5f,
                            65504.0f,
                            65519.0f,
                            65520.0f,
                            -70000.0f,
                            0x1p-24f,
                            0x1p-25f,
                            0x1.8p-25f,
                            0x1.8p-24f,
                            0x1.004p0f,
                            0x1.006p0f,
                            0x1.002p0f,
                            1e-8f,
                            1e-40f,
                            0.1f,
                            3.14159f,
                            -0x1.ff8p-15f,
                            0x1.ffcp-15f,
                            INFINITY,
                            -INFINITY,
                            std::numeric_limits<float>::quiet_NaN(),
                            std::bit_cast<float>(0x7fa12345u),
                            std::bit_cast<float>(0xff812345u),
                            std::bit_cast<float>(0x7fc12345u),
                            std::bit_cast<float>(0xffe00001u)};
    Rng r(9);
    while (v.size() < 64) v.push_back(r.range(-2.0f, 2.0f) * std::ldexp(1.0f, int(r.below(40)) - 25));
    return v;
}

std::vector<uint32_t> float_words(const std::vector<float>& v) {
    std::vector<uint32_t> w;
    w.reserve(v.size());
    for (float f : v) w.push_back(std::bit_cast<uint32_t>(f));
    return w;
}

std::string check_layout(const std::vector<Plane>& planes, const std::vector<uint32_t>& uni,
                         const std::vector<uint32_t>& push, const std::vector<float>& fin) {
    const std::vector<uint32_t> t = buffer_words(planes, 1), w = buffer_words(planes, 3), b = buffer_words(planes, 4);
    auto fail = [](const std::string& what, uint32_t i, uint32_t got, uint32_t want) {
        return what + " of invocation " + std::to_string(i) + " is " + std::to_string(got) + ", expected " +
               std::to_string(want);
    };
    for (uint32_t i = 0; i < 64; ++i) {
        const size_t e = size_t(i) * 48;
        const uint32_t want[] = {(byte_at(uni, 0) + i) & 0xFFu,
                                 half_at(uni, 2) ^ i,
                                 byte_at(uni, 4),
                                 (byte_at(uni, 8) + i) & 0xFFu,
                                 (byte_at(uni, 10) + i) & 0xFFu,
                                 (half_at(uni, 12) - i) & 0xFFFFu,
                                 (half_at(uni, 18) * i) & 0xFFFFu,
                                 (byte_at(uni, 48) + i) & 0xFFu,
                                 (i * 37) & 0xFFu};
        const uint32_t got[] = {byte_at(t, e),      half_at(t, e + 2),  byte_at(t, e + 4),
                                byte_at(t, e + 8),  byte_at(t, e + 10), half_at(t, e + 12),
                                half_at(t, e + 18), byte_at(t, e + 41), byte_at(t, e + 44)};
        for (size_t k = 0; k < std::size(want); ++k)
            if (got[k] != want[k]) return fail("member " + std::to_string(k), i, got[k], want[k]);
        const uint32_t hf = std::bit_cast<uint32_t>(half_value(half_at(uni, 22)));
        if (t[e / 4 + 6] != hf) return fail("float(u.h)", i, t[e / 4 + 6], hf);
        if (!std::isnan(fin[i]) && half_at(w, 512 + 2 * i) != half_rne(fin[i]))
            return fail("float16_t(x)", i, half_at(w, 512 + 2 * i), half_rne(fin[i]));
        const uint32_t pa = push[0] & 0xFF, pb = push[0] >> 8 & 0xFF;
        if (byte_at(b, 3 * i + 1) != ((pa + i) & 0xFF)) return fail("byte 3i+1", i, byte_at(b, 3 * i + 1), pa + i);
        const uint32_t pbi = uint32_t(int8_t(pb) * int8_t(i)) & 0xFF;
        if (byte_at(b, 3 * i + 2) != pbi) return fail("byte 3i+2", i, byte_at(b, 3 * i + 2), pbi);
        const uint32_t marker = uint8_t(kMarker >> (3 * i % 4 * 8));  // nobody writes byte 3i
        if (byte_at(b, 3 * i) != marker) return fail("byte 3i (not written)", i, byte_at(b, 3 * i), marker);
        const uint32_t pw = (push[0] >> 16) + (push[1] & 0xFF) * 65536u + (push[1] >> 8 & 0xFF) * 16777216u;
        if (w[2 * i] != pw) return fail("push word", i, w[2 * i], pw);
    }
    return {};
}

void add_layout_case(CaseList& out) {
    Rng r(11);
    std::vector<uint32_t> uni(24);
    for (uint32_t& x : uni) x = r.next();
    uni[5] = (uni[5] & 0xFFFFu) | 0x3C01u << 16;  // h@22: 1.0009765625
    uni[6] = 0x83FF0401u;                         // hv@24: a normal half and a negative denormal
    const std::vector<uint32_t> push = {0x1234F781u, 0xB9C92A05u, 0x0000FFFDu};  // pe@6: -0.6963 (0xB9C9)
    const std::vector<float> fin = half_inputs();
    ComputeSpec s;
    s.shaders = {kLayoutShader};
    s.buffers = {{uni, true},
                 {std::vector<uint32_t>(64 * 12, kMarker)},
                 {float_words(fin)},
                 {std::vector<uint32_t>(128 + 33, kMarker)},
                 {std::vector<uint32_t>(48, kMarker)}};
    s.push = push;
    s.steps = {dispatch(0, 4)};
    add_types_case(out, "storage.layouts_and_halves", std::move(s),
                   [uni, push, fin](const std::vector<Plane>& planes) { return check_layout(planes, uni, push, fin); });
}

// A fragment shader with 16- and 8-bit arithmetic: each pixel stores halves and bytes at its own index (sharing
// words with its neighbours) and writes a colour made from 8-bit values.
void add_fragment_case(CaseList& out) {
    constexpr uint32_t kSize = 16;
    ComputeSpec s;
    s.buffers = {{std::vector<uint32_t>(kSize * kSize, kMarker)}, {std::vector<uint32_t>(kSize * kSize / 4, kMarker)}};
    s.images = {{VK_FORMAT_R8G8B8A8_UNORM, kSize, kSize, {}, true}};
    s.draw = {
        "#version 450\n"
        "void main() {\n"
        "  vec2 p = vec2(float(gl_VertexIndex & 1) * 4.0 - 1.0, float(gl_VertexIndex >> 1) * 4.0 - 1.0);\n"
        "  gl_Position = vec4(p, 0.0, 1.0);\n"
        "}\n",
        "#version 450\n"
        "#extension GL_EXT_shader_explicit_arithmetic_types_int16 : require\n"
        "#extension GL_EXT_shader_explicit_arithmetic_types_int8 : require\n"
        "#extension GL_EXT_shader_16bit_storage : require\n"
        "#extension GL_EXT_shader_8bit_storage : require\n"
        "layout(std430, binding=0) buffer H { uint16_t h[256]; float16_t f[256]; } hb;\n"
        "layout(std430, binding=1) buffer B { uint8_t b[]; } bb;\n"
        "layout(location=0) out vec4 o;\n"
        "void main() {\n"
        "  uvec2 q = uvec2(gl_FragCoord.xy);\n"
        "  uint i = q.y * 16u + q.x;\n"
        "  int16_t x = int16_t(i) * int16_t(-1237) + int16_t(q.x << 11);\n"
        "  hb.h[i] = uint16_t(x >> int16_t(q.y & 15u)) ^ uint16_t(i * 40503u);\n"
        "  hb.f[i] = float16_t(gl_FragCoord.x / gl_FragCoord.y * 1000.0);\n"
        "  int8_t c = int8_t(x) / int8_t(int(q.y) - 7);\n"
        "  bb.b[i] = uint8_t(c) + uint8_t(x >> int16_t(8));\n"
        "  o = vec4(float(uint8_t(c)) / 255.0, float(uint8_t(x)) / 255.0, float(int8_t(x) < c), 1.0);\n"
        "}\n",
        3, -1};
    s.steps = {draw()};
    add_types_case(out, "fragment.int16_int8", std::move(s));
}

// float -> uint outside [0, 2^32) and NaN.
void add_f2u_case(CaseList& out) {
    std::vector<float> in = {-1.0f,   -0.5f,         std::numeric_limits<float>::quiet_NaN(),
                             0x1p32f, 3e9f,          -3e9f,
                             -100.0f, -0x1p31f,      0x1p31f,
                             4e9f,    INFINITY,      -INFINITY,
                             -0.0f,   0.99f,         -0.99f,
                             -1.5f,   -2147483520.f, 4294967040.0f,
                             1e-40f,  -1e-40f,       std::bit_cast<float>(0xffc00001u)};
    Rng r(13);
    while (in.size() < 64) in.push_back(r.sign() * std::ldexp(r.range(1.0f, 2.0f), int(r.below(36))));
    ComputeSpec s;
    s.shaders = {glsl_header(16) +
                 "layout(std430, binding=0) readonly buffer In { float a[]; } inp;\n"
                 "layout(std430, binding=1) buffer Out { uint r[]; } o;\n"
                 "void main() {\n"
                 "  uint i = gl_GlobalInvocationID.x;\n"
                 "  float x = inp.a[i];\n"
                 "  o.r[3u * i] = uint(x); o.r[3u * i + 1u] = uint(int(x)); o.r[3u * i + 2u] = uint(x * 0.5);\n"
                 "}\n"};
    s.buffers = {{float_words(in)}, {std::vector<uint32_t>(64 * 3, kMarker)}};
    s.steps = {dispatch(0, 4)};
    // The measured rule (lavapipe 22.3.6 on AVX2): trunc(x) for x in (-1, 2^32), all ones for everything else,
    // NaN included (the rule 64-bit conversions follow too, shader/README.md "64-bit types").
    Check check = [in](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> w = buffer_words(planes, 1);
        std::string msg;
        for (uint32_t i = 0; i < in.size(); ++i) {
            const float x = in[i];
            const uint32_t want = x > -1.0f && x < 0x1p32f ? uint32_t(x) : 0xFFFFFFFFu;
            if (w.size() != in.size() * 3 || w[3 * i] != want)
                msg += "uint(" + std::to_string(x) + ") is " + std::to_string(w.size() > 3 * i ? w[3 * i] : 0) +
                       ", expected " + std::to_string(want) + "; ";
        }
        return msg;
    };
    add_types_case(out, "convert.f2u", std::move(s), check);
}

}  // namespace

void add_types_narrow_storage_cases(CaseList& out) {
    add_layout_case(out);
    add_fragment_case(out);
    add_f2u_case(out);
}

}  // namespace tilevk::cts
