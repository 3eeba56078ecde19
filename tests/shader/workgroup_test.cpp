// Compute workgroups in both tiers (the compiled one unless TILEVK_JIT=0): Workgroup (shared) memory, OpControlBarrier
// run as lock-step phases of a workgroup's 16-lane batches, and the 32-bit atomics (integer and float) on storage
// buffers and shared memory. The answers are computed here; every case would fail if batches ran to the end one after
// the other (reads of a later batch's writes see zeros) or if atomics lost updates.
#include <gtest/gtest.h>

#include <spirv-tools/libspirv.hpp>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

#include "compute_harness.h"
#include "glsl.h"
#include "shader/jit/jit.h"

using namespace tilevk::shader;
using namespace tilevk::shader::test;

namespace {

std::vector<uint32_t> random_words(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint32_t> v(n);
    for (uint32_t& w : v) w = rng() % 100000;
    return v;
}

// A tree reduction in shared memory: each level reads what other batches wrote before the barrier.
const char* const kReduce = R"(#version 450
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) readonly buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
shared uint s[1024];
void main() {
    uint i = gl_LocalInvocationIndex;
    s[i] = x[gl_GlobalInvocationID.x];
    memoryBarrierShared();
    barrier();
    for (uint width = gl_WorkGroupSize.x; width > 1u;) {
        uint half_ = (width + 1u) / 2u;
        if (i < width - half_) s[i] += s[i + half_];
        memoryBarrierShared();
        barrier();
        width = half_;
    }
    if (i == 0u) y[gl_WorkGroupID.x] = s[0];
    // a value written by another batch of the workgroup, read after the last barrier
    y[64u + gl_GlobalInvocationID.x] = s[(i * 7u + 5u) % gl_WorkGroupSize.x];
})";

}  // namespace

TEST(ShaderWorkgroup, SharedReductionWithBarriers) {
    for (uint32_t n : {64u, 256u, 24u, 16u, 1u}) {
        SCOPED_TRACE(n);
        auto p = compute(kReduce, n);
        ASSERT_TRUE(p);
        EXPECT_TRUE(p->interface().uses_barriers);
        EXPECT_EQ(p->interface().shared_memory_bytes, 4096u);
        // compiled when the tier is on (TILEVK_JIT=0 runs this suite in the interpreter)
        EXPECT_EQ(p->compiled(), jit::enabled() && jit::host_supported());
        const uint32_t groups = 5;
        std::vector<uint32_t> x = random_words(size_t(n) * groups, n), y(64 + x.size(), 0xDEADu);
        Bindings b;
        b.set(0, 0, 0, storage(x));
        b.set(0, 1, 0, storage(y));
        Scratch s;
        dispatch(*p, b, 0, groups, groups, s);
        for (uint32_t g = 0; g < groups; ++g) {
            const uint32_t* in = x.data() + size_t(g) * n;
            EXPECT_EQ(y[g], std::accumulate(in, in + n, 0u)) << "workgroup " << g;
            // after the loop s[0] holds the sum and s[j] (j > 0) a partial sum: only check what is defined
            // without knowing the tree: every lane read the same s as lane 0 of the check below
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t j = (i * 7 + 5) % n;
                if (j == 0) {
                    EXPECT_EQ(y[64 + g * n + i], y[g]) << "invocation " << i;
                }
            }
        }
        EXPECT_EQ(s.loop_limit_hits(), 0u);
    }
}

// Values written before a barrier by every batch, read across batches after it (a reversal).
TEST(ShaderWorkgroup, BarrierOrdersSharedWritesAcrossBatches) {
    auto p = compute(R"(#version 450
        layout(local_size_x = 8, local_size_y = 5) in;
        layout(std430, set = 0, binding = 0) buffer Y { uint y[]; };
        shared uint s[40];
        shared uint t[40];
        void main() {
            uint i = gl_LocalInvocationIndex;
            s[i] = i * 1000u + gl_WorkGroupID.x;
            barrier();
            t[39u - i] = s[i] + 1u;
            barrier();
            y[gl_WorkGroupID.x * 40u + i] = t[i] + s[39u - i];
        })");
    ASSERT_TRUE(p);
    std::vector<uint32_t> y(3 * 40, 0);
    Bindings b;
    b.set(0, 0, 0, storage(y));
    Scratch s;
    dispatch(*p, b, 0, 3, 3, s);
    for (uint32_t g = 0; g < 3; ++g)
        for (uint32_t i = 0; i < 40; ++i) {
            const uint32_t v = (39 - i) * 1000 + g;
            EXPECT_EQ(y[g * 40 + i], 2 * v + 1) << g << " " << i;
        }
}

// Buffer atomics of every kind, from many workgroups on four threads: the order-independent results.
TEST(ShaderWorkgroup, BufferAtomicsFromFourThreads) {
    auto p = compute(R"(#version 450
        layout(local_size_x = 24) in;
        layout(std430, set = 0, binding = 0) readonly buffer X { uint x[]; };
        layout(std430, set = 0, binding = 1) buffer C {
            uint sum; int smin; int smax; uint umin; uint umax; uint andv; uint orv; uint xorv; uint count;
            uint dec; uint sub; uint exch; uint first; uint winners;
        } c;
        void main() {
            uint v = x[gl_GlobalInvocationID.x];
            atomicAdd(c.sum, v);
            atomicMin(c.smin, int(v) - 50000);
            atomicMax(c.smax, int(v) - 50000);
            atomicMin(c.umin, v);
            atomicMax(c.umax, v);
            atomicAnd(c.andv, ~(1u << (v % 32u)));
            atomicOr(c.orv, 1u << (v % 31u));
            atomicXor(c.xorv, v);
            atomicAdd(c.count, 1u);
            atomicAdd(c.dec, 0xFFFFFFFFu);
            atomicExchange(c.exch, 7u);
            if (atomicCompSwap(c.first, 0u, gl_GlobalInvocationID.x + 1u) == 0u) atomicAdd(c.winners, 1u);
        })");
    ASSERT_TRUE(p);
    EXPECT_TRUE(p->interface().uses_atomics);
    EXPECT_EQ(p->compiled(), jit::enabled() && jit::host_supported());
    const uint32_t groups = 400, n = groups * 24;
    std::vector<uint32_t> x = random_words(n, 99);
    std::vector<uint32_t> c(14, 0);
    c[1] = 0x7FFFFFFF, c[2] = 0x80000000u, c[3] = ~0u, c[5] = ~0u, c[9] = n;
    Bindings b;
    b.set(0, 0, 0, storage(x));
    b.set(0, 1, 0, storage(c));
    std::vector<std::thread> threads;
    for (uint32_t t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            Scratch s;
            dispatch(*p, b, t * groups / 4, groups / 4, groups, s);
        });
    for (std::thread& t : threads) t.join();
    uint32_t sum = 0, andv = ~0u, orv = 0, xorv = 0;
    for (uint32_t v : x) sum += v, andv &= ~(1u << (v % 32)), orv |= 1u << (v % 31), xorv ^= v;
    EXPECT_EQ(c[0], sum);
    EXPECT_EQ(int32_t(c[1]), int32_t(*std::min_element(x.begin(), x.end())) - 50000);
    EXPECT_EQ(int32_t(c[2]), int32_t(*std::max_element(x.begin(), x.end())) - 50000);
    EXPECT_EQ(c[3], *std::min_element(x.begin(), x.end()));
    EXPECT_EQ(c[4], *std::max_element(x.begin(), x.end()));
    EXPECT_EQ(c[5], andv);
    EXPECT_EQ(c[6], orv);
    EXPECT_EQ(c[7], xorv);
    EXPECT_EQ(c[8], n);
    EXPECT_EQ(c[9], 0u);
    EXPECT_EQ(c[11], 7u);
    EXPECT_GE(c[12], 1u);
    EXPECT_LE(c[12], n);
    EXPECT_EQ(c[13], 1u);  // exactly one compare-exchange found the 0
}

// Atomics on shared memory and the values they return: lanes apply in lane order, batches in order, so a counter
// hands out 0, 1, 2, ... in LocalInvocationIndex order (deterministic; Vulkan allows any order).
TEST(ShaderWorkgroup, SharedAtomicsReturnValuesInLaneOrder) {
    auto p = compute(R"(#version 450
        layout(local_size_x = 40) in;
        layout(std430, set = 0, binding = 0) buffer Y { uint y[]; };
        shared uint counter;
        shared uint mx;
        shared uint slot;
        void main() {
            if (gl_LocalInvocationIndex == 0u) { counter = 0u; mx = 0u; slot = 0u; }
            barrier();
            uint mine = atomicAdd(counter, 1u);
            atomicMax(mx, gl_LocalInvocationIndex * 3u);
            uint old = atomicCompSwap(slot, 0u, gl_LocalInvocationIndex + 100u);
            barrier();
            y[gl_LocalInvocationIndex * 4u] = mine;
            y[gl_LocalInvocationIndex * 4u + 1u] = counter;
            y[gl_LocalInvocationIndex * 4u + 2u] = mx;
            y[gl_LocalInvocationIndex * 4u + 3u] = old;
        })");
    ASSERT_TRUE(p);
    std::vector<uint32_t> y(160, 0xDEAD);
    Bindings b;
    b.set(0, 0, 0, storage(y));
    Scratch s;
    dispatch(*p, b, 0, 1, 1, s);
    for (uint32_t i = 0; i < 40; ++i) {
        EXPECT_EQ(y[i * 4], i);
        EXPECT_EQ(y[i * 4 + 1], 40u);
        EXPECT_EQ(y[i * 4 + 2], 39u * 3);
        EXPECT_EQ(y[i * 4 + 3], i == 0 ? 0u : 100u) << i;  // lane 0 of batch 0 swapped first
    }
}

// Float atomics (VK_EXT_shader_atomic_float): a shared float accumulates x[i] in LocalInvocationIndex order, so each
// invocation gets the rounded sum of the values before its own (computed here in the same order, IEEE without
// FTZ/DAZ as compute runs); buffer words take one-writer adds and exchanges. OpAtomicExchange on a 64-bit float and
// atomicAdd on a double (AtomicFloat64AddEXT, not offered) are refused by name.
TEST(ShaderWorkgroup, FloatAtomicsAddInLaneOrder) {
    auto p = compute(R"(#version 450
        #extension GL_EXT_shader_atomic_float : require
        layout(local_size_x = 40) in;
        layout(std430, set = 0, binding = 0) buffer X { float x[40]; float w[40]; float e[40]; };
        layout(std430, set = 0, binding = 1) buffer Y { float y[]; };
        shared float sum;
        void main() {
            uint i = gl_LocalInvocationIndex;
            if (i == 0u) sum = 0.5;
            barrier();
            float before = atomicAdd(sum, x[i]);
            float old_w = atomicAdd(w[i], x[39u - i]);
            float old_e = atomicExchange(e[i], -x[i]);
            barrier();
            y[i * 4u] = before;
            y[i * 4u + 1u] = sum;
            y[i * 4u + 2u] = old_w;
            y[i * 4u + 3u] = old_e;
        })");
    ASSERT_TRUE(p);
    std::vector<float> xf(120);
    for (uint32_t i = 0; i < 40; ++i) {
        xf[i] = float(i) * 0.1f + 1.0f / float(i + 3);  // long mantissas: the sums round
        xf[40 + i] = float(i) * -7.3f + 1e-3f;
        xf[80 + i] = float(i) + 0.25f;
    }
    std::vector<uint32_t> x(120), y(160, 0xDEAD);
    std::memcpy(x.data(), xf.data(), 480);
    Bindings b;
    b.set(0, 0, 0, storage(x));
    b.set(0, 1, 0, storage(y));
    Scratch s;
    dispatch(*p, b, 0, 1, 1, s);
    std::vector<float> got(160), after(120);
    std::memcpy(got.data(), y.data(), 640);
    std::memcpy(after.data(), x.data(), 480);
    float sum = 0.5f;
    std::vector<float> befores(40);
    for (uint32_t i = 0; i < 40; ++i) {
        befores[i] = sum;
        sum += xf[i];
    }
    for (uint32_t i = 0; i < 40; ++i) {
        EXPECT_EQ(got[i * 4], befores[i]) << i;
        EXPECT_EQ(got[i * 4 + 1], sum) << i;
        EXPECT_EQ(got[i * 4 + 2], xf[40 + i]) << i;
        EXPECT_EQ(got[i * 4 + 3], xf[80 + i]) << i;
        EXPECT_EQ(after[40 + i], xf[40 + i] + xf[39 - i]) << i;
        EXPECT_EQ(after[80 + i], -xf[i]) << i;
    }
    const std::string min_src = R"(#version 450
        #extension GL_EXT_shader_atomic_float : require
        layout(local_size_x = 4) in;
        layout(std430, set = 0, binding = 0) buffer X { double x[]; };
        void main() { atomicAdd(x[0], 1.0lf); })";
    Result r = Program::create(compile_glsl(Stage::Compute, min_src), Stage::Compute, "main", {});
    EXPECT_FALSE(r);
    EXPECT_NE(r.error.find("AtomicFloat64AddEXT"), std::string::npos) << r.error;
    const std::string add64_src = R"(#version 450
        #extension GL_EXT_shader_atomic_float : require
        layout(local_size_x = 4) in;
        layout(std430, set = 0, binding = 0) buffer X { double x[]; };
        void main() { atomicExchange(x[0], 1.0lf); })";
    r = Program::create(compile_glsl(Stage::Compute, add64_src), Stage::Compute, "main", {});
    EXPECT_FALSE(r);
    EXPECT_NE(r.error.find("OpAtomicExchange on a 64-bit float"), std::string::npos) << r.error;
}

namespace {

bool is_nan_bits(uint32_t b) {
    return (b & 0x7FFFFFFFu) > 0x7F800000u;
}

// The word atomicMin / atomicMax(memory old, operand v) leaves, by the rule of docs/lavapipe-rules.md "Float
// atomics" (no FTZ/DAZ in compute): a NaN in memory gives the operand, a NaN operand keeps memory, and memory is
// replaced only by a strictly smaller / larger operand (so a tie of zeros keeps memory's sign).
uint32_t min_max_rule(bool is_min, uint32_t old, uint32_t v) {
    if (is_nan_bits(old)) return v;
    if (is_nan_bits(v)) return old;
    float o, x;
    std::memcpy(&o, &old, 4);
    std::memcpy(&x, &v, 4);
    return (is_min ? x < o : x > o) ? v : old;
}

}  // namespace

// VK_EXT_shader_atomic_float2: atomicMin / atomicMax on 32-bit floats in a buffer (one writer per word) and in
// shared memory (every lane of the workgroup on the same two words, in LocalInvocationIndex order), over pairs of
// zeros of both signs, quiet, signalling and negative NaNs, infinities, denormals and ones.
TEST(ShaderWorkgroup, FloatMinMaxKeepMemoryOnTiesAndReplaceNaN) {
    auto p = compute(R"(#version 450
        #extension GL_EXT_shader_atomic_float2 : require
        layout(local_size_x = 64) in;
        layout(std430, set = 0, binding = 0) buffer X { float v[64]; float a[64]; float b[64]; float init[2]; };
        layout(std430, set = 0, binding = 1) buffer Y { float y[]; };
        shared float smin, smax;
        void main() {
            uint i = gl_LocalInvocationIndex;
            if (i == 0u) { smin = init[0]; smax = init[1]; }
            barrier();
            y[i * 4u] = atomicMin(a[i], v[i]);
            y[i * 4u + 1u] = atomicMax(b[i], v[i]);
            y[i * 4u + 2u] = atomicMin(smin, v[i]);
            y[i * 4u + 3u] = atomicMax(smax, v[i]);
            barrier();
            if (i == 0u) { y[256] = smin; y[257] = smax; }
        })");
    ASSERT_TRUE(p);
    const uint32_t special[] = {0x00000000u, 0x80000000u, 0x7FC00000u, 0x7F800001u,
                                0xFFC00123u, 0x7F800000u, 0xFF800000u, 0x00000001u};
    std::vector<uint32_t> x(3 * 64 + 2), y(258, 0xDEADu);
    for (uint32_t i = 0; i < 64; ++i) {
        x[i] = special[i % 8];                    // operand
        x[64 + i] = x[128 + i] = special[i / 8];  // memory
    }
    x[192] = 0x80000000u;  // -0: +0 operands tie with it
    x[193] = 0x7FC00000u;  // NaN: the first operand replaces it
    const std::vector<uint32_t> before = x;
    Bindings bind;
    bind.set(0, 0, 0, storage(x));
    bind.set(0, 1, 0, storage(y));
    Scratch s;
    dispatch(*p, bind, 0, 1, 1, s);
    uint32_t smin = before[192], smax = before[193];
    for (uint32_t i = 0; i < 64; ++i) {
        const uint32_t v = before[i], old = before[64 + i];
        EXPECT_EQ(y[i * 4], old) << i;
        EXPECT_EQ(y[i * 4 + 1], old) << i;
        EXPECT_EQ(x[64 + i], min_max_rule(true, old, v)) << "min of memory " << old << " and " << v;
        EXPECT_EQ(x[128 + i], min_max_rule(false, old, v)) << "max of memory " << old << " and " << v;
        EXPECT_EQ(y[i * 4 + 2], smin) << i;
        EXPECT_EQ(y[i * 4 + 3], smax) << i;
        smin = min_max_rule(true, smin, v);
        smax = min_max_rule(false, smax, v);
    }
    EXPECT_EQ(y[256], smin);
    EXPECT_EQ(y[257], smax);
}

// VK_KHR_shader_atomic_int64: 64-bit atomics on a shared word (in LocalInvocationIndex order, so every return is
// known) and on buffer words, with operands whose low words carry into and compare equal across the high words.
TEST(ShaderWorkgroup, Int64AtomicsCarryAcrossWords) {
    auto p = compute(R"(#version 450
        #extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
        #extension GL_EXT_shader_atomic_int64 : require
        layout(local_size_x = 40) in;
        layout(std430, set = 0, binding = 0) buffer X { uint64_t x[40]; uint64_t w[40]; int64_t m[2]; uint64_t u; };
        layout(std430, set = 0, binding = 1) buffer Y { uint64_t y[]; };
        shared uint64_t sum;
        shared int64_t smin;
        void main() {
            uint i = gl_LocalInvocationIndex;
            if (i == 0u) { sum = 0xFFFFFFFF00000000ul; smin = 0l; }
            barrier();
            y[i * 4u] = atomicAdd(sum, x[i]);
            y[i * 4u + 1u] = uint64_t(atomicMin(smin, int64_t(x[i])));
            y[i * 4u + 2u] = atomicCompSwap(w[i], (i & 1u) == 0u ? w[i] : ~w[i], x[39u - i]);
            atomicMax(m[0], int64_t(x[i]));
            atomicMin(m[1], int64_t(x[i]));
            atomicMax(u, x[i]);
            barrier();
            if (i == 0u) { y[160] = sum; y[161] = uint64_t(smin); }
        })");
    ASSERT_TRUE(p);
    std::vector<uint64_t> x(40 + 40 + 3);
    for (uint32_t i = 0; i < 40; ++i) {
        x[i] = uint64_t(i) * 0x9E3779B97F4A7C15ull | 0xFFFFFF00u;  // equal-ish low words, signs of both kinds
        x[40 + i] = uint64_t(i) << 32 | (i * 3u);
    }
    x[80] = x[81] = 0;
    x[82] = 0x00000000FFFFFFFFull;
    std::vector<uint32_t> xw(x.size() * 2), y(162 * 2, 0xDEADu);
    std::memcpy(xw.data(), x.data(), x.size() * 8);
    Bindings bind;
    bind.set(0, 0, 0, storage(xw));
    bind.set(0, 1, 0, storage(y));
    Scratch s;
    dispatch(*p, bind, 0, 1, 1, s);
    std::vector<uint64_t> after(x.size()), got(162);
    std::memcpy(after.data(), xw.data(), after.size() * 8);
    std::memcpy(got.data(), y.data(), got.size() * 8);
    uint64_t sum = 0xFFFFFFFF00000000ull;
    int64_t smin = 0, mx = 0, mn = 0;
    uint64_t umax = x[82];
    for (uint32_t i = 0; i < 40; ++i) {
        EXPECT_EQ(got[i * 4], sum) << i;
        EXPECT_EQ(got[i * 4 + 1], uint64_t(smin)) << i;
        EXPECT_EQ(got[i * 4 + 2], x[40 + i]) << i;
        EXPECT_EQ(after[40 + i], (i & 1u) == 0u ? x[39 - i] : x[40 + i]) << i;
        sum += x[i];
        smin = std::min(smin, int64_t(x[i]));
        mx = std::max(mx, int64_t(x[i]));
        mn = std::min(mn, int64_t(x[i]));
        umax = std::max(umax, x[i]);
    }
    EXPECT_EQ(got[160], sum);
    EXPECT_EQ(got[161], uint64_t(smin));
    EXPECT_EQ(int64_t(after[80]), mx);
    EXPECT_EQ(int64_t(after[81]), mn);
    EXPECT_EQ(after[82], umax);
    EXPECT_FALSE(p->compiled()) << "64-bit atomics stay in the interpreter";
}

// Atomics in a loop with a lane-dependent trip count: every lane keeps the value it got while it was active.
TEST(ShaderWorkgroup, AtomicsInDivergentLoops) {
    auto p = compute(R"(#version 450
        layout(local_size_x = 16) in;
        layout(std430, set = 0, binding = 0) buffer Y { uint total; uint y[]; };
        void main() {
            uint last = 0u;
            for (uint k = 0u; k <= gl_LocalInvocationIndex; ++k) last = atomicAdd(total, 1u);
            y[gl_LocalInvocationIndex] = last;
        })");
    ASSERT_TRUE(p);
    std::vector<uint32_t> y(17, 0);
    Bindings b;
    b.set(0, 0, 0, storage(y));
    Scratch s;
    dispatch(*p, b, 0, 1, 1, s);
    EXPECT_EQ(y[0], 136u);  // 1 + 2 + ... + 16
    // iteration k runs lanes k..15 in lane order: lane l's last add (k = l) returned sum_{j<l}(16-j) + 0
    for (uint32_t l = 0; l < 16; ++l) {
        uint32_t before = 0;
        for (uint32_t j = 0; j < l; ++j) before += 16 - j;
        EXPECT_EQ(y[1 + l], before) << l;
    }
}

// A barrier only some batches reach (non-uniform control flow, undefined in SPIR-V) and a loop around a barrier
// that never ends: both end (the latter at the watchdog), never hang.
TEST(ShaderWorkgroup, BarriersInNonUniformFlowAndEndlessLoopsEnd) {
    auto p = compute(R"(#version 450
        layout(local_size_x = 32) in;
        layout(std430, set = 0, binding = 0) buffer Y { uint y[]; };
        shared uint s[32];
        void main() {
            s[gl_LocalInvocationIndex] = gl_LocalInvocationIndex;
            if (gl_LocalInvocationIndex < 16u) barrier();
            y[gl_LocalInvocationIndex] = s[gl_LocalInvocationIndex] + 1u;
        })");
    ASSERT_TRUE(p);
    std::vector<uint32_t> y(32, 0);
    Bindings b;
    b.set(0, 0, 0, storage(y));
    Scratch s;
    dispatch(*p, b, 0, 1, 1, s);
    for (uint32_t i = 0; i < 32; ++i) EXPECT_EQ(y[i], i + 1);

    auto endless = compute(R"(#version 450
        layout(local_size_x = 20) in;
        layout(std430, set = 0, binding = 0) buffer Y { uint y[]; };
        void main() {
            while (y[0] == 0u) barrier();
            y[1] = 5u;
        })");
    ASSERT_TRUE(endless);
    std::vector<uint32_t> z(2, 0);
    Bindings bz;
    bz.set(0, 0, 0, storage(z));
    Scratch s2;
    dispatch(*endless, bz, 0, 1, 1, s2);
    EXPECT_EQ(s2.loop_limit_hits(), 2u);  // both batches cut by the watchdog
    EXPECT_EQ(z[1], 0u);
}

// Shared memory starts at zero in every workgroup (lavapipe leaves it undefined; tilevk keeps runs deterministic)
// and is not shared between workgroups.
TEST(ShaderWorkgroup, SharedMemoryIsPerWorkgroup) {
    auto p = compute(R"(#version 450
        layout(local_size_x = 4) in;
        layout(std430, set = 0, binding = 0) buffer Y { uint y[]; };
        shared uint acc;
        void main() {
            atomicAdd(acc, gl_WorkGroupID.x + 1u);
            barrier();
            y[gl_GlobalInvocationID.x] = acc;
        })");
    ASSERT_TRUE(p);
    std::vector<uint32_t> y(12, 0);
    Bindings b;
    b.set(0, 0, 0, storage(y));
    Scratch s;
    dispatch(*p, b, 0, 3, 3, s);
    for (uint32_t i = 0; i < 12; ++i) EXPECT_EQ(y[i], 4 * (i / 4 + 1)) << i;
}

// The atomics GLSL does not emit (OpAtomicIIncrement, IDecrement, ISub, Load, Store), on a storage buffer and on
// Workgroup memory, assembled by hand.
TEST(ShaderWorkgroup, AtomicsGlslDoesNotEmit) {
    const char* const text = R"(
               OpCapability Shader
               OpMemoryModel Logical GLSL450
               OpEntryPoint GLCompute %main "main" %lid
               OpExecutionMode %main LocalSize 20 1 1
               OpDecorate %lid BuiltIn LocalInvocationIndex
               OpDecorate %rt ArrayStride 4
               OpMemberDecorate %blk 0 Offset 0
               OpDecorate %blk BufferBlock
               OpDecorate %buf DescriptorSet 0
               OpDecorate %buf Binding 0
       %void = OpTypeVoid
         %fn = OpTypeFunction %void
       %uint = OpTypeInt 32 0
         %rt = OpTypeRuntimeArray %uint
        %blk = OpTypeStruct %rt
       %pblk = OpTypePointer Uniform %blk
      %puint = OpTypePointer Uniform %uint
        %pin = OpTypePointer Input %uint
         %c0 = OpConstant %uint 0
         %c1 = OpConstant %uint 1
         %c2 = OpConstant %uint 2
         %c3 = OpConstant %uint 3
         %c4 = OpConstant %uint 4
         %c5 = OpConstant %uint 5
        %c10 = OpConstant %uint 10
         %c8 = OpConstant %uint 8
        %c32 = OpConstant %uint 32
        %c56 = OpConstant %uint 56
        %c80 = OpConstant %uint 80
        %sem = OpConstant %uint 264
        %arr = OpTypeArray %uint %c2
       %psha = OpTypePointer Workgroup %arr
        %psh = OpTypePointer Workgroup %uint
        %buf = OpVariable %pblk Uniform
        %lid = OpVariable %pin Input
         %sh = OpVariable %psha Workgroup
       %main = OpFunction %void None %fn
      %entry = OpLabel
          %i = OpLoad %uint %lid
         %p0 = OpAccessChain %puint %buf %c0 %c0
         %p1 = OpAccessChain %puint %buf %c0 %c1
         %p2 = OpAccessChain %puint %buf %c0 %c2
         %p3 = OpAccessChain %puint %buf %c0 %c3
         %p4 = OpAccessChain %puint %buf %c0 %c4
         %s1 = OpAccessChain %psh %sh %c1
          %a = OpAtomicIIncrement %uint %p0 %c1 %c0
          %b = OpAtomicIDecrement %uint %p1 %c1 %c0
          %c = OpAtomicISub %uint %p2 %c1 %c0 %i
               OpAtomicStore %p3 %c1 %c0 %c5
          %d = OpAtomicLoad %uint %p4 %c1 %c0
               OpAtomicStore %s1 %c2 %c0 %c10
               OpControlBarrier %c2 %c2 %sem
          %e = OpAtomicIIncrement %uint %s1 %c2 %c0
          %f = OpAtomicISub %uint %s1 %c2 %c0 %i
          %g = OpAtomicIDecrement %uint %s1 %c2 %c0
               OpControlBarrier %c2 %c2 %sem
          %h = OpAtomicLoad %uint %s1 %c2 %c0
         %i8 = OpIAdd %uint %i %c8
        %i32 = OpIAdd %uint %i %c32
        %i56 = OpIAdd %uint %i %c56
        %i80 = OpIAdd %uint %i %c80
         %o8 = OpAccessChain %puint %buf %c0 %i8
        %o32 = OpAccessChain %puint %buf %c0 %i32
        %o56 = OpAccessChain %puint %buf %c0 %i56
        %o80 = OpAccessChain %puint %buf %c0 %i80
               OpStore %o8 %a
               OpStore %o32 %d
               OpStore %o56 %h
               OpStore %o80 %e
               OpReturn
               OpFunctionEnd
)";
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string msg;
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { msg += m; });
    std::vector<uint32_t> words;
    ASSERT_TRUE(tools.Assemble(text, &words)) << msg;
    Result r = Program::create(words, Stage::Compute);
    ASSERT_TRUE(r) << r.error;
    std::vector<uint32_t> y(100, 0);
    y[1] = 100, y[2] = 1000, y[4] = 77;
    Bindings b;
    b.set(0, 0, 0, storage(y));
    Scratch s;
    dispatch(*r.program, b, 0, 1, 1, s);
    EXPECT_EQ(y[0], 20u);
    EXPECT_EQ(y[1], 80u);
    EXPECT_EQ(y[2], 1000u - 190u);  // minus 0 + 1 + ... + 19
    EXPECT_EQ(y[3], 5u);
    for (uint32_t i = 0; i < 20; ++i) {
        EXPECT_EQ(y[8 + i], i);  // increments in lane order, batch 0 first
        EXPECT_EQ(y[32 + i], 77u);
        EXPECT_EQ(y[56 + i], 10u + 20u - 190u - 20u);
        // no barrier between the three shared atomics: batch 0 (lanes 0-15) does all three before batch 1 starts
        EXPECT_EQ(y[80 + i], i < 16 ? 10u + i : 10u + 16u - 120u - 16u + (i - 16u)) << i;
    }
}
