// random.compute.*: the seeded differential fuzzer for compute shaders. Each seed draws a workgroup shape (powers of
// two and not, 1..128 invocations), group counts, and a GLSL body of random statements over uint, int and float
// variables started from the built-ins and a random input buffer: integer arithmetic, shifts, bit operations,
// division by non-zero values, min/max/clamp, bitCount/findLSB/findMSB/bitfieldReverse, float + - * min max abs
// floor with conversions, branches and short loops, optionally shared memory (written, barrier, read from another
// invocation) and buffer atomics whose results do not depend on order (add, min, max, and, or, xor into 16 slots;
// returned values unused; each statement has slots of its own) and float atomicAdd (VK_EXT_shader_atomic_float) of
// quarters into 8 float slots, whose sums are exact in any order. Every invocation writes its variables out. Judged
// by the byte comparison only.
//
// Left out on purpose: float literals combined with computed values (NIR's inexact algebraic rules, see
// cases_random.cpp), NaN and infinity (every float result is clamped to +-1e6, so none arises), transcendental
// functions (their precision is the drivers' own), integer division by 0 and INT_MIN / -1 (undefined), % on negative
// ints (undefined in GLSL; glslang's OpSMod is a named difference: compute.basic.signed_division_and_modulo).
// TILEVK_CTS_RANDOM_COMPUTE_SEEDS=FIRST:COUNT explores other seeds; TILEVK_CTS_RANDOM_DUMP=1 prints the GLSL.
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "compute_case.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kInputWords = 256;

std::string uvar(Rng& r) {
    return "u" + std::to_string(r.below(4));
}
std::string fvar(Rng& r) {
    return "f" + std::to_string(r.below(2));
}

// One statement assigning a variable from others.
std::string statement(Rng& r) {
    const std::string d = uvar(r), a = uvar(r), b = uvar(r);
    switch (r.below(14)) {
        case 0:
            return d + " = " + a + " + " + b + ";";
        case 1:
            return d + " = " + a + " - " + b + " * " + uvar(r) + ";";
        case 2:
            return d + " = " + a + " ^ (" + b + " << (" + uvar(r) + " & 31u));";
        case 3:
            return d + " = (" + a + " >> (" + b + " & 31u)) | (" + uvar(r) + " & 0xF0F0F0F0u);";
        case 4:
            return d + " = " + a + " / (" + b + " | 1u) + " + a + " % (" + b + " | 3u);";
        case 5:
            return d + " = min(" + a + ", " + b + ") + max(" + uvar(r) + ", " + a + ");";
        case 6:
            return d + " = uint(bitCount(" + a + ") + findLSB(" + b + ") + findMSB(" + uvar(r) +
                   ")) + bitfieldReverse(" + a + ");";
        case 7:  // signed: division by a non-zero value that is never -1 with INT_MIN
            return "i0 = int(" + a + ") / ((int(" + b + ") & 0x7FF) + 1) - int(" + uvar(r) + " % 1000u) + " +
                   "clamp(i0, -5000, 5000);";
        case 8:
            return d + " = uint(i0 >> (" + a + " & 31u)) ^ " + b + ";";
        case 9:
            return fvar(r) + " = clamp(" + fvar(r) + " * " + fvar(r) + " + float(" + a + " & 0xFFFu), -1.0e6, 1.0e6);";
        case 10:
            return fvar(r) + " = clamp(min(" + fvar(r) + ", " + fvar(r) + ") - max(abs(" + fvar(r) +
                   "), floor(f1)), -1.0e6, 1.0e6);";
        case 11:
            return d + " = uint(clamp(" + fvar(r) + ", 0.0, 1.0e6)) + floatBitsToUint(f0);";
        case 12:
            return "if ((" + a + " & " + std::to_string(1u << r.below(4)) + "u) != 0u) { " + d + " += " + b +
                   " * 3u; } else { " + uvar(r) + " ^= 0x5A5Au; }";
        default:
            return "for (uint k = 0u; k < (" + a + " & 7u); ++k) { " + d + " = " + d + " * 1664525u + " + b + "; }";
    }
}

ComputeSpec random_compute_spec(uint32_t seed) {
    Rng r(seed * 7919u + 17u);
    const uint32_t xs[] = {1, 3, 7, 8, 13, 16, 24, 32, 33, 64, 100, 128};
    const uint32_t lx = r.pick(xs);
    uint32_t ly = 1 + r.below(3), lz = 1 + r.below(2);
    while (lx * ly * lz > 128) ly = lz = 1;
    const uint32_t gx = 1 + r.below(5), gy = 1 + r.below(3), gz = 1 + r.below(2);
    const uint32_t local = lx * ly * lz, total = local * gx * gy * gz;
    const bool shared = r.chance(0.5f), atomics = r.chance(0.5f);

    std::string g = glsl_header(lx, ly, lz);
    g += "layout(std430, binding=0) readonly buffer In { uint v[" + std::to_string(kInputWords) + "]; };\n";
    g += "layout(std430, binding=1) buffer Out { uvec4 o[]; };\n";
    g += "layout(std430, binding=2) buffer Slots { uint slot[16]; int islot[16]; };\n";
    if (shared) g += "shared uint sh[" + std::to_string(local) + "];\n";
    g += "void main() {\n"
         "  uvec3 total = gl_NumWorkGroups * gl_WorkGroupSize;\n"
         "  uint flat_id = gl_GlobalInvocationID.x + total.x * (gl_GlobalInvocationID.y + total.y * "
         "gl_GlobalInvocationID.z);\n"
         "  uint lid = gl_LocalInvocationIndex;\n"
         "  uint u0 = flat_id, u1 = v[(flat_id * 7u + lid) % " +
         std::to_string(kInputWords) +
         "u], u2 = gl_WorkGroupID.x ^ (gl_WorkGroupID.y << 8) ^ (gl_WorkGroupID.z << 16), u3 = v[lid % " +
         std::to_string(kInputWords) +
         "u];\n"
         "  int i0 = int(u1) >> 3;\n"
         "  float f0 = float(u1 & 0xFFFFu) * 0.25, f1 = float(u3 >> 20) - 2048.0;\n";
    const uint32_t n = 4 + r.below(10);
    for (uint32_t k = 0; k < n; ++k) g += "  " + statement(r) + "\n";
    if (shared) {
        const uint32_t step = 1 + r.below(local);
        g += "  sh[lid] = " + uvar(r) + ";\n  barrier();\n  " + uvar(r) + " ^= sh[(lid + " + std::to_string(step) +
             "u) % " + std::to_string(local) + "u];\n";
        g += "  " + statement(r) + "\n";
    }
    if (atomics) {
        // Each atomic statement has its own four slots: one operation per slot keeps the result order-independent.
        const char* uops[] = {"atomicAdd", "atomicMin", "atomicMax", "atomicAnd", "atomicOr", "atomicXor"};
        for (uint32_t k = 0, m = 1 + r.below(3); k < m; ++k) {
            const std::string at = "[(" + uvar(r) + " & 3u) + " + std::to_string(4 * k) + "u], ";
            if (r.chance(0.5f))
                g += std::string("  ") + r.pick(uops) + "(slot" + at + uvar(r) + ");\n";
            else
                g += std::string("  ") + r.pick(uops) + "(islot" + at + "int(" + uvar(r) + "));\n";
        }
    }
    // Float atomics from a generator of their own: every seed keeps the rest of the shader and the data it had.
    Rng fr(seed * 104729u + 3u);
    const bool float_atomics = fr.chance(0.3f);
    if (float_atomics) {
        g.insert(g.find('\n') + 1, "#extension GL_EXT_shader_atomic_float : require\n");
        g += "  float fq = float(" + uvar(fr) + " & 15u) * 0.25 - 1.5;\n";
        for (uint32_t k = 0, m = 1 + fr.below(3); k < m; ++k) g += "  atomicAdd(fslot[" + uvar(fr) + " & 7u], fq);\n";
        const size_t main_at = g.find("void main()");
        g.insert(main_at, "layout(std430, binding=3) buffer FSlots { float fslot[8]; };\n");
    }
    g += "  o[flat_id] = uvec4(u0 ^ u2, u1 + u3, floatBitsToUint(f0) ^ floatBitsToUint(f1), uint(i0));\n}\n";

    ComputeSpec s;
    s.shaders = {g};
    std::vector<uint32_t> in(kInputWords), slots(32);
    for (uint32_t& w : in) w = r.next();
    for (uint32_t k = 0; k < 16; ++k) {
        slots[k] = k & 4 ? 0xFFFFFFFFu : r.next() >> r.below(32);
        slots[16 + k] = int32_t(r.next()) >> r.below(32);
    }
    s.buffers = {{in, false, false}, {std::vector<uint32_t>(size_t(total) * 4, kMarker)}, {slots}};
    if (float_atomics) {
        std::vector<uint32_t> fslots(8);
        for (uint32_t k = 0; k < 8; ++k) fslots[k] = fbits(float(fr.below(64)) * 0.5f - 16.0f);
        s.buffers.push_back({fslots});
        s.atomic_float = true;
    }
    s.steps = {dispatch(0, gx, gy, gz)};
    if (std::getenv("TILEVK_CTS_RANDOM_DUMP"))
        std::fprintf(stderr, "random.compute.seed_%u: local %ux%ux%u, groups %ux%ux%u\n%s", seed, lx, ly, lz, gx, gy,
                     gz, g.c_str());
    return s;
}

}  // namespace

void add_random_compute_cases(CaseList& out) {
    // The default list is fixed (seeds 1..40); TILEVK_CTS_RANDOM_COMPUTE_SEEDS=FIRST:COUNT explores others.
    uint32_t first = 1, count = 40;
    if (const char* env = std::getenv("TILEVK_CTS_RANDOM_COMPUTE_SEEDS")) {
        if (std::sscanf(env, "%u:%u", &first, &count) != 2)
            throw std::runtime_error("TILEVK_CTS_RANDOM_COMPUTE_SEEDS: expected FIRST:COUNT, got " + std::string(env));
    }
    for (uint32_t seed = first; seed < first + count; ++seed) out.push_back(random_compute_seed_case(seed));
}

Case random_compute_seed_case(uint32_t seed) {
    Case c;
    c.name = "random.compute.seed_" + std::to_string(seed);
    c.scene = [seed] { return compute_scene(random_compute_spec(seed)); };
    return c;
}

}  // namespace tilevk::cts
