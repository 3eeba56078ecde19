// The float ops whose value in a lane is one libm call, as one list that both tiers expand: the interpreter's
// kernels (exec_math.h) and the compiled tier's lane calls (jit/runtime.cpp) call the same function per lane, so a
// compiled program gives the interpreter's bits by construction. X1(op, expression of a[l]) for one operand,
// X2(op, expression of a[l] and b[l]) for two. Ops whose interpreter kernel is not a libm call in every build
// (the rounding ops: vroundps with SSE4.1) are not listed.
#pragma once

#define TILEVK_LIBM_OPS(X1, X2)       \
    X2(FRem, std::fmod(a[l], b[l]))   \
    X1(Exp, std::exp(a[l]))           \
    X1(Exp2, std::exp2(a[l]))         \
    X1(Log, std::log(a[l]))           \
    X1(Log2, std::log2(a[l]))         \
    X2(Pow, std::pow(a[l], b[l]))     \
    X1(Sin, std::sin(a[l]))           \
    X1(Cos, std::cos(a[l]))           \
    X1(Tan, std::tan(a[l]))           \
    X1(Asin, std::asin(a[l]))         \
    X1(Acos, std::acos(a[l]))         \
    X1(Atan, std::atan(a[l]))         \
    X2(Atan2, std::atan2(a[l], b[l])) \
    X1(Sinh, std::sinh(a[l]))         \
    X1(Cosh, std::cosh(a[l]))         \
    X1(Tanh, std::tanh(a[l]))         \
    X1(Asinh, std::asinh(a[l]))       \
    X1(Acosh, std::acosh(a[l]))       \
    X1(Atanh, std::atanh(a[l]))
