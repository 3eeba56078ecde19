// Test helper: compute programs run as icd/execute_compute.cpp runs them — a workgroup's invocations in batches of
// kLanes in LocalInvocationIndex order, workgroups one after the other.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "glsl.h"
#include "shader/program.h"

namespace tilevk::shader::test {

// A compute program of GLSL `src`; local_x != 0 sets specialization constant 0 (local_size_x_id = 0).
inline std::shared_ptr<const Program> compute(const std::string& src, uint32_t local_x = 0, bool spirv_1_3 = false) {
    std::vector<uint32_t> spv = compile_glsl(Stage::Compute, src, spirv_1_3);
    SpecConstants spec;
    if (local_x != 0) spec.push_back({0, {local_x}});
    Result r = Program::create(spv, Stage::Compute, "main", spec);
    EXPECT_TRUE(r) << r.error;
    return r.program;
}

// The batches of one workgroup as icd/execute_compute.cpp lays them out (LocalInvocationIndex order).
inline std::vector<ComputeBatch> layout(const std::array<uint32_t, 3>& size) {
    const uint32_t n = size[0] * size[1] * size[2];
    std::vector<ComputeBatch> out((n + kLanes - 1) / kLanes);
    for (uint32_t b = 0; b < out.size(); ++b) {
        out[b].count = std::min<uint32_t>(kLanes, n - b * kLanes);
        for (uint32_t l = 0; l < uint32_t(kLanes); ++l) {
            const uint32_t i = b * kLanes + std::min(l, out[b].count - 1);
            out[b].local_index[l] = i;
            out[b].local_id[0][l] = i % size[0];
            out[b].local_id[1][l] = i / size[0] % size[1];
            out[b].local_id[2][l] = i / (size[0] * size[1]);
        }
    }
    return out;
}

// Workgroups first .. first + count - 1 of a dispatch of `total` workgroups along x.
inline void dispatch(const Program& p, const Bindings& b, uint32_t first, uint32_t count, uint32_t total, Scratch& s) {
    std::vector<ComputeBatch> batches = layout(p.interface().local_size);
    for (uint32_t g = first; g < first + count; ++g) {
        for (ComputeBatch& cb : batches) {
            cb.workgroup_id[0] = g;
            cb.num_workgroups[0] = total;
        }
        p.run_workgroup(b, batches, s);
    }
}

inline Descriptor storage(std::vector<uint32_t>& words) {
    return Descriptor{BufferView{words.data(), words.data(), words.size() * 4}};
}

}  // namespace tilevk::shader::test
