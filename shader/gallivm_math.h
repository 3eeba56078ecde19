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

}  // namespace tilevk::shader::gallivm
