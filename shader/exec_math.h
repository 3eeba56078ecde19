// Interpreter kernels: conversions, GLSL.std.450 maths, packing, derivatives.
#pragma once

#include "format/texel_codec.h"
#include "shader/exec_kernels.h"
#include "shader/exec_libm.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

[[gnu::always_inline]] inline void op_f2_s(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const f32a* __restrict a = FA;
    LANES d[l] = uint32_t(f2s(a[l]));
}

[[gnu::always_inline]] inline void op_f2_u(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const f32a* __restrict a = FA;
    LANES d[l] = f2u(a[l]);
}

[[gnu::always_inline]] inline void op_s2_f(const Inst& in, Machine& mc) {
    f32a* __restrict d = FD;
    const i32a* a = SA;
    LANES d[l] = float(a[l]);
}

[[gnu::always_inline]] inline void op_u2_f(const Inst& in, Machine& mc) {
    f32a* __restrict d = FD;
    const uint32_t* __restrict a = A;
    LANES d[l] = float(a[l]);
}

[[gnu::always_inline]] inline void op_floor(const Inst& in, Machine& mc) {
    F1(std::floor(a[l]))
}

[[gnu::always_inline]] inline void op_ceil(const Inst& in, Machine& mc) {
    F1(std::ceil(a[l]))
}

[[gnu::always_inline]] inline void op_trunc(const Inst& in, Machine& mc) {
    F1(std::trunc(a[l]))
}

[[gnu::always_inline]] inline void op_round(const Inst& in, Machine& mc) {
    F1(round_even(a[l]))  // GLSL round: halfway direction is implementation-defined
}

[[gnu::always_inline]] inline void op_round_even(const Inst& in, Machine& mc) {
    F1(round_even(a[l]))
}

// fract(x) = x - floor(x)
[[gnu::always_inline]] inline void op_fract(const Inst& in, Machine& mc) {
    F1(a[l] - std::floor(a[l]))
}

[[gnu::always_inline]] inline void op_f_sign(const Inst& in, Machine& mc) {
    F1(a[l] > 0.0f ? 1.0f : a[l] < 0.0f ? -1.0f : a[l] * 0.0f)
}

[[gnu::always_inline]] inline void op_sqrt(const Inst& in, Machine& mc) {
    F1(std::sqrt(a[l]))
}

[[gnu::always_inline]] inline void op_inv_sqrt(const Inst& in, Machine& mc) {
    F1(1.0f / std::sqrt(a[l]))
}

[[gnu::always_inline]] inline void op_f_clamp(const Inst& in, Machine& mc) {
    // clamp(x, lo, hi) = min(max(x, lo), hi)
    f32a* __restrict d = FD;
    const f32a* __restrict a = FA, * __restrict b = FB, * __restrict c = FC;
    LANES d[l] = min_f(max_f(a[l], b[l]), c[l]);
}

[[gnu::always_inline]] inline void op_step(const Inst& in, Machine& mc) {
    F2(b[l] < a[l] ? 0.0f : 1.0f)  // step(edge a, x b)
}

[[gnu::always_inline]] inline void op_smooth_step(const Inst& in, Machine& mc) {
    // t = clamp((x - e0) / (e1 - e0), 0, 1); t * t * (3 - 2 * t)
    f32a* __restrict d = FD;
    const f32a* __restrict a = FA, * __restrict b = FB, * __restrict c = FC;
    LANES {
        float t = min_f(max_f((c[l] - a[l]) / (b[l] - a[l]), 0.0f), 1.0f);
        d[l] = t * t * (3.0f - 2.0f * t);
    }
}

[[gnu::always_inline]] inline void op_ldexp(const Inst& in, Machine& mc) {
    f32a* __restrict d = FD;
    const f32a* __restrict a = FA;
    const i32a* b = SB;
    LANES d[l] = std::ldexp(a[l], std::clamp(b[l], -300, 300));
}

[[gnu::always_inline]] inline void op_frexp_sig(const Inst& in, Machine& mc) {
    // DAZ applies to the comparison: a denormal counts as zero and is returned unchanged (as lavapipe)
    uint32_t* __restrict d = D;
    const f32a* __restrict a = FA;
    LANES {
        float x = a[l], ax = std::fabs(x);
        uint32_t b = std::bit_cast<uint32_t>(x);
        d[l] = (0.0f < ax && ax <= std::numeric_limits<float>::max()) ? (b & 0x807fffffu) | 0x3f000000u : b;
    }
}

[[gnu::always_inline]] inline void op_frexp_exp(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const f32a* __restrict a = FA;
    LANES {
        float ax = std::fabs(a[l]);
        d[l] = (std::bit_cast<uint32_t>(ax) >> 23) - (ax != 0.0f ? 126u : 0u);
    }
}

// clang-format off (a list expansion without a semicolon)
// op_libm_<Op>: one kernel per op of exec_libm.h's list, dispatched by execute() from the same list.
#define TILEVK_EXEC_LIBM1(op, expr)                                                \
    [[gnu::always_inline]] inline void op_libm_##op(const Inst& in, Machine& mc) { \
        F1(expr)                                                                   \
    }
#define TILEVK_EXEC_LIBM2(op, expr)                                                \
    [[gnu::always_inline]] inline void op_libm_##op(const Inst& in, Machine& mc) { \
        F2(expr)                                                                   \
    }
TILEVK_LIBM_OPS(TILEVK_EXEC_LIBM1, TILEVK_EXEC_LIBM2)
#undef TILEVK_EXEC_LIBM1
#undef TILEVK_EXEC_LIBM2
// op_gallivm_<Op>: the eight-lane function of exec_libm.h's gallivm list on each half (a one-operand op reads its
// first operand as the second, which it ignores: in.b names no register then).
#define TILEVK_EXEC_GALLIVM(op, fn)                                                   \
    [[gnu::always_inline]] inline void op_gallivm_##op(const Inst& in, Machine& mc) { \
        static_assert(kLanes == 16);                                                  \
        float* d = reinterpret_cast<float*>(D);                                       \
        const float* a = reinterpret_cast<const float*>(A);                           \
        const float* b = in.b == kNoReg ? a : reinterpret_cast<const float*>(B);      \
        fn(d, a, b);                                                                  \
        fn(d + 8, a + 8, b + 8);                                                      \
    }
TILEVK_GALLIVM_OPS(TILEVK_EXEC_GALLIVM)
#undef TILEVK_EXEC_GALLIVM
// clang-format on

#define TILEVK_EXEC_MATH_OPS(X)   \
    X(F2S, op_f2_s)               \
    X(F2U, op_f2_u)               \
    X(S2F, op_s2_f)               \
    X(U2F, op_u2_f)               \
    X(Floor, op_floor)            \
    X(Ceil, op_ceil)              \
    X(Trunc, op_trunc)            \
    X(Round, op_round)            \
    X(RoundEven, op_round_even)   \
    X(Fract, op_fract)            \
    X(FSign, op_f_sign)           \
    X(Sqrt, op_sqrt)              \
    X(InvSqrt, op_inv_sqrt)       \
    X(FClamp, op_f_clamp)         \
    X(Step, op_step)              \
    X(SmoothStep, op_smooth_step) \
    X(Ldexp, op_ldexp)            \
    X(FrexpSig, op_frexp_sig)     \
    X(FrexpExp, op_frexp_exp)

[[gnu::always_inline]] inline void op_mul_hi_u(const Inst& in, Machine& mc) {
    U2(uint32_t((uint64_t(a[l]) * uint64_t(b[l])) >> 32))
}

[[gnu::always_inline]] inline void op_mul_hi_s(const Inst& in, Machine& mc) {
    S2(uint32_t(uint64_t(int64_t(a[l]) * int64_t(b[l])) >> 32))
}

[[gnu::always_inline]] inline void op_pack_half2x16(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const f32a* __restrict a = FA, * __restrict b = FB;
    LANES d[l] = float_to_half(a[l]) | (float_to_half(b[l]) << 16);
}

// unpackHalf2x16: lavapipe lowers it to an fpext of each half (nir lower_pack_split: f2f32(u2u16(a))), the same
// conversion as OpFConvert, so both go through the texel codec's half_to_float (NaN payloads kept). The result is
// moved as bits, so that no float copy can touch a NaN.
[[gnu::always_inline]] inline void op_unpack_half2x16_lo(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES d[l] = std::bit_cast<uint32_t>(format::half_to_float(uint16_t(a[l] & 0xffff)));
}

[[gnu::always_inline]] inline void op_unpack_half2x16_hi(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES d[l] = std::bit_cast<uint32_t>(format::half_to_float(uint16_t(a[l] >> 16)));
}

// packUnorm/packSnorm of kCount components of kBits each, the first in the low bits: unorm
// round(clamp(c, 0, 1) * (2^kBits - 1)), snorm round(clamp(c, -1, 1) * (2^(kBits - 1) - 1)).
template <int kCount, int kBits>
[[gnu::always_inline]] inline void pack_norm(const Inst& in, Machine& mc, bool sn) {
    constexpr float kUnormMax = float((1u << kBits) - 1), kSnormMax = float((1u << (kBits - 1)) - 1);
    constexpr uint32_t kMask = (1u << kBits) - 1;
    uint32_t* __restrict d = D;
    LANES {
        uint32_t r = 0;
        for (int i = 0; i < kCount; ++i) {
            float c = reinterpret_cast<const f32a*>(mc.R + size_t(in.a + i) * kLanes)[l];
            int v = sn ? int(round_even(std::fmin(std::fmax(c, -1.0f), 1.0f) * kSnormMax))
                       : int(round_even(std::fmin(std::fmax(c, 0.0f), 1.0f) * kUnormMax));
            r |= (uint32_t(v) & kMask) << (kBits * i);
        }
        d[l] = r;
    }
}

[[gnu::always_inline]] inline void op_pack_unorm4x8(const Inst& in, Machine& mc) {
    pack_norm<4, 8>(in, mc, in.op == Op::PackSnorm4x8);
}

[[gnu::always_inline]] inline void op_pack_unorm2x16(const Inst& in, Machine& mc) {
    pack_norm<2, 16>(in, mc, in.op == Op::PackSnorm2x16);
}

[[gnu::always_inline]] inline void op_unpack_unorm4x8(const Inst& in, Machine& mc) {
    F1(float((std::bit_cast<uint32_t>(a[l]) >> (8 * in.imm)) & 0xff) / 255.0f)
}

[[gnu::always_inline]] inline void op_unpack_snorm4x8(const Inst& in, Machine& mc) {
    F1(std::fmax(float(int8_t((std::bit_cast<uint32_t>(a[l]) >> (8 * in.imm)) & 0xff)) / 127.0f, -1.0f))
}

// 16-bit half `index` of `word` (0: low, 1: high); 0 for any other index, where a plain shift would be undefined
// (a translated program only uses 0 and 1; the op-by-op tests also try others).
inline uint32_t half_word(uint32_t word, uint32_t index) {
    return index < 2 ? (word >> (16 * index)) & 0xffff : 0;
}

[[gnu::always_inline]] inline void op_unpack_unorm2x16(const Inst& in, Machine& mc) {
    F1(float(half_word(std::bit_cast<uint32_t>(a[l]), in.imm)) / 65535.0f)
}

[[gnu::always_inline]] inline void op_unpack_snorm2x16(const Inst& in, Machine& mc) {
    F1(std::fmax(float(int16_t(half_word(std::bit_cast<uint32_t>(a[l]), in.imm))) / 32767.0f, -1.0f))
}

// fine: right - left in this lane's row; bottom - top in this lane's column
[[gnu::always_inline]] inline void op_ddx_fine(const Inst& in, Machine& mc) {
    F1(a[left(l) + 1] - a[left(l)])
}

[[gnu::always_inline]] inline void op_ddy_fine(const Inst& in, Machine& mc) {
    F1(a[top(l) + 2] - a[top(l)])
}

// coarse: the quad's top row / left column
[[gnu::always_inline]] inline void op_ddx_coarse(const Inst& in, Machine& mc) {
    F1(a[(l & ~3) + 1] - a[l & ~3])
}

[[gnu::always_inline]] inline void op_ddy_coarse(const Inst& in, Machine& mc) {
    F1(a[(l & ~3) + 2] - a[l & ~3])
}

#define TILEVK_EXEC_PACK_OPS(X)                \
    X(MulHiU, op_mul_hi_u)                     \
    X(MulHiS, op_mul_hi_s)                     \
    X(PackHalf2x16, op_pack_half2x16)          \
    X(UnpackHalf2x16Lo, op_unpack_half2x16_lo) \
    X(UnpackHalf2x16Hi, op_unpack_half2x16_hi) \
    X(PackUnorm4x8, op_pack_unorm4x8)          \
    X(PackSnorm4x8, op_pack_unorm4x8)          \
    X(PackUnorm2x16, op_pack_unorm2x16)        \
    X(PackSnorm2x16, op_pack_unorm2x16)        \
    X(UnpackUnorm4x8, op_unpack_unorm4x8)      \
    X(UnpackSnorm4x8, op_unpack_snorm4x8)      \
    X(UnpackUnorm2x16, op_unpack_unorm2x16)    \
    X(UnpackSnorm2x16, op_unpack_snorm2x16)    \
    X(DdxFine, op_ddx_fine)                    \
    X(DdyFine, op_ddy_fine)                    \
    X(DdxCoarse, op_ddx_coarse)                \
    X(DdyCoarse, op_ddy_coarse)

}  // namespace
}  // namespace tilevk::shader::exec
