// What the compiler knows of operand values. FAdd / FMul whose operand order cannot matter (nan_order_free). And
// lane-uniform arithmetic computed while compiling: an FAdd, FSub, FMul, FDiv or Sqrt whose operands are constants
// (const_regs no instruction writes) or values folded before it in the same pass, and whose result is a
// segment-local register, is not emitted; its value waits in LaneEmitter::known_ and reaches a machine register from
// the constant pool only when an emitted instruction reads it. E.g. meshes_lit's `normalize(-l + vec3(0, 0, -1))`
// of constants (bench/frame/lit_shader.h), which glslang leaves to run per lane: three products, two sums, a square
// root and three quotients per half and block. No one can tell: a local register is read by nothing outside its
// segment (analysis.h), and the interpreter's result is the same in every lane.
#include <cstring>

#include "shader/jit/codegen.h"

namespace tilevk::shader::jit {

namespace {

// The IEEE operation on one float, rounding to nearest, denormals kept (MXCSR 0x1f80 for the operation only). As
// volatile asm: the compiler neither evaluates it itself nor moves it across the MXCSR writes.
float compute(Op op, float a, float b) {
    float r = 0;
    uint32_t saved = 0;
    const uint32_t nearest = 0x1f80;
    asm volatile("stmxcsr %0" : "=m"(saved));
    asm volatile("ldmxcsr %0" : : "m"(nearest));
    switch (op) {
        case Op::FAdd:
            asm volatile("addss %2, %0" : "=x"(r) : "0"(a), "x"(b));
            break;
        case Op::FSub:
            asm volatile("subss %2, %0" : "=x"(r) : "0"(a), "x"(b));
            break;
        case Op::FMul:
            asm volatile("mulss %2, %0" : "=x"(r) : "0"(a), "x"(b));
            break;
        case Op::FDiv:
            asm volatile("divss %2, %0" : "=x"(r) : "0"(a), "x"(b));
            break;
        default:  // Sqrt
            asm volatile("sqrtss %1, %0" : "=x"(r) : "x"(a));
            break;
    }
    asm volatile("ldmxcsr %0" : : "m"(saved));
    return r;
}

uint32_t bits_of(float f) {
    uint32_t u = 0;
    std::memcpy(&u, &f, 4);
    return u;
}

float float_of(uint32_t u) {
    float f = 0;
    std::memcpy(&f, &u, 4);
    return f;
}

// Neither a NaN (its payload follows the operand order, analysis.h nan_order) nor a denormal (DAZ reads it as 0).
bool plain_operand(uint32_t u) {
    const uint32_t mag = u & 0x7fffffffu;
    return mag == 0 || (mag >= 0x00800000u && mag <= 0x7f800000u);
}

// A result that FTZ cannot change and that is not a NaN: 0 (exact, from operands that are not denormals), above
// the smallest normal (so not tiny, whether tininess is detected before or after rounding), or infinite.
bool plain_result(uint32_t u) {
    const uint32_t mag = u & 0x7fffffffu;
    return mag == 0 || (mag > 0x00800000u && mag <= 0x7f800000u);
}

}  // namespace

// The operand order decides a lane's result only where both operands are NaNs: with one NaN, the SSE/AVX
// instructions return that NaN (quieted) whichever operand it is (Intel SDM vol. 1, 4.8.3.5, table 4-7), as the
// interpreter's do. So it is free when both operands are one register (x * x: the same bits either way) or when
// one is a constant that is not a NaN.
bool LaneEmitter::nan_order_free(const Inst& in) const {
    if (in.a == in.b) return true;
    const auto not_nan_const = [&](uint32_t r) {
        return r < an_.is_const.size() && an_.is_const[r] && (an_.const_value[r] & 0x7fffffffu) <= 0x7f800000u;
    };
    return not_nan_const(in.a) || not_nan_const(in.b);
}

bool LaneEmitter::value_of(uint32_t r, uint32_t& bits) const {
    if (r < an_.is_const.size() && an_.is_const[r]) {
        bits = an_.const_value[r];
        return true;
    }
    if (r < known_.size() && known_[r]) {
        bits = known_bits_[r];
        return true;
    }
    return false;
}

void LaneEmitter::forget_value(uint32_t r) {
    if (r < known_.size()) known_[r] = 0;
}

// Same bits under the fragment and vertex stages' FTZ + DAZ and the compute stage's kept denormals (exec.cpp
// FloatEnv), both rounding to nearest: the operands and the result are plain (above).
bool LaneEmitter::fold(const Inst& in) {
    const bool two = in.op == Op::FAdd || in.op == Op::FSub || in.op == Op::FMul || in.op == Op::FDiv;
    if (!two && in.op != Op::Sqrt) return false;
    if (in.d >= known_.size() || !an_.local[in.d]) return false;
    uint32_t a = 0, b = 0;
    if (!value_of(in.a, a) || (two && !value_of(in.b, b))) return false;
    if (!plain_operand(a) || !plain_operand(b)) return false;
    const uint32_t r = bits_of(compute(in.op, float_of(a), float_of(b)));
    if (!plain_result(r)) return false;
    // d's old value (maybe an operand here, maybe in a machine register) is gone
    const uint64_t key = reg_key(in.d);
    if (where(key) >= 0) {
        phys_[where(key)] = Phys{};
        where(key) = -1;
    }
    known_[in.d] = 1;
    known_bits_[in.d] = r;
    known_list_.push_back(in.d);
    ++folded_;
    return true;
}

}  // namespace tilevk::shader::jit
