// compute.atomic.*: every 32-bit atomic GLSL reaches (OpAtomicIAdd, SMin/UMin, SMax/UMax, And, Or, Xor, Exchange,
// CompareExchange) on storage buffers and on shared memory, from many workgroups at once. Only results that do not
// depend on the order of the invocations are read back (final values of commutative operations, a counter whose
// returned indices must each be taken once, histograms, compare-exchange loops), so they are also the same for
// every thread count; the answers are computed here.
#include <functional>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kGroups = 8, kLocal = 64, kSlots = 16;

struct AtomicOp {
    const char* name;
    const char* glsl;  // the GLSL function
    bool is_signed;
    std::function<uint32_t(uint32_t, uint32_t)> apply;  // on the stored bits
};

int32_t s32(uint32_t v) {
    return int32_t(v);
}

const AtomicOp kOps[] = {
    {"add", "atomicAdd", false, [](uint32_t a, uint32_t b) { return a + b; }},
    {"add_signed", "atomicAdd", true, [](uint32_t a, uint32_t b) { return a + b; }},
    {"umin", "atomicMin", false, [](uint32_t a, uint32_t b) { return std::min(a, b); }},
    {"umax", "atomicMax", false, [](uint32_t a, uint32_t b) { return std::max(a, b); }},
    {"smin", "atomicMin", true, [](uint32_t a, uint32_t b) { return uint32_t(std::min(s32(a), s32(b))); }},
    {"smax", "atomicMax", true, [](uint32_t a, uint32_t b) { return uint32_t(std::max(s32(a), s32(b))); }},
    {"and", "atomicAnd", false, [](uint32_t a, uint32_t b) { return a & b; }},
    {"or", "atomicOr", false, [](uint32_t a, uint32_t b) { return a | b; }},
    {"xor", "atomicXor", false, [](uint32_t a, uint32_t b) { return a ^ b; }},
};

// The operand of invocation i (same expression in GLSL): spread over the 32 bits, negative half the time as int.
uint32_t operand(uint32_t i, bool is_signed, bool is_and) {
    uint32_t v = (i * 2654435761u) >> 3;
    if (is_and) v = ~(1u << (i % 32));  // and: each invocation clears one bit
    return is_signed ? v - (1u << 28) : v;
}
std::string operand_glsl(bool is_signed, bool is_and) {
    std::string v = is_and ? "~(1u << (i % 32u))" : "((i * 2654435761u) >> 3)";
    return is_signed ? "int(" + v + " - (1u << 28))" : v;
}

std::vector<uint32_t> initial_slots(bool is_and) {
    std::vector<uint32_t> v(kSlots);
    for (uint32_t k = 0; k < kSlots; ++k) v[k] = is_and ? 0xFFFFFFFFu : k * 0x01010101u + 0x80000000u * (k & 1);
    return v;
}

void add_buffer_op(CaseList& out, const AtomicOp& op) {
    const bool is_and = std::string(op.name) == "and";
    const std::string t = op.is_signed ? "int" : "uint";
    ComputeSpec s;
    s.shaders = {glsl_header(kLocal) + "layout(std430, binding=0) buffer C { " + t + " c[" + std::to_string(kSlots) +
                 "]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x; " +
                 op.glsl + "(c[i % " + std::to_string(kSlots) + "u], " + operand_glsl(op.is_signed, is_and) + "); }\n"};
    std::vector<uint32_t> want = initial_slots(is_and);
    s.buffers = {{want}};
    for (uint32_t i = 0; i < kGroups * kLocal; ++i)
        want[i % kSlots] = op.apply(want[i % kSlots], operand(i, op.is_signed, is_and));
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, std::string("atomic.buffer.") + op.name, std::move(s), words_are(0, want));
}

// The same in shared memory: each workgroup starts its slots from the initial values, applies its invocations'
// operands and writes the slots out.
void add_shared_op(CaseList& out, const AtomicOp& op) {
    const bool is_and = std::string(op.name) == "and";
    const std::string t = op.is_signed ? "int" : "uint", n = std::to_string(kSlots);
    ComputeSpec s;
    s.shaders = {glsl_header(kLocal) + "shared " + t + " sh[" + n +
                 "];\n"
                 "layout(std430, binding=0) readonly buffer I { " +
                 t + " init[" + n +
                 "]; };\n"
                 "layout(std430, binding=1) buffer O { " +
                 t +
                 " o[]; };\n"
                 "void main() {\n"
                 "  uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;\n"
                 "  if (l < " +
                 n +
                 "u) sh[l] = init[l];\n"
                 "  barrier();\n  " +
                 op.glsl + "(sh[i % " + n + "u], " + operand_glsl(op.is_signed, is_and) +
                 ");\n"
                 "  barrier();\n"
                 "  if (l < " +
                 n + "u) o[gl_WorkGroupID.x * " + n + "u + l] = sh[l];\n}\n"};
    const std::vector<uint32_t> init = initial_slots(is_and);
    std::vector<uint32_t> want(kGroups * kSlots);
    for (uint32_t g = 0; g < kGroups; ++g) {
        std::vector<uint32_t> sh = init;
        for (uint32_t l = 0; l < kLocal; ++l) {
            const uint32_t i = g * kLocal + l;
            sh[i % kSlots] = op.apply(sh[i % kSlots], operand(i, op.is_signed, is_and));
        }
        std::copy(sh.begin(), sh.end(), want.begin() + g * kSlots);
    }
    s.buffers = {{init, false, false}, {std::vector<uint32_t>(want.size(), kMarker)}};
    s.steps = {dispatch(0, kGroups)};
    add_compute_case(out, std::string("atomic.shared.") + op.name, std::move(s), words_are(1, want));
}

// Exchange on one slot per invocation: the old value comes back, the new one stays.
void add_exchange(CaseList& out, bool shared) {
    ComputeSpec s;
    std::string body = shared ? "shared uint sh[64];\n"
                                "layout(std430, binding=0) buffer C { uint c[]; };\n"
                                "layout(std430, binding=1) buffer R { uint r[]; };\n"
                                "void main() { uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;\n"
                                "  sh[l] = c[i]; barrier();\n"
                                "  r[i] = atomicExchange(sh[63u - l], i * 3u);\n"
                                "  barrier(); c[i] = sh[l]; }\n"
                              : "layout(std430, binding=0) buffer C { uint c[]; };\n"
                                "layout(std430, binding=1) buffer R { uint r[]; };\n"
                                "void main() { uint i = gl_GlobalInvocationID.x;\n"
                                "  r[i] = atomicExchange(c[i ^ 5u], i * 3u); }\n";
    s.shaders = {glsl_header(64) + body};
    const uint32_t n = 64 * 4;
    std::vector<uint32_t> c(n), want_c(n), want_r(n);
    for (uint32_t i = 0; i < n; ++i) c[i] = i * 1000 + 7;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t slot = shared ? (i / 64) * 64 + 63 - i % 64 : i ^ 5;
        want_r[i] = c[slot];
        want_c[slot] = i * 3;
    }
    s.buffers = {{c}, {std::vector<uint32_t>(n, kMarker)}};
    s.steps = {dispatch(0, 4)};
    add_compute_case(out, shared ? "atomic.shared.exchange" : "atomic.buffer.exchange", std::move(s),
                     all_of({words_are(0, want_c), words_are(1, want_r)}));
}

// A compare-exchange loop that adds (the loop retries while another invocation got in first); the sum is exact.
void add_compare_exchange(CaseList& out, bool shared) {
    ComputeSpec s;
    const std::string loop =
        "  uint old = SLOT;\n"
        "  for (;;) { uint prev = atomicCompSwap(SLOT, old, old + v); if (prev == old) break; old = prev; }\n";
    auto with = [&](const std::string& slot) {
        std::string l = loop;
        for (size_t p; (p = l.find("SLOT")) != std::string::npos;) l.replace(p, 4, slot);
        return l;
    };
    s.shaders = {glsl_header(64) + (shared ? "shared uint sh[4];\n" : "") +
                 "layout(std430, binding=0) buffer C { uint c[4]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex, v = i * 7u + 1u;\n" +
                 (shared ? "  if (l < 4u) sh[l] = 0u;\n  barrier();\n" + with("sh[i % 4u]") +
                               "  barrier();\n  if (l < 4u) atomicAdd(c[l], sh[l]);\n"
                         : with("c[i % 4u]")) +
                 "}\n"};
    std::vector<uint32_t> want = {5, 6, 7, 8};
    s.buffers = {{want}};
    for (uint32_t i = 0; i < 64 * 6; ++i) want[i % 4] += i * 7 + 1;
    s.steps = {dispatch(0, 6)};
    add_compute_case(out,
                     shared ? "atomic.shared.compare_exchange_add_loop" : "atomic.buffer.compare_exchange_add_loop",
                     std::move(s), words_are(0, want));
}

// A counter hands out slots: every slot must be taken exactly once whatever the order.
void add_counter(CaseList& out) {
    ComputeSpec s;
    s.shaders = {glsl_header(48) +
                 "layout(std430, binding=0) buffer C { uint counter; uint taken[]; };\n"
                 "void main() { uint k = atomicAdd(counter, 1u); atomicAdd(taken[k], 1u); }\n"};
    const uint32_t n = 48 * 11;
    s.buffers = {{std::vector<uint32_t>(n + 1, 0)}};
    s.steps = {dispatch(0, 11)};
    std::vector<uint32_t> want(n + 1, 1);
    want[0] = n;
    add_compute_case(out, "atomic.buffer.counter_slots", std::move(s), words_are(0, want));
}

// 256-bin histograms of LCG data: straight into the buffer, and per workgroup in shared memory first.
void add_histogram(CaseList& out, bool shared) {
    constexpr uint32_t kData = 16384;
    ComputeSpec s;
    const std::string body =
        shared ? "shared uint bins[256];\n"
                 "layout(std430, binding=0) readonly buffer D { uint d[]; };\n"
                 "layout(std430, binding=1) buffer H { uint h[256]; };\n"
                 "void main() { uint l = gl_LocalInvocationIndex;\n"
                 "  bins[l] = 0u; barrier();\n"
                 "  for (uint k = 0u; k < 4u; ++k) atomicAdd(bins[d[gl_GlobalInvocationID.x * 4u + k] & 255u], 1u);\n"
                 "  barrier(); atomicAdd(h[l], bins[l]); }\n"
               : "layout(std430, binding=0) readonly buffer D { uint d[]; };\n"
                 "layout(std430, binding=1) buffer H { uint h[256]; };\n"
                 "void main() {\n"
                 "  for (uint k = 0u; k < 4u; ++k) atomicAdd(h[d[gl_GlobalInvocationID.x * 4u + k] & 255u], 1u);\n"
                 "}\n";
    s.shaders = {glsl_header(256) + body};
    std::vector<uint32_t> d(kData), want(256, 0);
    Lcg g{99};
    for (uint32_t& x : d) {
        x = uint32_t(g.next() * 16777216.0f);
        x = x ^ (x >> 9);  // skewed bins: some much fuller than others
        ++want[x & 255];
    }
    s.buffers = {{d, false, false}, {std::vector<uint32_t>(256, 0)}};
    s.steps = {dispatch(0, kData / 4 / 256)};
    add_compute_case(out, shared ? "atomic.shared.histogram_256" : "atomic.buffer.histogram_256", std::move(s),
                     words_are(1, want));
}

}  // namespace

void add_compute_atomic_cases(CaseList& out) {
    for (const AtomicOp& op : kOps) add_buffer_op(out, op);
    for (const AtomicOp& op : kOps) add_shared_op(out, op);
    add_exchange(out, false);
    add_exchange(out, true);
    add_compare_exchange(out, false);
    add_compare_exchange(out, true);
    add_counter(out);
    add_histogram(out, false);
    add_histogram(out, true);
}

}  // namespace tilevk::cts
