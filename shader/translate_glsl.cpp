// GLSL.std.450 extended instructions -> SIMD instructions (split from translate_ops.cpp).
#include <bit>
#include <cmath>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

void Translator::glsl_op(const Instr& in) {
    auto def = [&](uint32_t n = 0) {
        uint32_t f = n ? n : std::max(1u, type(in[1]).flat);
        uint32_t r = alloc(f);
        vals_[in[2]] = Value{r, in[1]};
        return r;
    };
    auto alias = [&](uint32_t r) { vals_[in[2]] = Value{r, in[1]}; };
    auto flat_of = [&](uint32_t id) { return std::max(1u, type(val(id).type).flat); };
    // dot product: ((a0*b0 + a1*b1) + a2*b2) + a3*b3  (mul then add, left to right, as NIR's fsum after fmul)
    auto dot = [&](uint32_t a, uint32_t b, uint32_t n) {
        uint32_t s = emit1(SOp::FMul, a, b);
        for (uint32_t i = 1; i < n; ++i) s = emit1(SOp::FAdd, s, emit1(SOp::FMul, a + i, b + i));
        return s;
    };
    // GLSL.std.450
    if (in[3] != glsl_ext_ || glsl_ext_ == 0) fail("unsupported extended instruction set call");
    uint32_t e = in[4];
    auto arg = [&](int i) { return reg(in[5 + i]); };
    auto argn = [&](int i) { return flat_of(in[5 + i]); };
    uint32_t n = std::max(1u, type(in[1]).flat);
    auto map1 = [&](SOp o) {
        uint32_t a = arg(0), d = def();
        for (uint32_t i = 0; i < n; ++i) emit(o, d + i, a + i);
    };
    auto map2 = [&](SOp o) {
        uint32_t a = arg(0), b = arg(1), d = def();
        uint32_t fb = argn(1);
        for (uint32_t i = 0; i < n; ++i) emit(o, d + i, a + i, b + (fb > 1 ? i : 0));
    };
    auto map3 = [&](SOp o) {
        uint32_t a = arg(0), b = arg(1), c = arg(2), d = def();
        uint32_t fa = argn(0), fb = argn(1), fc = argn(2);
        for (uint32_t i = 0; i < n; ++i)
            emit(o, d + i, a + (fa > 1 ? i : 0), b + (fb > 1 ? i : 0), c + (fc > 1 ? i : 0));
    };
    switch (e) {
        case GLSLstd450Round:
            return map1(SOp::Round);
        case GLSLstd450RoundEven:
            return map1(SOp::RoundEven);
        case GLSLstd450Trunc:
            return map1(SOp::Trunc);
        case GLSLstd450FAbs:
            return map1(SOp::FAbs);
        case GLSLstd450SAbs:
            return map1(SOp::SAbs);
        case GLSLstd450FSign:
            return map1(SOp::FSign);
        case GLSLstd450SSign:
            return map1(SOp::SSign);
        case GLSLstd450Floor:
            return map1(SOp::Floor);
        case GLSLstd450Ceil:
            return map1(SOp::Ceil);
        case GLSLstd450Fract:
            return map1(SOp::Fract);
        case GLSLstd450Radians:
        case GLSLstd450Degrees: {
            // radians(x) = x * (pi/180) with the constant rounded to float
            float k = e == GLSLstd450Radians ? float(M_PI / 180.0) : float(180.0 / M_PI);
            uint32_t a = arg(0), d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::FMul, d + i, a + i, konstf(k));
            return;
        }
        case GLSLstd450Sin:
            return map1(SOp::Sin);
        case GLSLstd450Cos:
            return map1(SOp::Cos);
        case GLSLstd450Tan:
            return map1(SOp::Tan);
        case GLSLstd450Asin:
            return map1(SOp::Asin);
        case GLSLstd450Acos:
            return map1(SOp::Acos);
        case GLSLstd450Atan:
            return map1(SOp::Atan);
        case GLSLstd450Sinh:
            return map1(SOp::Sinh);
        case GLSLstd450Cosh:
            return map1(SOp::Cosh);
        case GLSLstd450Tanh:
            return map1(SOp::Tanh);
        case GLSLstd450Asinh:
            return map1(SOp::Asinh);
        case GLSLstd450Acosh:
            return map1(SOp::Acosh);
        case GLSLstd450Atanh:
            return map1(SOp::Atanh);
        case GLSLstd450Atan2:
            return map2(SOp::Atan2);
        case GLSLstd450Pow:
            return map2(SOp::Pow);
        case GLSLstd450Exp:
            return map1(SOp::Exp);
        case GLSLstd450Log:
            return map1(SOp::Log);
        case GLSLstd450Exp2:
            return map1(SOp::Exp2);
        case GLSLstd450Log2:
            return map1(SOp::Log2);
        case GLSLstd450Sqrt:
            return map1(SOp::Sqrt);
        case GLSLstd450InverseSqrt:
            return map1(SOp::InvSqrt);
        case GLSLstd450FMin:
        case GLSLstd450NMin:
            return map2(SOp::FMin);
        case GLSLstd450FMax:
        case GLSLstd450NMax:
            return map2(SOp::FMax);
        case GLSLstd450UMin:
            return map2(SOp::UMin);
        case GLSLstd450SMin:
            return map2(SOp::SMin);
        case GLSLstd450UMax:
            return map2(SOp::UMax);
        case GLSLstd450SMax:
            return map2(SOp::SMax);
        case GLSLstd450FClamp:
        case GLSLstd450NClamp:
            return map3(SOp::FClamp);
        case GLSLstd450UClamp:
        case GLSLstd450SClamp: {
            bool s = e == GLSLstd450SClamp;
            uint32_t a = arg(0), lo = arg(1), hi = arg(2), d = def();
            uint32_t fl = argn(1), fh = argn(2);
            for (uint32_t i = 0; i < n; ++i)
                emit(s ? SOp::SMin : SOp::UMin, d + i, emit1(s ? SOp::SMax : SOp::UMax, a + i, lo + (fl > 1 ? i : 0)),
                     hi + (fh > 1 ? i : 0));
            return;
        }
        case GLSLstd450FMix: {
            // mix(x, y, a) = x * (1 - a) + y * a  (see README: lavapipe lowers flrp; this is the exact-maths form)
            uint32_t x = arg(0), y = arg(1), a = arg(2), d = def();
            uint32_t fa = argn(2);
            for (uint32_t i = 0; i < n; ++i) {
                uint32_t ai = a + (fa > 1 ? i : 0);
                uint32_t l = emit1(SOp::FMul, x + i, emit1(SOp::FSub, konstf(1.0f), ai));
                emit(SOp::FAdd, d + i, l, emit1(SOp::FMul, y + i, ai));
            }
            return;
        }
        case GLSLstd450Step: {
            uint32_t edge = arg(0), x = arg(1), d = def();
            uint32_t fe = argn(0);
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Step, d + i, edge + (fe > 1 ? i : 0), x + i);
            return;
        }
        case GLSLstd450SmoothStep:
            return map3(SOp::SmoothStep);
        case GLSLstd450Fma: {
            // lavapipe lowers ffma to fmul + fadd (lower_ffma32): not fused
            uint32_t a = arg(0), b = arg(1), c = arg(2), d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::FAdd, d + i, emit1(SOp::FMul, a + i, b + i), c + i);
            return;
        }
        case GLSLstd450Ldexp:
            return map2(SOp::Ldexp);
        case GLSLstd450PackHalf2x16:
            emit(SOp::PackHalf2x16, def(), arg(0), arg(0) + 1);
            return;
        case GLSLstd450UnpackHalf2x16: {
            uint32_t d = def();
            emit(SOp::UnpackHalf2x16Lo, d, arg(0));
            emit(SOp::UnpackHalf2x16Hi, d + 1, arg(0));
            return;
        }
        case GLSLstd450PackUnorm4x8:
        case GLSLstd450PackSnorm4x8:
            emit(e == GLSLstd450PackUnorm4x8 ? SOp::PackUnorm4x8 : SOp::PackSnorm4x8, def(), arg(0));
            return;
        case GLSLstd450PackUnorm2x16:
        case GLSLstd450PackSnorm2x16:
            emit(e == GLSLstd450PackUnorm2x16 ? SOp::PackUnorm2x16 : SOp::PackSnorm2x16, def(), arg(0));
            return;
        case GLSLstd450UnpackUnorm4x8:
        case GLSLstd450UnpackSnorm4x8: {
            uint32_t d = def();
            for (uint32_t i = 0; i < 4; ++i)
                emit(e == GLSLstd450UnpackUnorm4x8 ? SOp::UnpackUnorm4x8 : SOp::UnpackSnorm4x8, d + i, arg(0), kNoReg,
                     kNoReg, i);
            return;
        }
        case GLSLstd450UnpackUnorm2x16:
        case GLSLstd450UnpackSnorm2x16: {
            uint32_t d = def();
            for (uint32_t i = 0; i < 2; ++i)
                emit(e == GLSLstd450UnpackUnorm2x16 ? SOp::UnpackUnorm2x16 : SOp::UnpackSnorm2x16, d + i, arg(0),
                     kNoReg, kNoReg, i);
            return;
        }
        case GLSLstd450Length: {
            uint32_t a = arg(0);
            alias(emit1(SOp::Sqrt, dot(a, a, argn(0))));
            return;
        }
        case GLSLstd450Distance: {
            uint32_t a = arg(0), b = arg(1), m = argn(0);
            uint32_t t = alloc(m);
            for (uint32_t i = 0; i < m; ++i) emit(SOp::FSub, t + i, a + i, b + i);
            alias(emit1(SOp::Sqrt, dot(t, t, m)));
            return;
        }
        case GLSLstd450Normalize: {
            // normalize(v) = v * inversesqrt(dot(v, v))
            uint32_t a = arg(0);
            uint32_t r = emit1(SOp::InvSqrt, dot(a, a, n));
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::FMul, d + i, a + i, r);
            return;
        }
        case GLSLstd450Cross: {
            // cross(a, b) = a.yzx * b.zxy - a.zxy * b.yzx
            uint32_t a = arg(0), b = arg(1), d = def();
            const int y[3] = {1, 2, 0}, z[3] = {2, 0, 1};
            for (int i = 0; i < 3; ++i)
                emit(SOp::FSub, d + i, emit1(SOp::FMul, a + y[i], b + z[i]), emit1(SOp::FMul, a + z[i], b + y[i]));
            return;
        }
        case GLSLstd450FaceForward: {
            // faceforward(N, I, Nref) = dot(Nref, I) < 0 ? N : -N
            uint32_t nn = arg(0), ii = arg(1), nr = arg(2);
            uint32_t lt = emit1(SOp::FOrdLt, dot(nr, ii, n), zero_);
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Select, d + i, nn + i, emit1(SOp::FNeg, nn + i), lt);
            return;
        }
        case GLSLstd450Reflect: {
            // reflect(I, N) = I - (2 * dot(N, I)) * N
            uint32_t ii = arg(0), nn = arg(1);
            uint32_t k = emit1(SOp::FMul, konstf(2.0f), dot(nn, ii, n));
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::FSub, d + i, ii + i, emit1(SOp::FMul, k, nn + i));
            return;
        }
        case GLSLstd450Refract: {
            // k = 1 - eta^2 (1 - dot(N,I)^2); k < 0 ? 0 : eta*I - (eta*dot(N,I) + sqrt(k)) * N
            uint32_t ii = arg(0), nn = arg(1), eta = arg(2);
            uint32_t ni = dot(nn, ii, n);
            uint32_t k = emit1(
                SOp::FSub, konstf(1.0f),
                emit1(SOp::FMul, emit1(SOp::FMul, eta, eta), emit1(SOp::FSub, konstf(1.0f), emit1(SOp::FMul, ni, ni))));
            uint32_t neg = emit1(SOp::FOrdLt, k, zero_);
            uint32_t s = emit1(SOp::FAdd, emit1(SOp::FMul, eta, ni), emit1(SOp::Sqrt, k));
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) {
                uint32_t r = emit1(SOp::FSub, emit1(SOp::FMul, eta, ii + i), emit1(SOp::FMul, s, nn + i));
                emit(SOp::Select, d + i, zero_, r, neg);
            }
            return;
        }
        case GLSLstd450FindILsb:
            return map1(SOp::FindLsb);
        case GLSLstd450FindSMsb:
            return map1(SOp::FindSMsb);
        case GLSLstd450FindUMsb:
            return map1(SOp::FindUMsb);
        case GLSLstd450Determinant: {
            const Type& mt = type(val(in[5]).type);
            uint32_t m = arg(0);
            auto at = [&](uint32_t c, uint32_t r) { return m + c * mt.count + r; };
            auto mul = [&](uint32_t a, uint32_t b) { return emit1(SOp::FMul, a, b); };
            auto sub = [&](uint32_t a, uint32_t b) { return emit1(SOp::FSub, a, b); };
            auto det2 = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) { return sub(mul(a, d), mul(b, c)); };
            if (mt.count == 2) {
                alias(det2(at(0, 0), at(1, 0), at(0, 1), at(1, 1)));
            } else if (mt.count == 3) {
                uint32_t a = mul(at(0, 0), det2(at(1, 1), at(2, 1), at(1, 2), at(2, 2)));
                uint32_t b = mul(at(1, 0), det2(at(0, 1), at(2, 1), at(0, 2), at(2, 2)));
                uint32_t c = mul(at(2, 0), det2(at(0, 1), at(1, 1), at(0, 2), at(1, 2)));
                alias(emit1(SOp::FAdd, sub(a, b), c));
            } else {
                fail("unsupported GLSL.std.450 Determinant of a 4x4 matrix");
            }
            return;
        }
        default:
            fail("unsupported GLSL.std.450 instruction " + std::to_string(e));
    }
}

}  // namespace tilevk::shader
