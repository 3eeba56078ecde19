// gallivm's exp2, log2 and pow (and GLSL's exp and log built on them) emitted inline in a segment: the operations
// of shader/gallivm_math_impl.h, in its order and with its constants (gallivm_math.h), so the bits are the lane
// call's (the interpreter's). The call cost more than the arithmetic: it writes the segment's live values home,
// goes through two functions and clobbers every YMM register, which the segment then reloads (meshes_lit's Phong
// exponent: a pow per 8 lanes). Emitted only while gallivm's AVX2/FMA build is the one that runs
// (gallivm::avx2_build_runs): these are its instructions, and its portable twin (TILEVK_SIMD=none, or forced by a
// test) keeps other NaN payloads where two NaNs meet; otherwise the op stays a lane call.
#include <bit>
#include <iterator>

#include "shader/gallivm_math.h"
#include "shader/jit/codegen.h"

namespace tilevk::shader::jit {

using namespace asmjit;

namespace {

using Ymm = x86::Ymm;

// vcmpps predicates of gallivm's unordered compares (gallivm_math.cpp's _CMP_EQ_UQ, _CMP_NLT_UQ, _CMP_NGE_UQ)
enum : uint32_t { kEqUQ = 0x08, kNltUQ = 0x15, kNgeUQ = 0x19 };
constexpr uint32_t kFloorNoExc = 0x9;  // _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC

constexpr uint32_t fbits(float f) {
    return std::bit_cast<uint32_t>(f);
}

// The registers of one expansion: the scratch t (pinned temporaries of the instruction).
struct Emit {
    x86::Assembler& a;
    ConstantPool& pool;
    Ymm t[6];

    x86::Mem splat(float f) { return pool.splat(fbits(f)); }

    // polynomial() of gallivm_math_impl.h: the even and the odd coefficients by Horner in v², then odd·v + even,
    // each step one FMA (the product is exact, so the operand order of the multiplication does not matter).
    template <size_t N>
    void polynomial(Ymm v, const float (&c)[N], Ymm v2, Ymm even, Ymm odd) {
        constexpr int kEven = (N - 1) & ~size_t(1), kOdd = N % 2 == 0 ? N - 1 : N - 2;
        a.vmulps(v2, v, v);
        a.vmovups(even, splat(c[kEven]));
        a.vmovups(odd, splat(c[kOdd]));
        for (int i = kEven - 2; i >= 0; i -= 2) a.vfmadd213ps(even, v2, splat(c[i]));  // v2·even + c
        for (int i = kOdd - 2; i >= 1; i -= 2) a.vfmadd213ps(odd, v2, splat(c[i]));
        a.vfmadd213ps(odd, v, even);  // v·odd + even
    }

    // log2_v(x) into t[5]; x is kept, t[0..4] are clobbered.
    Ymm log2(Ymm x) {
        const Ymm logexp = t[0], mant = t[1], y = t[2], res = t[5];
        a.vpand(logexp, x, pool.splat(0x7f800000u));
        a.vpsrld(logexp, logexp, 23);
        a.vpsubd(logexp, logexp, pool.splat(127u));
        a.vcvtdq2ps(logexp, logexp);
        a.vpand(mant, x, pool.splat(0x007fffffu));
        a.vpor(mant, mant, splat(1.0f));
        a.vsubps(y, mant, splat(1.0f));
        a.vaddps(mant, mant, splat(1.0f));
        a.vdivps(y, y, mant);
        const Ymm& z = mant;  // y² reuses the mantissa's register
        a.vmulps(z, y, y);
        polynomial(z, gallivm::kLog2Poly, t[3], t[4], res);
        a.vfmadd213ps(res, y, logexp);  // y·P(z) + exponent
        const Ymm m = t[0];
        a.vcmpps(m, x, splat(__builtin_inff()), kNltUQ);
        a.vblendvps(res, res, splat(__builtin_inff()), m);
        a.vcmpps(m, x, splat(0.0f), kEqUQ);
        a.vblendvps(res, res, splat(-__builtin_inff()), m);
        a.vcmpps(m, x, splat(0.0f), kNgeUQ);
        a.vblendvps(res, res, splat(__builtin_nanf("")), m);
        return res;
    }

    // exp2_v(v) into t[4]; v (any register but t[0..4]) is read first, t[0..3] are clobbered.
    Ymm exp2(Ymm v) {
        const Ymm e = t[0], x = t[1], res = t[4];
        a.vmovups(e, splat(gallivm::kExp2Max));
        a.vminps(e, e, v);  // MINPS(128, v): v where v is NaN
        a.vmovups(x, splat(gallivm::kExp2Min));
        a.vmaxps(x, x, e);
        a.vroundps(e, x, kFloorNoExc);  // ipart
        a.vsubps(x, x, e);              // fpart
        a.vcvttps2dq(e, e);
        a.vpaddd(e, e, pool.splat(127u));
        a.vpslld(e, e, 23);
        polynomial(x, gallivm::kExp2Poly, t[2], t[3], res);
        a.vmulps(res, e, res);
        return res;
    }
};

}  // namespace

std::optional<bool> LaneEmitter::gallivm_op(const Inst& in) {
    if (!inline_gallivm_) return std::nullopt;
    switch (in.op) {
        case Op::Exp2:
        case Op::Log2:
        case Op::Pow:
        case Op::Exp:
        case Op::Log:
            break;
        default:
            return std::nullopt;
    }
    const Ymm x = use(in.a);
    const Ymm y = in.op == Op::Pow ? use(in.b) : x;
    Emit e{a_, pool_, {temp(), temp(), temp(), temp(), temp(), temp()}};
    Ymm d;
    switch (in.op) {
        case Op::Exp2:
            d = e.exp2(x);
            break;
        case Op::Log2:
            d = e.log2(x);
            break;
        case Op::Log:  // log2(x)·(1/log2 e)
            d = e.log2(x);
            a_.vmulps(d, d, e.splat(gallivm::kLn2));
            break;
        case Op::Exp:  // exp2(x·log2 e)
            a_.vmulps(e.t[5], x, e.splat(gallivm::kLog2E));
            d = e.exp2(e.t[5]);
            break;
        default: {  // Pow: exp2(log2(x)·y), 0 where x == 0 or NaN
            const Ymm l = e.log2(x);
            a_.vmulps(l, l, y);  // log2 first: its NaN wins over y's (gallivm_math_impl.h mul_nan_of_a)
            d = e.exp2(l);
            a_.vcmpps(e.t[0], x, e.splat(0.0f), kEqUQ);
            a_.vblendvps(d, d, e.splat(0.0f), e.t[0]);
            break;
        }
    }
    def(in.d, d);
    return true;
}

}  // namespace tilevk::shader::jit
