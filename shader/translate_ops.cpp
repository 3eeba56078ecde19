// One SPIR-V instruction -> SIMD instructions: arithmetic, composites, memory, GLSL.std.450, images.
#include <bit>
#include <cmath>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/spirv_names.h"
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

namespace {
std::string opname(spv::Op op) {
    return names::opcode(uint32_t(op));
}
}  // namespace

// ---- memory ---------------------------------------------------------------------------------------------------

Pointer Translator::access_chain(const Pointer& base, const uint32_t* idx, size_t n) {
    Pointer p = base;
    for (size_t i = 0; i < n; ++i) {
        uint32_t id = idx[i];
        uint32_t cv = 0;
        bool is_const = const_of(id, cv);
        if (!is_const && val(id).reg == kNoReg) fail("invalid access chain index");
        if (p.in_array) {  // descriptor array element
            if (is_const)
                p.elem_const = cv;
            else
                p.elem = reg(id);
            p.in_array = false;
            p.type = type(p.type).elem;
            continue;
        }
        const Type& t = type(p.type);
        auto add_dyn = [&](uint32_t stride) {
            uint32_t scaled = stride == 1 ? reg(id) : emit1(SOp::IMul, reg(id), konst(stride));
            p.dyn = p.dyn == kNoReg ? scaled : emit1(SOp::IAdd, p.dyn, scaled);
        };
        if (p.space == Space::Local) {
            if (t.kind == Type::Struct) {
                if (!is_const || cv >= t.members.size()) fail("invalid struct index");
                for (uint32_t m = 0; m < cv; ++m) p.offset += type(t.members[m]).flat;
                p.type = t.members[cv];
            } else if (t.kind == Type::Array || t.kind == Type::Vector || t.kind == Type::Matrix) {
                uint32_t stride = type(t.elem).flat;
                if (is_const)
                    p.offset += std::min(cv, t.count - 1) * stride;
                else
                    add_dyn(stride);
                p.type = t.elem;
            } else {
                fail("access chain into a non-composite");
            }
            continue;
        }
        // Buffer layout (std140/std430 as decorated).
        if (t.kind == Type::Struct) {
            if (!is_const || cv >= t.members.size()) fail("invalid struct index");
            auto it = member_deco_.find({p.type, cv});
            if (it == member_deco_.end() || it->second.offset < 0) fail("buffer struct member without Offset");
            p.offset += uint32_t(it->second.offset);
            p.matrix_stride = uint32_t(it->second.matrix_stride);
            p.row_major = it->second.row_major;
            p.vec_stride = 4;
            p.type = t.members[cv];
        } else if (t.kind == Type::Array || t.kind == Type::RuntimeArray) {
            uint32_t stride = uint32_t(deco_[p.type].array_stride);
            if (stride == 0) fail("buffer array without ArrayStride");
            // a huge constant index stays in bounds of uint32 arithmetic; the executor rejects it
            if (is_const)
                p.offset = uint32_t(std::min<uint64_t>(p.offset + uint64_t(cv) * stride, 0x7fffffffu));
            else
                add_dyn(stride);
            p.type = t.elem;
        } else if (t.kind == Type::Matrix) {
            uint32_t col_stride = p.row_major ? 4 : p.matrix_stride;
            if (is_const)
                p.offset += std::min(cv, t.count) * col_stride;
            else
                add_dyn(col_stride);
            p.vec_stride = p.row_major ? p.matrix_stride : 4;
            p.type = t.elem;
        } else if (t.kind == Type::Vector) {
            if (is_const)
                p.offset += std::min(cv, t.count) * p.vec_stride;
            else
                add_dyn(p.vec_stride);
            p.type = t.elem;
        } else {
            fail("access chain into a non-composite");
        }
    }
    return p;
}

void Translator::load(const Pointer& p, uint32_t ty, uint32_t dst, uint32_t off) {
    const Type& t = type(ty);
    uint32_t dyn = p.dyn == kNoReg ? zero_ : p.dyn;
    if (p.space == Space::Local) {
        for (uint32_t i = 0; i < t.flat; ++i) {
            uint32_t w = p.base + p.offset + off + i;
            if (p.dyn == kNoReg && w < p.limit)
                emit(SOp::LoadLocalFixed, dst + i, kNoReg, kNoReg, kNoReg, w);
            else
                emit(SOp::LoadLocal, dst + i, dyn, kNoReg, kNoReg, w).n = p.limit;
        }
        return;
    }
    if (p.space == Space::Handle) {
        if (p.in_array) fail("load of a whole descriptor array");
        uint32_t shift = t.kind == Type::Sampler ? 16 : 0;
        bool both = t.kind == Type::SampledImage;
        if (p.elem == kNoReg) {
            uint32_t s = std::min(p.base + p.elem_const, p.base + p.limit - 1);
            emit(SOp::Mov, dst, konst(both ? (s | s << 16) : s << shift));
        } else {
            // clamp the element to the array (robust indexing)
            uint32_t e = emit1(SOp::UMin, p.elem, konst(p.limit - 1));
            uint32_t s = emit1(SOp::IAdd, e, konst(p.base));
            if (both)
                emit(SOp::Or, dst, s, emit1(SOp::Shl, s, konst(16)));
            else if (shift)
                emit(SOp::Shl, dst, s, konst(16));
            else
                emit(SOp::Mov, dst, s);
        }
        return;
    }
    uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
    auto scalar = [&](uint32_t d, uint32_t byte_off, uint32_t sty) {
        if (p.dyn == kNoReg && p.elem == kNoReg) {
            if (p.elem_const < p.limit)
                emit(SOp::LoadBufUniform, d, kNoReg, kNoReg, kNoReg, p.base + p.elem_const, p.offset + byte_off);
            else
                emit(SOp::Mov, d, zero_);
        } else {
            emit(SOp::LoadBuf, d, elem, dyn, kNoReg, p.base, p.offset + byte_off).n = p.limit;
        }
        if (type(sty).kind == Type::Bool) emit(SOp::INe, d, d, zero_);
    };
    switch (t.kind) {
        case Type::Bool:
        case Type::Int:
        case Type::Float:
            scalar(dst, off, ty);
            break;
        case Type::Vector:
            for (uint32_t i = 0; i < t.count; ++i) scalar(dst + i, off + i * p.vec_stride, t.elem);
            break;
        case Type::Matrix: {
            const Type& col = type(t.elem);
            for (uint32_t c = 0; c < t.count; ++c)
                for (uint32_t r = 0; r < col.count; ++r) {
                    uint32_t o = p.row_major ? c * 4 + r * p.matrix_stride : c * p.matrix_stride + r * 4;
                    scalar(dst + c * col.count + r, off + o, col.elem);
                }
            break;
        }
        case Type::Array: {
            uint32_t stride = uint32_t(deco_[ty].array_stride);
            if (!stride) fail("buffer array without ArrayStride");
            Pointer q = p;
            q.vec_stride = 4;
            for (uint32_t i = 0; i < t.count; ++i) load(q, t.elem, dst + i * type(t.elem).flat, off + i * stride);
            break;
        }
        case Type::Struct: {
            uint32_t at = 0;
            for (uint32_t m = 0; m < t.members.size(); ++m) {
                auto it = member_deco_.find({ty, m});
                if (it == member_deco_.end() || it->second.offset < 0) fail("buffer struct member without Offset");
                Pointer q = p;
                q.matrix_stride = uint32_t(it->second.matrix_stride);
                q.row_major = it->second.row_major;
                q.vec_stride = 4;
                load(q, t.members[m], dst + at, off + uint32_t(it->second.offset));
                at += type(t.members[m]).flat;
            }
            break;
        }
        default:
            fail("unsupported load type");
    }
}

void Translator::store(const Pointer& p, uint32_t ty, uint32_t src, uint32_t off) {
    const Type& t = type(ty);
    uint32_t dyn = p.dyn == kNoReg ? zero_ : p.dyn;
    if (p.space == Space::Local) {
        for (uint32_t i = 0; i < t.flat; ++i) {
            uint32_t w = p.base + p.offset + off + i;
            if (p.dyn == kNoReg && w < p.limit)
                emit(SOp::StoreLocalFixed, kNoReg, kNoReg, src + i, cur_mask_, w);
            else
                emit(SOp::StoreLocal, kNoReg, dyn, src + i, cur_mask_, w).n = p.limit;
        }
        return;
    }
    if (p.space == Space::Handle) fail("store to an image or sampler variable");
    if (!p.writable) fail("store to a read-only buffer");
    buffer_written_ = true;
    if (store_mask_ == kNoReg) {
        store_mask_ = stage_ == Stage::Fragment ? emit1(SOp::And, cur_mask_, p_.reg_live) : cur_mask_;
    }
    uint32_t mask = store_mask_;
    uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
    auto scalar = [&](uint32_t s, uint32_t byte_off, uint32_t sty) {
        uint32_t v = s;
        if (type(sty).kind == Type::Bool) v = emit1(SOp::And, s, konst(1));
        emit(SOp::StoreBuf, mask, elem, dyn, v, p.base, p.offset + byte_off).n = p.limit;
    };
    switch (t.kind) {
        case Type::Bool:
        case Type::Int:
        case Type::Float:
            scalar(src, off, ty);
            break;
        case Type::Vector:
            for (uint32_t i = 0; i < t.count; ++i) scalar(src + i, off + i * p.vec_stride, t.elem);
            break;
        case Type::Matrix: {
            const Type& col = type(t.elem);
            for (uint32_t c = 0; c < t.count; ++c)
                for (uint32_t r = 0; r < col.count; ++r) {
                    uint32_t o = p.row_major ? c * 4 + r * p.matrix_stride : c * p.matrix_stride + r * 4;
                    scalar(src + c * col.count + r, off + o, col.elem);
                }
            break;
        }
        case Type::Array: {
            uint32_t stride = uint32_t(deco_[ty].array_stride);
            if (!stride) fail("buffer array without ArrayStride");
            Pointer q = p;
            q.vec_stride = 4;
            for (uint32_t i = 0; i < t.count; ++i) store(q, t.elem, src + i * type(t.elem).flat, off + i * stride);
            break;
        }
        case Type::Struct: {
            uint32_t at = 0;
            for (uint32_t m = 0; m < t.members.size(); ++m) {
                auto it = member_deco_.find({ty, m});
                if (it == member_deco_.end() || it->second.offset < 0) fail("buffer struct member without Offset");
                Pointer q = p;
                q.matrix_stride = uint32_t(it->second.matrix_stride);
                q.row_major = it->second.row_major;
                q.vec_stride = 4;
                store(q, t.members[m], src + at, off + uint32_t(it->second.offset));
                at += type(t.members[m]).flat;
            }
            break;
        }
        default:
            fail("unsupported store type");
    }
}

// ---- instructions ---------------------------------------------------------------------------------------------

void Translator::op(const Instr& in) {
    // New value helpers: result type in[1], result id in[2].
    auto def = [&](uint32_t n = 0) {
        uint32_t f = n ? n : std::max(1u, type(in[1]).flat);
        uint32_t r = alloc(f);
        vals_[in[2]] = Value{r, in[1]};
        return r;
    };
    auto alias = [&](uint32_t r) { vals_[in[2]] = Value{r, in[1]}; };
    auto flat_of = [&](uint32_t id) { return std::max(1u, type(val(id).type).flat); };
    auto unary = [&](SOp o) {
        uint32_t a = reg(in[3]);
        uint32_t d = def();
        for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(o, d + i, a + i);
    };
    // Binary: operands may be a vector and a scalar (broadcast) for the ops that allow it.
    auto binary = [&](SOp o) {
        uint32_t a = reg(in[3]), b = reg(in[4]);
        uint32_t fa = flat_of(in[3]), fb = flat_of(in[4]);
        uint32_t d = def();
        for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(o, d + i, a + (fa > 1 ? i : 0), b + (fb > 1 ? i : 0));
    };
    auto swapped = [&](SOp o) {  // a > b  ==  b < a
        uint32_t a = reg(in[3]), b = reg(in[4]);
        uint32_t d = def();
        for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(o, d + i, b + i, a + i);
    };
    // dot product: ((a0*b0 + a1*b1) + a2*b2) + a3*b3  (mul then add, left to right, as NIR's fsum after fmul)
    auto dot = [&](uint32_t a, uint32_t b, uint32_t n) {
        uint32_t s = emit1(SOp::FMul, a, b);
        for (uint32_t i = 1; i < n; ++i) s = emit1(SOp::FAdd, s, emit1(SOp::FMul, a + i, b + i));
        return s;
    };

    switch (in.op) {
        case spv::Op::OpNop:
        case spv::Op::OpLine:
        case spv::Op::OpNoLine:
        case spv::Op::OpName:
        case spv::Op::OpSelectionMerge:
        case spv::Op::OpLoopMerge:
        case spv::Op::OpMemoryBarrier:
            return;

        // float arithmetic
        case spv::Op::OpFAdd:
            return binary(SOp::FAdd);
        case spv::Op::OpFSub:
            return binary(SOp::FSub);
        case spv::Op::OpFMul:
            return binary(SOp::FMul);
        case spv::Op::OpFDiv:
            return binary(SOp::FDiv);
        case spv::Op::OpFRem:
            return binary(SOp::FRem);
        case spv::Op::OpFMod:
            return binary(SOp::FMod);
        case spv::Op::OpFNegate:
            return unary(SOp::FNeg);
        case spv::Op::OpVectorTimesScalar:
        case spv::Op::OpMatrixTimesScalar:
            return binary(SOp::FMul);
        // integer arithmetic
        case spv::Op::OpIAdd:
            return binary(SOp::IAdd);
        case spv::Op::OpISub:
            return binary(SOp::ISub);
        case spv::Op::OpIMul:
            return binary(SOp::IMul);
        case spv::Op::OpSDiv:
            return binary(SOp::SDiv);
        case spv::Op::OpUDiv:
            return binary(SOp::UDiv);
        case spv::Op::OpSRem:
            return binary(SOp::SRem);
        case spv::Op::OpSMod:
            return binary(SOp::SMod);
        case spv::Op::OpUMod:
            return binary(SOp::UMod);
        case spv::Op::OpSNegate:
            return unary(SOp::INeg);
        case spv::Op::OpBitwiseAnd:
        case spv::Op::OpLogicalAnd:
            return binary(SOp::And);
        case spv::Op::OpBitwiseOr:
        case spv::Op::OpLogicalOr:
            return binary(SOp::Or);
        case spv::Op::OpBitwiseXor:
        case spv::Op::OpLogicalNotEqual:
            return binary(SOp::Xor);
        case spv::Op::OpLogicalEqual:
            return binary(SOp::IEq);
        case spv::Op::OpNot:
        case spv::Op::OpLogicalNot:
            return unary(SOp::Not);
        case spv::Op::OpShiftLeftLogical:
            return binary(SOp::Shl);
        case spv::Op::OpShiftRightLogical:
            return binary(SOp::ShrL);
        case spv::Op::OpShiftRightArithmetic:
            return binary(SOp::ShrA);
        case spv::Op::OpBitCount:
            return unary(SOp::BitCount);
        case spv::Op::OpBitReverse:
            return unary(SOp::BitReverse);
        case spv::Op::OpBitFieldSExtract:
        case spv::Op::OpBitFieldUExtract: {
            uint32_t a = reg(in[3]), off = reg(in[4]), cnt = reg(in[5]);
            uint32_t d = def();
            for (uint32_t i = 0; i < type(in[1]).flat; ++i)
                emit(in.op == spv::Op::OpBitFieldSExtract ? SOp::BfeS : SOp::BfeU, d + i, a + i, off, cnt);
            return;
        }
        case spv::Op::OpBitFieldInsert: {
            uint32_t a = reg(in[3]), ins = reg(in[4]), off = reg(in[5]), cnt = reg(in[6]);
            uint32_t d = def();
            for (uint32_t i = 0; i < type(in[1]).flat; ++i) emit(SOp::Bfi, d + i, a + i, ins + i, off, cnt);
            return;
        }
        // extended arithmetic: the result is a struct {low/value, high/carry/borrow} of equal vector types
        case spv::Op::OpIAddCarry:
        case spv::Op::OpISubBorrow:
        case spv::Op::OpUMulExtended:
        case spv::Op::OpSMulExtended: {
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t n = flat_of(in[3]);
            uint32_t d = def();
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
            return;
        }
        // comparisons
        case spv::Op::OpIEqual:
            return binary(SOp::IEq);
        case spv::Op::OpINotEqual:
            return binary(SOp::INe);
        case spv::Op::OpSLessThan:
            return binary(SOp::SLt);
        case spv::Op::OpSLessThanEqual:
            return binary(SOp::SLe);
        case spv::Op::OpSGreaterThan:
            return swapped(SOp::SLt);
        case spv::Op::OpSGreaterThanEqual:
            return swapped(SOp::SLe);
        case spv::Op::OpULessThan:
            return binary(SOp::ULt);
        case spv::Op::OpULessThanEqual:
            return binary(SOp::ULe);
        case spv::Op::OpUGreaterThan:
            return swapped(SOp::ULt);
        case spv::Op::OpUGreaterThanEqual:
            return swapped(SOp::ULe);
        case spv::Op::OpFOrdEqual:
            return binary(SOp::FOrdEq);
        case spv::Op::OpFOrdNotEqual:
            return binary(SOp::FOrdNe);
        case spv::Op::OpFOrdLessThan:
            return binary(SOp::FOrdLt);
        case spv::Op::OpFOrdLessThanEqual:
            return binary(SOp::FOrdLe);
        case spv::Op::OpFOrdGreaterThan:
            return swapped(SOp::FOrdLt);
        case spv::Op::OpFOrdGreaterThanEqual:
            return swapped(SOp::FOrdLe);
        case spv::Op::OpFUnordEqual:
            return binary(SOp::FUnordEq);
        case spv::Op::OpFUnordNotEqual:
            return binary(SOp::FUnordNe);
        case spv::Op::OpFUnordLessThan:
            return binary(SOp::FUnordLt);
        case spv::Op::OpFUnordLessThanEqual:
            return binary(SOp::FUnordLe);
        case spv::Op::OpFUnordGreaterThan:
            return swapped(SOp::FUnordLt);
        case spv::Op::OpFUnordGreaterThanEqual:
            return swapped(SOp::FUnordLe);
        case spv::Op::OpIsNan:
            return unary(SOp::IsNan);
        case spv::Op::OpIsInf:
            return unary(SOp::IsInf);
        case spv::Op::OpAny:
        case spv::Op::OpAll: {
            uint32_t a = reg(in[3]);
            uint32_t n = flat_of(in[3]);
            uint32_t r = a;
            for (uint32_t i = 1; i < n; ++i) r = emit1(in.op == spv::Op::OpAny ? SOp::Or : SOp::And, r, a + i);
            emit(SOp::Mov, def(), r);
            return;
        }
        case spv::Op::OpSelect: {
            uint32_t c = reg(in[3]), a = reg(in[4]), b = reg(in[5]);
            bool scalar_c = flat_of(in[3]) == 1;
            uint32_t d = def();
            for (uint32_t i = 0; i < type(in[1]).flat; ++i)
                emit(SOp::Select, d + i, a + i, b + i, c + (scalar_c ? 0 : i));
            return;
        }
        // conversions
        case spv::Op::OpConvertFToS:
            return unary(SOp::F2S);
        case spv::Op::OpConvertFToU:
            return unary(SOp::F2U);
        case spv::Op::OpConvertSToF:
            return unary(SOp::S2F);
        case spv::Op::OpConvertUToF:
            return unary(SOp::U2F);
        case spv::Op::OpBitcast:
        case spv::Op::OpCopyObject:
        case spv::Op::OpUConvert:
        case spv::Op::OpSConvert:
        case spv::Op::OpFConvert: {
            if (flat_of(in[3]) != std::max(1u, type(in[1]).flat)) fail(opname(in.op) + " between different sizes");
            const Value& v = val(in[3]);
            if (v.is_phi)
                unary(SOp::Mov);
            else if (v.ptr >= 0)
                vals_[in[2]] = Value{kNoReg, in[1], v.ptr};
            else
                alias(v.reg);
            return;
        }
        // composites
        case spv::Op::OpCompositeExtract: {
            const Value& v = val(in[3]);
            uint32_t t;
            uint32_t off = flat_index(v.type, in.w + 4, in.n - 4, &t);
            if (v.is_phi) {
                uint32_t d = def();
                for (uint32_t i = 0; i < std::max(1u, type(in[1]).flat); ++i) emit(SOp::Mov, d + i, v.reg + off + i);
            } else {
                alias(v.reg + off);
            }
            return;
        }
        case spv::Op::OpCompositeInsert: {
            const Value& obj = val(in[3]);
            const Value& comp = val(in[4]);
            uint32_t t;
            uint32_t off = flat_index(comp.type, in.w + 5, in.n - 5, &t);
            uint32_t n = type(in[1]).flat;
            uint32_t objr = obj.reg, compr = comp.reg, objn = type(obj.type).flat;
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Mov, d + i, compr + i);
            for (uint32_t i = 0; i < objn; ++i) emit(SOp::Mov, d + off + i, objr + i);
            return;
        }
        case spv::Op::OpCompositeConstruct: {
            uint32_t d = def();
            uint32_t at = 0;
            for (size_t k = 3; k < in.n; ++k) {
                uint32_t r = reg(in[k]);
                uint32_t f = flat_of(in[k]);
                for (uint32_t i = 0; i < f; ++i) emit(SOp::Mov, d + at + i, r + i);
                at += f;
            }
            return;
        }
        case spv::Op::OpVectorShuffle: {
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t na = flat_of(in[3]);
            uint32_t d = def();
            for (size_t k = 5; k < in.n; ++k) {
                uint32_t s = in[k];
                uint32_t src = s == 0xFFFFFFFFu ? zero_ : s < na ? a + s : b + (s - na);
                emit(SOp::Mov, d + uint32_t(k - 5), src);
            }
            return;
        }
        case spv::Op::OpVectorExtractDynamic: {
            uint32_t v = reg(in[3]), idx = reg(in[4]);
            uint32_t n = flat_of(in[3]);
            uint32_t d = def();
            emit(SOp::Mov, d, v);  // out-of-range index reads component 0 (undefined in SPIR-V)
            for (uint32_t i = 1; i < n; ++i) emit(SOp::Select, d, v + i, d, emit1(SOp::IEq, idx, konst(i)));
            return;
        }
        case spv::Op::OpVectorInsertDynamic: {
            uint32_t v = reg(in[3]), c = reg(in[4]), idx = reg(in[5]);
            uint32_t n = flat_of(in[3]);
            uint32_t d = def();
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Select, d + i, c, v + i, emit1(SOp::IEq, idx, konst(i)));
            return;
        }
        case spv::Op::OpTranspose: {
            const Type& rt = type(in[1]);
            uint32_t rows = type(rt.elem).count, cols = rt.count;  // result: cols columns of rows
            uint32_t m = reg(in[3]);
            uint32_t d = def();
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r) emit(SOp::Mov, d + c * rows + r, m + r * cols + c);
            return;
        }
        case spv::Op::OpDot: {
            uint32_t s = dot(reg(in[3]), reg(in[4]), flat_of(in[3]));
            alias(s);
            return;
        }
        case spv::Op::OpMatrixTimesVector: {
            // r = sum_i col_i * v_i, accumulated column by column: ((c0*v0 + c1*v1) + c2*v2) ...
            const Type& mt = type(val(in[3]).type);
            uint32_t rows = type(mt.elem).count, cols = mt.count;
            uint32_t m = reg(in[3]), v = reg(in[4]);
            uint32_t d = def();
            for (uint32_t r = 0; r < rows; ++r) {
                uint32_t s = emit1(SOp::FMul, m + r, v);
                for (uint32_t c = 1; c < cols; ++c) s = emit1(SOp::FAdd, s, emit1(SOp::FMul, m + c * rows + r, v + c));
                emit(SOp::Mov, d + r, s);
            }
            return;
        }
        case spv::Op::OpVectorTimesMatrix: {
            const Type& mt = type(val(in[4]).type);
            uint32_t rows = type(mt.elem).count, cols = mt.count;
            uint32_t v = reg(in[3]), m = reg(in[4]);
            uint32_t d = def();
            for (uint32_t c = 0; c < cols; ++c) emit(SOp::Mov, d + c, dot(v, m + c * rows, rows));
            return;
        }
        case spv::Op::OpMatrixTimesMatrix: {
            const Type& lt = type(val(in[3]).type);
            const Type& rt = type(val(in[4]).type);
            uint32_t rows = type(lt.elem).count, inner = lt.count, cols = rt.count;
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t d = def();
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r) {
                    uint32_t s = emit1(SOp::FMul, a + r, b + c * inner);
                    for (uint32_t k = 1; k < inner; ++k)
                        s = emit1(SOp::FAdd, s, emit1(SOp::FMul, a + k * rows + r, b + c * inner + k));
                    emit(SOp::Mov, d + c * rows + r, s);
                }
            return;
        }
        case spv::Op::OpOuterProduct: {
            uint32_t a = reg(in[3]), b = reg(in[4]);
            uint32_t rows = flat_of(in[3]), cols = flat_of(in[4]);
            uint32_t d = def();
            for (uint32_t c = 0; c < cols; ++c)
                for (uint32_t r = 0; r < rows; ++r) emit(SOp::FMul, d + c * rows + r, a + r, b + c);
            return;
        }
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
            uint32_t d = def();
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
            return;
        }
        case spv::Op::OpDemoteToHelperInvocation:
            if (stage_ != Stage::Fragment) fail("demote outside a fragment shader");
            iface_.uses_discard = true;
            emit(SOp::Kill, p_.reg_live, cur_mask_);
            store_mask_ = kNoReg;
            return;
        case spv::Op::OpIsHelperInvocationEXT:
            emit(SOp::Not, def(), p_.reg_live);
            return;
        // memory
        case spv::Op::OpUndef: {  // undefined value: zeros (deterministic)
            uint32_t d = def();
            for (uint32_t i = 0; i < std::max(1u, type(in[1]).flat); ++i) emit(SOp::Mov, d + i, zero_);
            return;
        }
        case spv::Op::OpVariable: {  // function variable (memory assigned in translate.cpp); initializer
            const Value& v = val(in[2]);
            if (in.n > 4) store(pointers_[size_t(v.ptr)], pointers_[size_t(v.ptr)].type, reg(in[4]), 0);
            return;
        }
        case spv::Op::OpAccessChain:
        case spv::Op::OpInBoundsAccessChain: {
            const Value& b = val(in[3]);
            if (b.ptr < 0) fail("access chain base is not a pointer");
            Pointer p = access_chain(pointers_[size_t(b.ptr)], in.w + 4, in.n - 4);
            pointers_.push_back(p);
            vals_[in[2]] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
            return;
        }
        case spv::Op::OpLoad: {
            const Value& pv = val(in[3]);
            if (pv.ptr < 0) fail("load from a non-pointer");
            Pointer p = pointers_[size_t(pv.ptr)];
            if (p.space == Space::Buffer && p.base == 0) {
                iface_.push_constant_size = std::max(iface_.push_constant_size, p.offset + 4 * type(in[1]).flat);
            }
            uint32_t d = def();
            if (p.space == Space::Buffer)  // shared memory: other lanes may change it while this one waits
                keep_active(d, std::max(1u, type(in[1]).flat), [&](uint32_t t) { load(p, in[1], t, 0); });
            else
                load(p, in[1], d, 0);
            return;
        }
        case spv::Op::OpStore: {
            const Value& pv = val(in[1]);
            if (pv.ptr < 0) fail("store to a non-pointer");
            Pointer p = pointers_[size_t(pv.ptr)];
            store(p, p.type, reg(in[2]), 0);
            return;
        }
        case spv::Op::OpArrayLength: {
            // length of the runtime array that ends a storage buffer block: (size - member offset) / stride
            const Value& sv = val(in[3]);
            if (sv.ptr < 0) fail("OpArrayLength of a non-pointer");
            const Pointer& p = pointers_[size_t(sv.ptr)];
            const Type& st = type(p.type);
            uint32_t m = in[4];
            if (p.space != Space::Buffer || p.in_array || st.kind != Type::Struct || m >= st.members.size() ||
                type(st.members[m]).kind != Type::RuntimeArray)
                fail("OpArrayLength needs a buffer block ending in a runtime array");
            auto it = member_deco_.find({p.type, m});
            uint32_t stride = uint32_t(deco_[st.members[m]].array_stride);
            if (it == member_deco_.end() || it->second.offset < 0 || stride == 0)
                fail("runtime array without Offset/ArrayStride");
            uint32_t elem = p.elem == kNoReg ? konst(p.elem_const) : p.elem;
            emit(SOp::BufArrayLength, def(), elem, konst(stride), kNoReg, p.base,
                 p.offset + uint32_t(it->second.offset))
                .n = p.limit;
            return;
        }
        case spv::Op::OpCopyMemory: {
            const Value& dv = val(in[1]);
            const Value& sv = val(in[2]);
            if (dv.ptr < 0 || sv.ptr < 0) fail("OpCopyMemory on non-pointers");
            Pointer dp = pointers_[size_t(dv.ptr)], sp = pointers_[size_t(sv.ptr)];
            uint32_t tmp = alloc(std::max(1u, type(sp.type).flat));
            load(sp, sp.type, tmp, 0);
            store(dp, dp.type, tmp, 0);
            return;
        }
        // images
        case spv::Op::OpSampledImage:
            emit(SOp::Or, def(), reg(in[3]), reg(in[4]));
            return;
        case spv::Op::OpImage:
            emit(SOp::And, def(), reg(in[3]), konst(0xFFFF));
            return;
        case spv::Op::OpImageSampleImplicitLod:
        case spv::Op::OpImageSampleExplicitLod:
        case spv::Op::OpImageSampleProjImplicitLod:
        case spv::Op::OpImageSampleProjExplicitLod:
        case spv::Op::OpImageFetch:
        case spv::Op::OpImageSampleDrefImplicitLod:
        case spv::Op::OpImageSampleDrefExplicitLod:
        case spv::Op::OpImageSampleProjDrefImplicitLod:
        case spv::Op::OpImageSampleProjDrefExplicitLod: {
            const Type& it =
                type(type(val(in[3]).type).kind == Type::SampledImage ? type(val(in[3]).type).elem : val(in[3]).type);
            if (type(it.elem).kind != Type::Float) fail("unsupported integer image sampling");
            uint32_t flags = 0;
            if (it.arrayed) flags |= kSampleArray;
            if (spv::Dim(it.dim) == spv::Dim::Dim1D) flags |= kSample1D;
            const spv::Op o = in.op;
            if (spv::Dim(it.dim) == spv::Dim::Buffer) {
                if (o != spv::Op::OpImageFetch) fail("texel buffers are read with texelFetch only");
                flags |= kSample1D;  // one row of `range / texel size` texels, level 0
            }
            bool dref = o == spv::Op::OpImageSampleDrefImplicitLod || o == spv::Op::OpImageSampleDrefExplicitLod ||
                        o == spv::Op::OpImageSampleProjDrefImplicitLod ||
                        o == spv::Op::OpImageSampleProjDrefExplicitLod;
            bool proj = o == spv::Op::OpImageSampleProjImplicitLod || o == spv::Op::OpImageSampleProjExplicitLod ||
                        o == spv::Op::OpImageSampleProjDrefImplicitLod ||
                        o == spv::Op::OpImageSampleProjDrefExplicitLod;
            bool implicit = o == spv::Op::OpImageSampleImplicitLod || o == spv::Op::OpImageSampleProjImplicitLod ||
                            o == spv::Op::OpImageSampleDrefImplicitLod ||
                            o == spv::Op::OpImageSampleProjDrefImplicitLod;
            if (proj) flags |= kSampleProj;
            uint32_t lod = kNoReg, grad = 0;
            size_t first_op = dref ? 6 : 5;  // the Dref variants carry the reference before the image operands
            uint32_t operands = in.n > first_op ? in[first_op] : 0;
            size_t at = first_op + 1;
            if (operands & uint32_t(spv::ImageOperandsMask::Bias)) {
                flags |= kSampleBias;
                lod = reg(in[at++]);
            }
            if (operands & uint32_t(spv::ImageOperandsMask::Lod)) {
                flags |= kSampleExplicitLod;
                lod = reg(in[at++]);
            }
            if (operands & uint32_t(spv::ImageOperandsMask::Grad)) {
                flags |= kSampleGrad;
                uint32_t gx = reg(in[at++]), gy = reg(in[at++]);
                uint32_t nc = (flags & kSample1D) ? 1 : 2;
                grad = alloc(4);
                for (uint32_t i = 0; i < 2; ++i) {
                    emit(SOp::Mov, grad + i, i < nc ? gx + i : zero_);
                    emit(SOp::Mov, grad + 2 + i, i < nc ? gy + i : zero_);
                }
            }
            if (operands & uint32_t(spv::ImageOperandsMask::ConstOffset)) {
                const Value& ov = val(in[at++]);
                uint32_t nc = std::max(1u, type(ov.type).flat);
                int32_t off[2] = {0, 0};
                for (uint32_t i = 0; i < nc && i < 2; ++i) {
                    auto found = reg_value_.find(ov.reg + i);
                    if (found == reg_value_.end()) fail("texel offset is not a constant");
                    off[i] = int32_t(found->second);
                    if (off[i] < -128 || off[i] > 127) fail("texel offset out of range");
                }
                flags |= kSampleOffset | (uint32_t(uint8_t(int8_t(off[0]))) << 16) |
                         (uint32_t(uint8_t(int8_t(off[1]))) << 24);
            }
            uint32_t other = operands & ~uint32_t(spv::ImageOperandsMask::Bias | spv::ImageOperandsMask::Lod |
                                                  spv::ImageOperandsMask::Grad | spv::ImageOperandsMask::ConstOffset);
            if (other) fail("unsupported image operands (dynamic offsets, min lod, sample) in " + opname(o));
            if (implicit) {
                if (stage_ != Stage::Fragment) fail("implicit-LOD sampling outside a fragment shader");
                flags |= kSampleImplicitLod;
                iface_.uses_derivatives = true;
            }
            uint32_t ncoord = flat_of(in[4]);
            uint32_t coords = reg(in[4]);
            uint32_t d;
            if (dref) {
                // coordinates followed by the reference in one register run; the result is a scalar
                flags |= kSampleDref;
                coords = alloc(ncoord + 1);
                for (uint32_t i = 0; i < ncoord; ++i) emit(SOp::Mov, coords + i, reg(in[4]) + i);
                emit(SOp::Mov, coords + ncoord, reg(in[5]));
                ++ncoord;
                d = alloc(4);
                vals_[in[2]] = Value{d, in[1]};
            } else {
                if (type(in[1]).flat != 4) fail("image result must be a 4-component vector");
                d = def(4);
            }
            auto sample = [&](uint32_t t) {
                emit(o == spv::Op::OpImageFetch ? SOp::Fetch : SOp::Sample, t, reg(in[3]), coords,
                     lod == kNoReg ? zero_ : lod, flags, ncoord)
                    .n = grad;
            };
            if (implicit)  // the LOD comes from neighbour lanes' coordinates
                keep_active(d, 4, sample);
            else
                sample(d);
            return;
        }
        case spv::Op::OpImageRead: {
            // subpassLoad(input, offset): texelFetch(input, ivec2(gl_FragCoord.xy) + offset, 0) on the bound
            // view (lavapipe lowers it the same way, nir_lower_input_attachments with frag coords).
            const Type& it = type(val(in[3]).type);
            if (it.kind != Type::Image || spv::Dim(it.dim) != spv::Dim::SubpassData)
                fail("unsupported storage image read (imageLoad)");
            if (type(it.elem).kind != Type::Float) fail("unsupported integer input attachment");
            if (in.n > 5 && in[5] != 0) fail("unsupported image operands on subpassLoad");
            if (type(in[1]).flat != 4) fail("image result must be a 4-component vector");
            if (subpass_coord_word_ == kNoReg) fail("input attachment without its pixel coordinate");
            uint32_t coords = alloc(2);
            for (uint32_t i = 0; i < 2; ++i) {
                uint32_t xy = alloc(1);
                emit(SOp::LoadLocalFixed, xy, kNoReg, kNoReg, kNoReg, subpass_coord_word_ + i);
                emit(SOp::IAdd, coords + i, emit1(SOp::F2S, xy), reg(in[4]) + i);
            }
            emit(SOp::Fetch, def(4), reg(in[3]), coords, zero_, 0u, 2u);
            return;
        }
        case spv::Op::OpImageQuerySizeLod:
        case spv::Op::OpImageQuerySize: {
            const Type& it = type(val(in[3]).type);
            uint32_t flags =
                (it.arrayed ? uint32_t(kSampleArray) : 0u) |
                (spv::Dim(it.dim) == spv::Dim::Dim1D || spv::Dim(it.dim) == spv::Dim::Buffer ? uint32_t(kSample1D)
                                                                                             : 0u);
            uint32_t lod = in.op == spv::Op::OpImageQuerySizeLod ? reg(in[4]) : zero_;
            emit(SOp::QuerySize, def(), reg(in[3]), lod, kNoReg, flags, std::max(1u, type(in[1]).flat));
            return;
        }
        case spv::Op::OpImageQueryLevels:
            emit(SOp::QueryLevels, def(), reg(in[3]));
            return;
        case spv::Op::OpExtInst:
            break;
        case spv::Op::OpFunctionCall:
            fail("unsupported opcode OpFunctionCall (function was not inlined)");
        default:
            fail("unsupported opcode " + opname(in.op));
    }

    glsl_op(in);
}

}  // namespace tilevk::shader
