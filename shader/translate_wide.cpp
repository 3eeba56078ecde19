// 64-bit integers and doubles (capabilities Int64, Float64): every 64-bit scalar is two registers, low word then
// high word, so moves, composites, phis, local memory and buffers (two words, translate_memory.cpp) need nothing
// else; arithmetic, comparisons and conversions become Op::Wide (exec_wide.h), one per component, whose kernels
// follow llvmpipe (shader/README.md "64-bit types"). An instruction with a 64-bit operand or result that is not
// listed here fails by name.
#include <bit>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

namespace {

// The per-component WideOp of a SPIR-V instruction with 64-bit operands (kNone: not an element-wise one).
constexpr auto kNone = WideOp(0xFFFF);
WideOp elementwise(spv::Op op) {
    switch (op) {
        case spv::Op::OpIAdd:
            return WideOp::IAdd;
        case spv::Op::OpISub:
            return WideOp::ISub;
        case spv::Op::OpIMul:
            return WideOp::IMul;
        case spv::Op::OpSDiv:
            return WideOp::SDiv;
        case spv::Op::OpUDiv:
            return WideOp::UDiv;
        case spv::Op::OpSRem:
            return WideOp::SRem;
        case spv::Op::OpSMod:
            return WideOp::SMod;
        case spv::Op::OpUMod:
            return WideOp::UMod;
        case spv::Op::OpSNegate:
            return WideOp::INeg;
        case spv::Op::OpNot:
            return WideOp::Not;
        case spv::Op::OpBitwiseAnd:
            return WideOp::And;
        case spv::Op::OpBitwiseOr:
            return WideOp::Or;
        case spv::Op::OpBitwiseXor:
            return WideOp::Xor;
        case spv::Op::OpShiftLeftLogical:
            return WideOp::Shl;
        case spv::Op::OpShiftRightLogical:
            return WideOp::ShrL;
        case spv::Op::OpShiftRightArithmetic:
            return WideOp::ShrA;
        case spv::Op::OpFAdd:
            return WideOp::FAdd;
        case spv::Op::OpFSub:
            return WideOp::FSub;
        case spv::Op::OpFMul:
            return WideOp::FMul;
        case spv::Op::OpVectorTimesScalar:
            return WideOp::FMul;
        case spv::Op::OpMatrixTimesScalar:
            return WideOp::FMul;
        case spv::Op::OpFDiv:
            return WideOp::FDiv;
        case spv::Op::OpFRem:
            return WideOp::FRem;
        case spv::Op::OpFMod:
            return WideOp::FMod;
        case spv::Op::OpFNegate:
            return WideOp::FNeg;
        case spv::Op::OpIEqual:
            return WideOp::IEq;
        case spv::Op::OpINotEqual:
            return WideOp::INe;
        case spv::Op::OpSLessThan:
            return WideOp::SLt;
        case spv::Op::OpSLessThanEqual:
            return WideOp::SLe;
        case spv::Op::OpULessThan:
            return WideOp::ULt;
        case spv::Op::OpULessThanEqual:
            return WideOp::ULe;
        case spv::Op::OpFOrdEqual:
            return WideOp::FOrdEq;
        case spv::Op::OpFOrdNotEqual:
            return WideOp::FOrdNe;
        case spv::Op::OpFOrdLessThan:
            return WideOp::FOrdLt;
        case spv::Op::OpFOrdLessThanEqual:
            return WideOp::FOrdLe;
        case spv::Op::OpFUnordEqual:
            return WideOp::FUnordEq;
        case spv::Op::OpFUnordNotEqual:
            return WideOp::FUnordNe;
        case spv::Op::OpFUnordLessThan:
            return WideOp::FUnordLt;
        case spv::Op::OpFUnordLessThanEqual:
            return WideOp::FUnordLe;
        case spv::Op::OpIsNan:
            return WideOp::IsNan;
        case spv::Op::OpIsInf:
            return WideOp::IsInf;
        case spv::Op::OpBitCount:
            return WideOp::BitCount;
        default:
            return kNone;
    }
}

// a > b as b < a (operands swapped)
WideOp swapped_compare(spv::Op op) {
    switch (op) {
        case spv::Op::OpSGreaterThan:
            return WideOp::SLt;
        case spv::Op::OpSGreaterThanEqual:
            return WideOp::SLe;
        case spv::Op::OpUGreaterThan:
            return WideOp::ULt;
        case spv::Op::OpUGreaterThanEqual:
            return WideOp::ULe;
        case spv::Op::OpFOrdGreaterThan:
            return WideOp::FOrdLt;
        case spv::Op::OpFOrdGreaterThanEqual:
            return WideOp::FOrdLe;
        case spv::Op::OpFUnordGreaterThan:
            return WideOp::FUnordLt;
        case spv::Op::OpFUnordGreaterThanEqual:
            return WideOp::FUnordLe;
        default:
            return kNone;
    }
}

}  // namespace

bool Translator::is_wide_type(uint32_t t) const {
    return t != 0 && t < bound_ && is_type_[t] && type(component_type(t)).wide;
}
bool Translator::is_wide_value(uint32_t id) const {
    return id < bound_ && !is_type_[id] && vals_[id].reg != kNoReg && vals_[id].type != 0 &&
           (type(vals_[id].type).kind == Type::Int || type(vals_[id].type).kind == Type::Float ||
            type(vals_[id].type).kind == Type::Vector || type(vals_[id].type).kind == Type::Matrix) &&
           is_wide_type(vals_[id].type);
}
uint32_t Translator::words_of(uint32_t t) const {
    return is_wide_type(t) ? 2 : 1;
}
uint32_t Translator::components_of(uint32_t t) const {
    return std::max(1u, type(t).flat) / words_of(t);
}
uint32_t Translator::konst64(uint64_t v) {
    const uint32_t r = alloc(2);
    set_const(r, uint32_t(v));
    set_const(r + 1, uint32_t(v >> 32));
    return r;
}
uint32_t Translator::wide(WideOp o, uint32_t d, uint32_t a, uint32_t b, uint32_t c) {
    if (d == kNoReg) d = alloc((wide_shape(o) & 1) ? 2 : 1);
    emit(SOp::Wide, d, a, b, c).pad = uint16_t(o);
    return d;
}

// o per component of the result; operands ids[] (a scalar operand of a vector result is broadcast). Register k of
// an operand is its component k's first word.
void Translator::wide_each(const Instr& in, WideOp o, std::initializer_list<uint32_t> ids, uint32_t d) {
    const uint32_t n = components_of(in[1]), dw = words_of(in[1]);
    if (d == kNoReg) d = def(in);
    for (uint32_t k = 0; k < n; ++k) {
        uint32_t ops[3] = {kNoReg, kNoReg, kNoReg}, j = 0;
        for (uint32_t id : ids) {
            const uint32_t t = val(id).type;
            ops[j++] = reg(id) + (components_of(t) > 1 ? k : 0) * words_of(t);
        }
        wide(o, d + k * dw, ops[0], ops[1], ops[2]);
    }
}

// One instruction with a 64-bit operand or result; false for any other (and for the moves, which need nothing).
bool Translator::op_wide(const Instr& in) {
    // 64-bit atomics are refused by translate_atomic.cpp, with the Vulkan features that would allow them
    if ((in.op >= spv::Op::OpAtomicLoad && in.op <= spv::Op::OpAtomicXor) || in.op == spv::Op::OpAtomicFAddEXT)
        return false;
    const bool result = in.n > 2 && is_wide_type(in[1]);
    bool any = result;
    const size_t end = in.op == spv::Op::OpVectorShuffle ? 5 : in.n;
    for (size_t i = 3; i < end && !any; ++i) any = is_wide_value(in[i]);
    if (!any) return false;
    switch (in.op) {
        case spv::Op::OpBitcast:
        case spv::Op::OpCopyObject:
        case spv::Op::OpCopyLogical:
        case spv::Op::OpCompositeExtract:
        case spv::Op::OpCompositeInsert:
        case spv::Op::OpCompositeConstruct:
        case spv::Op::OpLoad:
        case spv::Op::OpStore:
        case spv::Op::OpVariable:
        case spv::Op::OpAccessChain:  // a 64-bit index: its low word, the same offset in 32-bit arithmetic
        case spv::Op::OpInBoundsAccessChain:
        case spv::Op::OpPtrAccessChain:
        case spv::Op::OpUndef:
        case spv::Op::OpPhi:
        case spv::Op::OpReturnValue:
        case spv::Op::OpGroupNonUniformBroadcast:  // per register (translate_subgroup.cpp)
        case spv::Op::OpGroupNonUniformBroadcastFirst:
            return false;
        case spv::Op::OpGroupNonUniformAllEqual:  // word by word: right for integers, not for doubles (-0, NaN)
            if (type(component_type(val(in[4]).type)).kind == Type::Int) return false;
            break;
        default:
            break;
    }
    if (const WideOp o = elementwise(in.op); o != kNone) {
        // a 32-bit result of a shift or bit count with 64-bit operands
        if (!result && wide_shape(o) & 1) {
            if (in.op == spv::Op::OpShiftLeftLogical || in.op == spv::Op::OpShiftRightLogical ||
                in.op == spv::Op::OpShiftRightArithmetic) {
                // a 32-bit base shifted by a 64-bit count: the count's low word
                const SOp s = in.op == spv::Op::OpShiftLeftLogical    ? SOp::Shl
                              : in.op == spv::Op::OpShiftRightLogical ? SOp::ShrL
                                                                      : SOp::ShrA;
                const uint32_t n = components_of(in[1]), d = def(in), a = reg(in[3]), b = reg(in[4]);
                for (uint32_t k = 0; k < n; ++k) emit(s, d + k, a + k, b + k * 2);
                return true;
            }
            fail(opname(in.op) + " with a 64-bit operand and a 32-bit result is not supported");
        }
        if (o == WideOp::BitCount && result) {  // bitCount of a 64-bit value into a 64-bit result: high word 0
            const uint32_t n = components_of(in[1]), d = def(in);
            for (uint32_t k = 0; k < n; ++k) {
                wide(o, d + 2 * k, reg(in[3]) + 2 * k);
                emit(SOp::Mov, d + 2 * k + 1, zero_);
            }
            return true;
        }
        std::initializer_list<uint32_t> one = {in[3]}, two = {in[3], in.n > 4 ? in[4] : in[3]};
        wide_each(in, o, in.n > 4 ? two : one);
        return true;
    }
    if (const WideOp o = swapped_compare(in.op); o != kNone) {
        wide_each(in, o, {in[4], in[3]});
        return true;
    }
    if (op_wide_convert(in) || op_wide_composite(in)) return true;
    fail("unsupported 64-bit operation " + opname(in.op));
}

// OpFConvert, OpSConvert, OpUConvert, OpConvertFToS/FToU/SToF/UToF with a 64-bit side.
bool Translator::op_wide_convert(const Instr& in) {
    const bool to64 = is_wide_type(in[1]), from64 = is_wide_type(val(in[3]).type);
    const uint32_t n = components_of(in[1]), a = reg(in[3]);
    auto each = [&](WideOp o) {
        wide_each(in, o, {in[3]});
        return true;
    };
    switch (in.op) {
        case spv::Op::OpFConvert:
            if (to64 == from64) return false;  // same width: a copy (translate_ops.cpp)
            return each(to64 ? WideOp::F32ToF64 : WideOp::F64ToF32);
        case spv::Op::OpUConvert:
        case spv::Op::OpSConvert: {
            if (to64 == from64) return false;
            const uint32_t d = def(in);
            for (uint32_t k = 0; k < n; ++k) {
                if (!to64) {  // the low word
                    emit(SOp::Mov, d + k, a + 2 * k);
                    continue;
                }
                emit(SOp::Mov, d + 2 * k, a + k);
                if (in.op == spv::Op::OpSConvert)
                    emit(SOp::ShrA, d + 2 * k + 1, a + k, konst(31));
                else
                    emit(SOp::Mov, d + 2 * k + 1, zero_);
            }
            return true;
        }
        case spv::Op::OpConvertFToS:
            if (from64) f2s_of_[in[2]] = in[3];
            if (to64) return each(from64 ? WideOp::F64ToS64 : WideOp::F32ToS64);
            return each(WideOp::F64ToS32);
        case spv::Op::OpConvertFToU:
            if (to64) return each(from64 ? WideOp::F64ToU64 : WideOp::F32ToU64);
            return each(WideOp::F64ToU32);
        case spv::Op::OpConvertSToF:
            // NIR's algebraic rule i2f(f2i(a)) -> ftrunc(a) for a double a (lavapipe's double(int(x)) of an x out of
            // int range is trunc(x), not -2^31: cts types.float64.*)
            if (auto it = f2s_of_.find(in[3]); to64 && it != f2s_of_.end() && val(it->second).type == in[1]) {
                wide_each(in, WideOp::Trunc, {it->second});
                return true;
            }
            if (to64) return each(from64 ? WideOp::S64ToF64 : WideOp::S32ToF64);
            return each(WideOp::S64ToF32);
        case spv::Op::OpConvertUToF:
            if (to64) return each(from64 ? WideOp::U64ToF64 : WideOp::U32ToF64);
            return each(WideOp::U64ToF32);
        default:
            return false;
    }
}

// Sum of products over n components of 64-bit vectors at a and b (component k at a + 2k): ((a0*b0 + a1*b1) +
// a2*b2) + a3*b3, as the 32-bit dot (fsum of fmul).
uint32_t Translator::dot64(uint32_t a, uint32_t b, uint32_t n) {
    uint32_t s = wide(WideOp::FMul, kNoReg, a, b);
    for (uint32_t i = 1; i < n; ++i)
        s = wide(WideOp::FAdd, kNoReg, s, wide(WideOp::FMul, kNoReg, a + 2 * i, b + 2 * i));
    return s;
}

// Selects, shuffles, dynamic component access, vector and matrix products of 64-bit values.
bool Translator::op_wide_composite(const Instr& in) {
    switch (in.op) {
        case spv::Op::OpSelect: {  // one condition per component, both words
            const uint32_t c = reg(in[3]), a = reg(in[4]), b = reg(in[5]), d = def(in);
            const bool scalar_c = flat_of(in[3]) == 1;
            const uint32_t w = words_of(in[1]);
            for (uint32_t i = 0; i < type(in[1]).flat; ++i)
                emit(SOp::Select, d + i, a + i, b + i, c + (scalar_c ? 0 : i / w));
            return true;
        }
        case spv::Op::OpVectorShuffle: {
            const uint32_t a = reg(in[3]), b = reg(in[4]), na = components_of(val(in[3]).type), d = def(in);
            for (size_t k = 5; k < in.n; ++k) {
                const uint32_t s = in[k];
                for (uint32_t w = 0; w < 2; ++w) {
                    const uint32_t src = s == 0xFFFFFFFFu ? zero_ : s < na ? a + 2 * s + w : b + 2 * (s - na) + w;
                    emit(SOp::Mov, d + 2 * uint32_t(k - 5) + w, src);
                }
            }
            return true;
        }
        case spv::Op::OpVectorExtractDynamic: {  // out of range: component 0 (undefined in SPIR-V)
            const uint32_t v = reg(in[3]), idx = reg(in[4]), n = components_of(val(in[3]).type), d = def(in);
            emit(SOp::Mov, d, v);
            emit(SOp::Mov, d + 1, v + 1);
            for (uint32_t i = 1; i < n; ++i) {
                const uint32_t eq = emit1(SOp::IEq, idx, konst(i));
                for (uint32_t w = 0; w < 2; ++w) emit(SOp::Select, d + w, v + 2 * i + w, d + w, eq);
            }
            return true;
        }
        case spv::Op::OpVectorInsertDynamic: {
            const uint32_t v = reg(in[3]), c = reg(in[4]), idx = reg(in[5]), n = components_of(in[1]), d = def(in);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t eq = emit1(SOp::IEq, idx, konst(i));
                for (uint32_t w = 0; w < 2; ++w) emit(SOp::Select, d + 2 * i + w, c + w, v + 2 * i + w, eq);
            }
            return true;
        }
        case spv::Op::OpTranspose: {
            const Type& rt = type(in[1]);
            const uint32_t rows = type(rt.elem).count, cols = rt.count, m = reg(in[3]), d = def(in);
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r)
                    for (uint32_t w = 0; w < 2; ++w)
                        emit(SOp::Mov, d + 2 * (c * rows + r) + w, m + 2 * (r * cols + c) + w);
            return true;
        }
        case spv::Op::OpDot:
            alias(in, dot64(reg(in[3]), reg(in[4]), components_of(val(in[3]).type)));
            return true;
        case spv::Op::OpOuterProduct: {
            const uint32_t a = reg(in[3]), b = reg(in[4]), d = def(in);
            const uint32_t rows = components_of(val(in[3]).type), cols = components_of(val(in[4]).type);
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r) wide(WideOp::FMul, d + 2 * (c * rows + r), a + 2 * r, b + 2 * c);
            return true;
        }
        default:
            return op_wide_matrix(in);
    }
}

// Matrix products in lavapipe's order (translate_ops.cpp OpMatrixTimesVector: from the last column back, each
// ffma split into mul then add by lower_ffma64).
bool Translator::op_wide_matrix(const Instr& in) {
    // column c of the product: sum over k of a[k][r] * b[c][k], from k = inner - 1 down
    auto product = [&](uint32_t a, uint32_t rows, uint32_t inner, uint32_t bcol, uint32_t d) {
        for (uint32_t r = 0; r < rows; ++r) {
            uint32_t s = wide(WideOp::FMul, kNoReg, a + 2 * ((inner - 1) * rows + r), bcol + 2 * (inner - 1));
            for (uint32_t k = inner - 1; k-- > 0;)
                s = wide(WideOp::FAdd, kNoReg, wide(WideOp::FMul, kNoReg, a + 2 * (k * rows + r), bcol + 2 * k), s);
            emit(SOp::Mov, d + 2 * r, s);
            emit(SOp::Mov, d + 2 * r + 1, s + 1);
        }
    };
    switch (in.op) {
        case spv::Op::OpMatrixTimesVector: {
            const Type& mt = type(val(in[3]).type);
            product(reg(in[3]), type(mt.elem).count, mt.count, reg(in[4]), def(in));
            return true;
        }
        case spv::Op::OpMatrixTimesMatrix: {
            const Type& lt = type(val(in[3]).type);
            const Type& rt = type(val(in[4]).type);
            const uint32_t rows = type(lt.elem).count, inner = lt.count, d = def(in);
            for (uint32_t c = 0; c < rt.count; ++c)
                product(reg(in[3]), rows, inner, reg(in[4]) + 2 * c * inner, d + 2 * c * rows);
            return true;
        }
        case spv::Op::OpVectorTimesMatrix: {
            const Type& mt = type(val(in[4]).type);
            const uint32_t rows = type(mt.elem).count, v = reg(in[3]), m = reg(in[4]), d = def(in);
            for (uint32_t c = 0; c < mt.count; ++c) {
                const uint32_t s = dot64(v, m + 2 * c * rows, rows);
                emit(SOp::Mov, d + 2 * c, s);
                emit(SOp::Mov, d + 2 * c + 1, s + 1);
            }
            return true;
        }
        default:
            return false;
    }
}

// GLSL.std.450 on 64-bit values: the instructions GLSL allows on doubles and 64-bit integers (lavapipe's NIR for
// them, as the 32-bit forms in translate_glsl.cpp); false when no operand or result is 64-bit.
bool Translator::glsl_wide(const Instr& in) {
    bool any = is_wide_type(in[1]);
    for (size_t i = 5; i < in.n && !any; ++i) any = is_wide_value(in[i]);
    if (!any) return false;
    const uint32_t e = in[4];
    const uint32_t x = in.n > 5 ? in[5] : 0, y = in.n > 6 ? in[6] : 0, z = in.n > 7 ? in[7] : 0;
    auto each = [&](WideOp o, std::initializer_list<uint32_t> ids) {
        wide_each(in, o, ids);
        return true;
    };
    switch (e) {
        case GLSLstd450FAbs:
            return each(WideOp::FAbs, {x});
        case GLSLstd450FSign:
            return each(WideOp::FSign, {x});
        case GLSLstd450Floor:
            return each(WideOp::Floor, {x});
        case GLSLstd450Ceil:
            return each(WideOp::Ceil, {x});
        case GLSLstd450Trunc:
            return each(WideOp::Trunc, {x});
        case GLSLstd450Round:  // vtn: fround_even
        case GLSLstd450RoundEven:
            return each(WideOp::RoundEven, {x});
        case GLSLstd450Fract:
            return each(WideOp::Fract, {x});
        case GLSLstd450Sqrt:
            return each(WideOp::Sqrt, {x});
        case GLSLstd450InverseSqrt:
            return each(WideOp::InvSqrt, {x});
        case GLSLstd450FMin:
            return each(WideOp::FMin, {x, y});
        case GLSLstd450FMax:
            return each(WideOp::FMax, {x, y});
        case GLSLstd450Step:
            return each(WideOp::Step, {x, y});
        case GLSLstd450FClamp:
            return each(WideOp::FClamp, {x, y, z});
        case GLSLstd450SmoothStep:
            return each(WideOp::SmoothStep, {x, y, z});
        case GLSLstd450SAbs:
            return each(WideOp::SAbs, {x});
        case GLSLstd450SSign:
            return each(WideOp::SSign, {x});
        case GLSLstd450SMin:
            return each(WideOp::SMin, {x, y});
        case GLSLstd450SMax:
            return each(WideOp::SMax, {x, y});
        case GLSLstd450UMin:
            return each(WideOp::UMin, {x, y});
        case GLSLstd450UMax:
            return each(WideOp::UMax, {x, y});
        case GLSLstd450SClamp:
        case GLSLstd450UClamp: {  // min(max(x, lo), hi)
            const bool s = e == GLSLstd450SClamp;
            const uint32_t d = def(in);
            wide_each(in, s ? WideOp::SMax : WideOp::UMax, {x, y}, d);
            vals_[in[2]] = Value{d, in[1]};
            const uint32_t hi = reg(z), n = components_of(in[1]), fh = components_of(val(z).type);
            for (uint32_t k = 0; k < n; ++k)
                wide(s ? WideOp::SMin : WideOp::UMin, d + 2 * k, d + 2 * k, hi + (fh > 1 ? 2 * k : 0));
            return true;
        }
        case GLSLstd450PackDouble2x32:  // uvec2 (low, high) and a double: the same two registers
        case GLSLstd450UnpackDouble2x32:
            alias(in, reg(x));
            return true;
        default:
            return glsl_wide_composite(in, e);
    }
}

// Mix, fma and the geometric functions on doubles.
bool Translator::glsl_wide_composite(const Instr& in, uint32_t e) {
    const uint32_t n = components_of(in[1]);
    auto arg = [&](int i) { return reg(in[5 + i]); };
    auto comp = [&](int i, uint32_t k) {  // register of component k of argument i (scalars broadcast)
        return arg(i) + (components_of(val(in[5 + i]).type) > 1 ? 2 * k : 0);
    };
    auto argn = [&](int i) { return components_of(val(in[5 + i]).type); };
    auto mul = [&](uint32_t a, uint32_t b) { return wide(WideOp::FMul, kNoReg, a, b); };
    switch (e) {
        case GLSLstd450FMix: {  // x * (1 - a) + y * a, the 32-bit form (translate_glsl.cpp)
            const uint32_t d = def(in), one = konst64(std::bit_cast<uint64_t>(1.0));
            for (uint32_t k = 0; k < n; ++k)
                wide(WideOp::FAdd, d + 2 * k, mul(comp(0, k), wide(WideOp::FSub, kNoReg, one, comp(2, k))),
                     mul(comp(1, k), comp(2, k)));
            return true;
        }
        case GLSLstd450Fma: {  // lower_ffma64: mul then add
            const uint32_t d = def(in);
            for (uint32_t k = 0; k < n; ++k) wide(WideOp::FAdd, d + 2 * k, mul(comp(0, k), comp(1, k)), comp(2, k));
            return true;
        }
        case GLSLstd450Length:
            alias(in, wide(WideOp::Sqrt, kNoReg, dot64(arg(0), arg(0), argn(0))));
            return true;
        case GLSLstd450Distance: {
            const uint32_t m = argn(0), t = alloc(2 * m);
            for (uint32_t k = 0; k < m; ++k) wide(WideOp::FSub, t + 2 * k, arg(0) + 2 * k, arg(1) + 2 * k);
            alias(in, wide(WideOp::Sqrt, kNoReg, dot64(t, t, m)));
            return true;
        }
        case GLSLstd450Normalize: {  // v / sqrt(dot(v, v)), as the 32-bit form
            const uint32_t len = wide(WideOp::Sqrt, kNoReg, dot64(arg(0), arg(0), n)), d = def(in);
            for (uint32_t k = 0; k < n; ++k) wide(WideOp::FDiv, d + 2 * k, arg(0) + 2 * k, len);
            return true;
        }
        case GLSLstd450Cross: {  // a.yzx * b.zxy - a.zxy * b.yzx
            const uint32_t a = arg(0), b = arg(1), d = def(in);
            const uint32_t yy[3] = {1, 2, 0}, zz[3] = {2, 0, 1};
            for (int i = 0; i < 3; ++i)
                wide(WideOp::FSub, d + 2 * i, mul(a + 2 * yy[i], b + 2 * zz[i]), mul(a + 2 * zz[i], b + 2 * yy[i]));
            return true;
        }
        case GLSLstd450FaceForward: {  // dot(Nref, I) < 0 ? N : -N
            const uint32_t lt = wide(WideOp::FOrdLt, kNoReg, dot64(arg(2), arg(1), n), konst64(0)), d = def(in);
            for (uint32_t k = 0; k < n; ++k) {
                const uint32_t neg = wide(WideOp::FNeg, kNoReg, arg(0) + 2 * k);
                for (uint32_t w = 0; w < 2; ++w) emit(SOp::Select, d + 2 * k + w, arg(0) + 2 * k + w, neg + w, lt);
            }
            return true;
        }
        case GLSLstd450Reflect: {  // I - (2 * dot(N, I)) * N
            const uint32_t k2 = mul(konst64(std::bit_cast<uint64_t>(2.0)), dot64(arg(1), arg(0), n)), d = def(in);
            for (uint32_t k = 0; k < n; ++k) wide(WideOp::FSub, d + 2 * k, arg(0) + 2 * k, mul(k2, arg(1) + 2 * k));
            return true;
        }
        default:
            fail(std::string("unsupported GLSL.std.450 ") + glsl_std450_name(e) + " on 64-bit values");
    }
}

}  // namespace tilevk::shader
