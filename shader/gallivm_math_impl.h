// The algorithms of gallivm_math.h, written once over a lane policy K (gallivm_math.cpp defines one with AVX2/FMA
// intrinsics and one scalar). Included inside each build's namespace, after its K, so that every function here
// takes that build's target options. Each step names the gallivm/NIR instruction it reproduces; the order of the
// operations is theirs, because rounding depends on it. No include guard: included once per build.
// NOLINTBEGIN(readability-identifier-naming): the names follow gallivm's.

using V = typename K::V;
using I = typename K::I;

// lp_build_polynomial: even and odd coefficients by Horner in x², then odd·x + even, each step a fmuladd.
template <int N>
[[gnu::always_inline]] inline V polynomial(V x, const float (&c)[N]) {
    const V x2 = K::mul(x, x);
    V even = K::splat(c[(N - 1) & ~1]), odd = K::splat(c[N % 2 == 0 ? N - 1 : N - 2]);
    for (int i = ((N - 1) & ~1) - 2; i >= 0; i -= 2) even = K::mad(x2, even, K::splat(c[i]));
    for (int i = (N % 2 == 0 ? N - 1 : N - 2) - 2; i >= 1; i -= 2) odd = K::mad(x2, odd, K::splat(c[i]));
    return K::mad(odd, x, even);
}

// lp_build_exp2 (EXP_POLY_DEGREE 5): x clamped to [-126.99999, 128] keeping NaN (MINPS/MAXPS with x second),
// 2^floor(x) built in the exponent field, times the polynomial of the fraction.
[[gnu::always_inline]] inline V exp2_v(V x) {
    x = K::min(K::splat(kExp2Max), x);
    x = K::max(K::splat(kExp2Min), x);
    const V ipart = K::floor(x);
    const V fpart = K::sub(x, ipart);
    const I e = K::shl23(K::iadd(K::cvtt(ipart), K::isplat(127)));
    return K::mul(K::from_bits(e), polynomial(fpart, kExp2Poly));
}

// lp_build_log2_approx with handle_edge_cases (lp_build_log2_safe, LOG_POLY_DEGREE 4): exponent + y·P(y²) with
// y = (m-1)/(m+1) for the mantissa m in [1, 2); then +Inf → +Inf, ±0 → -Inf, negative or NaN → NaN (unordered
// compares, so a NaN takes the last selection).
[[gnu::always_inline]] inline V log2_v(V x) {
    const I i = K::bits(x);
    const I expo = K::iand(i, K::isplat(0x7f800000));
    const V logexp = K::cvt(K::isub(K::srl23(expo), K::isplat(127)));
    const V one = K::splat(1.0f);
    const V mant = K::from_bits(K::ior(K::iand(i, K::isplat(0x007fffff)), K::bits(one)));
    const V y = K::div(K::sub(mant, one), K::add(mant, one));
    const V z = K::mul(y, y);
    V res = K::mad(y, polynomial(z, kLog2Poly), logexp);
    const V inf = K::splat(__builtin_inff()), zero = K::splat(0.0f);
    res = K::select(K::cmp_uge(x, inf), inf, res);
    res = K::select(K::cmp_ueq(x, zero), K::splat(-__builtin_inff()), res);
    return K::select(K::cmp_ult(x, zero), K::splat(__builtin_nanf("")), res);
}

// a·b with a's NaN (quieted) where both are NaN, as the compiled tier's `vmulps d, a, b` gives (shader/jit/
// gallivm_ops.cpp). A plain multiplication leaves the order to the C++ compiler, which commutes it freely: the
// optimised build happened to put a first and the ASan build b.
[[gnu::always_inline]] inline V mul_nan_of_a(V a, V b) {
    return K::select(K::cmp_unord(a, a), K::add(a, a), K::mul(a, b));
}

// lp_build_pow: exp2(log2_safe(x)·y), 0 where x == 0 (unordered: also where x is NaN). The product is the one
// place where two NaNs meet (log2 of a negative x and a NaN y): log2's wins.
[[gnu::always_inline]] inline V pow_v(V x, V y) {
    const V res = exp2_v(mul_nan_of_a(log2_v(x), y));
    return K::select(K::cmp_ueq(x, K::splat(0.0f)), K::splat(0.0f), res);
}

// vtn_glsl450.c build_exp and build_log (kLog2E, kLn2).
[[gnu::always_inline]] inline V exp_v(V x) {
    return exp2_v(K::mul(x, K::splat(kLog2E)));
}
[[gnu::always_inline]] inline V log_v(V x) {
    return K::mul(log2_v(x), K::splat(kLn2));
}

// lp_build_sin_or_cos (cephes' sinf/cosf in SSE): octant j of |x|·4/π (CVTTPS2DQ, rounded up to even), |x| reduced
// by j·π/4 in three fmuladds, one of two polynomials picked by the octant, the sign from the octant (and x's sign
// for sin), clamped to [-1, 1] with MINPS/MAXPS, NaN where x is not finite.
[[gnu::always_inline]] inline V sin_or_cos_v(V a, bool cos) {
    const I ai = K::bits(a);
    const V x_abs = K::from_bits(K::iand(ai, K::isplat(0x7fffffff)));
    const V scale_y = K::mul(x_abs, K::splat(float(1.27323954473516)));
    const I emm2_add = K::iadd(K::cvtt(scale_y), K::isplat(1));
    const I emm2_and = K::iand(emm2_add, K::isplat(~1));
    const V y_2 = K::cvt(emm2_and);
    const I emm2_2 = cos ? K::isub(emm2_and, K::isplat(2)) : emm2_and;
    const I sign_bit = cos ? K::shl29(K::iandnot(emm2_2, K::isplat(4)))
                           : K::iand(K::ixor(ai, K::shl29(emm2_add)), K::isplat(int32_t(0x80000000u)));
    const I poly_mask = K::ieq(K::iand(emm2_2, K::isplat(2)), K::isplat(0));
    V x_3 = K::mad(y_2, K::splat(-0.78515625f), x_abs);
    x_3 = K::mad(y_2, K::splat(float(-2.4187564849853515625e-4)), x_3);
    x_3 = K::mad(y_2, K::splat(float(-3.77489497744594108e-8)), x_3);
    const V z = K::mul(x_3, x_3);
    V y = K::mad(z, K::splat(float(2.443315711809948E-005)), K::splat(float(-1.388731625493765E-003)));
    y = K::mad(y, z, K::splat(float(4.166664568298827E-002)));
    y = K::mul(K::mul(y, z), z);
    y = K::add(K::sub(y, K::mul(z, K::splat(0.5f))), K::splat(1.0f));
    V y2 = K::mad(z, K::splat(float(-1.9515295891E-4)), K::splat(float(8.3321608736E-3)));
    y2 = K::mad(y2, z, K::splat(float(-1.6666654611E-1)));
    y2 = K::mad(K::mul(y2, z), x_3, x_3);
    const I combined = K::ior(K::iandnot(poly_mask, K::bits(y)), K::iand(K::bits(y2), poly_mask));
    V res = K::from_bits(K::ixor(combined, sign_bit));
    res = K::max(K::min(res, K::splat(1.0f)), K::splat(-1.0f));
    const I finite = K::inot(K::ieq(K::iand(ai, K::isplat(0x7f800000)), K::isplat(0x7f800000)));
    return K::select(K::from_bits(finite), res, K::splat(__builtin_nanf("")));
}

// vtn_glsl450.c: Tan = fdiv(sin, cos); Sinh, Cosh = 0.5·(exp(x) ∓ exp(-x)).
[[gnu::always_inline]] inline V tan_v(V x) {
    return K::div(sin_or_cos_v(x, false), sin_or_cos_v(x, true));
}
[[gnu::always_inline]] inline V sinh_v(V x) {
    return K::mul(K::sub(exp_v(x), exp_v(K::neg(x))), K::splat(0.5f));
}
// For a NaN x both terms are NaNs, and an add keeps one of them by operand order, which compilers commute freely:
// lavapipe's sum keeps exp(-x)'s, the quieted -x (found by quirks.transcendental.cosh), so that is selected here.
[[gnu::always_inline]] inline V cosh_v(V x) {
    const V sum = K::mul(K::add(exp_v(x), exp_v(K::neg(x))), K::splat(0.5f));
    const V nan = K::from_bits(K::ior(K::bits(K::neg(x)), K::isplat(0x00400000)));
    return K::select(K::cmp_unord(x, x), nan, sum);
}
// NOLINTEND(readability-identifier-naming)
