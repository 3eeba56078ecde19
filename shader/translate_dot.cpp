// Integer dot products (SPV_KHR_integer_dot_product, icd's shaderIntegerDotProduct): OpSDot, OpUDot, OpSUDot and
// their AccSat forms, lowered to the integer IR (no kernel of their own, so the interpreter and the compiled tier
// run them alike). Operands are vectors of 32-bit integers (DotProductInputAll: tilevk has no narrower integer
// type) or 32-bit scalars holding four packed 8-bit components (DotProductInput4x8BitPacked, component 0 in the low
// byte).
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

namespace {

bool is_dot(spv::Op op) {
    switch (op) {
        case spv::Op::OpSDot:
        case spv::Op::OpUDot:
        case spv::Op::OpSUDot:
        case spv::Op::OpSDotAccSat:
        case spv::Op::OpUDotAccSat:
        case spv::Op::OpSUDotAccSat:
            return true;
        default:
            return false;
    }
}

bool accumulates(spv::Op op) {
    return op == spv::Op::OpSDotAccSat || op == spv::Op::OpUDotAccSat || op == spv::Op::OpSUDotAccSat;
}

}  // namespace

// Byte k of packed `x`, sign- or zero-extended to 32 bits.
uint32_t Translator::packed_byte(uint32_t x, uint32_t k, bool is_signed) {
    const uint32_t high = emit1(SOp::Shl, x, konst(24 - 8 * k));
    return emit1(is_signed ? SOp::ShrA : SOp::ShrL, high, konst(24));
}

bool Translator::op_dot(const Instr& in) {
    if (!is_dot(in.op)) return false;
    const bool acc = accumulates(in.op);
    // Signedness of the first and second operand's components (the result of the signed forms is signed).
    const bool s1 = in.op != spv::Op::OpUDot && in.op != spv::Op::OpUDotAccSat;
    const bool s2 = in.op == spv::Op::OpSDot || in.op == spv::Op::OpSDotAccSat;
    const uint32_t a = reg(in[3]), b = reg(in[4]);
    const uint32_t n = flat_of(in[3]);
    // The products' sum: the low 32 bits of the exact value (OpSDot and the others), which for 32-bit components is
    // the wrapping sum of the wrapping products whatever their signedness. With AccSat the sum must not overflow
    // (otherwise the result is undefined), so only the accumulation saturates.
    uint32_t sum = kNoReg;
    const uint32_t terms = n == 1 ? 4 : n;  // a scalar operand is the packed 4x8-bit form
    for (uint32_t k = 0; k < terms; ++k) {
        const uint32_t x = n == 1 ? packed_byte(a, k, s1) : a + k;
        const uint32_t y = n == 1 ? packed_byte(b, k, s2) : b + k;
        const uint32_t p = emit1(SOp::IMul, x, y);
        sum = sum == kNoReg ? p : emit1(SOp::IAdd, sum, p);
    }
    const uint32_t d = def(in);
    if (!acc) {
        emit(SOp::Mov, d, sum);
        return true;
    }
    const uint32_t c = reg(in[5]);
    const uint32_t s = emit1(SOp::IAdd, c, sum);
    if (s1) {
        // Signed overflow: both addends' signs differ from the sum's; then the bound on the accumulator's side.
        const uint32_t over = emit1(SOp::SLt, emit1(SOp::And, emit1(SOp::Xor, c, s), emit1(SOp::Xor, sum, s)), zero_);
        const uint32_t bound = emit1(SOp::Xor, emit1(SOp::ShrA, c, konst(31)), konst(0x7fffffffu));
        emit(SOp::Select, d, bound, s, over);
    } else {
        emit(SOp::Select, d, konst(0xffffffffu), s, emit1(SOp::ULt, s, c));  // a carry out: UINT32_MAX
    }
    return true;
}

}  // namespace tilevk::shader
