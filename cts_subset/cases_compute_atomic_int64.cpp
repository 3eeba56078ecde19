// compute.atomic_int64.* (VK_KHR_shader_atomic_int64): every 64-bit integer atomic GLSL reaches on storage buffers
// and shared memory, from several workgroups at once. The operands spread over all 64 bits so that a kernel working
// on one word, or carrying wrongly between the words, gives another answer. As in compute.atomic.*, only results the
// order of the invocations cannot change are read back (final values of commutative operations, one writer per word
// where a returned value is kept, a compare-exchange loop); the answers are computed here.
#include <algorithm>
#include <functional>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kGroups = 4, kLocal = 64, kN = kGroups * kLocal, kSlots = 8;

std::string header() {
    const std::string h = glsl_header(kLocal);
    const size_t eol = h.find('\n') + 1;  // extensions come before any declaration
    return h.substr(0, eol) + "#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require\n" +
           "#extension GL_EXT_shader_atomic_int64 : require\n" + h.substr(eol);
}

ComputeSpec spec() {
    ComputeSpec s;
    s.atomic_int64 = true;
    return s;
}

struct Op64 {
    const char* name;
    const char* glsl;
    bool is_signed;
    std::function<uint64_t(uint64_t, uint64_t)> apply;  // on the stored bits
};

int64_t s64(uint64_t v) {
    return int64_t(v);
}

const Op64 kOps[] = {
    {"add", "atomicAdd", false, [](uint64_t a, uint64_t b) { return a + b; }},
    {"umin", "atomicMin", false, [](uint64_t a, uint64_t b) { return std::min(a, b); }},
    {"umax", "atomicMax", false, [](uint64_t a, uint64_t b) { return std::max(a, b); }},
    {"smin", "atomicMin", true, [](uint64_t a, uint64_t b) { return uint64_t(std::min(s64(a), s64(b))); }},
    {"smax", "atomicMax", true, [](uint64_t a, uint64_t b) { return uint64_t(std::max(s64(a), s64(b))); }},
    {"and", "atomicAnd", false, [](uint64_t a, uint64_t b) { return a & b; }},
    {"or", "atomicOr", false, [](uint64_t a, uint64_t b) { return a | b; }},
    {"xor", "atomicXor", false, [](uint64_t a, uint64_t b) { return a ^ b; }},
};

// The operand of invocation i (same expression in GLSL): a 64-bit hash whose high word differs between invocations
// while many low words are close (so that comparisons must look at both words); and: one bit cleared.
uint64_t operand(uint32_t i, bool is_and) {
    if (is_and) return ~(uint64_t(1) << (i % 64u));
    return uint64_t(i) * 0x9E3779B97F4A7C15ull ^ (uint64_t(i % 7u) << 61);
}
std::string operand_glsl(bool is_signed, bool is_and) {
    const std::string v =
        is_and ? "~(1ul << (i % 64u))" : "(uint64_t(i) * 0x9E3779B97F4A7C15ul ^ (uint64_t(i % 7u) << 61))";
    return is_signed ? "int64_t(" + v + ")" : v;
}

std::vector<uint64_t> initial_slots(bool is_and) {
    std::vector<uint64_t> v(kSlots);
    for (uint32_t k = 0; k < kSlots; ++k)
        v[k] = is_and ? ~uint64_t(0) : uint64_t(k) * 0x0101010101010101ull + (uint64_t(k & 1) << 63) + 0xFFFFFFF0u;
    return v;
}

std::vector<uint32_t> words(const std::vector<uint64_t>& v) {
    std::vector<uint32_t> out;
    for (uint64_t x : v) out.insert(out.end(), {uint32_t(x), uint32_t(x >> 32)});
    return out;
}

void add_buffer_op(CaseList& out, const Op64& op) {
    const bool is_and = std::string(op.name) == "and";
    const std::string t = op.is_signed ? "int64_t" : "uint64_t";
    ComputeSpec s = spec();
    s.shaders = {header() + "layout(std430, binding=0) buffer C { " + t + " c[" + std::to_string(kSlots) +
                 "]; };\nvoid main() { uint i = gl_GlobalInvocationID.x; " + op.glsl + "(c[i % " +
                 std::to_string(kSlots) + "u], " + operand_glsl(op.is_signed, is_and) + "); }\n"};
    std::vector<uint64_t> want = initial_slots(is_and);
    s.buffers = {{words(want)}};
    for (uint32_t i = 0; i < kN; ++i) want[i % kSlots] = op.apply(want[i % kSlots], operand(i, is_and));
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, std::string("atomic_int64.buffer.") + op.name, std::move(s), words_are(0, words(want)));
}

// The same in shared memory: each workgroup starts its slots from the initial values, applies its invocations'
// operands and writes the slots out.
void add_shared_op(CaseList& out, const Op64& op) {
    const bool is_and = std::string(op.name) == "and";
    const std::string t = op.is_signed ? "int64_t" : "uint64_t", n = std::to_string(kSlots);
    ComputeSpec s = spec();
    s.shaders = {
        header() + "shared " + t + " sh[" + n + "];\nlayout(std430, binding=0) readonly buffer I { " + t + " init[" +
        n + "]; };\nlayout(std430, binding=1) buffer O { " + t +
        " o[]; };\nvoid main() {\n  uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;\n  if (l < " + n +
        "u) sh[l] = init[l];\n  barrier();\n  " + op.glsl + "(sh[i % " + n + "u], " +
        operand_glsl(op.is_signed, is_and) + ");\n  barrier();\n  if (l < " + n + "u) o[gl_WorkGroupID.x * " + n +
        "u + l] = sh[l];\n}\n"};
    const std::vector<uint64_t> init = initial_slots(is_and);
    std::vector<uint64_t> want(kGroups * kSlots);
    for (uint32_t g = 0; g < kGroups; ++g) {
        std::vector<uint64_t> sh = init;
        for (uint32_t l = 0; l < kLocal; ++l) {
            const uint32_t i = g * kLocal + l;
            sh[i % kSlots] = op.apply(sh[i % kSlots], operand(i, is_and));
        }
        std::copy(sh.begin(), sh.end(), want.begin() + g * kSlots);
    }
    s.buffers = {{words(init), false, false}, {std::vector<uint32_t>(2 * want.size(), kMarker)}};
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, std::string("atomic_int64.shared.") + op.name, std::move(s), words_are(1, words(want)));
}

// One writer per word: exchange, compare-exchange (matching and not), increment / decrement and subtraction (which
// borrow across the words) return the old value; buffer 0 the words, buffer 1 the returns (4 per invocation). In
// shared memory the words are loaded from buffer 0 first and written back at the end.
void add_one_writer(CaseList& out, bool shared) {
    ComputeSpec s = spec();
    const std::string w = shared ? "sh" : "c";
    s.shaders = {header() + (shared ? "shared uint64_t sh[" + std::to_string(2 * kLocal) + "];\n" : std::string()) +
                 "layout(std430, binding=0) buffer C { uint64_t c[]; };\n"
                 "layout(std430, binding=1) buffer R { uint64_t r[]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x, l = " +
                 (shared ? "gl_LocalInvocationIndex" : "i") + ";\n" +
                 (shared ? "  sh[2u * l] = c[2u * i]; sh[2u * l + 1u] = c[2u * i + 1u];\n" : "") +
                 "  uint64_t k = uint64_t(i) << 32 | 0xFFFFFFFFul;\n"
                 "  r[4u * i] = atomicExchange(" +
                 w +
                 "[2u * l], k ^ 0x8000000000000001ul);\n"
                 "  r[4u * i + 1u] = atomicCompSwap(" +
                 w +
                 "[2u * l], (i & 1u) == 0u ? k ^ 0x8000000000000001ul : k, k + 1ul);\n"
                 "  r[4u * i + 2u] = atomicAdd(" +
                 w +
                 "[2u * l + 1u], 1ul);\n"
                 "  r[4u * i + 3u] = atomicAdd(" +
                 w + "[2u * l + 1u], -(uint64_t(i) + 3ul));\n" +
                 (shared ? "  c[2u * i] = sh[2u * l]; c[2u * i + 1u] = sh[2u * l + 1u];\n" : "") + "}\n"};
    std::vector<uint64_t> c(2 * kN), r(4 * kN);
    for (uint32_t i = 0; i < kN; ++i) {
        c[2 * i] = uint64_t(i) * 0x100000001ull;
        c[2 * i + 1] = i % 3u == 0u ? 0xFFFFFFFFull : uint64_t(i) << 33;  // the increment carries
    }
    s.buffers = {{words(c)}, {std::vector<uint32_t>(8 * kN, kMarker)}};
    for (uint32_t i = 0; i < kN; ++i) {
        const uint64_t k = uint64_t(i) << 32 | 0xFFFFFFFFull, x = k ^ 0x8000000000000001ull;
        r[4 * i] = c[2 * i];
        c[2 * i] = x;
        r[4 * i + 1] = c[2 * i];
        if ((i & 1u) == 0u) c[2 * i] = k + 1;
        r[4 * i + 2] = c[2 * i + 1];
        c[2 * i + 1] += 1;
        r[4 * i + 3] = c[2 * i + 1];
        c[2 * i + 1] -= uint64_t(i) + 3;
    }
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, shared ? "atomic_int64.shared.one_writer" : "atomic_int64.buffer.one_writer", std::move(s),
                     all_of({words_are(0, words(c)), words_are(1, words(r))}));
}

// A compare-exchange loop that adds 64-bit values whose sum overflows the low word many times.
void add_compare_exchange_loop(CaseList& out) {
    ComputeSpec s = spec();
    s.shaders = {header() +
                 "layout(std430, binding=0) buffer C { uint64_t c[4]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x; uint64_t v = uint64_t(i) * 0xC0000001ul;\n"
                 "  uint64_t old = c[i % 4u];\n"
                 "  for (;;) { uint64_t prev = atomicCompSwap(c[i % 4u], old, old + v); if (prev == old) break;"
                 " old = prev; }\n}\n"};
    std::vector<uint64_t> want = {5, 0xFFFFFFFFull, 1ull << 40, ~uint64_t(0) - 100};
    s.buffers = {{words(want)}};
    for (uint32_t i = 0; i < kN; ++i) want[i % 4] += uint64_t(i) * 0xC0000001ull;
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, "atomic_int64.buffer.compare_exchange_add_loop", std::move(s), words_are(0, words(want)));
}

}  // namespace

void add_compute_atomic_int64_cases(CaseList& out) {
    for (const Op64& op : kOps) add_buffer_op(out, op);
    for (const Op64& op : kOps) add_shared_op(out, op);
    add_one_writer(out, false);
    add_one_writer(out, true);
    add_compare_exchange_loop(out);
}

}  // namespace tilevk::cts
