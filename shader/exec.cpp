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
#define U1(expr)                          \
    {                                     \
        uint32_t* __restrict d = D;       \
        const uint32_t* __restrict a = A; \
        LANES d[l] = (expr);              \
    }                                     \
    break;
#define F1(expr)                       \
    {                                  \
        f32a* __restrict d = FD;       \
        const f32a* __restrict a = FA; \
        LANES d[l] = (expr);           \
    }                                  \
    break;
#define F2(expr)                                            \
    {                                                       \
        f32a* __restrict d = FD;                            \
        const f32a* __restrict a = FA, * __restrict b = FB; \
        LANES d[l] = (expr);                                \
    }                                                       \
    break;
#define FCMP(expr)                                          \
    {                                                       \
        uint32_t* __restrict d = D;                         \
        const f32a* __restrict a = FA, * __restrict b = FB; \
        LANES d[l] = mask(expr);                            \
    }                                                       \
    break;
#define U2(expr)                                              \
    {                                                         \
        uint32_t* __restrict d = D;                           \
        const uint32_t* __restrict a = A, * __restrict b = B; \
        LANES d[l] = (expr);                                  \
    }                                                         \
    break;
#define S2(expr)                                            \
    {                                                       \
        uint32_t* __restrict d = D;                         \
        const i32a* __restrict a = SA, * __restrict b = SB; \
        LANES d[l] = uint32_t(expr);                        \
    }                                                       \
    break;
        switch (in.op) {
            case Op::Mov:
                U1(a[l])
            case Op::Select: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A, * __restrict b = B, * __restrict c = C;
                LANES d[l] = (c[l] & a[l]) | (~c[l] & b[l]);
                break;
            }
            case Op::MaskedMov: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict a = A, * __restrict c = C;
                LANES d[l] = (c[l] & a[l]) | (~c[l] & d[l]);
                break;
            }
            case Op::FAdd:
                F2(a[l] + b[l])
            case Op::FSub:
                F2(a[l] - b[l])
            case Op::FMul:
                F2(a[l] * b[l])
            case Op::FDiv:
                F2(a[l] / b[l])
            case Op::FNeg:
                U1(a[l] ^ 0x80000000u)
            case Op::FAbs:
                U1(a[l] & 0x7fffffffu)
            case Op::FMin:
                F2(min_f(a[l], b[l]))
            case Op::FMax:
                F2(max_f(a[l], b[l]))
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
                FCMP(a[l] == b[l])
            case Op::FOrdNe:
                FCMP(a[l] < b[l] || a[l] > b[l])
            case Op::FOrdLt:
                FCMP(a[l] < b[l])
            case Op::FOrdLe:
                FCMP(a[l] <= b[l])
            case Op::FOrdGt:
                FCMP(a[l] > b[l])
            case Op::FOrdGe:
                FCMP(a[l] >= b[l])
            case Op::FUnordEq:
                FCMP(!(a[l] < b[l] || a[l] > b[l]))
            case Op::FUnordNe:
                FCMP(!(a[l] == b[l]))
            case Op::FUnordLt:
                FCMP(!(a[l] >= b[l]))
            case Op::FUnordLe:
                FCMP(!(a[l] > b[l]))
            case Op::FUnordGt:
                FCMP(!(a[l] <= b[l]))
            case Op::FUnordGe:
                FCMP(!(a[l] < b[l]))
            case Op::IsNan:
                U1(mask((a[l] & 0x7fffffffu) > 0x7f800000u))
            case Op::IsInf:
                U1(mask((a[l] & 0x7fffffffu) == 0x7f800000u))
            case Op::IAdd:
                U2(a[l] + b[l])
            case Op::ISub:
                U2(a[l] - b[l])
            case Op::IMul:
                U2(a[l] * b[l])
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
                U1(0u - a[l])
            case Op::And:
                U2(a[l] & b[l])
            case Op::Or:
                U2(a[l] | b[l])
            case Op::Xor:
                U2(a[l] ^ b[l])
            case Op::Not:
                U1(~a[l])
            case Op::Shl:
                U2(a[l] << (b[l] & 31))
            case Op::ShrL:
                U2(a[l] >> (b[l] & 31))
            case Op::ShrA:
                S2(a[l] >> (b[l] & 31))
            case Op::IEq:
                U2(mask(a[l] == b[l]))
            case Op::INe:
                U2(mask(a[l] != b[l]))
            case Op::SLt:
                S2(mask(a[l] < b[l]))
            case Op::SLe:
                S2(mask(a[l] <= b[l]))
            case Op::SGt:
                S2(mask(a[l] > b[l]))
            case Op::SGe:
                S2(mask(a[l] >= b[l]))
            case Op::ULt:
                U2(mask(a[l] < b[l]))
            case Op::ULe:
                U2(mask(a[l] <= b[l]))
            case Op::UGt:
                U2(mask(a[l] > b[l]))
            case Op::UGe:
                U2(mask(a[l] >= b[l]))
            case Op::SMin:
                S2(std::min(a[l], b[l]))
            case Op::SMax:
                S2(std::max(a[l], b[l]))
            case Op::UMin:
                U2(std::min(a[l], b[l]))
            case Op::UMax:
                U2(std::max(a[l], b[l]))
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
            case Op::LoadLocalFixed: {
                uint32_t* __restrict d = D;
                const uint32_t* __restrict m = M + size_t(in.imm) * kLanes;
                LANES d[l] = m[l];
                break;
            }
            case Op::StoreLocalFixed: {
                uint32_t* __restrict m = M + size_t(in.imm) * kLanes;
                const uint32_t* __restrict b = B, * __restrict c = C;
                LANES m[l] = (c[l] & b[l]) | (~c[l] & m[l]);
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
                if (any) pc = in.imm;
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
