// Differential test of the two tiers on compute programs (shader/jit/README.md, "Compute"): Workgroup memory,
// barriers (the compiled code returns at a Barrier and the next phase resumes it there), shared and buffer atomics
// (return values in lane order; float ones too), subgroups and out-of-range shared indices. Each program is created
// twice, compiled and interpreted, and runs the same workgroups on the same random buffers; every buffer byte and the
// watchdog count must match, and the programs together must reach every compute op the tier knows but the storage-image
// ones.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "compute_harness.h"
#include "glsl.h"
#include "shader/ir.h"
#include "shader/jit/jit.h"

using namespace tilevk::shader;
using namespace tilevk::shader::test;

namespace {

// A 32x32 float matrix product in 8x8 tiles through shared memory, bench/frame's matmul512 in small.
const char* const kMatmul = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, set = 0, binding = 0) buffer A { float a[]; };
layout(std430, set = 0, binding = 1) buffer B { float b[]; };
layout(std430, set = 0, binding = 2) buffer C { float c[]; };
shared float ta[8][8];
shared float tb[8][8];
void main() {
    uint row = gl_GlobalInvocationID.y % 32u, col = gl_GlobalInvocationID.x % 32u;
    uint ty = gl_LocalInvocationID.y, tx = gl_LocalInvocationID.x;
    float sum = 0.0;
    for (uint t = 0u; t < 4u; ++t) {
        ta[ty][tx] = a[row * 32u + t * 8u + tx];
        tb[ty][tx] = b[(t * 8u + ty) * 32u + col];
        barrier();
        for (uint k = 0u; k < 8u; ++k) sum += ta[ty][k] * tb[k][tx];
        barrier();
    }
    c[(row * 32u + col) % 256u] = sum;
})";

// Every shared and buffer atomic with its return value kept, a shared histogram, lanes that collide on one word.
const char* const kAtomics = R"(#version 450
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
layout(std430, set = 0, binding = 2) buffer H { uint h[]; };
shared uint bins[16];
shared int s[8];
void main() {
    uint i = gl_LocalInvocationIndex, v = x[gl_GlobalInvocationID.x % 128u];
    if (i < 8u) s[i] = int(x[i + 3u]);
    barrier();
    uint r0 = atomicAdd(bins[v % 16u], v);
    int r1 = atomicMin(s[v % 8u], int(v));
    int r2 = atomicMax(s[(v >> 3) % 8u], int(v));
    uint r3 = atomicAnd(bins[(v >> 5) % 16u], v | 0xF0F0F0F0u);
    uint r4 = atomicOr(bins[(v >> 7) % 16u], v & 0x0F0F0F0Fu);
    uint r5 = atomicXor(bins[(v >> 9) % 16u], v);
    uint r6 = atomicExchange(bins[(v >> 11) % 16u], v);
    uint r7 = atomicCompSwap(bins[(v >> 13) % 16u], v % 3u, i);
    uint r8 = uint(atomicMin(s[i % 8u], -int(v)));
    uint r9 = atomicMax(bins[i % 16u], v);
    uint ra = atomicMin(bins[(i + 1u) % 16u], v);
    barrier();
    uint base = (gl_GlobalInvocationID.x % 64u) * 12u;
    y[base] = r0, y[base + 1u] = uint(r1), y[base + 2u] = uint(r2), y[base + 3u] = r3, y[base + 4u] = r4;
    y[base + 5u] = r5, y[base + 6u] = r6, y[base + 7u] = r7, y[base + 8u] = r8, y[base + 9u] = r9;
    y[base + 10u] = ra, y[base + 11u] = bins[i % 16u] ^ uint(s[i % 8u]);
    uint q0 = atomicAdd(h[v % 32u], 1u);
    uint q1 = atomicMin(h[32u + v % 8u], v);
    uint q2 = atomicMax(h[40u + v % 8u], v);
    uint q3 = atomicAnd(h[48u + v % 4u], v);
    uint q4 = atomicOr(h[52u + v % 4u], v);
    uint q5 = atomicXor(h[56u + v % 4u], v);
    uint q6 = atomicExchange(h[60u], v);
    uint q7 = atomicCompSwap(h[61u + v % 2u], v % 5u, i);
    int q8 = atomicAdd(s[v % 8u], -1);
    h[64u + (gl_GlobalInvocationID.x % 56u)] = q0 ^ q1 ^ q2 ^ q3 ^ q4 ^ q5 ^ q6 ^ q7 ^ uint(q8);
})";

// Float atomics (VK_EXT_shader_atomic_float) on shared and buffer words from random bits (NaNs, infinities,
// denormals among them): colliding and one-writer adds and exchanges with their returns kept.
const char* const kFloatAtomics = R"(#version 450
#extension GL_EXT_shader_atomic_float : require
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) buffer X { float x[]; };
layout(std430, set = 0, binding = 1) buffer Y { float y[]; };
layout(std430, set = 0, binding = 2) buffer H { float h[]; };
shared float s[16];
void main() {
    uint i = gl_LocalInvocationIndex, g = gl_GlobalInvocationID.x;
    float v = x[g % 128u];
    uint k = floatBitsToUint(v);
    if (i < 16u) s[i] = x[i + 200u];
    barrier();
    float r0 = atomicAdd(s[k % 16u], v);
    float r1 = atomicExchange(s[(k >> 4) % 16u], x[(g + 7u) % 128u]);
    float r2 = atomicAdd(s[i % 16u], x[300u + i % 64u]);
    float r3 = atomicAdd(h[k % 32u], v);
    float r4 = atomicExchange(h[32u + (k >> 5) % 8u], v);
    barrier();
    uint base = (g % 64u) * 6u;
    y[base] = r0, y[base + 1u] = r1, y[base + 2u] = r2, y[base + 3u] = r3, y[base + 4u] = r4;
    y[base + 5u] = s[i % 16u];
})";

// VK_EXT_shader_atomic_float2: contended float min / max on shared words (the compiled tier's own loop) and buffer
// words (the interpreter's code), over random words (many NaNs and denormals) with the sign flipped for some, so
// that zeros of both signs meet.
const char* const kFloatMinMax = R"(#version 450
#extension GL_EXT_shader_atomic_float2 : require
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) buffer X { float x[]; };
layout(std430, set = 0, binding = 1) buffer Y { float y[]; };
layout(std430, set = 0, binding = 2) buffer H { float h[]; };
shared float s[16];
void main() {
    uint i = gl_LocalInvocationIndex, g = gl_GlobalInvocationID.x;
    uint k = floatBitsToUint(x[g % 128u]);
    float v = uintBitsToFloat((k & 32u) != 0u ? k ^ 0x80000000u : k);
    if (i < 16u) s[i] = x[i + 200u];
    barrier();
    float r0 = atomicMin(s[k % 16u], v);
    float r1 = atomicMax(s[(k >> 4) % 16u], v);
    float r2 = atomicMin(h[k % 32u], v);
    float r3 = atomicMax(h[32u + (k >> 5) % 8u], v);
    barrier();
    uint base = (g % 64u) * 5u;
    y[base] = r0, y[base + 1u] = r1, y[base + 2u] = r2, y[base + 3u] = r3;
    y[base + 4u] = s[i % 16u];
})";

// A reduction whose barriers sit in a loop and in divergent-looking code, reads of other batches' words after the
// last barrier, and shared indices past the array (clamped to its last word) in loads, stores and atomics.
const char* const kReduceClamp = R"(#version 450
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
shared uint s[64];
shared uint tail[3];
void main() {
    uint i = gl_LocalInvocationIndex, v = x[gl_GlobalInvocationID.x % 128u];
    s[i % 64u] = v;
    if ((v & 7u) == 3u) tail[v] = i;  // past the end: the last word, last lane wins
    barrier();
    for (uint width = gl_WorkGroupSize.x; width > 1u;) {
        uint half_ = (width + 1u) / 2u;
        if (i < width - half_) s[i % 64u] += s[(i + half_) % 64u];
        barrier();
        width = half_;
    }
    uint k = atomicAdd(tail[v % 5u], 1u);  // indices 3 and 4 clamp to tail[2]
    barrier();
    uint base = (gl_GlobalInvocationID.x % 64u) * 4u;
    y[base] = s[0];
    y[base + 1u] = s[(i * 7u + 5u) % gl_WorkGroupSize.x % 64u];
    y[base + 2u] = tail[v] + tail[2] * 3u + k;
    y[base + 3u] = s[v];  // any index: clamped
})";

// Subgroup ops between barriers (they run through the interpreter's code for one instruction).
const char* const kSubgroups = R"(#version 450
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
shared uint s[64];
void main() {
    uint i = gl_LocalInvocationIndex, v = x[gl_GlobalInvocationID.x % 128u];
    s[i % 64u] = subgroupBroadcastFirst(v) + gl_SubgroupInvocationID;
    barrier();
    uint r = 0u;
    if (v % 3u != 0u) {
        r = (subgroupElect() ? 1u : 0u) | (subgroupAll(v > 10u) ? 2u : 0u) | (subgroupAny(v > 90u) ? 4u : 0u) |
            (subgroupAllEqual(v / 100u) ? 8u : 0u) | subgroupBroadcast(v, 5u) << 4;
        uvec4 b = subgroupBallot(v % 2u == 0u);
        r ^= b.x << 16 ^ subgroupBallotBitCount(b) << 24 ^ subgroupBallotExclusiveBitCount(b) << 28;
        r ^= subgroupInverseBallot(b) ? 0x8000u : 0u;
    }
    y[(gl_GlobalInvocationID.x % 64u) * 2u] = r;
    y[(gl_GlobalInvocationID.x % 64u) * 2u + 1u] = s[(i + 9u) % gl_WorkGroupSize.x % 64u];
})";

// The loop around a barrier never ends: the watchdog cuts every batch in both tiers, counting back edges over all
// phases of the run.
const char* const kEndless = R"(#version 450
layout(local_size_x = 20) in;
layout(std430, set = 0, binding = 0) buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
shared uint s[20];
void main() {
    uint n = 0u;
    while (x[0] != 12345u) {
        s[gl_LocalInvocationIndex] = n++;
        barrier();
    }
    y[gl_LocalInvocationIndex] = s[19u - gl_LocalInvocationIndex] + n;
})";

// Inputs of every kind the atomics and indices care about: small values (collisions), huge and negative ones.
std::vector<uint32_t> random_words(std::mt19937& rng, size_t n) {
    std::vector<uint32_t> w(n);
    for (uint32_t& x : w) {
        switch (rng() % 4) {
            case 0:
                x = rng() % 16;
                break;
            case 1:
                x = uint32_t(rng());
                break;
            case 2:
                x = uint32_t(-int32_t(rng() % 100));
                break;
            default:
                x = rng() % 1000;
                break;
        }
    }
    return w;
}

struct Pair {
    std::shared_ptr<const Program> compiled, interpreted;
};

Pair build(const std::string& glsl, uint32_t local_x, bool spirv_1_3 = false) {
    set_jit_enabled(true);
    Pair p{compute(glsl, local_x, spirv_1_3), nullptr};
    set_jit_enabled(false);
    p.interpreted = compute(glsl, local_x, spirv_1_3);
    set_jit_enabled(true);
    return p;
}

// Runs `groups` workgroups of both programs on the same random buffers (bindings 0-2, 512 words each), `seeds`
// times; the first difference, or empty.
std::string compare(const Pair& p, uint32_t groups, int seeds) {
    for (int seed = 0; seed < seeds; ++seed) {
        std::mt19937 rng(uint32_t(seed) * 977u + 13u);
        std::vector<uint32_t> buf[2][3];
        for (int k = 0; k < 3; ++k) buf[0][k] = buf[1][k] = random_words(rng, 512);
        Scratch scratch[2];
        const Program* programs[2] = {p.compiled.get(), p.interpreted.get()};
        for (int t = 0; t < 2; ++t) {
            Bindings b;
            for (int k = 0; k < 3; ++k) b.set(0, uint32_t(k), 0, storage(buf[t][k]));
            dispatch(*programs[t], b, 0, groups, groups, scratch[t]);
        }
        for (int k = 0; k < 3; ++k)
            for (size_t w = 0; w < buf[0][k].size(); ++w)
                if (buf[0][k][w] != buf[1][k][w]) {
                    std::ostringstream s;
                    s << "seed " << seed << ", buffer " << k << " word " << w << ": compiled 0x" << std::hex
                      << buf[0][k][w] << ", interpreted 0x" << buf[1][k][w];
                    return s.str();
                }
        if (scratch[0].loop_limit_hits() != scratch[1].loop_limit_hits())
            return "seed " + std::to_string(seed) + ": watchdog " + std::to_string(scratch[0].loop_limit_hits()) +
                   " vs " + std::to_string(scratch[1].loop_limit_hits());
    }
    return {};
}

class JitComputeDiff : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!jit::host_supported()) GTEST_SKIP() << "the CPU lacks AVX2/FMA: there is no compiled tier to compare";
        if (!jit::enabled()) GTEST_SKIP() << "TILEVK_JIT=0: the compiled tier is off";
    }
};

}  // namespace

TEST_F(JitComputeDiff, ProgramsMatchInterpreterBitForBit) {
    struct Case {
        const char* name;
        const char* glsl;
        std::vector<uint32_t> sizes;  // local_size_x through specialization constant 0 (0: the shader's own)
        bool spirv_1_3;
    };
    const Case cases[] = {
        {"matmul", kMatmul, {0}, false},
        {"atomics", kAtomics, {64, 24, 16, 1, 40}, false},
        {"float_atomics", kFloatAtomics, {64, 24, 16, 1}, false},
        {"float_min_max", kFloatMinMax, {64, 24, 16, 1}, false},
        {"reduce_clamp", kReduceClamp, {64, 24, 17, 1}, false},
        {"subgroups", kSubgroups, {64, 24, 8}, true},
    };
    std::set<Op> seen;
    for (const Case& c : cases)
        for (uint32_t size : c.sizes) {
            SCOPED_TRACE(std::string(c.name) + " size " + std::to_string(size));
            const Pair p = build(c.glsl, size, c.spirv_1_3);
            ASSERT_TRUE(p.compiled && p.interpreted);
            EXPECT_TRUE(p.compiled->compiled()) << "stayed in the interpreter (TILEVK_LOG_PIPELINES=1 says why)";
            EXPECT_FALSE(p.interpreted->compiled());
            for (const Inst& in : p.compiled->internal().code) seen.insert(in.op);
            const std::string diff = compare(p, 3, 6);
            EXPECT_TRUE(diff.empty()) << diff;
        }
    // the compute ops of the tier's table; the storage-image ones are covered by the conformance subset's
    // random.compute groups (with the JIT on and off)
    std::string missing;
    for (Op op :
         {Op::LoadShared, Op::StoreShared, Op::AtomicBuf, Op::AtomicShared, Op::Barrier, Op::SgLaneId, Op::SgElect,
          Op::SgAll, Op::SgAny, Op::SgAllEqual, Op::SgBroadcast, Op::SgBroadcastFirst, Op::SgBallot})
        if (!seen.count(op)) missing += " " + jit::op_name(op);
    EXPECT_TRUE(missing.empty()) << "compute ops no program reaches:" << missing;
}

// A loop around a barrier that never ends: both tiers stop every batch at the watchdog (two batches), with the
// same memory.
TEST_F(JitComputeDiff, EndlessLoopAroundBarrierEndsAlike) {
    const Pair p = build(kEndless, 0);
    ASSERT_TRUE(p.compiled && p.interpreted);
    ASSERT_TRUE(p.compiled->compiled());
    EXPECT_EQ(compare(p, 1, 1), "");
}
