// compute.atomic_float.* (VK_EXT_shader_atomic_float): atomicAdd, atomicExchange, atomicLoad and atomicStore on
// 32-bit floats in storage buffers, shared memory, R32_SFLOAT storage images and storage texel buffers, and from a
// fragment shader. Float addition is not associative, so every result read back is one the order of the invocations
// cannot change: contended adds of quarters whose sums are exact in any order, and one writer per word wherever a
// returned value or a rounded sum is kept (those sums then also show the rounding and the denormals: compute runs
// without FTZ/DAZ, fragment shaders with both, as in lavapipe). The answers are computed here.
#include <bit>
#include <cmath>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kGroups = 4, kLocal = 64, kN = kGroups * kLocal, kSlots = 16;

std::string header(uint32_t x, uint32_t y = 1) {
    const std::string h = glsl_header(x, y);
    const size_t eol = h.find('\n') + 1;  // after #version: extensions come before any declaration
    return h.substr(0, eol) + "#extension GL_EXT_shader_atomic_float : require\n" +
           "#extension GL_KHR_memory_scope_semantics : require\n" + h.substr(eol);
}

// A compute shader of kLocal invocations: the declarations, then main's body with i = gl_GlobalInvocationID.x.
std::string shader(const std::string& decls, const std::string& body) {
    return header(kLocal) + decls + "void main() { uint i = gl_GlobalInvocationID.x;\n" + body + "}\n";
}

ComputeSpec spec() {
    ComputeSpec s;
    s.atomic_float = true;
    return s;
}

// The quarter invocation i adds (same expression in GLSL): 13 values in [-1.5, 1.5], every partial sum exact.
float quarter(uint32_t i) {
    return float(int32_t(i % 13u) - 6) * 0.25f;
}
const char* const kQuarterGlsl = "(float(int(i % 13u) - 6) * 0.25)";

// The operand of invocation i's one-writer adds, with a long mantissa (the rounding shows) or denormal (every 8th).
// The shaders read it from a buffer (kAwkwardGlsl) rather than compute it, so that only the atomic's own addition
// is under test.
float awkward(uint32_t i) {
    return i % 8u == 5u ? std::ldexp(float(i + 1u), -140) : float(i) / 3.0f + 0.1f;
}
const char* const kAwkwardGlsl = "v[i]";
std::string awkward_decl(uint32_t binding) {
    return "layout(std430, binding=" + std::to_string(binding) + ") readonly buffer V { float v[]; };\n";
}

std::vector<uint32_t> bits(const std::vector<float>& v) {
    std::vector<uint32_t> out(v.size());
    for (size_t k = 0; k < v.size(); ++k) out[k] = fbits(v[k]);
    return out;
}

// The buffer kAwkwardGlsl reads: awkward(i) for every invocation, not read back.
ComputeBuffer awkward_buffer() {
    std::vector<float> v(kN);
    for (uint32_t i = 0; i < kN; ++i) v[i] = awkward(i);
    return {bits(v), false, false};
}

// Contended: every invocation adds its quarter to slot i % 16 of a buffer; the slots start at k / 2.
void add_buffer_contended(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {header(kLocal) + "layout(std430, binding=0) buffer C { float c[]; };\n" +
                 "void main() { uint i = gl_GlobalInvocationID.x; atomicAdd(c[i % 16u], " + kQuarterGlsl + "); }\n"};
    std::vector<float> c(kSlots);
    for (uint32_t k = 0; k < kSlots; ++k) c[k] = float(k) * 0.5f;
    s.buffers = {{bits(c)}};
    for (uint32_t i = 0; i < kN; ++i) c[i % kSlots] += quarter(i);
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_float.buffer.add_contended", std::move(s), words_are(0, bits(c)));
}

// One writer per word: atomicAdd and atomicExchange return the old value; atomicStore then atomicLoad of the
// invocation's own word. Buffer 0 holds the words, buffer 1 the returns (3 per invocation).
void add_buffer_one_writer(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {
        header(kLocal) +
        "layout(std430, binding=0) buffer W { float a[256]; float x[256]; float st[256]; };\n"
        "layout(std430, binding=1) buffer R { float r[]; };\n" +
        awkward_decl(2) +
        "void main() { uint i = gl_GlobalInvocationID.x;\n"
        "  r[3u * i] = atomicAdd(a[i], " +
        kAwkwardGlsl +
        ");\n"
        "  r[3u * i + 1u] = atomicExchange(x[i], -float(i) * 1.5);\n"
        "  atomicStore(st[i], float(i) + 0.125, gl_ScopeDevice, 0, 0);\n"
        "  r[3u * i + 2u] = atomicLoad(st[i], gl_ScopeDevice, 0, 0) + atomicLoad(x[i], gl_ScopeDevice, 0, 0);\n"
        "}\n"};
    std::vector<float> w(3 * kN), r(3 * kN);
    for (uint32_t i = 0; i < kN; ++i) {
        w[i] = i % 8u == 3u ? std::ldexp(float(i), -139) : float(i) * 0.7f - 40.0f;  // denormals too
        w[kN + i] = float(i) + 1000.0f;
        w[2 * kN + i] = -1.0f;
    }
    s.buffers = {{bits(w)}, {std::vector<uint32_t>(3 * kN, kMarker)}, awkward_buffer()};
    for (uint32_t i = 0; i < kN; ++i) {
        r[3 * i] = w[i];
        w[i] += awkward(i);  // compute: IEEE, no FTZ/DAZ
        r[3 * i + 1] = w[kN + i];
        w[kN + i] = -float(i) * 1.5f;
        w[2 * kN + i] = float(i) + 0.125f;
        r[3 * i + 2] = w[2 * kN + i] + w[kN + i];
    }
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_float.buffer.one_writer", std::move(s),
                     all_of({words_are(0, bits(w)), words_are(1, bits(r))}));
}

// Shared memory: each workgroup's 4 slots start at 100 * k, take every invocation's quarter (contended) and are
// written out; one slot per invocation takes an exchange and an add whose returns are kept.
void add_shared(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {header(kLocal) +
                 "shared float acc[4];\nshared float own[64];\n"
                 "layout(std430, binding=0) buffer O { float o[]; };\n"
                 "layout(std430, binding=1) buffer R { float r[]; };\n" +
                 awkward_decl(2) +
                 "void main() { uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;\n"
                 "  if (l < 4u) acc[l] = float(l) * 100.0;\n"
                 "  own[l] = float(l) * 0.3;\n"
                 "  barrier();\n"
                 "  atomicAdd(acc[l % 4u], " +
                 kQuarterGlsl +
                 ");\n"
                 "  r[2u * i] = atomicExchange(own[l], " +
                 kAwkwardGlsl +
                 ");\n"
                 "  r[2u * i + 1u] = atomicAdd(own[l], 2.5);\n"
                 "  barrier();\n"
                 "  if (l < 4u) o[gl_WorkGroupID.x * 4u + l] = acc[l];\n"
                 "  o[" +
                 std::to_string(kGroups * 4) + "u + i] = own[l];\n}\n"};
    std::vector<float> o(kGroups * 4 + kN), r(2 * kN);
    for (uint32_t g = 0; g < kGroups; ++g) {
        float acc[4] = {0.0f, 100.0f, 200.0f, 300.0f};
        for (uint32_t l = 0; l < kLocal; ++l) acc[l % 4] += quarter(g * kLocal + l);
        for (uint32_t k = 0; k < 4; ++k) o[g * 4 + k] = acc[k];
        for (uint32_t l = 0; l < kLocal; ++l) {
            const uint32_t i = g * kLocal + l;
            r[2 * i] = float(l) * 0.3f;
            r[2 * i + 1] = awkward(i);
            o[kGroups * 4 + i] = awkward(i) + 2.5f;
        }
    }
    s.buffers = {
        {std::vector<uint32_t>(o.size(), kMarker)}, {std::vector<uint32_t>(r.size(), kMarker)}, awkward_buffer()};
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_float.shared.add_exchange", std::move(s),
                     all_of({words_are(0, bits(o)), words_are(1, bits(r))}));
}

// An R32_SFLOAT storage image (16x16): texels (x, 0..3) of the first 4 columns take contended quarters from every
// invocation; texel i of rows 4..15 (one writer) takes an exchange, an add and a load whose returns are kept. The
// image is also copied into buffer 1 at the end; buffer 0 holds the returns.
void add_image(CaseList& out) {
    ComputeSpec s = spec();
    const std::string decls =
        "layout(binding=3, r32f) uniform image2D img;\n"
        "layout(std430, binding=0) buffer R { float r[]; };\n" +
        awkward_decl(2);
    s.shaders = {shader(decls, std::string("  imageAtomicAdd(img, ivec2(i % 4u, i / 4u % 4u), ") + kQuarterGlsl +
                                   ");\n  if (i < 192u) { ivec2 p = ivec2(i % 16u, 4u + i / 16u);\n"
                                   "    r[3u * i] = imageAtomicExchange(img, p, float(i) * -0.75);\n"
                                   "    r[3u * i + 1u] = imageAtomicAdd(img, p, " +
                                   kAwkwardGlsl +
                                   ");\n"
                                   "    r[3u * i + 2u] = imageAtomicLoad(img, p, gl_ScopeDevice, 0, 0); }\n")};
    std::vector<float> img(256), r(3 * 192);
    for (uint32_t t = 0; t < 256; ++t) img[t] = float(t) * 0.0625f - 3.0f;
    std::vector<uint8_t> init(256 * 4);
    for (uint32_t t = 0; t < 256; ++t) {
        const uint32_t b = fbits(img[t]);
        std::memcpy(&init[t * 4], &b, 4);
    }
    for (uint32_t i = 0; i < kN; ++i) img[(i / 4 % 4) * 16 + i % 4] += quarter(i);
    for (uint32_t i = 0; i < 192; ++i) {
        float& t = img[(4 + i / 16) * 16 + i % 16];
        r[3 * i] = t;
        t = float(i) * -0.75f;
        r[3 * i + 1] = t;
        t += awkward(i);
        r[3 * i + 2] = t;
    }
    s.buffers = {{std::vector<uint32_t>(r.size(), kMarker)}, {std::vector<uint32_t>(256, kMarker)}, awkward_buffer()};
    s.images = {{VK_FORMAT_R32_SFLOAT, 16, 16, init}};
    s.steps = {dispatch(0, kGroups), copy_image_to_buffer(0, 1)};
    add_compute_case(out, "atomic_float.image.r32_sfloat", std::move(s),
                     all_of({words_are(0, bits(r)), words_are(1, bits(img))}));
}

// An R32_SFLOAT storage texel buffer: 8 words take contended quarters, 128 one-writer adds return the old value.
void add_texel_buffer(CaseList& out) {
    ComputeSpec s = spec();
    const std::string decls =
        "layout(binding=0, r32f) uniform imageBuffer t;\n"
        "layout(std430, binding=1) buffer R { float r[]; };\n" +
        awkward_decl(2);
    s.shaders = {shader(decls, std::string("  imageAtomicAdd(t, int(i % 8u), ") + kQuarterGlsl +
                                   ");\n  if (i < 128u) r[i] = imageAtomicAdd(t, int(8u + i), " + kAwkwardGlsl +
                                   ");\n")};
    std::vector<float> t(136), r(128);
    for (uint32_t k = 0; k < t.size(); ++k) t[k] = float(k) * 1.25f + 0.01f;
    ComputeBuffer tb{bits(t)};
    tb.texel_format = VK_FORMAT_R32_SFLOAT;
    for (uint32_t i = 0; i < kN; ++i) t[i % 8] += quarter(i);
    for (uint32_t i = 0; i < 128; ++i) {
        r[i] = t[8 + i];
        t[8 + i] += awkward(i);
    }
    s.buffers = {tb, {std::vector<uint32_t>(r.size(), kMarker)}, awkward_buffer()};
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_float.texel_buffer.r32_sfloat", std::move(s),
                     all_of({words_are(0, bits(t)), words_are(1, bits(r))}));
}

// The value a float takes under DAZ (a denormal input reads as a zero of its sign) and FTZ (likewise a denormal
// result), the fragment stage's mode in lavapipe and tilevk.
float daz(float v) {
    return std::fpclassify(v) == FP_SUBNORMAL ? std::copysign(0.0f, v) : v;
}

// From a fragment shader (one writer per pixel of a 16x16 draw): atomicAdd of a value with a long mantissa, or of a
// denormal, to a word that may be denormal; the returns and the sums show FTZ and DAZ.
void add_fragment(CaseList& out) {
    ComputeSpec s = spec();
    s.images = {{VK_FORMAT_R8G8B8A8_UNORM, 16, 16, {}, true}};
    s.draw = {
        "#version 450\n"
        "void main() { vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);\n"
        "  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n",
        "#version 450\n#extension GL_EXT_shader_atomic_float : require\n"
        "layout(std430, binding=0) buffer W { float w[]; };\n"
        "layout(std430, binding=1) buffer R { float r[]; };\n" +
            awkward_decl(2) +
            "layout(location=0) out vec4 o;\n"
            "void main() { uint i = uint(gl_FragCoord.y) * 16u + uint(gl_FragCoord.x);\n"
            "  r[i] = atomicAdd(w[i], " +
            std::string(kAwkwardGlsl) +
            ");\n"
            "  o = vec4(0.5); }\n",
        3, -1};
    std::vector<float> w(256), r(256);
    for (uint32_t i = 0; i < 256; ++i) w[i] = i % 4u == 1u ? std::ldexp(float(i), -138) : float(i) * -0.37f;
    s.buffers = {{bits(w)}, {std::vector<uint32_t>(256, kMarker)}, awkward_buffer()};
    for (uint32_t i = 0; i < 256; ++i) {
        r[i] = w[i];  // the old word comes back as it was stored, denormal or not
        w[i] = daz(daz(w[i]) + daz(awkward(i)));
    }
    s.steps = {draw()};
    add_compute_case(out, "atomic_float.fragment.add_ftz_daz", std::move(s),
                     all_of({words_are(0, bits(w)), words_are(1, bits(r))}));
}

}  // namespace

void add_compute_atomic_float_cases(CaseList& out) {
    add_buffer_contended(out);
    add_buffer_one_writer(out);
    add_shared(out);
    add_image(out);
    add_texel_buffer(out);
    add_fragment(out);
}

}  // namespace tilevk::cts
