// Interpreter kernels: 64-bit integers and doubles (Op::Wide, translate_wide.cpp). A 64-bit value is two registers,
// low word then high word. Every kernel follows what llvmpipe emits for the NIR op lavapipe makes of the SPIR-V one
// (gallivm/lp_bld_nir.c): IEEE double arithmetic under the same FTZ/DAZ the run sets (MXCSR applies to doubles),
// shifts masked to 0..63, division by 0 as do_int_divide / do_int_mod, conversions as lavapipe's LLVM code gives
// them. These programs stay in the interpreter (jit/analysis.cpp has no row for Op::Wide).
#pragma once

#include <bit>
#include <cmath>
#include <cstring>

#include "shader/exec_kernels.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

inline double as_f64(uint64_t u) {
    return std::bit_cast<double>(u);
}
inline uint64_t as_u64(double f) {
    return std::bit_cast<uint64_t>(f);
}
inline float as_f32(uint64_t u) {
    return std::bit_cast<float>(uint32_t(u));
}
// cvttsd2si / cvttss2si with a 64-bit destination: out of range and NaN give INT64_MIN.
template <typename F>
inline uint64_t trunc_s64(F x) {
    if (!(x >= F(-9223372036854775808.0) && x < F(9223372036854775808.0))) return uint64_t(1) << 63;
    return uint64_t(int64_t(x));
}
// fptoui as lavapipe's LLVM code gives it (measured against lavapipe 22.3, cts types.float64.*): x in (-1, 2^n)
// truncates; below, above, infinite or NaN gives all ones, for 32- and 64-bit results alike.
template <typename F>
inline uint64_t trunc_u(F x, int bits) {
    const F limit = bits == 64 ? F(18446744073709551616.0) : F(4294967296.0);
    if (!(x > F(-1.0) && x < limit)) return bits == 64 ? ~uint64_t(0) : 0xFFFFFFFFu;
    return uint64_t(x);
}
// (a, b): sdiv by 0 gives 0, udiv and both remainders by 0 all ones (do_int_divide / do_int_mod OR the zero mask
// in); INT64_MIN / -1 divides by 1 instead (get_signed_divisor).
inline uint64_t s_div64(int64_t a, int64_t b) {
    if (b == 0) return 0;
    if (b == -1 && a == INT64_MIN) b = 1;
    return uint64_t(a / b);
}
inline uint64_t s_rem64(int64_t a, int64_t b) {
    if (b == 0) return ~uint64_t(0);
    if (b == -1) return 0;
    return uint64_t(a % b);
}
inline double min_d(double a, double b) {
    return (a < b || b != b) ? a : b;
}
inline double max_d(double a, double b) {
    return (a > b || b != b) ? a : b;
}

// Integer ops: a, b 64-bit (shift counts: the low word of b, masked)
inline uint64_t wide_int(WideOp op, uint64_t a, uint64_t b) {
    const auto sa = int64_t(a), sb = int64_t(b);
    switch (op) {
        case WideOp::IAdd:
            return a + b;
        case WideOp::ISub:
            return a - b;
        case WideOp::IMul:
            return a * b;
        case WideOp::SDiv:
            return s_div64(sa, sb);
        case WideOp::UDiv:
            return b ? a / b : ~uint64_t(0);
        case WideOp::SRem:
            return s_rem64(sa, sb);
        // imod is irem for 64 bits in lavapipe 22.3 (do_int_mod: LLVM srem for both; measured, cts types.int64.*),
        // where the 32-bit OpSMod takes the divisor's sign
        case WideOp::SMod:
            return s_rem64(sa, sb);
        case WideOp::UMod:
            return b ? a % b : ~uint64_t(0);
        case WideOp::And:
            return a & b;
        case WideOp::Or:
            return a | b;
        case WideOp::Xor:
            return a ^ b;
        case WideOp::SMin:
            return sa < sb ? a : b;
        case WideOp::SMax:
            return sa > sb ? a : b;
        case WideOp::UMin:
            return a < b ? a : b;
        case WideOp::UMax:
            return a > b ? a : b;
        case WideOp::Shl:
            return a << (b & 63);
        case WideOp::ShrL:
            return a >> (b & 63);
        case WideOp::ShrA:
            return uint64_t(sa >> (b & 63));
        case WideOp::INeg:
            return 0 - a;
        case WideOp::Not:
            return ~a;
        case WideOp::SAbs:
            return sa < 0 ? 0 - a : a;
        case WideOp::SSign:
            return sa > 0 ? 1 : sa < 0 ? ~uint64_t(0) : 0;
        default:
            return 0;
    }
}

// Double ops: a, b, c doubles; the result's bits.
inline uint64_t wide_float(WideOp op, double a, double b, double c) {
    switch (op) {
        case WideOp::FAdd:
            return as_u64(a + b);
        case WideOp::FSub:
            return as_u64(a - b);
        case WideOp::FMul:
            return as_u64(a * b);
        case WideOp::FDiv:
            return as_u64(a / b);
        case WideOp::FMod:
            return as_u64(a - b * std::floor(a / b));  // lower_fmod
        case WideOp::FRem:
            return as_u64(std::fmod(a, b));  // LLVM frem
        case WideOp::FMin:
            return as_u64(min_d(a, b));
        case WideOp::FMax:
            return as_u64(max_d(a, b));
        case WideOp::Step:
            return as_u64(b < a ? 0.0 : 1.0);  // step(edge a, x b)
        case WideOp::FNeg:
            return as_u64(a) ^ (uint64_t(1) << 63);
        case WideOp::FAbs:
            return as_u64(a) & ~(uint64_t(1) << 63);
        case WideOp::Floor:
            return as_u64(std::floor(a));
        case WideOp::Ceil:
            return as_u64(std::ceil(a));
        case WideOp::Trunc:
            return as_u64(std::trunc(a));
        case WideOp::RoundEven:
            return as_u64(std::nearbyint(a));
        case WideOp::Fract:
            return as_u64(a - std::floor(a));
        case WideOp::FSign:
            return as_u64(a > 0.0 ? 1.0 : a < 0.0 ? -1.0 : 0.0);  // lp_build_sgn: ±0, NaN -> +0
        case WideOp::Sqrt:
            return as_u64(std::sqrt(a));
        case WideOp::InvSqrt:
            return as_u64(1.0 / std::sqrt(a));
        case WideOp::FClamp:
            return as_u64(min_d(max_d(a, b), c));
        case WideOp::FFma:
            return as_u64(std::fma(a, b, c));
        case WideOp::SmoothStep: {  // smoothstep(e0 a, e1 b, x c)
            const double t = min_d(max_d((c - a) / (b - a), 0.0), 1.0);
            return as_u64(t * (t * (3.0 - 2.0 * t)));  // vtn's order (measured: (t * t) * ... differs by an ulp)
        }
        default:
            return 0;
    }
}

// Comparisons and tests: a 32-bit mask from 64-bit a, b.
inline uint32_t wide_compare(WideOp op, uint64_t a, uint64_t b) {
    const double fa = as_f64(a), fb = as_f64(b);
    bool r = false;
    switch (op) {
        case WideOp::IEq:
            r = a == b;
            break;
        case WideOp::INe:
            r = a != b;
            break;
        case WideOp::SLt:
            r = int64_t(a) < int64_t(b);
            break;
        case WideOp::SLe:
            r = int64_t(a) <= int64_t(b);
            break;
        case WideOp::ULt:
            r = a < b;
            break;
        case WideOp::ULe:
            r = a <= b;
            break;
        case WideOp::FOrdEq:
            r = fa == fb;
            break;
        case WideOp::FOrdNe:
            r = fa < fb || fa > fb;
            break;
        case WideOp::FOrdLt:
            r = fa < fb;
            break;
        case WideOp::FOrdLe:
            r = fa <= fb;
            break;
        case WideOp::FUnordEq:
            r = !(fa < fb || fa > fb);
            break;
        case WideOp::FUnordNe:
            r = !(fa == fb);
            break;
        case WideOp::FUnordLt:
            r = !(fa >= fb);
            break;
        case WideOp::FUnordLe:
            r = !(fa > fb);
            break;
        case WideOp::IsNan:
            r = fa != fa;
            break;
        case WideOp::IsInf:
            r = std::fabs(fa) == INFINITY;
            break;
        case WideOp::BitCount:
            return uint32_t(std::popcount(a));
        default:
            break;
    }
    return r ? ~0u : 0u;
}

// Conversions: a is the source's bits (32 or 64), the result's bits.
inline uint64_t wide_convert(WideOp op, uint64_t a) {
    switch (op) {
        case WideOp::F32ToF64:
            return as_u64(double(as_f32(a)));
        case WideOp::S32ToF64:
            return as_u64(double(int32_t(a)));
        case WideOp::U32ToF64:
            return as_u64(double(uint32_t(a)));
        case WideOp::F32ToS64:
            return trunc_s64(as_f32(a));
        case WideOp::F32ToU64:
            return trunc_u(as_f32(a), 64);
        case WideOp::F64ToF32:
            return std::bit_cast<uint32_t>(float(as_f64(a)));
        case WideOp::F64ToS32: {  // cvttpd2dq: out of range and NaN give INT32_MIN
            const double x = as_f64(a);
            return (x > -2147483649.0 && x < 2147483648.0) ? uint32_t(int32_t(x)) : 0x80000000u;
        }
        case WideOp::F64ToU32:
            return trunc_u(as_f64(a), 32);
        case WideOp::S64ToF32:
            return std::bit_cast<uint32_t>(float(int64_t(a)));
        case WideOp::U64ToF32:
            return std::bit_cast<uint32_t>(float(a));
        case WideOp::S64ToF64:
            return as_u64(double(int64_t(a)));
        case WideOp::U64ToF64:
            return as_u64(double(a));
        case WideOp::F64ToS64:
            return trunc_s64(as_f64(a));
        case WideOp::F64ToU64:
            return trunc_u(as_f64(a), 64);
        default:
            return 0;
    }
}

inline uint64_t wide_lane(WideOp op, uint64_t a, uint64_t b, uint64_t c) {
    if (op <= WideOp::SSign) return wide_int(op, a, b);
    if (op <= WideOp::SmoothStep) return wide_float(op, as_f64(a), as_f64(b), as_f64(c));
    if (op <= WideOp::BitCount) return wide_compare(op, a, b);
    return wide_convert(op, a);
}

// One Op::Wide: operands read whole first (d may alias an operand register).
[[gnu::always_inline]] inline void op_wide(const Inst& in, Machine& mc) {
    const auto op = WideOp(in.pad);
    const uint32_t shape = wide_shape(op);
    uint64_t v[3][kLanes] = {};
    const uint32_t src[3] = {in.a, in.b, in.c};
    for (int k = 0; k < 3; ++k) {
        if (src[k] == kNoReg) continue;
        const uint32_t* lo = mc.R + size_t(src[k]) * kLanes;
        const bool wide = (shape >> (k + 1)) & 1;
        LANES v[k][l] = wide ? (uint64_t(lo[kLanes + l]) << 32) | lo[l] : lo[l];
    }
    uint32_t* d = D;
    uint64_t r[kLanes];
    LANES r[l] = wide_lane(op, v[0][l], v[1][l], v[2][l]);
    LANES d[l] = uint32_t(r[l]);
    if (shape & 1) LANES d[kLanes + l] = uint32_t(r[l] >> 32);
}

#define TILEVK_EXEC_WIDE_OPS(X) X(Wide, op_wide)

}  // namespace
}  // namespace tilevk::shader::exec
