// C++ functions the generated code calls. Each starts with vzeroupper: the code that called it leaves the upper
// halves of the YMM registers dirty, and libm's SSE code would pay for that on every instruction.
#pragma once

#include "shader/ir.h"

namespace tilevk::shader::jit {

// Runs `code` (one instruction followed by Halt) with the interpreter: libm maths, images, buffer access and
// the rarer integer ops are the interpreter's own code, so both tiers compute them identically.
void run_one_instruction(Scratch::Impl* s, const Inst* code);

// Sample instruction number `index` of the program (code[0], followed by Halt): the RGBA8 kernel bound to it
// (s->samples[index], bound at its first run after prepare) when it covers the case, else the interpreter.
void run_sample(Scratch::Impl* s, const Inst* code, uint32_t index);

// One 8-lane half of a libm op inside a segment (lanes.cpp lane_call): d[l] = f(a[l]) or f(a[l], b[l]) with the
// interpreter's own lane expression (exec_math.h, exec_arith.h), so both tiers call the same libm function on the
// same bits under the same MXCSR. d may be a or b. No vzeroupper here: the generated code runs it before the call.
using LaneFn = void (*)(float* d, const float* a, const float* b);
// The lane function of op (Exp ... Atanh, Pow, Atan2, FRem; without TILEVK_SIMD_AVX2, whose interpreter rounds
// with libm, also Floor, Ceil, Trunc, Round, RoundEven, Fract, FMod), or null.
LaneFn lane_function(Op op);

// The loop watchdog stopped a run (exec.cpp's rule: more than kMaxLoopBackEdges back edges).
void count_loop_limit_hit(Scratch::Impl* s);

}  // namespace tilevk::shader::jit
