// compute.atomic_float2.* (VK_EXT_shader_atomic_float2's 32-bit members): atomicMin and atomicMax on 32-bit floats
// in storage buffers, shared memory and R32_SFLOAT storage images. The spec leaves the result of ±0 ties and NaN
// operands open; lavapipe's (LLVM 15's minnum / maxnum on x86, docs/lavapipe-rules.md "Float atomics") is the rule
// the answers follow: a NaN in memory is replaced by the operand, a NaN operand leaves memory as it is, and of two
// zeros (or of a zero and a value equal to it) memory keeps its own. Tables of (memory, operand) pairs, one writer
// per word, show every such case with its returned value; contended cases use operands without ties, whose result
// no order of the invocations changes. The answers are computed here.
#include <algorithm>
#include <bit>
#include <iterator>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kGroups = 4, kLocal = 64, kN = kGroups * kLocal;

std::string header() {
    const std::string h = glsl_header(kLocal);
    const size_t eol = h.find('\n') + 1;  // extensions come before any declaration
    return h.substr(0, eol) + "#extension GL_EXT_shader_atomic_float2 : require\n" + h.substr(eol);
}

ComputeSpec spec() {
    ComputeSpec s;
    s.atomic_float = true;
    s.atomic_float_min_max = true;
    return s;
}

// The special values of the pair tables: zeros, NaNs (quiet, signalling, negative, with a payload), infinities,
// denormals, ones.
constexpr uint32_t kSpecial[] = {0x00000000u, 0x80000000u, 0x7FC00000u, 0x7F800001u, 0xFFC00123u, 0x7F800000u,
                                 0xFF800000u, 0x00000001u, 0x80000010u, 0x3F800000u, 0xBF800000u, 0x00400000u,
                                 0x7FFFFFFFu, 0x3F800001u, 0x80400000u, 0x42F60000u};
constexpr uint32_t kNumSpecial = std::size(kSpecial);  // 16: 256 pairs, one per invocation

bool is_nan(uint32_t b) {
    return (b & 0x7FFFFFFFu) > 0x7F800000u;
}
float as_float(uint32_t b) {
    return std::bit_cast<float>(b);
}

// The word left by atomicMin / atomicMax(memory = old, operand = v), without FTZ / DAZ (compute).
uint32_t min_max(bool is_min, uint32_t old, uint32_t v) {
    if (is_nan(old)) return v;
    if (is_nan(v)) return old;
    const float o = as_float(old), x = as_float(v);
    return (is_min ? x < o : x > o) ? v : old;
}

// Invocation i's pair: memory kSpecial[i / 16], operand kSpecial[i % 16].
uint32_t pair_old(uint32_t i) {
    return kSpecial[i / kNumSpecial % kNumSpecial];
}
uint32_t pair_v(uint32_t i) {
    return kSpecial[i % kNumSpecial];
}
std::string special_decl(uint32_t binding) {  // the operands, read from a buffer so that only the atomic is tested
    return "layout(std430, binding=" + std::to_string(binding) + ") readonly buffer V { float v[]; };\n";
}
ComputeBuffer special_buffer() {
    std::vector<uint32_t> v(kN);
    for (uint32_t i = 0; i < kN; ++i) v[i] = pair_v(i);
    return {v, false, false};
}

// One writer per word: word i holds pair_old(i) and takes atomicMin (buffer 0) or atomicMax (buffer 1) of
// pair_v(i); the returns go to buffer 2 (two per invocation).
void add_buffer_pairs(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {header() +
                 "layout(std430, binding=0) buffer A { float a[]; };\n"
                 "layout(std430, binding=1) buffer B { float b[]; };\n"
                 "layout(std430, binding=2) buffer R { float r[]; };\n" +
                 special_decl(3) +
                 "void main() { uint i = gl_GlobalInvocationID.x;\n"
                 "  r[2u * i] = atomicMin(a[i], v[i]);\n  r[2u * i + 1u] = atomicMax(b[i], v[i]); }\n"};
    std::vector<uint32_t> a(kN), b(kN), r(2 * kN);
    for (uint32_t i = 0; i < kN; ++i) a[i] = b[i] = pair_old(i);
    s.buffers = {{a}, {b}, {std::vector<uint32_t>(2 * kN, kMarker)}, special_buffer()};
    for (uint32_t i = 0; i < kN; ++i) {
        r[2 * i] = a[i], r[2 * i + 1] = b[i];
        a[i] = min_max(true, a[i], pair_v(i));
        b[i] = min_max(false, b[i], pair_v(i));
    }
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_float2.buffer.min_max_pairs", std::move(s),
                     all_of({words_are(0, a), words_are(1, b), words_are(2, r)}));
}

// The same pairs in shared memory (loaded from buffer 0, written back to buffers 0 and 1 after both atomics).
void add_shared_pairs(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {header() +
                 "shared float sa[64];\nshared float sb[64];\n"
                 "layout(std430, binding=0) buffer A { float a[]; };\n"
                 "layout(std430, binding=1) buffer B { float b[]; };\n"
                 "layout(std430, binding=2) buffer R { float r[]; };\n" +
                 special_decl(3) +
                 "void main() { uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;\n"
                 "  sa[l] = a[i]; sb[l] = a[i];\n"
                 "  r[2u * i] = atomicMin(sa[l], v[i]);\n  r[2u * i + 1u] = atomicMax(sb[l], v[i]);\n"
                 "  a[i] = sa[l]; b[i] = sb[l]; }\n"};
    std::vector<uint32_t> a(kN), b(kN), r(2 * kN);
    for (uint32_t i = 0; i < kN; ++i) a[i] = pair_old(i);
    s.buffers = {{a}, {std::vector<uint32_t>(kN, kMarker)}, {std::vector<uint32_t>(2 * kN, kMarker)}, special_buffer()};
    for (uint32_t i = 0; i < kN; ++i) {
        const uint32_t old = a[i];
        r[2 * i] = old, r[2 * i + 1] = old;
        a[i] = min_max(true, old, pair_v(i));
        b[i] = min_max(false, old, pair_v(i));
    }
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_float2.shared.min_max_pairs", std::move(s),
                     all_of({words_are(0, a), words_are(1, b), words_are(2, r)}));
}

// An R32_SFLOAT storage image (16x16, texel i = pair_old(i)) takes imageAtomicMin of pair_v(i) for the even
// invocations and imageAtomicMax for the odd ones; the returns go to buffer 0, the image is copied to buffer 1
// (the image's binding follows the buffers').
void add_image_pairs(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {header() +
                 "layout(binding=3, r32f) uniform image2D img;\n"
                 "layout(std430, binding=0) buffer R { float r[]; };\n" +
                 special_decl(2) +
                 "void main() { uint i = gl_GlobalInvocationID.x; ivec2 p = ivec2(i % 16u, i / 16u);\n"
                 "  r[i] = (i & 1u) == 0u ? imageAtomicMin(img, p, v[i]) : imageAtomicMax(img, p, v[i]); }\n"};
    std::vector<uint32_t> img(kN), r(kN);
    std::vector<uint8_t> init(kN * 4);
    for (uint32_t i = 0; i < kN; ++i) {
        img[i] = pair_old(i);
        std::memcpy(&init[i * 4], &img[i], 4);
    }
    for (uint32_t i = 0; i < kN; ++i) {
        r[i] = img[i];
        img[i] = min_max((i & 1u) == 0u, img[i], pair_v(i));
    }
    s.buffers = {{std::vector<uint32_t>(kN, kMarker)}, {std::vector<uint32_t>(kN, kMarker)}, special_buffer()};
    s.images = {{VK_FORMAT_R32_SFLOAT, 16, 16, init}};
    s.steps = {dispatch(0, kGroups), copy_image_to_buffer(0, 1)};
    add_compute_case(out, "atomic_float2.image.min_max_pairs", std::move(s),
                     all_of({words_are(0, r), words_are(1, img)}));
}

// Contended: every invocation takes the min into slot i % 8 and the max into slot 8 + i % 8 of distinct finite
// values, NaN operands (no effect) and one -0.0 per slot; the slots start at NaN (replaced by the first operand) or
// at finite values. The result is the smallest / largest operand whatever the order.
void add_contended(CaseList& out, bool shared) {
    ComputeSpec s = spec();
    const std::string op =
        "(i % 17u == 3u ? uintBitsToFloat(0x7FC00000u) : i < 8u ? -0.0 : "
        "float(int((i * 2654435761u) >> 20) - 2048) * 0.375 + float(i) * 0.0009765625)";
    s.shaders = {header() + (shared ? "shared float sh[16];\n" : "") +
                 "layout(std430, binding=0) buffer C { float c[]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex; float x = " +
                 op + ";\n" +
                 (shared ? "  if (l < 16u) sh[l] = c[l];\n  barrier();\n"
                           "  atomicMin(sh[i % 8u], x); atomicMax(sh[8u + i % 8u], x);\n  barrier();\n"
                           "  if (l < 16u) c[16u + gl_WorkGroupID.x * 16u + l] = sh[l];\n"
                         : "  atomicMin(c[i % 8u], x); atomicMax(c[8u + i % 8u], x);\n") +
                 "}\n"};
    auto x_of = [](uint32_t i) {
        if (i % 17u == 3u) return 0x7FC00000u;
        if (i < 8u) return 0x80000000u;
        return fbits(float(int32_t((i * 2654435761u) >> 20) - 2048) * 0.375f + float(i) * 0.0009765625f);
    };
    std::vector<uint32_t> init(16);
    for (uint32_t k = 0; k < 16; ++k) init[k] = k % 3u == 0u ? 0x7FC00000u : fbits(float(k) * 100.0f - 700.0f);
    std::vector<uint32_t> c = init;
    if (shared) c.resize(16 + 16 * kGroups, kMarker);
    for (uint32_t g = 0; g < kGroups; ++g) {
        std::vector<uint32_t> sh = init;
        for (uint32_t l = 0; l < kLocal; ++l) {
            const uint32_t i = g * kLocal + l;
            std::vector<uint32_t>& w = shared ? sh : c;
            w[i % 8] = min_max(true, w[i % 8], x_of(i));
            w[8 + i % 8] = min_max(false, w[8 + i % 8], x_of(i));
        }
        if (shared) std::copy(sh.begin(), sh.end(), c.begin() + 16 + g * 16);
    }
    std::vector<uint32_t> start = init;
    if (shared) start.resize(16 + 16 * kGroups, kMarker);
    s.buffers = {{start}};
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, shared ? "atomic_float2.shared.min_max_contended" : "atomic_float2.buffer.min_max_contended",
                     std::move(s), words_are(0, c));
}

}  // namespace

void add_compute_atomic_float2_cases(CaseList& out) {
    add_buffer_pairs(out);
    add_shared_pairs(out);
    add_image_pairs(out);
    add_contended(out, false);
    add_contended(out, true);
}

}  // namespace tilevk::cts
