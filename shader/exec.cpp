// The interpreter: one switch over pre-decoded instructions, each an inner loop over kLanes lanes that the
// compiler vectorizes (-mavx2). Runs with FTZ/DAZ like lavapipe.
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "shader/ir.h"

namespace tilevk::shader {

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

inline float half_to_float(uint32_t h) {
    uint32_t s = (h >> 15) & 1, e = (h >> 10) & 31, m = h & 1023;
    float v;
    if (e == 0)
        v = std::ldexp(float(m), -24);
    else if (e == 31)
        v = m ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
    else
        v = std::ldexp(float(m | 1024), int(e) - 25);
    return s ? -v : v;
}

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
inline uint32_t f2u(float x) {
    if (!(x > -1.0f)) return 0;  // negative and NaN -> 0
    if (x >= 4294967296.0f) return 0xFFFFFFFFu;
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

void execute(const ProgramImpl& p, Scratch::Impl& s) {
    uint32_t* R = s.regs.data();
    uint32_t* M = s.local.data();
    const Descriptor* const* slots = s.slots.data();
    const uint32_t num_slots = uint32_t(s.slots.size());
    const Inst* code = p.code.data();
    size_t pc = 0;
    uint64_t back_edges = 0;  // loop watchdog: a valid shader may loop forever; never hang the caller
    for (;;) {
        const Inst& in = code[pc++];
#define D (R + size_t(in.d) * kLanes)
#define A (R + size_t(in.a) * kLanes)
#define B (R + size_t(in.b) * kLanes)
#define C (R + size_t(in.c) * kLanes)
#define FD reinterpret_cast<f32a*>(D)
#define FA reinterpret_cast<const f32a*>(A)
#define FB reinterpret_cast<const f32a*>(B)
#define FC reinterpret_cast<const f32a*>(C)
#define SA reinterpret_cast<const i32a*>(A)
#define SB reinterpret_cast<const i32a*>(B)
#define SC reinterpret_cast<const i32a*>(C)
// Operands are copied into local arrays: they cannot alias, so GCC vectorizes every lane loop (register
// pointers would need alias checks it does not emit). The copies compile to plain vector loads and stores.
#define LOAD_U(x, src)              \
    alignas(64) uint32_t x[kLanes]; \
    std::memcpy(x, src, sizeof(x));
#define LOAD_F(x, src)           \
    alignas(64) float x[kLanes]; \
    std::memcpy(x, src, sizeof(x));
#define LOAD_S(x, src)             \
    alignas(64) int32_t x[kLanes]; \
    std::memcpy(x, src, sizeof(x));
#define KERNEL(DT, load_a, load_b, expr)        \
    {                                           \
        load_a load_b alignas(64) DT d[kLanes]; \
        LANES d[l] = (expr);                    \
        std::memcpy(D, d, sizeof(d));           \
    }                                           \
    break;
#define VOP2(V, expr)                       \
    {                                       \
        V a = vload<V>(A), b = vload<V>(B); \
        vstore(D, (expr));                  \
    }                                       \
    break;
#define VOP1(V, expr)      \
    {                      \
        V a = vload<V>(A); \
        vstore(D, (expr)); \
    }                      \
    break;
#define U1(expr) KERNEL(uint32_t, LOAD_U(a, A), , expr)
#define F1(expr) KERNEL(float, LOAD_F(a, A), , expr)
#define F2(expr) KERNEL(float, LOAD_F(a, A), LOAD_F(b, B), expr)
#define FCMP(expr) KERNEL(uint32_t, LOAD_F(a, A), LOAD_F(b, B), mask(expr))
#define U2(expr) KERNEL(uint32_t, LOAD_U(a, A), LOAD_U(b, B), expr)
#define S2(expr) KERNEL(uint32_t, LOAD_S(a, A), LOAD_S(b, B), uint32_t(expr))
        switch (in.op) {
            case Op::Mov:
                VOP1(VU, a)
            case Op::Select: {
                VU a = vload<VU>(A), b = vload<VU>(B), c = vload<VU>(C);
                vstore(D, (c & a) | (~c & b));
                break;
            }
            case Op::MaskedMov: {
                VU a = vload<VU>(A), c = vload<VU>(C), d = vload<VU>(D);
                vstore(D, (c & a) | (~c & d));
                break;
            }
            case Op::FAdd:
                VOP2(VF, a + b)
            case Op::FSub:
                VOP2(VF, a - b)
            case Op::FMul:
                VOP2(VF, a * b)
            case Op::FDiv:
                VOP2(VF, a / b)
            case Op::FNeg:
                VOP1(VU, a ^ 0x80000000u)
            case Op::FAbs:
                VOP1(VU, a & 0x7fffffffu)
            case Op::FMin:
                VOP2(VF, ((a < b) | (b != b)) ? a : b)
            case Op::FMax:
                VOP2(VF, ((a > b) | (b != b)) ? a : b)
            // mod(x, y) = x - y * floor(x / y)
            case Op::FMod:
                F2(a[l] - b[l] * std::floor(a[l] / b[l]))
            case Op::FRem:
                F2(std::fmod(a[l], b[l]))
            case Op::Fma: {
                f32a* __restrict d = FD;
                const f32a* __restrict a = FA, * __restrict b = FB, * __restrict c = FC;
                LANES d[l] = std::fma(a[l], b[l], c[l]);
                break;
            }
            case Op::FOrdEq:
                VOP2(VF, VU(a == b))
            case Op::FOrdNe:
                VOP2(VF, VU((a < b) | (a > b)))
            case Op::FOrdLt:
                VOP2(VF, VU(a < b))
            case Op::FOrdLe:
                VOP2(VF, VU(a <= b))
            case Op::FOrdGt:
                VOP2(VF, VU(a > b))
            case Op::FOrdGe:
                VOP2(VF, VU(a >= b))
            case Op::FUnordEq:
                VOP2(VF, ~VU((a < b) | (a > b)))
            case Op::FUnordNe:
                VOP2(VF, ~VU(a == b))
            case Op::FUnordLt:
                VOP2(VF, ~VU(a >= b))
            case Op::FUnordLe:
                VOP2(VF, ~VU(a > b))
            case Op::FUnordGt:
                VOP2(VF, ~VU(a <= b))
            case Op::FUnordGe:
                VOP2(VF, ~VU(a < b))
            case Op::IsNan:
                U1(mask((a[l] & 0x7fffffffu) > 0x7f800000u))
            case Op::IsInf:
                U1(mask((a[l] & 0x7fffffffu) == 0x7f800000u))
            case Op::IAdd:
                VOP2(VU, a + b)
            case Op::ISub:
                VOP2(VU, a - b)
            case Op::IMul:
                VOP2(VU, a * b)
            // division by zero: udiv gives 0xFFFFFFFF, sdiv 0 (as llvmpipe); INT_MIN / -1 = INT_MIN
            case Op::UDiv:
                U2(b[l] ? a[l] / b[l] : 0xFFFFFFFFu)
            case Op::UMod:
                U2(b[l] ? a[l] % b[l] : 0xFFFFFFFFu)
            case Op::SDiv:
                S2(b[l] == 0 ? 0 : (b[l] == -1 ? int32_t(0u - uint32_t(a[l])) : a[l] / b[l]))
            case Op::SRem:
                S2(b[l] == 0 || b[l] == -1 ? 0 : a[l] % b[l])
            case Op::SMod: {
                // result has the sign of b
                uint32_t* __restrict d = D;
                const i32a* __restrict a = SA, * __restrict b = SB;
                LANES {
                    int32_t r = (b[l] == 0 || b[l] == -1) ? 0 : a[l] % b[l];
                    if (r != 0 && ((r < 0) != (b[l] < 0))) r += b[l];
                    d[l] = uint32_t(r);
                }
                break;
            }
            case Op::INeg:
                VOP1(VU, 0u - a)
            case Op::And:
                VOP2(VU, a & b)
            case Op::Or:
                VOP2(VU, a | b)
            case Op::Xor:
                VOP2(VU, a ^ b)
            case Op::Not:
                VOP1(VU, ~a)
            case Op::Shl:
                VOP2(VU, a << (b & 31u))
            case Op::ShrL:
                VOP2(VU, a >> (b & 31u))
            case Op::ShrA:
                VOP2(VS, a >> (b & 31))
            case Op::IEq:
                VOP2(VU, VU(a == b))
            case Op::INe:
                VOP2(VU, VU(a != b))
            case Op::SLt:
                VOP2(VS, VU(a < b))
            case Op::SLe:
                VOP2(VS, VU(a <= b))
            case Op::SGt:
                VOP2(VS, VU(a > b))
            case Op::SGe:
                VOP2(VS, VU(a >= b))
            case Op::ULt:
                VOP2(VU, VU(a < b))
            case Op::ULe:
                VOP2(VU, VU(a <= b))
            case Op::UGt:
                VOP2(VU, VU(a > b))
            case Op::UGe:
                VOP2(VU, VU(a >= b))
            case Op::SMin:
                VOP2(VS, (a < b) ? a : b)
            case Op::SMax:
                VOP2(VS, (a > b) ? a : b)
            case Op::UMin:
                VOP2(VU, (a < b) ? a : b)
            case Op::UMax:
                VOP2(VU, (a > b) ? a : b)
            case Op::SAbs:
                U1(int32_t(a[l]) < 0 ? 0u - a[l] : a[l])
            case Op::SSign:
                U1(int32_t(a[l]) > 0 ? 1u : int32_t(a[l]) < 0 ? ~0u : 0u)
            case Op::BitCount:
                U1(uint32_t(std::popcount(a[l])))
            case Op::BitReverse: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A;
                LANES {
                    uint32_t x = a[l], r = 0;
                    for (int i = 0; i < 32; ++i) r |= ((x >> i) & 1u) << (31 - i);
                    d[l] = r;
                }
                break;
            }
            case Op::FindLsb:
                U1(a[l] ? uint32_t(std::countr_zero(a[l])) : ~0u)
            case Op::FindUMsb:
                U1(a[l] ? uint32_t(31 - std::countl_zero(a[l])) : ~0u)
            case Op::FindSMsb: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A;
                LANES {
                    uint32_t x = int32_t(a[l]) < 0 ? ~a[l] : a[l];
                    d[l] = x ? uint32_t(31 - std::countl_zero(x)) : ~0u;
                }
                break;
            }
            case Op::BfeU:
            case Op::BfeS: {
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
                break;
            }
            case Op::Bfi: {
                // d = base with bits [off, off+count) replaced by insert's low bits; operands a, b, c, count in n
                uint32_t* __restrict d = D;
                const uint32_t *a = A, *b = B, *c = C, *n = R + size_t(in.imm) * kLanes;
                LANES {
                    uint32_t off = c[l] & 31, cnt = std::min(n[l], 32u - off);
                    uint32_t m = (cnt == 32 ? ~0u : ((1u << cnt) - 1)) << off;
                    d[l] = (a[l] & ~m) | ((b[l] << off) & m);
                }
                break;
            }
            case Op::F2S: {
                uint32_t* __restrict d = D;
                const f32a* __restrict a = FA;
                LANES d[l] = uint32_t(f2s(a[l]));
                break;
            }
            case Op::F2U: {
                uint32_t* __restrict d = D;
                const f32a* __restrict a = FA;
                LANES d[l] = f2u(a[l]);
                break;
            }
            case Op::S2F: {
                f32a* __restrict d = FD;
                const i32a* a = SA;
                LANES d[l] = float(a[l]);
                break;
            }
            case Op::U2F: {
                f32a* __restrict d = FD;
                const uint32_t* __restrict a = A;
                LANES d[l] = float(a[l]);
                break;
            }
            case Op::Floor:
                F1(std::floor(a[l]))
            case Op::Ceil:
                F1(std::ceil(a[l]))
            case Op::Trunc:
                F1(std::trunc(a[l]))
            case Op::Round:
                F1(round_even(a[l]))  // GLSL round: halfway direction is implementation-defined
            case Op::RoundEven:
                F1(round_even(a[l]))
            // fract(x) = x - floor(x)
            case Op::Fract:
                F1(a[l] - std::floor(a[l]))
            case Op::FSign:
                F1(a[l] > 0.0f ? 1.0f : a[l] < 0.0f ? -1.0f : a[l] * 0.0f)
            case Op::Sqrt:
                F1(std::sqrt(a[l]))
            case Op::InvSqrt:
                F1(1.0f / std::sqrt(a[l]))
            case Op::Exp:
                F1(std::exp(a[l]))
            case Op::Exp2:
                F1(std::exp2(a[l]))
            case Op::Log:
                F1(std::log(a[l]))
            case Op::Log2:
                F1(std::log2(a[l]))
            case Op::Pow:
                F2(std::pow(a[l], b[l]))
            case Op::Sin:
                F1(std::sin(a[l]))
            case Op::Cos:
                F1(std::cos(a[l]))
            case Op::Tan:
                F1(std::tan(a[l]))
            case Op::Asin:
                F1(std::asin(a[l]))
            case Op::Acos:
                F1(std::acos(a[l]))
            case Op::Atan:
                F1(std::atan(a[l]))
            case Op::Atan2:
                F2(std::atan2(a[l], b[l]))
            case Op::Sinh:
                F1(std::sinh(a[l]))
            case Op::Cosh:
                F1(std::cosh(a[l]))
            case Op::Tanh:
                F1(std::tanh(a[l]))
            case Op::Asinh:
                F1(std::asinh(a[l]))
            case Op::Acosh:
                F1(std::acosh(a[l]))
            case Op::Atanh:
                F1(std::atanh(a[l]))
            case Op::FClamp: {
                // clamp(x, lo, hi) = min(max(x, lo), hi)
                f32a* __restrict d = FD;
                const f32a* __restrict a = FA, * __restrict b = FB, * __restrict c = FC;
                LANES d[l] = min_f(max_f(a[l], b[l]), c[l]);
                break;
            }
            case Op::Step:
                F2(b[l] < a[l] ? 0.0f : 1.0f)  // step(edge a, x b)
            case Op::SmoothStep: {
                // t = clamp((x - e0) / (e1 - e0), 0, 1); t * t * (3 - 2 * t)
                f32a* __restrict d = FD;
                const f32a* __restrict a = FA, * __restrict b = FB, * __restrict c = FC;
                LANES {
                    float t = min_f(max_f((c[l] - a[l]) / (b[l] - a[l]), 0.0f), 1.0f);
                    d[l] = t * t * (3.0f - 2.0f * t);
                }
                break;
            }
            case Op::Ldexp: {
                f32a* __restrict d = FD;
                const f32a* __restrict a = FA;
                const i32a* b = SB;
                LANES d[l] = std::ldexp(a[l], std::clamp(b[l], -300, 300));
                break;
            }
            case Op::FrexpSig: {
                // DAZ applies to the comparison: a denormal counts as zero and is returned unchanged (as lavapipe)
                uint32_t* __restrict d = D;
                const f32a* __restrict a = FA;
                LANES {
                    float x = a[l], ax = std::fabs(x);
                    uint32_t b = std::bit_cast<uint32_t>(x);
                    d[l] = (0.0f < ax && ax <= std::numeric_limits<float>::max()) ? (b & 0x807fffffu) | 0x3f000000u : b;
                }
                break;
            }
            case Op::FrexpExp: {
                uint32_t* __restrict d = D;
                const f32a* __restrict a = FA;
                LANES {
                    float ax = std::fabs(a[l]);
                    d[l] = (std::bit_cast<uint32_t>(ax) >> 23) - (ax != 0.0f ? 126u : 0u);
                }
                break;
            }
            case Op::MulHiU:
                U2(uint32_t((uint64_t(a[l]) * uint64_t(b[l])) >> 32))
            case Op::MulHiS:
                S2(uint32_t(uint64_t(int64_t(a[l]) * int64_t(b[l])) >> 32))
            case Op::PackHalf2x16: {
                uint32_t* __restrict d = D;
                const f32a* __restrict a = FA, * __restrict b = FB;
                LANES d[l] = float_to_half(a[l]) | (float_to_half(b[l]) << 16);
                break;
            }
            case Op::UnpackHalf2x16Lo: {
                f32a* __restrict d = FD;
                const uint32_t* __restrict a = A;
                LANES d[l] = half_to_float(a[l] & 0xffff);
                break;
            }
            case Op::UnpackHalf2x16Hi: {
                f32a* __restrict d = FD;
                const uint32_t* __restrict a = A;
                LANES d[l] = half_to_float(a[l] >> 16);
                break;
            }
            case Op::PackUnorm4x8:
            case Op::PackSnorm4x8: {
                // unorm: round(clamp(c, 0, 1) * 255); snorm: round(clamp(c, -1, 1) * 127)
                uint32_t* __restrict d = D;
                bool sn = in.op == Op::PackSnorm4x8;
                LANES {
                    uint32_t r = 0;
                    for (int i = 0; i < 4; ++i) {
                        float c = reinterpret_cast<const f32a*>(R + size_t(in.a + i) * kLanes)[l];
                        int v = sn ? int(round_even(std::fmin(std::fmax(c, -1.0f), 1.0f) * 127.0f))
                                   : int(round_even(std::fmin(std::fmax(c, 0.0f), 1.0f) * 255.0f));
                        r |= (uint32_t(v) & 0xff) << (8 * i);
                    }
                    d[l] = r;
                }
                break;
            }
            case Op::PackUnorm2x16:
            case Op::PackSnorm2x16: {
                uint32_t* __restrict d = D;
                bool sn = in.op == Op::PackSnorm2x16;
                LANES {
                    uint32_t r = 0;
                    for (int i = 0; i < 2; ++i) {
                        float c = reinterpret_cast<const f32a*>(R + size_t(in.a + i) * kLanes)[l];
                        int v = sn ? int(round_even(std::fmin(std::fmax(c, -1.0f), 1.0f) * 32767.0f))
                                   : int(round_even(std::fmin(std::fmax(c, 0.0f), 1.0f) * 65535.0f));
                        r |= (uint32_t(v) & 0xffff) << (16 * i);
                    }
                    d[l] = r;
                }
                break;
            }
            case Op::UnpackUnorm4x8:
                F1(float((std::bit_cast<uint32_t>(a[l]) >> (8 * in.imm)) & 0xff) / 255.0f)
            case Op::UnpackSnorm4x8:
                F1(std::fmax(float(int8_t((std::bit_cast<uint32_t>(a[l]) >> (8 * in.imm)) & 0xff)) / 127.0f, -1.0f))
            case Op::UnpackUnorm2x16:
                F1(float((std::bit_cast<uint32_t>(a[l]) >> (16 * in.imm)) & 0xffff) / 65535.0f)
            case Op::UnpackSnorm2x16:
                F1(std::fmax(float(int16_t((std::bit_cast<uint32_t>(a[l]) >> (16 * in.imm)) & 0xffff)) / 32767.0f,
                             -1.0f))
            // fine: right - left in this lane's row; bottom - top in this lane's column
            case Op::DdxFine:
                F1(a[left(l) + 1] - a[left(l)])
            case Op::DdyFine:
                F1(a[top(l) + 2] - a[top(l)])
            // coarse: the quad's top row / left column
            case Op::DdxCoarse:
                F1(a[(l & ~3) + 1] - a[l & ~3])
            case Op::DdyCoarse:
                F1(a[(l & ~3) + 2] - a[l & ~3])
            case Op::LoadLocal: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A;
                LANES {
                    uint64_t w = std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1);  // clamp to the variable
                    d[l] = M[w * kLanes + l];
                }
                break;
            }
            case Op::StoreLocal: {
                const uint32_t* __restrict a = A, * __restrict b = B, * __restrict c = C;
                LANES {
                    uint64_t w = std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1);
                    if (c[l]) M[w * kLanes + l] = b[l];
                }
                break;
            }
            case Op::LoadLocalFixed:
                vstore(D, vload<VU>(M + size_t(in.imm) * kLanes));
                break;
            case Op::StoreLocalFixed: {
                uint32_t* m = M + size_t(in.imm) * kLanes;
                VU b = vload<VU>(B), c = vload<VU>(C), old = vload<VU>(m);
                vstore(m, (c & b) | (~c & old));
                break;
            }
            case Op::LoadBuf: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A, * __restrict b = B;
                LANES {
                    uint32_t v = 0;
                    if (a[l] < in.n && in.imm + a[l] < num_slots) {
                        const Descriptor* desc = slots[in.imm + a[l]];
                        uint64_t off = uint64_t(b[l]) + in.extra;
                        if (desc && desc->buffer.data && off + 4 <= desc->buffer.size)
                            std::memcpy(&v, static_cast<const uint8_t*>(desc->buffer.data) + off, 4);
                    }
                    d[l] = v;
                }
                break;
            }
            case Op::LoadBufUniform: {
                // constant element and offset: one bounds-checked read, broadcast
                uint32_t v = 0;
                if (in.imm < num_slots) {
                    const Descriptor* desc = slots[in.imm];
                    uint64_t off = in.extra;
                    if (desc && desc->buffer.data && off + 4 <= desc->buffer.size)
                        std::memcpy(&v, static_cast<const uint8_t*>(desc->buffer.data) + off, 4);
                }
                uint32_t* __restrict d = D;
                LANES d[l] = v;
                break;
            }
            case Op::StoreBuf: {
                const uint32_t *m = D, *a = A, *b = B, *c = C;
                LANES {
                    if (!m[l] || a[l] >= in.n || in.imm + a[l] >= num_slots) continue;
                    const Descriptor* desc = slots[in.imm + a[l]];
                    uint64_t off = uint64_t(b[l]) + in.extra;
                    if (desc && desc->buffer.writable && off + 4 <= desc->buffer.size)
                        std::memcpy(static_cast<uint8_t*>(desc->buffer.writable) + off, &c[l], 4);
                }
                break;
            }
            case Op::BufArrayLength: {
                // runtime array length = (buffer size - member offset) / stride, 0 when missing or too small
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A, * __restrict b = B;
                LANES {
                    uint32_t v = 0;
                    if (a[l] < in.n && in.imm + a[l] < num_slots && b[l]) {
                        const Descriptor* desc = slots[in.imm + a[l]];
                        if (desc && desc->buffer.data && desc->buffer.size > in.extra)
                            v = uint32_t(std::min<uint64_t>((desc->buffer.size - in.extra) / b[l], 0xFFFFFFFFu));
                    }
                    d[l] = v;
                }
                break;
            }
            case Op::Sample:
            case Op::Fetch:
            case Op::QuerySize:
            case Op::QueryLevels:
                exec_image(in, R, slots, num_slots);
                break;
            case Op::Jump:
                pc = in.imm;
                break;
            case Op::JumpIfNone: {
                const uint32_t* __restrict a = A;
                uint32_t any = 0;
                LANES any |= a[l];
                if (!any) pc = in.imm;
                break;
            }
            case Op::JumpIfAny: {
                const uint32_t* __restrict a = A;
                uint32_t any = 0;
                LANES any |= a[l];
                if (any) {
                    if (++back_edges > kMaxLoopBackEdges) {
                        ++s.loop_limit_hits;
                        return;
                    }
                    pc = in.imm;
                }
                break;
            }
            case Op::Kill: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A;
                LANES d[l] &= ~a[l];
                break;
            }
            case Op::Halt:
                return;
        }
    }
}

namespace {

// Set up the scratch for a program: sizes, constants, resolved descriptors.
void prepare(const ProgramImpl& p, const Bindings& bindings, Scratch::Impl& s, Descriptor& push) {
    if (s.last != p.serial) {
        s.regs.assign(size_t(p.num_regs) * kLanes, 0);
        for (size_t i = 0; i + 1 < p.const_regs.size(); i += 2)
            for (int l = 0; l < kLanes; ++l) s.regs[size_t(p.const_regs[i]) * kLanes + l] = p.const_regs[i + 1];
        s.last = p.serial;
    }
    size_t words = size_t(std::max(1u, p.local_words)) * kLanes;
    if (s.local.size() < words) s.local.resize(words);
    std::memset(s.local.data(), 0, words * 4);  // variables start at zero, so results never depend on history
    if (s.slots.size() != p.num_slots) s.slots.resize(p.num_slots);
    push.buffer.data = bindings.push_constants.data();
    push.buffer.size = bindings.push_constants.size();
    s.slots[0] = &push;
    uint32_t at = 1;
    for (const SlotBinding& b : p.slots)
        for (uint32_t e = 0; e < b.count; ++e) s.slots[at++] = bindings.find(b.set, b.binding, e);
}

struct FloatEnv {
    // lavapipe runs shaders with denormals flushed (FTZ) and treated as zero (DAZ)
    unsigned saved = _mm_getcsr();
    FloatEnv() { _mm_setcsr((saved & ~0x6000u) | 0x8040u); }
    ~FloatEnv() { _mm_setcsr(saved); }
};

inline void copy_lanes(uint32_t* dst, const uint32_t* src) {
    std::memcpy(dst, src, kLanes * 4);
}

}  // namespace

void Program::run_vertex(const Bindings& bindings, VertexBatch& vb, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    Descriptor push;
    prepare(p, bindings, s, push);
    uint32_t* M = s.local.data();
    for (const IoCopy& c : p.io_in) {
        uint32_t* w = M + size_t(c.word) * kLanes;
        switch (c.slot) {
            case IoSlot::Input:
                copy_lanes(w, vb.inputs[c.index / 4][c.index % 4]);
                break;
            case IoSlot::VertexIndex:
                copy_lanes(w, vb.vertex_index);
                break;
            case IoSlot::InstanceIndex:
                copy_lanes(w, vb.instance_index);
                break;
            case IoSlot::BaseVertex:
                LANES w[l] = vb.base_vertex;
                break;
            case IoSlot::BaseInstance:
                LANES w[l] = vb.base_instance;
                break;
            case IoSlot::DrawIndex:
                LANES w[l] = vb.draw_index;
                break;
            default:
                break;
        }
    }
    uint32_t* entry = s.regs.data() + size_t(p.reg_entry_mask) * kLanes;
    LANES entry[l] = uint32_t(l) < vb.count ? ~0u : 0u;
    {
        FloatEnv env;
        execute(p, s);
    }
    for (const IoCopy& c : p.io_out) {
        const uint32_t* w = M + size_t(c.word) * kLanes;
        switch (c.slot) {
            case IoSlot::Output:
                copy_lanes(vb.outputs[c.index / 4][c.index % 4], w);
                break;
            case IoSlot::Position:
                copy_lanes(vb.position[c.index], w);
                break;
            case IoSlot::PointSize:
                copy_lanes(vb.point_size, w);
                break;
            case IoSlot::ClipDistance:
                copy_lanes(vb.clip_distance[c.index], w);
                break;
            case IoSlot::CullDistance:
                copy_lanes(vb.cull_distance[c.index], w);
                break;
            default:
                break;
        }
    }
}

void Program::run_fragment(const Bindings& bindings, FragmentBlock& fb, Scratch& scratch) const {
    const ProgramImpl& p = *impl_;
    Scratch::Impl& s = *scratch.impl();
    Descriptor push;
    prepare(p, bindings, s, push);
    uint32_t* M = s.local.data();
    for (const IoCopy& c : p.io_in) {
        uint32_t* w = M + size_t(c.word) * kLanes;
        switch (c.slot) {
            case IoSlot::Input:
                copy_lanes(w, fb.inputs[c.index / 4][c.index % 4]);
                break;
            case IoSlot::FragCoord:
                copy_lanes(w, fb.frag_coord[c.index]);
                break;
            case IoSlot::PointCoord:
                copy_lanes(w, fb.point_coord[c.index]);
                break;
            case IoSlot::FrontFacing:
                LANES w[l] = fb.front_facing ? ~0u : 0u;
                break;
            case IoSlot::SampleMaskIn:
                copy_lanes(w, fb.sample_mask_in);
                break;
            case IoSlot::SampleId:
                LANES w[l] = fb.sample_id;
                break;
            case IoSlot::HelperInvocation:
                LANES w[l] = (fb.cover_mask >> l) & 1 ? 0u : ~0u;
                break;
            default:
                break;
        }
    }
    uint32_t* entry = s.regs.data() + size_t(p.reg_entry_mask) * kLanes;
    uint32_t* live = s.regs.data() + size_t(p.reg_live) * kLanes;
    LANES {
        entry[l] = ~0u;  // helper lanes run too (derivatives)
        live[l] = (fb.cover_mask >> l) & 1 ? ~0u : 0u;
    }
    {
        FloatEnv env;
        execute(p, s);
    }
    uint32_t out = 0;
    LANES out |= (live[l] & 1u) << l;
    fb.live_mask = out & fb.cover_mask;
    for (const IoCopy& c : p.io_out) {
        const uint32_t* w = M + size_t(c.word) * kLanes;
        switch (c.slot) {
            case IoSlot::Output:
                copy_lanes(fb.outputs[c.index / 4][c.index % 4], w);
                break;
            case IoSlot::FragDepth:
                copy_lanes(fb.frag_depth, w);
                break;
            case IoSlot::SampleMask:
                copy_lanes(fb.sample_mask, w);
                break;
            default:
                break;
        }
    }
}

}  // namespace tilevk::shader
