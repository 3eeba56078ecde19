// Interpreter kernels: moves, selects, float and integer arithmetic, comparisons, bit operations.
#pragma once

#include "shader/exec_kernels.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
// Whole-register operations (one vector expression over the 16 lanes), dispatched directly by execute()'s loop.
#define TILEVK_EXEC_VECTOR_OPS(X)                   \
    X(Mov, VOP1(VU, a))                             \
    X(FAdd, VOP2(VF, a + b))                        \
    X(FSub, VOP2(VF, a - b))                        \
    X(FMul, VOP2(VF, a* b))                         \
    X(FDiv, VOP2(VF, a / b))                        \
    X(FNeg, VOP1(VU, a ^ 0x80000000u))              \
    X(FAbs, VOP1(VU, a & 0x7fffffffu))              \
    X(FMin, VOP2(VF, ((a < b) | (b != b)) ? a : b)) \
    X(FMax, VOP2(VF, ((a > b) | (b != b)) ? a : b)) \
    X(FOrdEq, VOP2(VF, VU(a == b)))                 \
    X(FOrdNe, VOP2(VF, VU((a < b) | (a > b))))      \
    X(FOrdLt, VOP2(VF, VU(a < b)))                  \
    X(FOrdLe, VOP2(VF, VU(a <= b)))                 \
    X(FOrdGt, VOP2(VF, VU(a > b)))                  \
    X(FOrdGe, VOP2(VF, VU(a >= b)))                 \
    X(FUnordEq, VOP2(VF, ~VU((a < b) | (a > b))))   \
    X(FUnordNe, VOP2(VF, ~VU(a == b)))              \
    X(FUnordLt, VOP2(VF, ~VU(a >= b)))              \
    X(FUnordLe, VOP2(VF, ~VU(a > b)))               \
    X(FUnordGt, VOP2(VF, ~VU(a <= b)))              \
    X(FUnordGe, VOP2(VF, ~VU(a < b)))               \
    X(IAdd, VOP2(VU, a + b))                        \
    X(ISub, VOP2(VU, a - b))                        \
    X(IMul, VOP2(VU, a* b))                         \
    X(INeg, VOP1(VU, 0u - a))                       \
    X(And, VOP2(VU, a& b))                          \
    X(Or, VOP2(VU, a | b))                          \
    X(Xor, VOP2(VU, a ^ b))                         \
    X(Not, VOP1(VU, ~a))                            \
    X(Shl, VOP2(VU, a << (b & 31u)))                \
    X(ShrL, VOP2(VU, a >> (b & 31u)))               \
    X(ShrA, VOP2(VS, a >> (b & 31)))                \
    X(IEq, VOP2(VU, VU(a == b)))                    \
    X(INe, VOP2(VU, VU(a != b)))                    \
    X(SLt, VOP2(VS, VU(a < b)))                     \
    X(SLe, VOP2(VS, VU(a <= b)))                    \
    X(SGt, VOP2(VS, VU(a > b)))                     \
    X(SGe, VOP2(VS, VU(a >= b)))                    \
    X(ULt, VOP2(VU, VU(a < b)))                     \
    X(ULe, VOP2(VU, VU(a <= b)))                    \
    X(UGt, VOP2(VU, VU(a > b)))                     \
    X(UGe, VOP2(VU, VU(a >= b)))                    \
    X(SMin, VOP2(VS, (a < b) ? a : b))              \
    X(SMax, VOP2(VS, (a > b) ? a : b))              \
    X(UMin, VOP2(VU, (a < b) ? a : b))              \
    X(UMax, VOP2(VU, (a > b) ? a : b))

namespace tilevk::shader::exec {
namespace {

[[gnu::always_inline]] inline void op_f_mod(const Inst& in, Machine& mc) {
    F2(a[l] - b[l] * std::floor(a[l] / b[l]))
}

[[gnu::always_inline]] inline void op_fma(const Inst& in, Machine& mc) {
    f32a* __restrict d = FD;
    const f32a* __restrict a = FA, * __restrict b = FB, * __restrict c = FC;
    LANES d[l] = std::fma(a[l], b[l], c[l]);
}

[[gnu::always_inline]] inline void op_is_nan(const Inst& in, Machine& mc) {
    U1(mask((a[l] & 0x7fffffffu) > 0x7f800000u))
}

[[gnu::always_inline]] inline void op_is_inf(const Inst& in, Machine& mc) {
    U1(mask((a[l] & 0x7fffffffu) == 0x7f800000u))
}

#define TILEVK_EXEC_FLOAT_OPS(X) \
    X(FMod, op_f_mod)            \
    X(Fma, op_fma)               \
    X(IsNan, op_is_nan)          \
    X(IsInf, op_is_inf)

// division by zero: udiv gives 0xFFFFFFFF, sdiv 0 (as llvmpipe); INT_MIN / -1 = INT_MIN
[[gnu::always_inline]] inline void op_u_div(const Inst& in, Machine& mc) {
    U2(b[l] ? a[l] / b[l] : 0xFFFFFFFFu)
}

[[gnu::always_inline]] inline void op_u_mod(const Inst& in, Machine& mc) {
    U2(b[l] ? a[l] % b[l] : 0xFFFFFFFFu)
}

[[gnu::always_inline]] inline void op_s_div(const Inst& in, Machine& mc) {
    S2(b[l] == 0 ? 0 : (b[l] == -1 ? int32_t(0u - uint32_t(a[l])) : a[l] / b[l]))
}

[[gnu::always_inline]] inline void op_s_rem(const Inst& in, Machine& mc) {
    S2(b[l] == 0 || b[l] == -1 ? 0 : a[l] % b[l])
}

[[gnu::always_inline]] inline void op_s_mod(const Inst& in, Machine& mc) {
    // result has the sign of b
    uint32_t* __restrict d = D;
    const i32a* __restrict a = SA, * __restrict b = SB;
    LANES {
        int32_t r = (b[l] == 0 || b[l] == -1) ? 0 : a[l] % b[l];
        if (r != 0 && ((r < 0) != (b[l] < 0))) r += b[l];
        d[l] = uint32_t(r);
    }
}

[[gnu::always_inline]] inline void op_s_abs(const Inst& in, Machine& mc) {
    U1(int32_t(a[l]) < 0 ? 0u - a[l] : a[l])
}

[[gnu::always_inline]] inline void op_s_sign(const Inst& in, Machine& mc) {
    U1(int32_t(a[l]) > 0 ? 1u : int32_t(a[l]) < 0 ? ~0u : 0u)
}

[[gnu::always_inline]] inline void op_bit_count(const Inst& in, Machine& mc) {
    U1(uint32_t(std::popcount(a[l])))
}

[[gnu::always_inline]] inline void op_bit_reverse(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES {
        uint32_t x = a[l], r = 0;
        for (int i = 0; i < 32; ++i) r |= ((x >> i) & 1u) << (31 - i);
        d[l] = r;
    }
}

[[gnu::always_inline]] inline void op_find_lsb(const Inst& in, Machine& mc) {
    U1(a[l] ? uint32_t(std::countr_zero(a[l])) : ~0u)
}

[[gnu::always_inline]] inline void op_find_u_msb(const Inst& in, Machine& mc) {
    U1(a[l] ? uint32_t(31 - std::countl_zero(a[l])) : ~0u)
}

[[gnu::always_inline]] inline void op_find_s_msb(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES {
        uint32_t x = int32_t(a[l]) < 0 ? ~a[l] : a[l];
        d[l] = x ? uint32_t(31 - std::countl_zero(x)) : ~0u;
    }
}

[[gnu::always_inline]] inline void op_bfe_u(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A, * __restrict b = B, * __restrict c = C;
    bool sgn = in.op == Op::BfeS;
    LANES {
        uint32_t off = b[l] & 31, cnt = std::min(c[l], 32u - off);
        if (cnt == 0) {
            d[l] = 0;
            continue;
        }
        uint32_t v = (a[l] >> off) & (cnt == 32 ? ~0u : ((1u << cnt) - 1));
        if (sgn && cnt < 32 && (v >> (cnt - 1)) & 1) v |= ~0u << cnt;
        d[l] = v;
    }
}

[[gnu::always_inline]] inline void op_bfi(const Inst& in, Machine& mc) {
    // d = base with bits [off, off+count) replaced by insert's low bits; operands a, b, c, count in n
    uint32_t* __restrict d = D;
    const uint32_t *a = A, *b = B, *c = C, *n = mc.R + size_t(in.imm) * kLanes;
    LANES {
        uint32_t off = c[l] & 31, cnt = std::min(n[l], 32u - off);
        uint32_t m = (cnt == 32 ? ~0u : ((1u << cnt) - 1)) << off;
        d[l] = (a[l] & ~m) | ((b[l] << off) & m);
    }
}

#define TILEVK_EXEC_INT_OPS(X)    \
    X(UDiv, op_u_div)             \
    X(UMod, op_u_mod)             \
    X(SDiv, op_s_div)             \
    X(SRem, op_s_rem)             \
    X(SMod, op_s_mod)             \
    X(SAbs, op_s_abs)             \
    X(SSign, op_s_sign)           \
    X(BitCount, op_bit_count)     \
    X(BitReverse, op_bit_reverse) \
    X(FindLsb, op_find_lsb)       \
    X(FindUMsb, op_find_u_msb)    \
    X(FindSMsb, op_find_s_msb)    \
    X(BfeU, op_bfe_u)             \
    X(BfeS, op_bfe_u)             \
    X(Bfi, op_bfi)

}  // namespace
}  // namespace tilevk::shader::exec
