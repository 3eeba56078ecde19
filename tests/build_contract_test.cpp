// The exactness contract depends on the compiler never fusing a*b+c on its own (see -ffp-contract=off in
// meson.build): lavapipe fuses exactly where it calls fmuladd, and so must we, through std::fma, nowhere else.
#include <gtest/gtest.h>

#include <cmath>

namespace {

TEST(BuildContract, MultiplyAddIsNotContracted) {
    // (1 + 2^-12)^2 = 1 + 2^-11 + 2^-24: the product rounds (tie to even) to 1 + 2^-11, the fused sum keeps 2^-24.
    volatile float a = 1.0f + 0x1p-12f, c = -1.0f;
    float x = a, z = c;
    float separate = x * x + z;
    float fused = std::fma(x, x, z);
    EXPECT_EQ(separate, 0x1p-11f);
    EXPECT_EQ(fused, 0x1p-11f + 0x1p-24f);
}

}  // namespace
