// One SPIR-V instruction -> SIMD instructions: the dispatcher and the arithmetic, logic, composite and fragment
// families (memory: translate_memory.cpp, images: translate_image.cpp, GLSL.std.450: translate_glsl.cpp).
#include <bit>
#include <cmath>

#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

// New value helpers: result type in[1], result id in[2].
uint32_t Translator::def(const Instr& in, uint32_t n) {
    uint32_t f = n ? n : std::max(1u, type(in[1]).flat);
    uint32_t r = alloc(f);
    vals_[in[2]] = Value{r, in[1]};
    return r;
}
void Translator::alias(const Instr& in, uint32_t r) {
    vals_[in[2]] = Value{r, in[1]};
}
uint32_t Translator::flat_of(uint32_t id) {
    return std::max(1u, type(val(id).type).flat);
}
bool Translator::unary(const Instr& in, Op o) {
    uint32_t a = reg(in[3]);
    uint32_t d = def(in);
    for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(o, d + i, a + i);
    return true;
}
// Binary: operands may be a vector and a scalar (broadcast) for the ops that allow it.
bool Translator::binary(const Instr& in, Op o) {
    uint32_t a = reg(in[3]), b = reg(in[4]);
    uint32_t fa = flat_of(in[3]), fb = flat_of(in[4]);
    uint32_t d = def(in);
    for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(o, d + i, a + (fa > 1 ? i : 0), b + (fb > 1 ? i : 0));
    return true;
}
bool Translator::swapped(const Instr& in, Op o) {  // a > b  ==  b < a
    uint32_t a = reg(in[3]), b = reg(in[4]);
    uint32_t d = def(in);
    for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(o, d + i, b + i, a + i);
    return true;
}
// dot product: ((a0*b0 + a1*b1) + a2*b2) + a3*b3  (mul then add, left to right, as NIR's fsum after fmul)
uint32_t Translator::dot(uint32_t a, uint32_t b, uint32_t n) {
    uint32_t s = emit1(Op::FMul, a, b);
    for (uint32_t i = 1; i < n; ++i) s = emit1(Op::FAdd, s, emit1(Op::FMul, a + i, b + i));
    return s;
}

// One instruction of a block, by family.
void Translator::op(const Instr& in) {
    switch (in.op) {
        case spv::Op::OpNop:
        case spv::Op::OpLine:
        case spv::Op::OpNoLine:
        case spv::Op::OpName:
        case spv::Op::OpSelectionMerge:
        case spv::Op::OpLoopMerge:
        // A workgroup runs on one thread, its memory coherent; buffer atomics are sequentially consistent: a memory
        // barrier has nothing left to order.
        case spv::Op::OpMemoryBarrier:
            return;
        case spv::Op::OpExtInst:
            if (in.n > 3 && in[3] != glsl_ext_) return;  // NonSemantic.*: no effect (collect_blocks)
            if (op_narrow(in) || (in.n > 4 && in[3] == glsl_ext_ && glsl_wide(in))) return;
            return glsl_op(in);
        case spv::Op::OpFunctionCall:
            fail("unsupported opcode OpFunctionCall (function was not inlined)");
        default:
            break;
    }
    if (op_narrow(in) || op_pointer(in) || op_wide(in)) return;
    if (op_arith(in) || op_logic(in) || op_composite(in) || op_fragment(in) || op_memory(in) || op_image(in) ||
        op_atomic(in) || op_subgroup(in) || op_dot(in))
        return;
    fail("unsupported opcode " + opname(in.op));
}

// Float and integer arithmetic, bit operations, extended arithmetic.
bool Translator::op_arith(const Instr& in) {
    switch (in.op) {
        // float arithmetic
        case spv::Op::OpFAdd:
            return binary(in, SOp::FAdd);
        case spv::Op::OpFSub:
            return binary(in, SOp::FSub);
        case spv::Op::OpFMul:
            return binary(in, SOp::FMul);
        case spv::Op::OpFDiv:
            return binary(in, SOp::FDiv);
        case spv::Op::OpFRem:
            return binary(in, SOp::FRem);
        case spv::Op::OpFMod:
            return binary(in, SOp::FMod);
        case spv::Op::OpFNegate:
            return unary(in, SOp::FNeg);
        case spv::Op::OpVectorTimesScalar:
        case spv::Op::OpMatrixTimesScalar:
            return binary(in, SOp::FMul);
        // integer arithmetic
        case spv::Op::OpIAdd:
            return binary(in, SOp::IAdd);
        case spv::Op::OpISub:
            return binary(in, SOp::ISub);
        case spv::Op::OpIMul:
            return binary(in, SOp::IMul);
        case spv::Op::OpSDiv:
            return binary(in, SOp::SDiv);
        case spv::Op::OpUDiv:
            return binary(in, SOp::UDiv);
        case spv::Op::OpSRem:
            return binary(in, SOp::SRem);
        case spv::Op::OpSMod:
            return binary(in, SOp::SMod);
        case spv::Op::OpUMod:
            return binary(in, SOp::UMod);
        case spv::Op::OpSNegate:
            return unary(in, SOp::INeg);
        case spv::Op::OpBitwiseAnd:
        case spv::Op::OpLogicalAnd:
            return binary(in, SOp::And);
        case spv::Op::OpBitwiseOr:
        case spv::Op::OpLogicalOr:
            return binary(in, SOp::Or);
        case spv::Op::OpBitwiseXor:
        case spv::Op::OpLogicalNotEqual:
            return binary(in, SOp::Xor);
        case spv::Op::OpLogicalEqual:
            return binary(in, SOp::IEq);
        case spv::Op::OpNot:
        case spv::Op::OpLogicalNot:
            return unary(in, SOp::Not);
        case spv::Op::OpShiftLeftLogical:
            return binary(in, SOp::Shl);
        case spv::Op::OpShiftRightLogical:
            return binary(in, SOp::ShrL);
        case spv::Op::OpShiftRightArithmetic:
            return binary(in, SOp::ShrA);
        case spv::Op::OpBitCount:
            return unary(in, SOp::BitCount);
        case spv::Op::OpBitReverse:
            return unary(in, SOp::BitReverse);
        case spv::Op::OpBitFieldSExtract:
        case spv::Op::OpBitFieldUExtract: {
            uint32_t a = reg(in[3]), off = reg(in[4]), cnt = reg(in[5]);
            uint32_t d = def(in);
            for (uint32_t i = 0; i < type(in[1]).flat; ++i)
                emit(in.op == spv::Op::OpBitFieldSExtract ? SOp::BfeS : SOp::BfeU, d + i, a + i, off, cnt);
            return true;
        }
        case spv::Op::OpBitFieldInsert: {
            uint32_t a = reg(in[3]), ins = reg(in[4]), off = reg(in[5]), cnt = reg(in[6]);
            uint32_t d = def(in);
            for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(SOp::Bfi, d + i, a + i, ins + i, off, cnt);
            return true;
        }
        // extended arithmetic: the result is a struct {low/value, high/carry/borrow} of equal vector types
        case spv::Op::OpIAddCarry:
        case spv::Op::OpISubBorrow:
        case spv::Op::OpUMulExtended:
        case spv::Op::OpSMulExtended: {
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t n = flat_of(in[3]);
            uint32_t d = def(in);
            for (uint32_t i = 0; i < n; ++i) {
                switch (in.op) {
                    case spv::Op::OpIAddCarry:  // carry = (a + b) < a
                        emit(SOp::IAdd, d + i, a + i, b + i);
                        emit(SOp::And, d + n + i, emit1(SOp::ULt, d + i, a + i), konst(1));
                        break;
                    case spv::Op::OpISubBorrow:  // borrow = a < b
                        emit(SOp::ISub, d + i, a + i, b + i);
                        emit(SOp::And, d + n + i, emit1(SOp::ULt, a + i, b + i), konst(1));
                        break;
                    default:
                        emit(SOp::IMul, d + i, a + i, b + i);
                        emit(in.op == spv::Op::OpUMulExtended ? SOp::MulHiU : SOp::MulHiS, d + n + i, a + i, b + i);
                        break;
                }
            }
            return true;
        }
        default:
            return false;
    }
}

// Comparisons, logical reductions, selects, conversions.
bool Translator::op_logic(const Instr& in) {
    switch (in.op) {
        // comparisons
        case spv::Op::OpIEqual:
            return binary(in, SOp::IEq);
        case spv::Op::OpINotEqual:
            return binary(in, SOp::INe);
        case spv::Op::OpSLessThan:
            return binary(in, SOp::SLt);
        case spv::Op::OpSLessThanEqual:
            return binary(in, SOp::SLe);
        case spv::Op::OpSGreaterThan:
            return swapped(in, SOp::SLt);
        case spv::Op::OpSGreaterThanEqual:
            return swapped(in, SOp::SLe);
        case spv::Op::OpULessThan:
            return binary(in, SOp::ULt);
        case spv::Op::OpULessThanEqual:
            return binary(in, SOp::ULe);
        case spv::Op::OpUGreaterThan:
            return swapped(in, SOp::ULt);
        case spv::Op::OpUGreaterThanEqual:
            return swapped(in, SOp::ULe);
        case spv::Op::OpFOrdEqual:
            return binary(in, SOp::FOrdEq);
        case spv::Op::OpFOrdNotEqual:
            return binary(in, SOp::FOrdNe);
        case spv::Op::OpFOrdLessThan:
            return binary(in, SOp::FOrdLt);
        case spv::Op::OpFOrdLessThanEqual:
            return binary(in, SOp::FOrdLe);
        case spv::Op::OpFOrdGreaterThan:
            return swapped(in, SOp::FOrdLt);
        case spv::Op::OpFOrdGreaterThanEqual:
            return swapped(in, SOp::FOrdLe);
        case spv::Op::OpFUnordEqual:
            return binary(in, SOp::FUnordEq);
        case spv::Op::OpFUnordNotEqual:
            return binary(in, SOp::FUnordNe);
        case spv::Op::OpFUnordLessThan:
            return binary(in, SOp::FUnordLt);
        case spv::Op::OpFUnordLessThanEqual:
            return binary(in, SOp::FUnordLe);
        case spv::Op::OpFUnordGreaterThan:
            return swapped(in, SOp::FUnordLt);
        case spv::Op::OpFUnordGreaterThanEqual:
            return swapped(in, SOp::FUnordLe);
        case spv::Op::OpIsNan:
            return unary(in, SOp::IsNan);
        case spv::Op::OpIsInf:
            return unary(in, SOp::IsInf);
        case spv::Op::OpAny:
        case spv::Op::OpAll: {
            uint32_t a = reg(in[3]);
            uint32_t n = flat_of(in[3]);
            uint32_t r = a;
            for (uint32_t i = 1; i < n; ++i) r = emit1(in.op == spv::Op::OpAny ? SOp::Or : SOp::And, r, a + i);
            emit(SOp::Mov, def(in), r);
            return true;
        }
        case spv::Op::OpSelect: {
            uint32_t c = reg(in[3]), a = reg(in[4]), b = reg(in[5]);
            bool scalar_c = flat_of(in[3]) == 1;
            uint32_t d = def(in);
            for (uint32_t i = 0; i < type(in[1]).flat; ++i)
                emit(SOp::Select, d + i, a + i, b + i, c + (scalar_c ? 0 : i));
            return true;
        }
        // conversions
        case spv::Op::OpConvertFToS:
            return unary(in, SOp::F2S);
        case spv::Op::OpConvertFToU:
            return unary(in, SOp::F2U);
        case spv::Op::OpConvertSToF:
            return unary(in, SOp::S2F);
        case spv::Op::OpConvertUToF:
            return unary(in, SOp::U2F);
        case spv::Op::OpBitcast:
        case spv::Op::OpCopyObject:
        case spv::Op::OpCopyLogical:  // SPIR-V 1.4: a copy between types of another layout; registers have none
        case spv::Op::OpUConvert:
        case spv::Op::OpSConvert:
        case spv::Op::OpFConvert: {
            if (flat_of(in[3]) != std::max(1u, type(in[1]).flat)) fail(opname(in.op) + " between different sizes");
            const Value& v = val(in[3]);
            if (v.is_phi)
                unary(in, SOp::Mov);
            else if (v.ptr >= 0)  // (PhysicalStorageBuffer pointers have registers too)
                vals_[in[2]] = Value{v.reg, in[1], v.ptr};
            else
                alias(in, v.reg);
            return true;
        }
        default:
            return false;
    }
}

// Composites, vector/matrix products.
bool Translator::op_composite(const Instr& in) {
    switch (in.op) {
        // composites
        case spv::Op::OpCompositeExtract: {
            const Value& v = val(in[3]);
            uint32_t t;
            uint32_t off = flat_index(v.type, in.w + 4, in.n - 4, &t);
            if (v.is_phi) {
                uint32_t d = def(in);
                for (uint32_t i = 0; i < std::max(1u, type(in[1]).flat); ++i) emit(SOp::Mov, d + i, v.reg + off + i);
            } else {
                alias(in, v.reg + off);
            }
            return true;
        }
        case spv::Op::OpCompositeInsert: {
            const Value& obj = val(in[3]);
            const Value& comp = val(in[4]);
            uint32_t t;
            uint32_t off = flat_index(comp.type, in.w + 5, in.n - 5, &t);
            uint32_t n = type(in[1]).flat;
            uint32_t objr = obj.reg, compr = comp.reg, objn = type(obj.type).flat;
            uint32_t d = def(in);
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Mov, d + i, compr + i);
            for (uint32_t i = 0; i < objn; ++i) emit(SOp::Mov, d + off + i, objr + i);
            return true;
        }
        case spv::Op::OpCompositeConstruct: {
            uint32_t d = def(in);
            uint32_t at = 0;
            for (size_t k = 3; k < in.n; ++k) {
                uint32_t r = reg(in[k]);
                uint32_t f = flat_of(in[k]);
                for (uint32_t i = 0; i < f; ++i) emit(SOp::Mov, d + at + i, r + i);
                at += f;
            }
            return true;
        }
        case spv::Op::OpVectorShuffle: {
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t na = flat_of(in[3]);
            uint32_t d = def(in);
            for (size_t k = 5; k < in.n; ++k) {
                uint32_t s = in[k];
                uint32_t src = s == 0xFFFFFFFFu ? zero_ : s < na ? a + s : b + (s - na);
                emit(SOp::Mov, d + uint32_t(k - 5), src);
            }
            return true;
        }
        case spv::Op::OpVectorExtractDynamic: {
            uint32_t v = reg(in[3]), idx = reg(in[4]);
            uint32_t n = flat_of(in[3]);
            uint32_t d = def(in);
            emit(SOp::Mov, d, v);  // out-of-range index reads component 0 (undefined in SPIR-V)
            for (uint32_t i = 1; i < n; ++i) emit(SOp::Select, d, v + i, d, emit1(SOp::IEq, idx, konst(i)));
            return true;
        }
        case spv::Op::OpVectorInsertDynamic: {
            uint32_t v = reg(in[3]), c = reg(in[4]), idx = reg(in[5]);
            uint32_t n = flat_of(in[3]);
            uint32_t d = def(in);
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Select, d + i, c, v + i, emit1(SOp::IEq, idx, konst(i)));
            return true;
        }
        case spv::Op::OpTranspose: {
            const Type& rt = type(in[1]);
            uint32_t rows = type(rt.elem).count, cols = rt.count;  // result: cols columns of rows
            uint32_t m = reg(in[3]);
            uint32_t d = def(in);
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r) emit(SOp::Mov, d + c * rows + r, m + r * cols + c);
            return true;
        }
        case spv::Op::OpDot: {
            uint32_t s = dot(reg(in[3]), reg(in[4]), flat_of(in[3]));
            alias(in, s);
            return true;
        }
        case spv::Op::OpMatrixTimesVector: {
            // As lavapipe (Mesa's spirv/vtn_alu.c matrix_multiply): from the last column back to the first,
            // r = c3*v3, then r = c_j*v_j + r (its ffma, split into mul then add by lower_ffma32):
            // ((c3*v3 + c2*v2) + c1*v1) + c0*v0. The opposite order differs in the last bit (vkcube's MVP).
            const Type& mt = type(val(in[3]).type);
            uint32_t rows = type(mt.elem).count, cols = mt.count;
            uint32_t m = reg(in[3]), v = reg(in[4]);
            uint32_t d = def(in);
            for (uint32_t r = 0; r < rows; ++r) {
                uint32_t s = emit1(SOp::FMul, m + (cols - 1) * rows + r, v + cols - 1);
                for (uint32_t c = cols - 1; c-- > 0;)
                    s = emit1(SOp::FAdd, emit1(SOp::FMul, m + c * rows + r, v + c), s);
                emit(SOp::Mov, d + r, s);
            }
            return true;
        }
        case spv::Op::OpVectorTimesMatrix: {
            const Type& mt = type(val(in[4]).type);
            uint32_t rows = type(mt.elem).count, cols = mt.count;
            uint32_t v = reg(in[3]), m = reg(in[4]);
            uint32_t d = def(in);
            for (uint32_t c = 0; c < cols; ++c) emit(SOp::Mov, d + c, dot(v, m + c * rows, rows));
            return true;
        }
        case spv::Op::OpMatrixTimesMatrix: {
            const Type& lt = type(val(in[3]).type);
            const Type& rt = type(val(in[4]).type);
            uint32_t rows = type(lt.elem).count, inner = lt.count, cols = rt.count;
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t d = def(in);
            for (uint32_t c = 0; c < cols; ++c)  // each column as OpMatrixTimesVector: last term first
                for (uint32_t r = 0; r < rows; ++r) {
                    uint32_t s = emit1(SOp::FMul, a + (inner - 1) * rows + r, b + c * inner + inner - 1);
                    for (uint32_t k = inner - 1; k-- > 0;)
                        s = emit1(SOp::FAdd, emit1(SOp::FMul, a + k * rows + r, b + c * inner + k), s);
                    emit(SOp::Mov, d + c * rows + r, s);
                }
            return true;
        }
        case spv::Op::OpOuterProduct: {
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t rows = flat_of(in[3]), cols = flat_of(in[4]);
            uint32_t d = def(in);
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r) emit(SOp::FMul, d + c * rows + r, a + r, b + c);
            return true;
        }
        default:
            return false;
    }
}

// Derivatives, demote, helper-invocation queries (fragment shaders).
bool Translator::op_fragment(const Instr& in) {
    switch (in.op) {
        // derivatives
        case spv::Op::OpDPdx:
        case spv::Op::OpDPdxFine:
        case spv::Op::OpDPdy:
        case spv::Op::OpDPdyFine:
        case spv::Op::OpDPdxCoarse:
        case spv::Op::OpDPdyCoarse:
        case spv::Op::OpFwidth:
        case spv::Op::OpFwidthFine:
        case spv::Op::OpFwidthCoarse: {
            if (stage_ != Stage::Fragment) fail(opname(in.op) + " outside a fragment shader");
            iface_.uses_derivatives = true;
            bool coarse =
                in.op == spv::Op::OpDPdxCoarse || in.op == spv::Op::OpDPdyCoarse || in.op == spv::Op::OpFwidthCoarse;
            SOp dx = coarse ? SOp::DdxCoarse : SOp::DdxFine, dy = coarse ? SOp::DdyCoarse : SOp::DdyFine;
            uint32_t a = reg(in[3]);
            uint32_t d = def(in);
            uint32_t n = std::max(1u, type(in[1]).flat);
            // reads neighbour lanes: in a loop, keep the value a lane computed while it was active
            keep_active(d, n, [&](uint32_t t) {
                for (uint32_t i = 0; i < n; ++i) {
                    if (in.op == spv::Op::OpDPdx || in.op == spv::Op::OpDPdxFine || in.op == spv::Op::OpDPdxCoarse)
                        emit(dx, t + i, a + i);
                    else if (in.op == spv::Op::OpDPdy || in.op == spv::Op::OpDPdyFine || in.op == spv::Op::OpDPdyCoarse)
                        emit(dy, t + i, a + i);
                    else
                        emit(SOp::FAdd, t + i, emit1(SOp::FAbs, emit1(dx, a + i)), emit1(SOp::FAbs, emit1(dy, a + i)));
                }
            });
            return true;
        }
        case spv::Op::OpDemoteToHelperInvocation:
            if (stage_ != Stage::Fragment) fail("demote outside a fragment shader");
            iface_.uses_discard = true;
            emit(SOp::Kill, p_.reg_live, cur_mask_);
            store_mask_ = kNoReg;
            return true;
        case spv::Op::OpIsHelperInvocationEXT:
            emit(SOp::Not, def(in), p_.reg_live);
            return true;
        default:
            return false;
    }
}

}  // namespace tilevk::shader
