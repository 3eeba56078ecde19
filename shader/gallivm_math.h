// lavapipe's transcendental functions, bit for bit: gallivm's polynomial approximations (Mesa 22.3.6
// auxiliary/gallivm/lp_bld_arit.c) as llvmpipe's NIR backend calls them, and the GLSL.std450 ops that NIR builds
// from them (vtn_glsl450.c: Exp = exp2(x·log2 e), Log = log2(x)·ln 2, Tan = sin/cos, Sinh/Cosh from exp).
// Each function computes eight lanes, d[l] = op(a[l], b[l]), reading every operand before writing: d may be a or
// b. They have the signature of the compiled tier's lane calls (jit/helpers.h LaneFn), and the interpreter calls
// the same functions for its 16 lanes (exec_math.h), so both tiers give the same bits by construction.
//
// gallivm multiplies-adds with llvm.fmuladd, which LLVM fuses when the host CPU has FMA (lavapipe compiles for the
// host): so do these, decided once by CPUID. The arithmetic runs under the caller's MXCSR (FTZ/DAZ as lavapipe's
// threads set it). Two builds of one algorithm (gallivm_math_impl.h): AVX2/FMA intrinsics when the CPU has them
// and TILEVK_SIMD is not "none", else a portable scalar twin that reproduces the x86 instructions' rules (MINPS
// returns its second operand for NaN, CVTTPS2DQ gives INT_MIN out of range, ROUNDPS honours DAZ).
#pragma once

namespace tilevk::shader::gallivm {

// The constants of the algorithms (gallivm_math_impl.h), also emitted inline by the compiled tier
// (jit/gallivm_ops.cpp). lp_build_exp2's polynomial (EXP_POLY_DEGREE 5) and its input clamp; lp_build_log2_approx's
// (LOG_POLY_DEGREE 4).
inline constexpr float kExp2Poly[6] = {float(1.000000000000000000000),   float(0.693153073200168932794),
                                       float(0.240153617044375388211),   float(0.0558263180532956664775),
                                       float(0.00898934009049466391101), float(0.00187757667519147912699)};
inline constexpr float kExp2Max = 128.0f, kExp2Min = float(-126.99999);
inline constexpr float kLog2Poly[5] = {float(2.88539009343309178325L), float(0.961791550404184197881L),
                                       float(0.577440339438736392009L), float(0.403343858251329912514L),
                                       float(0.406718052498846252698L)};
// vtn_glsl450.c build_exp and build_log: the double M_LOG2E and 1/M_LOG2E rounded to float.
inline constexpr float kLog2E = float(1.4426950408889634), kLn2 = float(1.0 / 1.4426950408889634);

void exp2(float* d, const float* a, const float* b);
void log2(float* d, const float* a, const float* b);  // lp_build_log2_safe
void pow(float* d, const float* a, const float* b);   // exp2(log2(a)·b); a == 0 (or NaN) gives 0
void exp(float* d, const float* a, const float* b);
void log(float* d, const float* a, const float* b);
void sin(float* d, const float* a, const float* b);
void cos(float* d, const float* a, const float* b);
void tan(float* d, const float* a, const float* b);
void sinh(float* d, const float* a, const float* b);
void cosh(float* d, const float* a, const float* b);

// Which build runs (tests): "avx2-fma", "portable-fma" or "portable" (unfused, as on a CPU without FMA).
const char* implementation_name();
// Tests: run the portable build (with `fused` multiply-adds) from now on, or the automatic choice again.
void force_portable_for_testing(bool on, bool fused);
// Whether the AVX2/FMA build runs (the compiled tier emits its instructions inline only then: the portable twin
// gives other NaN payloads where two NaNs meet, e.g. pow's log2(x)·y, whose operand order is GCC's choice).
bool avx2_build_runs();

}  // namespace tilevk::shader::gallivm
