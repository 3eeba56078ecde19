// The float ops evaluated by a function call rather than inline code, as lists that both tiers expand: the
// interpreter's kernels (exec_math.h) and the compiled tier's lane calls (jit/runtime.cpp) call the same function,
// so a compiled program gives the interpreter's bits by construction. Ops whose interpreter kernel is not a call in
// every build (the rounding ops: vroundps with SSE4.1) are not listed.
#pragma once

#include "shader/gallivm_math.h"

// The ops lavapipe evaluates with gallivm's polynomials (gallivm_math.h): X(op, function of eight lanes), called
// by the interpreter for each half of its 16 lanes and by the compiled tier as its lane call.
#define TILEVK_GALLIVM_OPS(X) \
    X(Exp, gallivm::exp)      \
    X(Exp2, gallivm::exp2)    \
    X(Log, gallivm::log)      \
    X(Log2, gallivm::log2)    \
    X(Pow, gallivm::pow)      \
    X(Sin, gallivm::sin)      \
    X(Cos, gallivm::cos)      \
    X(Tan, gallivm::tan)      \
    X(Sinh, gallivm::sinh)    \
    X(Cosh, gallivm::cosh)

// The rest: one libm call per lane. X1(op, expression of a[l]) for one operand, X2(op, expression of a[l] and
// b[l]) for two.
#define TILEVK_LIBM_OPS(X1, X2)       \
    X2(FRem, std::fmod(a[l], b[l]))   \
    X1(Asin, std::asin(a[l]))         \
    X1(Acos, std::acos(a[l]))         \
    X1(Atan, std::atan(a[l]))         \
    X2(Atan2, std::atan2(a[l], b[l])) \
    X1(Tanh, std::tanh(a[l]))         \
    X1(Asinh, std::asinh(a[l]))       \
    X1(Acosh, std::acosh(a[l]))       \
    X1(Atanh, std::atanh(a[l]))
