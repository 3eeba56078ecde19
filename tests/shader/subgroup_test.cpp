// Compute subgroups in the interpreter (SPIR-V GroupNonUniform basic, vote, ballot): a subgroup is kSubgroupSize
// consecutive invocations in LocalInvocationIndex order. Every record is checked against a model computed here from
// that definition, with divergent branches (only some lanes take part), loops whose lanes leave at different
// iterations, and workgroups whose last subgroup is partial.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <vector>

#include <fstream>
#include <sstream>

#include "compute_harness.h"
#include "shader/jit/jit.h"

using namespace tilevk::shader;
using namespace tilevk::shader::test;

namespace {

constexpr uint32_t kWords = 16;  // words of each invocation's record

// The shader (also run on both drivers by tests/icd): a record of kWords words per invocation.
std::string subgroup_shader() {
    std::ifstream in(TILEVK_TEST_SHADER_DIR "/cp_subgroup.comp");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_FALSE(text.str().empty()) << TILEVK_TEST_SHADER_DIR "/cp_subgroup.comp";
    return text.str();
}

// The records of one workgroup of n invocations with inputs x, from the definition of a subgroup.
std::vector<uint32_t> model(const uint32_t* x, uint32_t n) {
    std::vector<uint32_t> y(size_t(n) * kWords, 0xDEADu);
    const uint32_t S = kSubgroupSize, all = (1u << S) - 1;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t id = i % S, first = i - id, end = std::min(first + S, n);
        uint32_t* r = y.data() + size_t(i) * kWords;
        r[0] = S;
        r[1] = id;
        r[2] = i / S;
        r[3] = (n + S - 1) / S;
        r[4] = ((1u << id) - 1) | (1u << id) << 8 | (all & ~((2u << id) - 1)) << 16 | (all & ~((1u << id) - 1)) << 24;
        r[5] = (2u << id) - 1;
        uint32_t acc = 0;
        for (uint32_t k = 0; k < x[i] % 4; ++k) {
            uint32_t count = 0;
            for (uint32_t j = first; j < end; ++j) count += x[j] % 4 > k;
            acc += count << (8 * k);
        }
        r[14] = acc;
        if (x[i] % 3 == 0) continue;
        uint32_t active = 0, ballot = 0;
        bool all10 = true, any90 = false, equal = true;
        for (uint32_t j = first; j < end; ++j) {
            if (x[j] % 3 == 0) continue;
            if (active == 0)
                equal = true;
            else
                equal &= x[j] / 100 == x[first + uint32_t(std::countr_zero(active))] / 100;
            active |= 1u << (j - first);
            ballot |= (x[j] % 2 == 0 ? 1u : 0u) << (j - first);
            all10 &= x[j] > 10;
            any90 |= x[j] > 90;
        }
        const uint32_t lowest = first + uint32_t(std::countr_zero(active));
        r[6] = (lowest == i ? 1u : 0u) | (all10 ? 2u : 0u) | (any90 ? 4u : 0u) | (equal ? 8u : 0u) | (equal ? 16u : 0u);
        r[7] = first + 5 < n ? x[first + 5] : 0xDEADu;  // no lane 5 in a partial subgroup: undefined, not compared
        r[8] = x[lowest];
        r[9] = ballot;
        r[10] = 0;
        r[11] = uint32_t(std::popcount(ballot)) | uint32_t(std::popcount(ballot & ((2u << id) - 1))) << 8 |
                uint32_t(std::popcount(ballot & ((1u << id) - 1))) << 16;
        r[12] =
            ballot == 0 ? 0xFFFFu : uint32_t(std::countr_zero(ballot)) | uint32_t(31 - std::countl_zero(ballot)) << 8;
        r[13] = (ballot >> id & 1) | (ballot >> 3 & 1) << 1;
    }
    return y;
}

// Inputs with lane 5 of every subgroup taking part (subgroupBroadcast(v, 5) reads it) and few distinct v / 100.
std::vector<uint32_t> inputs(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint32_t> x(count);
    for (size_t i = 0; i < count; ++i) {
        x[i] = rng() % 200;
        if (i % kSubgroupSize == 5 && x[i] % 3 == 0) ++x[i];
    }
    return x;
}

}  // namespace

TEST(ShaderSubgroup, BasicVoteAndBallotEqualTheModel) {
    static_assert(kSubgroupSize == 8, "the shader's masks and the model assume 8 lanes");
    for (uint32_t n : {64u, 24u, 8u, 13u, 5u, 1u}) {
        SCOPED_TRACE(n);
        auto p = compute(subgroup_shader(), n, true);
        ASSERT_TRUE(p);
        EXPECT_EQ(p->compiled(), jit::enabled() && jit::host_supported());  // compiled unless TILEVK_JIT=0
        const uint32_t groups = 3;
        std::vector<uint32_t> x = inputs(size_t(n) * groups, n), y(x.size() * kWords, 0xDEADu);
        Bindings b;
        b.set(0, 0, 0, storage(x));
        b.set(0, 1, 0, storage(y));
        Scratch s;
        dispatch(*p, b, 0, groups, groups, s);
        for (uint32_t g = 0; g < groups; ++g) {
            const std::vector<uint32_t> want = model(x.data() + size_t(g) * n, n);
            for (uint32_t i = 0; i < n; ++i)
                for (uint32_t w = 0; w < kWords; ++w) {
                    // lane 5 of a partial subgroup may not exist: its broadcast is undefined
                    if (w == 7 && i - i % kSubgroupSize + 5 >= n) continue;
                    ASSERT_EQ(y[(size_t(g) * n + i) * kWords + w], want[size_t(i) * kWords + w])
                        << "workgroup " << g << " invocation " << i << " word " << w << " (v = " << x[g * n + i] << ")";
                }
        }
    }
}

// Subgroup operations in a vertex or fragment shader are refused by name (VkPhysicalDeviceSubgroupProperties
// lists the compute stage only).
TEST(ShaderSubgroup, OtherStagesAreRefusedByName) {
    const std::vector<uint32_t> spv = compile_glsl(Stage::Fragment, R"(#version 450
#extension GL_KHR_shader_subgroup_basic : require
layout(location = 0) out vec4 o;
void main() { o = vec4(subgroupElect() ? 1.0 : 0.0); })",
                                                   true);
    ASSERT_FALSE(spv.empty());
    const Result r = Program::create(spv, Stage::Fragment, "main", {});
    EXPECT_FALSE(r);
    EXPECT_NE(r.error.find("OpGroupNonUniformElect in a fragment shader"), std::string::npos) << r.error;
}
