// compute.basic.* (with GLSL packUnorm/packSnorm, unpackHalf2x16), compute.shared.* and compute.ssbo.*: dispatches
// through compute.hpp's harness, every result buffer compared byte for byte with the reference, and each case's answer
// computed here from the definitions (the built-ins, sums and prefix sums, std430 offsets) as an independent check.
#include <cmath>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

// --- compute.basic: every built-in at workgroup sizes with and without powers of two ---

// Each invocation writes 16 words at its flat global index: GlobalInvocationID, LocalInvocationID, WorkGroupID,
// NumWorkGroups (xyz, padded to 4), LocalInvocationIndex in the fourth word of the first.
const char* kBuiltinsBody =
    "layout(std430, binding=0) buffer Out { uvec4 v[]; } o;\n"
    "void main() {\n"
    "  uvec3 total = gl_NumWorkGroups * gl_WorkGroupSize;\n"
    "  uint flat_id = gl_GlobalInvocationID.x + total.x * (gl_GlobalInvocationID.y + total.y * "
    "gl_GlobalInvocationID.z);\n"
    "  o.v[flat_id * 4 + 0] = uvec4(gl_GlobalInvocationID, gl_LocalInvocationIndex);\n"
    "  o.v[flat_id * 4 + 1] = uvec4(gl_LocalInvocationID, 0);\n"
    "  o.v[flat_id * 4 + 2] = uvec4(gl_WorkGroupID, 0);\n"
    "  o.v[flat_id * 4 + 3] = uvec4(gl_NumWorkGroups, 0);\n"
    "}\n";

std::vector<uint32_t> builtins_answer(const uint32_t l[3], const uint32_t g[3]) {
    const uint32_t tx = l[0] * g[0], ty = l[1] * g[1], tz = l[2] * g[2];
    std::vector<uint32_t> w(size_t(tx) * ty * tz * 16);
    for (uint32_t z = 0; z < tz; ++z)
        for (uint32_t y = 0; y < ty; ++y)
            for (uint32_t x = 0; x < tx; ++x) {
                uint32_t* r = &w[(x + tx * (y + ty * z)) * 16];
                const uint32_t lx = x % l[0], ly = y % l[1], lz = z % l[2];
                const uint32_t rec[16] = {
                    x,    y,    z, lx + l[0] * (ly + l[1] * lz), lx, ly, lz, 0, x / l[0], y / l[1], z / l[2], 0, g[0],
                    g[1], g[2], 0};
                std::copy(rec, rec + 16, r);
            }
    return w;
}

void add_builtin_case(CaseList& out, const std::string& name, std::array<uint32_t, 3> l, std::array<uint32_t, 3> g,
                      bool by_spec, bool indirect) {
    ComputeSpec s;
    const std::vector<uint32_t> want = builtins_answer(l.data(), g.data());
    if (by_spec) {
        // The size comes from specialization constants 0..2 (the WorkgroupSize built-in in the module).
        s.shaders = {"#version 450\nlayout(local_size_x_id=0, local_size_y_id=1, local_size_z_id=2) in;\n" +
                     std::string(kBuiltinsBody)};
        s.spec_values = {l[0], l[1], l[2]};
    } else {
        s.shaders = {glsl_header(l[0], l[1], l[2]) + kBuiltinsBody};
    }
    s.buffers = {{std::vector<uint32_t>(want.size(), kMarker)}};
    if (indirect) {
        // Counts at byte offset 8 of buffer 1, after two words the dispatch must not read.
        s.buffers.push_back({{7, 7, g[0], g[1], g[2], 9}});
        s.steps = {dispatch_indirect(0, 1, 8)};
    } else {
        s.steps = {dispatch(0, g[0], g[1], g[2])};
    }
    add_compute_case(out, "basic." + name, std::move(s), words_are(0, want));
}

// packUnorm4x8, packSnorm4x8, packUnorm2x16 (xy) and packSnorm2x16 (zw) of 64 vec4s: out of range, signed zeros,
// ties of the scaled value (0.5 * 255 = 127.5), random values in [-1.5, 1.5]. The answer from GLSL's definition:
// round(clamp(c, 0, 1) * (2^n - 1)) and round(clamp(c, -1, 1) * (2^(n-1) - 1)), ties to even as both drivers round.
void add_pack_norm_case(CaseList& out) {
    std::vector<float> v = {-2.0f, -1.0f, -0.75f, -0.5f, -0.0f, 0.0f,          0.5f,           1.0f / 255.0f,
                            0.25f, 0.75f, 1.0f,   1.5f,  2.0f,  0.5f / 127.0f, -0.5f / 127.0f, 1e-30f};
    Lcg g{4321};
    while (v.size() < 64 * 4) v.push_back(g.next() * 3.0f - 1.5f);
    const auto unorm = [](float c, float n) {
        return uint32_t(std::nearbyint(std::fmin(std::fmax(c, 0.0f), 1.0f) * n));
    };
    const auto snorm = [](float c, float n) {
        return uint32_t(int32_t(std::nearbyint(std::fmin(std::fmax(c, -1.0f), 1.0f) * n)));
    };
    std::vector<uint32_t> in, want;
    for (size_t i = 0; i < v.size(); i += 4) {
        uint32_t u8 = 0, s8 = 0;
        for (size_t k = 0; k < 4; ++k) {
            in.push_back(fbits(v[i + k]));
            u8 |= unorm(v[i + k], 255.0f) << (8 * k);
            s8 |= (snorm(v[i + k], 127.0f) & 0xFFu) << (8 * k);
        }
        want.push_back(u8);
        want.push_back(s8);
        want.push_back(unorm(v[i], 65535.0f) | unorm(v[i + 1], 65535.0f) << 16);
        want.push_back((snorm(v[i + 2], 32767.0f) & 0xFFFFu) | snorm(v[i + 3], 32767.0f) << 16);
    }
    ComputeSpec s;
    s.shaders = {glsl_header(16) +
                 "layout(std430, binding=0) readonly buffer I { vec4 v[]; };\n"
                 "layout(std430, binding=1) buffer O { uvec4 o[]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x; vec4 c = v[i];\n"
                 "  o[i] = uvec4(packUnorm4x8(c), packSnorm4x8(c), packUnorm2x16(c.xy), packSnorm2x16(c.zw)); }\n"};
    s.buffers = {{in, false, false}, {std::vector<uint32_t>(want.size(), kMarker)}};
    s.steps = {dispatch(0, 4)};
    add_compute_case(out, "basic.pack_norm", std::move(s), words_are(1, want));
}

// unpackHalf2x16 of halves with every class: NaNs with payloads (quiet and signalling, both signs), infinities,
// denormals, zeros, normals. lavapipe lowers it to an fpext of each half (nir lower_pack_split, LLVM fpext:
// VCVTPH2PS), which is exact, quiets a signalling NaN and keeps its payload. The answer from IEEE 754's widening:
// the half's fields moved into a float, a NaN's payload shifted up by 13 with the quiet bit set.
void add_unpack_half_case(CaseList& out) {
    const auto widen = [](uint32_t h) {
        const uint32_t sign = (h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu, man = h & 0x3ffu;
        if (exp == 0x1f) return sign | 0x7f800000u | (man ? 0x400000u | (man << 13) : 0u);
        if (exp != 0) return sign | ((exp - 15 + 127) << 23) | (man << 13);
        if (man == 0) return sign;
        int e = -14;  // denormal: man * 2^-24, normalised
        uint32_t m = man;
        while (!(m & 0x400u)) m <<= 1, --e;
        return sign | (uint32_t(e + 127) << 23) | ((m & 0x3ffu) << 13);
    };
    const std::vector<uint32_t> halves = {0x7e01, 0x7c01, 0xfd55, 0x7fff, 0xfe00, 0x7e00, 0x7c00, 0xfc00,
                                          0x0001, 0x83ff, 0x0000, 0x8000, 0x3c00, 0xc155, 0x7bff, 0x0400};
    std::vector<uint32_t> in, want;
    for (size_t i = 0; i < halves.size(); ++i) {
        const uint32_t lo = halves[i], hi = halves[(i * 7 + 3) % halves.size()];
        in.push_back(lo | hi << 16);
        want.push_back(widen(lo));
        want.push_back(widen(hi));
    }
    ComputeSpec s;
    s.shaders = {glsl_header(16) +
                 "layout(std430, binding=0) readonly buffer I { uint v[]; };\n"
                 "layout(std430, binding=1) buffer O { uvec2 o[]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x; o[i] = floatBitsToUint(unpackHalf2x16(v[i])); }\n"};
    s.buffers = {{in, false, false}, {std::vector<uint32_t>(want.size(), kMarker)}};
    s.steps = {dispatch(0, 1)};
    add_compute_case(out, "basic.unpack_half_nan_payload", std::move(s), words_are(1, want));
}

void add_basic_cases(CaseList& out) {
    add_pack_norm_case(out);
    add_unpack_half_case(out);
    const struct {
        const char* name;
        std::array<uint32_t, 3> l, g;
    } sizes[] = {{"size_1x1x1", {1, 1, 1}, {3, 2, 1}},         {"size_16x1x1", {16, 1, 1}, {4, 1, 1}},
                 {"size_8x8x1", {8, 8, 1}, {2, 3, 1}},         {"size_4x4x4", {4, 4, 4}, {2, 1, 2}},
                 {"size_7x3x2", {7, 3, 2}, {3, 2, 2}},         {"size_5x1x1", {5, 1, 1}, {7, 1, 1}},
                 {"size_1x1x13", {1, 1, 13}, {2, 1, 3}},       {"size_128x1x1", {128, 1, 1}, {3, 1, 1}},
                 {"size_17x1x1_many", {17, 1, 1}, {61, 1, 1}}, {"size_3x5x7", {3, 5, 7}, {1, 2, 1}}};
    for (const auto& z : sizes) add_builtin_case(out, "builtins." + std::string(z.name), z.l, z.g, false, false);
    add_builtin_case(out, "builtins.spec_size_12x5x1", {12, 5, 1}, {2, 2, 1}, true, false);
    add_builtin_case(out, "builtins.spec_size_3x3x3", {3, 3, 3}, {1, 2, 3}, true, false);
    add_builtin_case(out, "builtins.indirect_4x4x1", {4, 4, 1}, {3, 2, 2}, false, true);
    add_builtin_case(out, "builtins.indirect_spec_9x1x1", {9, 1, 1}, {5, 1, 1}, true, true);

    // SAXPY with a from a push constant and n from a specialization constant (the tail beyond n untouched).
    {
        ComputeSpec s;
        s.shaders = {glsl_header(64) +
                     "layout(constant_id=0) const uint N = 1;\n"
                     "layout(push_constant) uniform P { float a; } p;\n"
                     "layout(std430, binding=0) readonly buffer X { float x[]; };\n"
                     "layout(std430, binding=1) buffer Y { float y[]; };\n"
                     "void main() { uint i = gl_GlobalInvocationID.x; if (i < N) y[i] = p.a * x[i] + y[i]; }\n"};
        const uint32_t n = 1000;
        s.spec_values = {n};
        s.push = {fbits(2.5f)};
        std::vector<uint32_t> x(1024), y(1024), want(1024);
        for (uint32_t i = 0; i < 1024; ++i) {
            x[i] = fbits(float(i) * 0.5f);
            y[i] = fbits(float(i % 7));
            // a * x + y with small integers and halves: exact in float whether or not the driver fuses it
            want[i] = i < n ? fbits(2.5f * (float(i) * 0.5f) + float(i % 7)) : y[i];
        }
        s.buffers = {{x, false, false}, {y}};
        s.steps = {dispatch(0, 16)};
        add_compute_case(out, "basic.saxpy_push_constant_spec_count", std::move(s), words_are(1, want));
    }
    // Signed division and GLSL's % on ints (OpSDiv truncates; glslang makes % an OpSMod: the sign of the divisor),
    // over every sign combination.
    {
        ComputeSpec s;
        s.shaders = {glsl_header(16) +
                     "layout(std430, binding=0) readonly buffer I { ivec2 ab[]; };\n"
                     "layout(std430, binding=1) buffer O { ivec2 qr[]; };\n"
                     "void main() { uint i = gl_GlobalInvocationID.x; ivec2 v = ab[i]; qr[i] = ivec2(v.x / v.y, "
                     "v.x % v.y); }\n"};
        const int32_t as[] = {-1234, 1234, -1000, 999, -1, 0, 7, -7}, bs[] = {1000, -1000, 3, -3};
        std::vector<uint32_t> in, want;
        for (int32_t a : as)
            for (int32_t b : bs) {
                in.push_back(uint32_t(a));
                in.push_back(uint32_t(b));
                const int32_t q = a / b, rem = a % b;  // C++ truncates: the remainder has the dividend's sign
                want.push_back(uint32_t(q));
                want.push_back(uint32_t(rem != 0 && (rem < 0) != (b < 0) ? rem + b : rem));
            }
        s.buffers = {{in, false, false}, {std::vector<uint32_t>(in.size(), kMarker)}};
        s.steps = {dispatch(0, 2)};
        add_compute_case(out, "basic.signed_division_and_modulo", std::move(s), words_are(1, want));
        out.back().named_difference =
            "lavapipe's OpSMod keeps the dividend's sign (gallivm do_int_mod computes nir imod as irem)";
    }
    // A uniform buffer read by every invocation; an empty dispatch (no groups) writes nothing.
    {
        ComputeSpec s;
        s.shaders = {glsl_header(32) +
                     "layout(std140, binding=0) uniform U { uvec4 k[4]; } u;\n"
                     "layout(std430, binding=1) buffer O { uint o[]; };\n"
                     "void main() { uint i = gl_GlobalInvocationID.x; o[i] = u.k[i % 4].x * 1000u + u.k[i % 4].w; }\n"};
        std::vector<uint32_t> k = {1, 0, 0, 11, 2, 0, 0, 22, 3, 0, 0, 33, 4, 0, 0, 44}, want(64);
        for (uint32_t i = 0; i < 64; ++i) want[i] = (i % 4 + 1) * 1000 + (i % 4 + 1) * 11;
        s.buffers = {{k, true, false}, {std::vector<uint32_t>(64, kMarker)}};
        s.steps = {dispatch(0, 2), dispatch(0, 0)};
        add_compute_case(out, "basic.uniform_buffer_and_empty_dispatch", std::move(s), words_are(1, want));
    }
    // One dispatch writes the group counts the next one reads indirectly (compute -> indirect command).
    {
        ComputeSpec s;
        s.shaders = {glsl_header(1) +
                         "layout(std430, binding=0) buffer C { uint c[4]; };\n"
                         "void main() { c[0] = 3u; c[1] = 2u; c[2] = 1u; }\n",
                     glsl_header(4) +
                         "layout(std430, binding=1) buffer O { uint o[]; };\n"
                         "void main() { uint i = gl_WorkGroupID.y * 12u + gl_GlobalInvocationID.x; o[i] = i + 1u; }\n"};
        std::vector<uint32_t> want(32, kMarker);
        for (uint32_t i = 0; i < 24; ++i) want[i] = i + 1;
        s.buffers = {{{0, 0, 0, 0}, false, true}, {std::vector<uint32_t>(32, kMarker)}};
        s.steps = {dispatch(0, 1), dispatch_indirect(1, 0, 0)};
        add_compute_case(out, "basic.indirect_counts_from_compute", std::move(s), words_are(1, want));
    }
    // Ten dispatches in a chain, each reading what the previous one wrote: a read-after-write between every pair.
    {
        ComputeSpec s;
        s.shaders = {glsl_header(64) +
                     "layout(std430, binding=0) buffer A { uint a[]; };\n"
                     "void main() { uint i = gl_GlobalInvocationID.x; a[i] = a[i] * 3u + (i ^ 5u); }\n"};
        std::vector<uint32_t> a(256);
        for (uint32_t i = 0; i < 256; ++i) a[i] = i * 7 + 1;
        s.buffers = {{a}};
        for (int d = 0; d < 10; ++d) {
            s.steps.push_back(dispatch(0, 4));
            for (uint32_t i = 0; i < 256; ++i) a[i] = a[i] * 3 + (i ^ 5);
        }
        add_compute_case(out, "basic.chained_dispatches", std::move(s), words_are(0, a));
    }
}

// VK_EXT_conditional_rendering on dispatches (modelled on dEQP-VK.conditional_rendering.dispatch.*): dispatch k
// writes o[k] = k + 1 under the predicate it names; a skipped one leaves the marker. The predicates (buffer 0) are
// 0, 0x100 (no bit in the low byte) and 5; the last conditional dispatch reads a predicate a fill of the same
// command buffer zeroed just before it (read when it executes, not when recorded or submitted).
void add_conditional_dispatch_case(CaseList& out) {
    ComputeSpec s;
    for (uint32_t k = 0; k < 8; ++k)
        s.shaders.push_back(glsl_header(1) + "layout(std430, binding=1) buffer O { uint o[8]; };\nvoid main() { o[" +
                            std::to_string(k) + "] = " + std::to_string(k + 1) + "u; }\n");
    s.buffers = {{{0, 0x100, 5, 0}}, {std::vector<uint32_t>(8, kMarker)}, {{1, 1, 1}, false, false}};
    auto when = [](ComputeStep st, uint32_t offset, bool inverted) {
        st.condition = 0;
        st.condition_offset = offset;
        st.condition_inverted = inverted;
        return st;
    };
    s.steps = {when(dispatch(0, 1), 0, false),
               when(dispatch(1, 1), 4, false),
               when(dispatch(2, 1), 0, true),
               when(dispatch(3, 1), 8, true),
               when(dispatch_indirect(4, 2, 0), 0, false),
               when(dispatch_indirect(5, 2, 0), 4, false),
               fill(0, 0),
               when(dispatch(6, 1), 4, false),
               dispatch(7, 1)};
    add_compute_case(out, "conditional_rendering.dispatch", std::move(s),
                     words_are(1, {kMarker, 2, 3, kMarker, kMarker, 6, kMarker, 8}));
}

}  // namespace

void add_compute_shared_cases(CaseList& out);  // cases_compute_shared.cpp
void add_compute_atomic_cases(CaseList& out);  // cases_compute_atomic.cpp
void add_compute_atomic_float_cases(CaseList& out);  // cases_compute_atomic_float.cpp
void add_compute_atomic_float2_cases(CaseList& out);  // cases_compute_atomic_float2.cpp
void add_compute_atomic_int64_cases(CaseList& out);   // cases_compute_atomic_int64.cpp
void add_compute_image_cases(CaseList& out);   // cases_compute_image.cpp
void add_compute_store_cases(CaseList& out);   // cases_compute_stores.cpp
void add_compute_limit_cases(CaseList& out);   // cases_limits.cpp
void add_compute_robustness2_cases(CaseList& out);  // cases_robustness2.cpp

void add_compute_cases(CaseList& out) {
    add_basic_cases(out);
    add_conditional_dispatch_case(out);
    add_compute_shared_cases(out);
    add_compute_atomic_cases(out);
    add_compute_atomic_float_cases(out);
    add_compute_atomic_float2_cases(out);
    add_compute_atomic_int64_cases(out);
    add_compute_image_cases(out);
    add_compute_store_cases(out);
    add_compute_limit_cases(out);
    add_compute_robustness2_cases(out);
}

}  // namespace tilevk::cts
