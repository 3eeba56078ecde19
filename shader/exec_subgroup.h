// Interpreter kernels: compute's subgroup operations (SPIR-V GroupNonUniform basic, vote and ballot).
//
// A subgroup is kSubgroupSize consecutive lanes of a batch (program.h). C is the mask of the lanes taking part (the
// block's execution mask); lanes outside it take part in nothing, but get the subgroup's result too (their
// registers are not observed, and in loops the translator keeps what they had). Every kernel handles each subgroup
// of the batch on its own.
#pragma once

#include <bit>
#include <cstring>

#include "shader/exec_kernels.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

constexpr int kSubgroupsPerBatch = kLanes / int(kSubgroupSize);

// The active lanes of subgroup g as bits (bit i = lane g * kSubgroupSize + i).
inline uint32_t active_bits(const uint32_t* mask, int g) {
    uint32_t bits = 0;
    for (uint32_t i = 0; i < kSubgroupSize; ++i)
        if (mask[g * int(kSubgroupSize) + int(i)] != 0) bits |= 1u << i;
    return bits;
}

// Sets every lane of subgroup g to v.
inline void fill_subgroup(uint32_t* d, int g, uint32_t v) {
    for (uint32_t i = 0; i < kSubgroupSize; ++i) d[g * int(kSubgroupSize) + int(i)] = v;
}

[[gnu::always_inline]] inline void op_sg_lane_id(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    LANES d[l] = uint32_t(l) % kSubgroupSize;
}

[[gnu::always_inline]] inline void op_sg_elect(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t* c = C;
    for (int g = 0; g < kSubgroupsPerBatch; ++g) {
        const uint32_t active = active_bits(c, g);
        for (uint32_t i = 0; i < kSubgroupSize; ++i)
            d[g * int(kSubgroupSize) + int(i)] = active != 0 && std::countr_zero(active) == int(i) ? ~0u : 0u;
    }
}

// The active lanes of subgroup g whose predicate a is true.
inline uint32_t true_bits(const uint32_t* a, const uint32_t* c, int g) {
    uint32_t bits = 0;
    for (uint32_t i = 0; i < kSubgroupSize; ++i) {
        const int l = g * int(kSubgroupSize) + int(i);
        if (c[l] != 0 && a[l] != 0) bits |= 1u << i;
    }
    return bits;
}

[[gnu::always_inline]] inline void op_sg_all(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    for (int g = 0; g < kSubgroupsPerBatch; ++g)
        fill_subgroup(d, g, true_bits(a, c, g) == active_bits(c, g) ? ~0u : 0u);
}

[[gnu::always_inline]] inline void op_sg_any(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    for (int g = 0; g < kSubgroupsPerBatch; ++g) fill_subgroup(d, g, true_bits(a, c, g) != 0 ? ~0u : 0u);
}

[[gnu::always_inline]] inline void op_sg_all_equal(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    const bool as_float = in.imm != 0;
    for (int g = 0; g < kSubgroupsPerBatch; ++g) {
        const uint32_t active = active_bits(c, g);
        bool equal = true;
        if (active != 0) {
            const uint32_t first = a[g * int(kSubgroupSize) + std::countr_zero(active)];
            for (uint32_t i = 0; i < kSubgroupSize; ++i) {
                if ((active >> i & 1) == 0) continue;
                const uint32_t v = a[g * int(kSubgroupSize) + int(i)];
                // floats: ordered == (a NaN equals nothing, -0 equals +0)
                equal &= as_float ? std::bit_cast<float>(v) == std::bit_cast<float>(first) : v == first;
            }
        }
        fill_subgroup(d, g, equal ? ~0u : 0u);
    }
}

[[gnu::always_inline]] inline void op_sg_broadcast(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *b = B, *c = C;
    uint32_t values[kLanes];  // d may be a itself
    std::memcpy(values, a, sizeof values);
    for (int g = 0; g < kSubgroupsPerBatch; ++g) {
        const uint32_t active = active_bits(c, g);
        const int first = g * int(kSubgroupSize) + (active != 0 ? std::countr_zero(active) : 0);
        const uint32_t from = b[first] % kSubgroupSize;  // the id is dynamically uniform; past the subgroup: undefined
        fill_subgroup(d, g, values[g * int(kSubgroupSize) + int(from)]);
    }
}

[[gnu::always_inline]] inline void op_sg_broadcast_first(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    uint32_t values[kLanes];
    std::memcpy(values, a, sizeof values);
    for (int g = 0; g < kSubgroupsPerBatch; ++g) {
        const uint32_t active = active_bits(c, g);
        fill_subgroup(d, g, values[g * int(kSubgroupSize) + (active != 0 ? std::countr_zero(active) : 0)]);
    }
}

[[gnu::always_inline]] inline void op_sg_ballot(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    uint32_t bits[kSubgroupsPerBatch];
    for (int g = 0; g < kSubgroupsPerBatch; ++g) bits[g] = true_bits(a, c, g);
    for (int g = 0; g < kSubgroupsPerBatch; ++g) fill_subgroup(d, g, bits[g]);
}

#define TILEVK_EXEC_SUBGROUP_OPS(X)            \
    X(SgLaneId, op_sg_lane_id)                 \
    X(SgElect, op_sg_elect)                    \
    X(SgAll, op_sg_all)                        \
    X(SgAny, op_sg_any)                        \
    X(SgAllEqual, op_sg_all_equal)             \
    X(SgBroadcast, op_sg_broadcast)            \
    X(SgBroadcastFirst, op_sg_broadcast_first) \
    X(SgBallot, op_sg_ballot)

}  // namespace
}  // namespace tilevk::shader::exec
