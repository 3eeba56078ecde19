// shader/gallivm_math.h: values known without gallivm (exact powers of two, the special values gallivm defines,
// closeness to the true function), and the AVX2/FMA build against its portable twin bit for bit. The comparison
// with lavapipe itself is cts_subset's quirks.transcendental.* group.
#include "shader/gallivm_math.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace tilevk::shader {
namespace {

using Fn = void (*)(float*, const float*, const float*);

float one(Fn f, float a, float b = 1.0f) {
    float x[8], y[8], d[8];
    for (int l = 0; l < 8; ++l) {
        x[l] = a;
        y[l] = b;
    }
    f(d, x, y);
    for (int l = 1; l < 8; ++l) EXPECT_EQ(std::bit_cast<uint32_t>(d[l]), std::bit_cast<uint32_t>(d[0]));
    return d[0];
}

uint32_t bits(float f) {
    return std::bit_cast<uint32_t>(f);
}

TEST(GallivmMath, Exp2OfIntegersIsExactAndClampsAtTheEnds) {
    for (int k = -126; k <= 127; ++k) EXPECT_EQ(one(gallivm::exp2, float(k)), std::ldexp(1.0f, k)) << k;
    EXPECT_EQ(one(gallivm::exp2, 128.0f), INFINITY);
    EXPECT_EQ(one(gallivm::exp2, 1e30f), INFINITY);
    EXPECT_EQ(bits(one(gallivm::exp2, -126.5f)), 0u);  // 2^floor below the normals: +0
    EXPECT_EQ(bits(one(gallivm::exp2, -INFINITY)), 0u);
    EXPECT_EQ(bits(one(gallivm::exp2, std::bit_cast<float>(0x7fc12345u))), 0x7fc12345u);  // the NaN passes through
    EXPECT_NEAR(one(gallivm::exp2, 0.5f), std::sqrt(2.0f), 4e-7f);
}

TEST(GallivmMath, Log2OfPowersOfTwoIsExactWithD3D10Specials) {
    for (int k = -126; k <= 127; ++k) EXPECT_EQ(one(gallivm::log2, std::ldexp(1.0f, k)), float(k)) << k;
    EXPECT_EQ(one(gallivm::log2, 0.0f), -INFINITY);
    EXPECT_EQ(one(gallivm::log2, -0.0f), -INFINITY);
    EXPECT_EQ(one(gallivm::log2, INFINITY), INFINITY);
    EXPECT_EQ(bits(one(gallivm::log2, -1.0f)), 0x7fc00000u);  // gallivm's NaN constant
    EXPECT_EQ(bits(one(gallivm::log2, -INFINITY)), 0x7fc00000u);
    EXPECT_EQ(bits(one(gallivm::log2, std::bit_cast<float>(0x7fc12345u))), 0x7fc00000u);
    EXPECT_NEAR(one(gallivm::log2, 3.0f), std::log2(3.0), 4e-7);
}

TEST(GallivmMath, PowIsExp2OfLog2TimesYWithZeroForZeroAndNaNBases) {
    EXPECT_EQ(one(gallivm::pow, 2.0f, 10.0f), 1024.0f);
    EXPECT_EQ(one(gallivm::pow, 0.25f, 3.0f), 1.0f / 64);
    EXPECT_EQ(one(gallivm::pow, 8.0f, 1.0f / 3.0f), 2.0f);  // log2 8 = 3 exactly, 3·fl(1/3) rounds to 1
    EXPECT_EQ(bits(one(gallivm::pow, 0.0f, 0.0f)), 0u);     // not 1: gallivm selects 0 wherever x == 0
    EXPECT_EQ(bits(one(gallivm::pow, 0.0f, -2.0f)), 0u);
    EXPECT_EQ(bits(one(gallivm::pow, NAN, 2.0f)), 0u);  // the compare is unordered
    EXPECT_TRUE(std::isnan(one(gallivm::pow, -2.0f, 2.0f)));
    // log2 of a negative base is NaN and so is y: the product keeps log2's NaN (gallivm_math_impl.h mul_nan_of_a,
    // the compiled tier's operand order) in every build, whatever order the compiler gives a plain multiplication.
    for (bool portable : {false, true}) {
        gallivm::force_portable_for_testing(portable, true);
        EXPECT_EQ(bits(one(gallivm::pow, -2.0f, std::bit_cast<float>(0x7facc4e7u))), 0x7fc00000u) << portable;
        EXPECT_EQ(bits(one(gallivm::pow, -2.0f, std::bit_cast<float>(0xffc12345u))), 0x7fc00000u) << portable;
        EXPECT_EQ(bits(one(gallivm::pow, 2.0f, std::bit_cast<float>(0x7fc12345u))), 0x7fc12345u) << portable;
        gallivm::force_portable_for_testing(false, false);
    }
    EXPECT_EQ(one(gallivm::pow, 2.0f, 200.0f), INFINITY);
    EXPECT_NEAR(one(gallivm::pow, 0.9f, 32.0f), std::pow(0.9, 32.0), 2e-6);
}

TEST(GallivmMath, ExpAndLogScaleByLog2E) {
    EXPECT_EQ(one(gallivm::exp, 0.0f), 1.0f);
    EXPECT_NEAR(one(gallivm::exp, 1.0f), std::exp(1.0), 1e-6);
    EXPECT_EQ(bits(one(gallivm::log, 1.0f)), 0u);
    EXPECT_EQ(one(gallivm::log, 0.0f), -INFINITY);
    EXPECT_NEAR(one(gallivm::log, 10.0f), std::log(10.0), 1e-6);
}

TEST(GallivmMath, SinCosAreBoundedAndNaNOutsideTheFiniteRange) {
    EXPECT_EQ(bits(one(gallivm::sin, 0.0f)), 0u);
    EXPECT_EQ(bits(one(gallivm::sin, -0.0f)), 0x80000000u);
    EXPECT_EQ(one(gallivm::cos, 0.0f), 1.0f);
    for (float x : {INFINITY, -INFINITY, NAN}) {
        EXPECT_EQ(bits(one(gallivm::sin, x)), 0x7fc00000u);
        EXPECT_EQ(bits(one(gallivm::cos, x)), 0x7fc00000u);
    }
    for (float x = -50.0f; x < 50.0f; x += 0.37f) {
        EXPECT_NEAR(one(gallivm::sin, x), std::sin(double(x)), 1e-6) << x;
        EXPECT_NEAR(one(gallivm::cos, x), std::cos(double(x)), 1e-6) << x;
    }
    // beyond 2^31·π/4 the octant is CVTTPS2DQ's INT_MIN: garbage, but still clamped to [-1, 1]
    EXPECT_LE(std::fabs(one(gallivm::sin, 3e38f)), 1.0f);
    EXPECT_NEAR(one(gallivm::tan, 0.5f), std::tan(0.5), 1e-6);
    EXPECT_NEAR(one(gallivm::sinh, 2.0f), std::sinh(2.0), 1e-5);
    EXPECT_NEAR(one(gallivm::cosh, 2.0f), std::cosh(2.0), 1e-5);
    EXPECT_EQ(bits(one(gallivm::cosh, std::bit_cast<float>(0x7f812345u))), 0xffc12345u);  // -x, quieted
}

// Every op over random words and ranged values: the automatic build equals the portable one with fused
// multiply-adds bit for bit (the CPU here has FMA when the automatic build is avx2-fma).
TEST(GallivmMath, VectorBuildEqualsItsPortableTwin) {
    const Fn fns[] = {gallivm::exp2, gallivm::log2, gallivm::pow, gallivm::exp,  gallivm::log,
                      gallivm::sin,  gallivm::cos,  gallivm::tan, gallivm::sinh, gallivm::cosh};
    std::mt19937 rng(7);
    std::vector<float> a(4096), b(4096);
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = i % 2 ? std::bit_cast<float>(uint32_t(rng())) : std::uniform_real_distribution<float>(-30, 30)(rng);
        b[i] = std::uniform_real_distribution<float>(-50, 50)(rng);
    }
    const std::string automatic = gallivm::implementation_name();
    if (automatic == "portable") GTEST_SKIP() << "no FMA here: nothing to compare the portable build with";
    for (Fn f : fns) {
        std::vector<float> v(a.size()), p(a.size());
        for (size_t i = 0; i < a.size(); i += 8) f(&v[i], &a[i], &b[i]);
        gallivm::force_portable_for_testing(true, true);
        for (size_t i = 0; i < a.size(); i += 8) f(&p[i], &a[i], &b[i]);
        gallivm::force_portable_for_testing(false, false);
        // A NaN result's sign and payload are not fixed by either build: the compiler may commute an add or multiply
        // of two NaNs (so may LLVM in lavapipe). A sanitizer build of the portable copy did so. Every other result
        // is compared bit for bit.
        for (size_t i = 0; i < a.size(); ++i) {
            if (std::isnan(v[i]) || std::isnan(p[i])) {
                ASSERT_TRUE(std::isnan(v[i]) && std::isnan(p[i])) << "input " << a[i] << ", " << b[i];
                continue;
            }
            ASSERT_EQ(bits(v[i]), bits(p[i])) << "input " << a[i] << ", " << b[i] << " (" << automatic << ")";
        }
    }
}

// Without FMA the multiply-adds round twice: some results change (lavapipe's change the same way on such a CPU).
TEST(GallivmMath, UnfusedBuildDiffersSomewhere) {
    std::vector<float> a(4096), f(4096), u(4096);
    for (size_t i = 0; i < a.size(); ++i) a[i] = 0.001f + float(i) * 0.0123f;
    gallivm::force_portable_for_testing(true, true);
    for (size_t i = 0; i < a.size(); i += 8) gallivm::log2(&f[i], &a[i], &a[i]);
    gallivm::force_portable_for_testing(true, false);
    for (size_t i = 0; i < a.size(); i += 8) gallivm::log2(&u[i], &a[i], &a[i]);
    gallivm::force_portable_for_testing(false, false);
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += bits(f[i]) != bits(u[i]);
    EXPECT_GT(differ, 0u);
}

TEST(GallivmMath, OperandsMayBeTheDestination) {
    float x[8] = {0.5f, 1, 2, 3, 4, 5, 6, 7}, y[8], d[8];
    std::copy(x, x + 8, y);
    gallivm::pow(d, x, y);
    gallivm::pow(x, x, y);
    for (int l = 0; l < 8; ++l) EXPECT_EQ(bits(x[l]), bits(d[l]));
}

}  // namespace
}  // namespace tilevk::shader
