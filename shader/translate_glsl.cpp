// GLSL.std.450 extended instructions -> SIMD instructions (split from translate_ops.cpp).
#include <bit>
#include <cmath>
#include <functional>
#include <vector>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

namespace {
// Instruction names for error messages, indexed by the GLSL.std.450 opcode (GLSL.std.450.h order).
constexpr const char* kGlslNames[] = {
    "Bad",
    "Round",
    "RoundEven",
    "Trunc",
    "FAbs",
    "SAbs",
    "FSign",
    "SSign",
    "Floor",
    "Ceil",
    "Fract",
    "Radians",
    "Degrees",
    "Sin",
    "Cos",
    "Tan",
    "Asin",
    "Acos",
    "Atan",
    "Sinh",
    "Cosh",
    "Tanh",
    "Asinh",
    "Acosh",
    "Atanh",
    "Atan2",
    "Pow",
    "Exp",
    "Log",
    "Exp2",
    "Log2",
    "Sqrt",
    "InverseSqrt",
    "Determinant",
    "MatrixInverse",
    "Modf",
    "ModfStruct",
    "FMin",
    "UMin",
    "SMin",
    "FMax",
    "UMax",
    "SMax",
    "FClamp",
    "UClamp",
    "SClamp",
    "FMix",
    "IMix",
    "Step",
    "SmoothStep",
    "Fma",
    "Frexp",
    "FrexpStruct",
    "Ldexp",
    "PackSnorm4x8",
    "PackUnorm4x8",
    "PackSnorm2x16",
    "PackUnorm2x16",
    "PackHalf2x16",
    "PackDouble2x32",
    "UnpackSnorm2x16",
    "UnpackUnorm2x16",
    "UnpackHalf2x16",
    "UnpackSnorm4x8",
    "UnpackUnorm4x8",
    "UnpackDouble2x32",
    "Length",
    "Distance",
    "Cross",
    "Normalize",
    "FaceForward",
    "Reflect",
    "Refract",
    "FindILsb",
    "FindSMsb",
    "FindUMsb",
    "InterpolateAtCentroid",
    "InterpolateAtSample",
    "InterpolateAtOffset",
    "NMin",
    "NMax",
    "NClamp",
};
static_assert(sizeof(kGlslNames) / sizeof(kGlslNames[0]) == GLSLstd450Count);
}  // namespace

const char* glsl_std450_name(uint32_t e) {
    return e < GLSLstd450Count ? kGlslNames[e] : "(unknown)";
}

// One switch over the GLSL.std.450 instructions (over 150 lines): a case per instruction, a few lines each, sharing
// the def/operand helpers declared at its top; a split by family would only move the cases into smaller switches.
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
    // Pow with a constant operand, per component as NIR's inexact rules rewrite it for lavapipe (nir_opt_algebraic:
    // pow(a, 1) = a, pow(a, 2) = a·a, pow(a, 4) = (a·a)·(a·a), pow(2, b) = exp2(b)); any other pow is gallivm's.
    auto pow = [&] {
        const uint32_t a = arg(0), b = arg(1), d = def(), fa = argn(0), fb = argn(1);
        auto is = [&](uint32_t r, float f) {
            auto it = reg_value_.find(r);
            return it != reg_value_.end() && it->second == std::bit_cast<uint32_t>(f);
        };
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t ai = a + (fa > 1 ? i : 0), bi = b + (fb > 1 ? i : 0);
            if (is(bi, 1.0f)) {
                emit(SOp::Mov, d + i, ai);
            } else if (is(bi, 2.0f)) {
                emit(SOp::FMul, d + i, ai, ai);
            } else if (is(bi, 4.0f)) {
                const uint32_t sq = emit1(SOp::FMul, ai, ai);
                emit(SOp::FMul, d + i, sq, sq);
            } else if (is(ai, 2.0f)) {
                emit(SOp::Exp2, d + i, bi);
            } else {
                emit(SOp::Pow, d + i, ai, bi);
            }
        }
    };
    auto map3 = [&](SOp o) {
        uint32_t a = arg(0), b = arg(1), c = arg(2), d = def();
        uint32_t fa = argn(0), fb = argn(1), fc = argn(2);
        for (uint32_t i = 0; i < n; ++i)
            emit(o, d + i, a + (fa > 1 ? i : 0), b + (fb > 1 ? i : 0), c + (fc > 1 ? i : 0));
    };
    // Matrices as columns of row registers, for lavapipe's determinant (vtn build_det): expand along column 0,
    // prod_i = m[0][i] * subdet(without row i, column 0), det = (prod_0 - prod_1) + (prod_2 - prod_3).
    using Mat = std::vector<std::vector<uint32_t>>;
    auto columns = [&](uint32_t id) {
        const Type& mt = type(val(id).type);
        if (mt.kind != Type::Matrix || mt.count < 2 || mt.count > 4 || type(mt.elem).count != mt.count)
            fail("determinant/inverse of a non-square matrix");
        uint32_t r0 = reg(id);
        Mat m(mt.count, std::vector<uint32_t>(mt.count));
        for (uint32_t c = 0; c < mt.count; ++c)
            for (uint32_t r = 0; r < mt.count; ++r) m[c][r] = r0 + c * mt.count + r;
        return m;
    };
    std::function<uint32_t(const Mat&)> det;
    // determinant of m without row `row` and column `col` (a 2x2's is the opposite element)
    auto subdet = [&](const Mat& m, uint32_t row, uint32_t col) -> uint32_t {
        size_t size = m.size();
        if (size == 2) return m[1 - col][1 - row];
        Mat sub;
        for (size_t j = 0; j < size; ++j) {
            if (j == col) continue;
            std::vector<uint32_t> c;
            for (size_t r = 0; r < size; ++r)
                if (r != row) c.push_back(m[j][r]);
            sub.push_back(c);
        }
        return det(sub);
    };
    det = [&](const Mat& m) -> uint32_t {
        uint32_t size = uint32_t(m.size());
        std::vector<uint32_t> prod(size);
        for (uint32_t i = 0; i < size; ++i) prod[i] = emit1(SOp::FMul, m[0][i], subdet(m, i, 0));
        uint32_t result = kNoReg;
        for (uint32_t i = 0; i < size; i += 2) {
            uint32_t term = i + 1 < size ? emit1(SOp::FSub, prod[i], prod[i + 1]) : prod[i];
            result = result == kNoReg ? term : emit1(SOp::FAdd, result, term);
        }
        return result;
    };
    // Modf/Frexp return the second part through a pointer operand; the *Struct forms return {first, second}.
    auto store_pair = [&](bool through_pointer, uint32_t first, uint32_t second, uint32_t m) {
        uint32_t d = def();
        for (uint32_t i = 0; i < m; ++i) emit(SOp::Mov, d + i, first + i);
        if (!through_pointer) {
            for (uint32_t i = 0; i < m; ++i) emit(SOp::Mov, d + m + i, second + i);
            return;
        }
        const Value& pv = val(in[6]);
        if (pv.ptr < 0) fail(std::string(glsl_std450_name(e)) + " output operand is not a pointer");
        const Pointer& p = pointers_[size_t(pv.ptr)];
        store(p, p.type, second, 0);
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
            return pow();
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
            // normalize(v) = v / sqrt(dot(v, v)): a division by the length, as lavapipe's SPIR-V front end
            // writes it (each lane rounds differently from v * inversesqrt(dot(v, v)), by up to an ulp)
            uint32_t a = arg(0);
            uint32_t len = emit1(SOp::Sqrt, dot(a, a, n));
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::FDiv, d + i, a + i, len);
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
            Mat m = columns(in[5]);
            alias(det(m));
            return;
        }
        case GLSLstd450MatrixInverse: {
            // lavapipe (vtn matrix_inverse): adjugate from the same sub-determinants, times 1/det (a division)
            Mat m = columns(in[5]);
            uint32_t size = uint32_t(m.size());
            uint32_t inv = emit1(SOp::FDiv, konstf(1.0f), det(m));
            uint32_t d = def();
            for (uint32_t c = 0; c < size; ++c)
                for (uint32_t r = 0; r < size; ++r) {
                    // adj[c][r] = (-1)^(r+c) * subdet(without row c, column r)
                    uint32_t a = subdet(m, c, r);
                    if ((r + c) % 2) a = emit1(SOp::FNeg, a);
                    emit(SOp::FMul, d + c * size + r, a, inv);
                }
            return;
        }
        case GLSLstd450Modf:
        case GLSLstd450ModfStruct: {
            // lavapipe (vtn): sign = sign(x), a = |x|; fract = |x| == inf ? (x & sign bit) : sign * fract(a);
            // whole = sign * floor(a)
            uint32_t x = arg(0);
            uint32_t m = argn(0);
            uint32_t fr = alloc(m), wh = alloc(m);
            for (uint32_t i = 0; i < m; ++i) {
                uint32_t sg = emit1(SOp::FSign, x + i), a = emit1(SOp::FAbs, x + i);
                uint32_t inf = emit1(SOp::IEq, a, konst(0x7f800000u));
                uint32_t f = emit1(SOp::FMul, sg, emit1(SOp::Fract, a));
                emit(SOp::Select, fr + i, emit1(SOp::And, x + i, konst(0x80000000u)), f, inf);
                emit(SOp::FMul, wh + i, sg, emit1(SOp::Floor, a));
            }
            store_pair(e == GLSLstd450Modf, fr, wh, m);
            return;
        }
        case GLSLstd450Frexp:
        case GLSLstd450FrexpStruct: {
            // nir_lower_frexp: significand in [0.5, 1) with x's sign, exponent such that x = sig * 2^exp
            uint32_t x = arg(0);
            uint32_t m = argn(0);
            uint32_t sig = alloc(m), ex = alloc(m);
            for (uint32_t i = 0; i < m; ++i) {
                emit(SOp::FrexpSig, sig + i, x + i);
                emit(SOp::FrexpExp, ex + i, x + i);
            }
            store_pair(e == GLSLstd450Frexp, sig, ex, m);
            return;
        }
        case GLSLstd450InterpolateAtCentroid:
        case GLSLstd450InterpolateAtSample:
        case GLSLstd450InterpolateAtOffset:
            return interpolate_at(in, e);
        case GLSLstd450PackDouble2x32:
        case GLSLstd450UnpackDouble2x32:
            fail(std::string("unsupported GLSL.std.450 instruction ") + glsl_std450_name(e) +
                 " (64-bit types are not supported)");
        default:  // IMix (reserved) and anything newer
            fail(std::string("unsupported GLSL.std.450 instruction ") + glsl_std450_name(e));
    }
}

}  // namespace tilevk::shader
