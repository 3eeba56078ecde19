// 8- and 16-bit integers and 16-bit floats (Int8, Int16, the 8- and 16-bit storage capabilities): one register per
// scalar holding the value zero-extended, so moves, composites, phis, selects, local and Workgroup memory,
// equality, unsigned comparisons and bit operations need nothing new. The other operations are 32-bit IR around
// it: results that can leave the width are cut back (add, sub, mul, negate, not, shift left, divisions), signed
// operations see their operands sign-extended, shift counts are masked to the width, as llvmpipe computes the
// narrow LLVM types (lp_bld_nir.c: ishl/ishr/ushr mask the count with bit_size - 1; do_int_divide / do_int_mod:
// division by 0 gives all ones unsigned, 0 signed). Buffers: LoadBufN / StoreBufN (exec_narrow.h). Half floats
// are storage only: loads, stores and OpFConvert to and from 32-bit floats (HalfToFloat / FloatToHalf);
// arithmetic on them needs Float16, which is not supported (shaderFloat16 is not reported).
#include <spirv/unified1/GLSL.std.450.h>

#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

uint32_t Translator::narrow_bits(uint32_t t) const {
    if (t == 0 || t >= bound_ || !is_type_[t]) return 0;
    const Type& c = type(component_type(t));
    return (c.kind == Type::Int || c.kind == Type::Float) && c.bits < 32 ? c.bits : 0;
}
bool Translator::is_narrow_value(uint32_t id) const {
    return id < bound_ && !is_type_[id] && vals_[id].reg != kNoReg && vals_[id].type != 0 &&
           (type(vals_[id].type).kind == Type::Int || type(vals_[id].type).kind == Type::Float ||
            type(vals_[id].type).kind == Type::Vector) &&
           narrow_bits(vals_[id].type) != 0;
}
uint32_t Translator::bits_of(uint32_t t) const {  // component width of a scalar/vector type: 8, 16, 32 or 64
    const Type& c = type(component_type(t));
    return c.wide ? 64 : c.bits;
}
uint32_t Translator::sext(uint32_t r, uint32_t bits) {
    if (bits >= 32) return r;
    return emit1(SOp::ShrA, emit1(SOp::Shl, r, konst(32 - bits)), konst(32 - bits));
}
uint32_t Translator::wrap(uint32_t r, uint32_t bits) {
    if (bits >= 32) return r;
    return emit1(SOp::And, r, konst((1u << bits) - 1));
}

namespace {

// Operations that work on the zero-extended registers unchanged (or, loads and stores, through the layout walk).
bool narrow_as_is(spv::Op op) {
    switch (op) {
        case spv::Op::OpCopyObject:
        case spv::Op::OpCopyLogical:
        case spv::Op::OpCompositeExtract:
        case spv::Op::OpCompositeInsert:
        case spv::Op::OpCompositeConstruct:
        case spv::Op::OpVectorShuffle:
        case spv::Op::OpVectorExtractDynamic:
        case spv::Op::OpVectorInsertDynamic:
        case spv::Op::OpSelect:
        case spv::Op::OpLoad:
        case spv::Op::OpStore:
        case spv::Op::OpVariable:
        case spv::Op::OpAccessChain:  // a narrow index is its value, zero-extended
        case spv::Op::OpInBoundsAccessChain:
        case spv::Op::OpUndef:
        case spv::Op::OpPhi:
        case spv::Op::OpReturnValue:
        case spv::Op::OpIEqual:
        case spv::Op::OpINotEqual:
        case spv::Op::OpULessThan:
        case spv::Op::OpULessThanEqual:
        case spv::Op::OpUGreaterThan:
        case spv::Op::OpUGreaterThanEqual:
        case spv::Op::OpBitwiseAnd:
        case spv::Op::OpBitwiseOr:
        case spv::Op::OpBitwiseXor:
        case spv::Op::OpBitCount:
        case spv::Op::OpGroupNonUniformBroadcast:  // per register (translate_subgroup.cpp)
        case spv::Op::OpGroupNonUniformBroadcastFirst:
            return true;
        default:
            return false;
    }
}

}  // namespace

// One narrow operand per component: register of component i of operand `id` (a scalar is broadcast).
uint32_t Translator::narrow_operand(uint32_t id, uint32_t i, bool is_signed) {
    const uint32_t r = reg(id) + (flat_of(id) > 1 ? i : 0);
    return is_signed ? sext(r, bits_of(val(id).type)) : r;
}

bool Translator::op_narrow(const Instr& in) {
    bool any = in.n > 2 && narrow_bits(in[1]) != 0;
    const size_t end = in.op == spv::Op::OpVectorShuffle ? 5 : in.n;
    for (size_t i = in.op == spv::Op::OpExtInst ? 5 : 3; i < end && !any; ++i) any = is_narrow_value(in[i]);
    if (!any) return false;
    if (in.op == spv::Op::OpExtInst) {
        if (in.n > 4 && in[3] == glsl_ext_ && glsl_narrow(in)) return true;
        fail(std::string("unsupported GLSL.std.450 ") + (in.n > 4 ? glsl_std450_name(in[4]) : "?") +
             " on 8- or 16-bit values");
    }
    if (narrow_as_is(in.op)) return false;
    // integers compare equal as registers; halves would not (-0 == +0, NaN), and need Float16 anyway
    if (in.op == spv::Op::OpGroupNonUniformAllEqual && in.n > 4 &&
        type(component_type(val(in[4]).type)).kind == Type::Int)
        return false;
    if (op_narrow_convert(in)) return true;
    const uint32_t bits = narrow_bits(in[1]);  // of the result (0: a 32-bit bool of a comparison)
    // d_i = wrap(o(a_i, b_i)) with the operands sign-extended or not
    auto each = [&](SOp o, bool is_signed, bool cut) {
        const uint32_t n = std::max(1u, type(in[1]).flat), d = def(in);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = narrow_operand(in[3], i, is_signed);
            const uint32_t b = in.n > 4 ? narrow_operand(in[4], i, is_signed) : kNoReg;
            const uint32_t r = emit1(o, a, b);
            emit(SOp::Mov, d + i, cut ? wrap(r, bits) : r);
        }
        return true;
    };
    // shifts: the count masked to the width (lavapipe truncates it to the width, then ands bits - 1)
    auto shift = [&](SOp o, bool is_signed) {
        const uint32_t n = std::max(1u, type(in[1]).flat), d = def(in);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = narrow_operand(in[3], i, is_signed);
            const uint32_t c = emit1(SOp::And, reg(in[4]) + (flat_of(in[4]) > 1 ? i : 0), konst(bits - 1));
            emit(SOp::Mov, d + i, wrap(emit1(o, a, c), bits));
        }
        return true;
    };
    switch (in.op) {
        case spv::Op::OpIAdd:
            return each(SOp::IAdd, false, true);
        case spv::Op::OpISub:
            return each(SOp::ISub, false, true);
        case spv::Op::OpIMul:
            return each(SOp::IMul, false, true);
        case spv::Op::OpSNegate:
            return each(SOp::INeg, false, true);
        case spv::Op::OpNot:
            return each(SOp::Not, false, true);
        case spv::Op::OpUDiv:  // by 0: 32-bit all ones, cut to the width
            return each(SOp::UDiv, false, true);
        case spv::Op::OpUMod:
            return each(SOp::UMod, false, true);
        case spv::Op::OpSDiv:  // INT_MIN / -1 wraps back to INT_MIN once cut
            return each(SOp::SDiv, true, true);
        case spv::Op::OpSRem:
        case spv::Op::OpSMod: {  // lavapipe: srem at these widths, by 0 all ones (do_int_mod; cts types.int16.*)
            const uint32_t n = std::max(1u, type(in[1]).flat), d = def(in);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t a = narrow_operand(in[3], i, true), b = narrow_operand(in[4], i, true);
                const uint32_t r = emit1(SOp::Or, emit1(SOp::SRem, a, b), emit1(SOp::IEq, b, zero_));
                emit(SOp::Mov, d + i, wrap(r, bits));
            }
            return true;
        }
        case spv::Op::OpSLessThan:
            return each(SOp::SLt, true, false);
        case spv::Op::OpSLessThanEqual:
            return each(SOp::SLe, true, false);
        case spv::Op::OpSGreaterThan:
            return each(SOp::SGt, true, false);
        case spv::Op::OpSGreaterThanEqual:
            return each(SOp::SGe, true, false);
        case spv::Op::OpShiftLeftLogical:
            return shift(SOp::Shl, false);
        case spv::Op::OpShiftRightLogical:
            return shift(SOp::ShrL, false);
        case spv::Op::OpShiftRightArithmetic:
            return shift(SOp::ShrA, true);
        default:
            break;
    }
    fail("unsupported opcode " + opname(in.op) + " on 8- or 16-bit values");
}

// Conversions between widths, to and from floats, and bitcasts between vectors of other component sizes.
bool Translator::op_narrow_convert(const Instr& in) {
    switch (in.op) {
        case spv::Op::OpUConvert:
        case spv::Op::OpSConvert:
        case spv::Op::OpFConvert:
        case spv::Op::OpConvertSToF:
        case spv::Op::OpConvertUToF:
        case spv::Op::OpConvertFToS:
        case spv::Op::OpConvertFToU:
        case spv::Op::OpBitcast:
            break;
        default:
            return false;
    }
    const uint32_t to = bits_of(in[1]), from = bits_of(val(in[3]).type);
    const bool to_float = type(component_type(in[1])).kind == Type::Float;
    const bool from_float = type(component_type(val(in[3]).type)).kind == Type::Float;
    const uint32_t n = components_of(in[1]), a = reg(in[3]);
    auto per = [&](auto f) {
        const uint32_t d = def(in);
        for (uint32_t k = 0; k < n; ++k) f(d, k);
        return true;
    };
    switch (in.op) {
        case spv::Op::OpUConvert:
        case spv::Op::OpSConvert:
            return per([&](uint32_t d, uint32_t k) {
                const uint32_t src = a + k * (from == 64 ? 2 : 1);  // a 64-bit value: its low word
                const bool extend = in.op == spv::Op::OpSConvert && to > from;
                const uint32_t v = wrap(extend ? sext(src, from) : src, to);
                if (to < 64) return void(emit(SOp::Mov, d + k, v));
                emit(SOp::Mov, d + 2 * k, v);
                emit(extend ? SOp::ShrA : SOp::Mov, d + 2 * k + 1, extend ? v : zero_, extend ? konst(31) : kNoReg);
            });
        case spv::Op::OpFConvert:
            if (to == 64 || from == 64) fail("unsupported OpFConvert between 16- and 64-bit floats");
            return per(
                [&](uint32_t d, uint32_t k) { emit(to == 16 ? SOp::FloatToHalf : SOp::HalfToFloat, d + k, a + k); });
        case spv::Op::OpConvertSToF:
        case spv::Op::OpConvertUToF:
            if (to != 32) fail(opname(in.op) + " to a " + std::to_string(to) + "-bit float is not supported");
            return per([&](uint32_t d, uint32_t k) {
                const bool s = in.op == spv::Op::OpConvertSToF;
                emit(s ? SOp::S2F : SOp::U2F, d + k, s ? sext(a + k, from) : a + k);
            });
        case spv::Op::OpConvertFToS:
        case spv::Op::OpConvertFToU:
            // LLVM converts a float to a narrow integer, signed or not, with cvttps2dq and keeps the low bits
            if (from != 32) fail(opname(in.op) + " from a " + std::to_string(from) + "-bit float is not supported");
            return per([&](uint32_t d, uint32_t k) { emit(SOp::Mov, d + k, wrap(emit1(SOp::F2S, a + k), to)); });
        case spv::Op::OpBitcast:
            if (from_float != to_float && (from == 16 || to == 16) && flat_of(in[3]) == type(in[1]).flat)
                return false;  // half <-> int16 of one component each: the same bits (translate_ops.cpp)
            return bitcast_pieces(in);
        default:
            return false;
    }
}

// OpBitcast between vectors of other component widths (u16vec2 <-> uint, i8vec4 <-> int, u16vec4 <-> uint64_t,
// ...): the value as a little-endian bit string, cut into the result's pieces (64-bit components: two 32-bit words).
bool Translator::bitcast_pieces(const Instr& in) {
    struct Piece {
        uint32_t reg, at, bits;
    };
    auto pieces = [&](uint32_t t, uint32_t r) {
        const uint32_t w = std::min(bits_of(t), 32u), regs = std::max(1u, type(t).flat);
        std::vector<Piece> v;
        for (uint32_t i = 0; i < regs; ++i) v.push_back({r + i, i * w, w});
        return v;
    };
    const std::vector<Piece> src = pieces(val(in[3]).type, reg(in[3]));
    const uint32_t d = def(in);
    const std::vector<Piece> dst = pieces(in[1], d);
    if (src.empty() || dst.empty() || src.back().at + src.back().bits != dst.back().at + dst.back().bits)
        fail("OpBitcast between different sizes");
    for (const Piece& p : dst) {
        uint32_t acc = kNoReg;
        for (const Piece& s : src) {
            if (s.at + s.bits <= p.at || s.at >= p.at + p.bits) continue;
            uint32_t v = s.reg;
            if (s.bits >= p.bits)  // the result piece lies inside this source piece
                v = wrap(s.at == p.at ? v : emit1(SOp::ShrL, v, konst(p.at - s.at)), p.bits);
            else if (s.at != p.at)  // a whole (zero-extended) source piece inside the result piece
                v = emit1(SOp::Shl, v, konst(s.at - p.at));
            acc = acc == kNoReg ? v : emit1(SOp::Or, acc, v);
        }
        emit(SOp::Mov, p.reg, acc);
    }
    return true;
}

// GLSL.std.450 on 8- and 16-bit integers: the integer min/max/clamp/abs/sign family.
bool Translator::glsl_narrow(const Instr& in) {
    const uint32_t e = in[4], n = std::max(1u, type(in[1]).flat), bits = narrow_bits(in[1]);
    if (bits == 0 || type(component_type(in[1])).kind != Type::Int) return false;
    auto each = [&](SOp o1, SOp o2, bool is_signed, uint32_t args) {
        const uint32_t d = def(in);
        for (uint32_t i = 0; i < n; ++i) {
            uint32_t r = narrow_operand(in[5], i, is_signed);
            if (args == 1) r = emit1(o1, r);
            if (args >= 2) r = emit1(o1, r, narrow_operand(in[6], i, is_signed));
            if (args == 3) r = emit1(o2, r, narrow_operand(in[7], i, is_signed));
            emit(SOp::Mov, d + i, wrap(r, bits));
        }
        return true;
    };
    switch (e) {
        case GLSLstd450SAbs:
            return each(SOp::SAbs, SOp::Mov, true, 1);
        case GLSLstd450SSign:
            return each(SOp::SSign, SOp::Mov, true, 1);
        case GLSLstd450SMin:
            return each(SOp::SMin, SOp::Mov, true, 2);
        case GLSLstd450SMax:
            return each(SOp::SMax, SOp::Mov, true, 2);
        case GLSLstd450UMin:
            return each(SOp::UMin, SOp::Mov, false, 2);
        case GLSLstd450UMax:
            return each(SOp::UMax, SOp::Mov, false, 2);
        case GLSLstd450SClamp:  // min(max(x, lo), hi), as the 32-bit form (translate_glsl.cpp)
            return each(SOp::SMax, SOp::SMin, true, 3);
        case GLSLstd450UClamp:
            return each(SOp::UMax, SOp::UMin, false, 3);
        default:
            return false;
    }
}

}  // namespace tilevk::shader
