// Building blocks of the interpreter (exec.cpp and its instruction families exec_*.h): whole-register vector
// types, scalar helpers with lavapipe's semantics, and the lane-loop macros over an instruction's operands D, A, B,
// C (registers of `in` in the register file R). Included by exec.cpp only, after every other header.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "shader/ir.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

using f32a = float __attribute__((may_alias));
// Whole-register vector types (GCC vector extension): one operation over all 16 lanes, AVX2 or SSE alike.
using VF = float __attribute__((vector_size(64)));
using VU = uint32_t __attribute__((vector_size(64)));
using VS = int32_t __attribute__((vector_size(64)));
template <typename V>
inline V vload(const uint32_t* p) {
    V v;
    std::memcpy(&v, p, sizeof(v));
    return v;
}
template <typename V>
inline void vstore(uint32_t* p, V v) {
    std::memcpy(p, &v, sizeof(v));
}
using i32a = int32_t __attribute__((may_alias));

#define LANES for (int l = 0; l < kLanes; ++l)

// float -> half, round to nearest even (GLSL packHalf2x16)
inline uint32_t float_to_half(float f) {
    uint32_t x = std::bit_cast<uint32_t>(f);
    uint32_t s = (x >> 16) & 0x8000;
    uint32_t e = (x >> 23) & 0xff;
    uint32_t m = x & 0x7fffff;
    if (e == 0xff) return s | 0x7c00 | (m ? 0x200 : 0);
    int ne = int(e) - 127 + 15;
    if (ne >= 31) return s | 0x7c00;
    if (ne <= 0) {
        if (ne < -10) return s;
        m |= 0x800000;
        uint32_t shift = uint32_t(14 - ne);
        uint32_t hm = m >> shift;
        uint32_t rem = m & ((1u << shift) - 1), half = 1u << (shift - 1);
        if (rem > half || (rem == half && (hm & 1))) ++hm;
        return s | hm;
    }
    uint32_t hm = m >> 13, rem = m & 0x1fff;
    uint32_t r = s | (uint32_t(ne) << 10) | hm;
    if (rem > 0x1000 || (rem == 0x1000 && (hm & 1))) ++r;
    return r;
}

inline int32_t f2s(float x) {
    // out of range and NaN give INT32_MIN, like cvttps2dq
    if (!(x >= -2147483648.0f && x < 2147483648.0f)) return std::numeric_limits<int32_t>::min();
    return int32_t(x);
}
// float -> uint32 as lavapipe converts (measured, cts types.convert.f2u): x in (-1, 2^32) truncates, everything
// else (negative values from -1 down, 2^32 and up, infinities, NaN) gives 0xFFFFFFFF.
inline uint32_t f2u(float x) {
    if (!(x > -1.0f && x < 4294967296.0f)) return 0xFFFFFFFFu;
    return uint32_t(x);
}
inline float round_even(float x) {
    return std::nearbyint(x);
}
inline uint32_t mask(bool b) {
    return b ? ~0u : 0u;
}
// fmin/fmax semantics (a NaN operand yields the other one), in a form GCC vectorizes
inline float min_f(float a, float b) {
    return (a < b || b != b) ? a : b;
}
inline float max_f(float a, float b) {
    return (a > b || b != b) ? a : b;
}

// Quad neighbours: lane = quad*4 + (y&1)*2 + (x&1)
inline int left(int l) {
    return l & ~1;
}
inline int top(int l) {
    return l & ~2;
}

}  // namespace
}  // namespace tilevk::shader::exec

// The machine state an instruction works on: registers, SoA local memory, resolved descriptors.
namespace tilevk::shader::exec {
struct Machine {
    uint32_t* R;  // register r = R + r * kLanes
    uint32_t* M;  // local word w = M + w * kLanes
    const Descriptor* const* slots;
    uint32_t num_slots;
    uint32_t* S = nullptr;  // compute: the workgroup's shared memory, word w = S[w] (one word for every lane)
};
}  // namespace tilevk::shader::exec

// Operands of `in` in the machine `mc`.
#define D (mc.R + size_t(in.d) * kLanes)
#define A (mc.R + size_t(in.a) * kLanes)
#define B (mc.R + size_t(in.b) * kLanes)
#define C (mc.R + size_t(in.c) * kLanes)
#define FD (reinterpret_cast<f32a*>(D))
#define FA (reinterpret_cast<const f32a*>(A))
#define FB (reinterpret_cast<const f32a*>(B))
#define FC (reinterpret_cast<const f32a*>(C))
#define SA (reinterpret_cast<const i32a*>(A))
#define SB (reinterpret_cast<const i32a*>(B))
#define SC (reinterpret_cast<const i32a*>(C))
// Operands are copied into local arrays: they cannot alias, so GCC vectorizes every lane loop (register
// pointers would need alias checks it does not emit). The copies compile to plain vector loads and stores.
#define LOAD_U(x, src)                                                                                 \
    alignas(64) uint32_t x[kLanes]; /* NOLINT(bugprone-macro-parentheses): x names a declared array */ \
    std::memcpy(x, src, sizeof(x));
#define LOAD_F(x, src)                                                                              \
    alignas(64) float x[kLanes]; /* NOLINT(bugprone-macro-parentheses): x names a declared array */ \
    std::memcpy(x, src, sizeof(x));
#define LOAD_S(x, src)                                                                                \
    alignas(64) int32_t x[kLanes]; /* NOLINT(bugprone-macro-parentheses): x names a declared array */ \
    std::memcpy(x, src, sizeof(x));
#define KERNEL(DT, load_a, load_b, expr)        \
    {                                           \
        load_a load_b alignas(64) DT d[kLanes]; \
        LANES d[l] = (expr);                    \
        std::memcpy(D, d, sizeof(d));           \
    }
#define VOP2(V, expr)                       \
    {                                       \
        V a = vload<V>(A), b = vload<V>(B); \
        vstore(D, (expr));                  \
    }
#define VOP1(V, expr)      \
    {                      \
        V a = vload<V>(A); \
        vstore(D, (expr)); \
    }
#define U1(expr) KERNEL(uint32_t, LOAD_U(a, A), , expr)
#define F1(expr) KERNEL(float, LOAD_F(a, A), , expr)
#define F2(expr) KERNEL(float, LOAD_F(a, A), LOAD_F(b, B), expr)
#define FCMP(expr) KERNEL(uint32_t, LOAD_F(a, A), LOAD_F(b, B), mask(expr))
#define U2(expr) KERNEL(uint32_t, LOAD_U(a, A), LOAD_U(b, B), expr)
#define S2(expr) KERNEL(uint32_t, LOAD_S(a, A), LOAD_S(b, B), uint32_t(expr))
