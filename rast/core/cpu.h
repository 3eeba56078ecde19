// Which instruction-set build of the SIMD kernels this process runs (isa.h): the AVX2/FMA one when it was built
// and the CPU has AVX2, FMA, BMI1, BMI2 and LZCNT (host/cpu.h), unless TILEVK_SIMD=none
// asks for the portable one. Decided once, at the first call. Both builds give the same bytes (every SIMD kernel
// has a scalar twin and a test that they agree; tests/rast/fragment/stage_test.cpp renders with both builds).
#pragma once

namespace tilevk::rast {

enum class Isa { kPortable, kAvx2 };

Isa kernel_isa();
// Whether the CPU could run the AVX2/FMA build (whatever TILEVK_SIMD says, and whether it was built).
bool cpu_has_avx2_kernels();
// Whether this build has the AVX2/FMA kernels at all (-Dsimd=auto on x86-64, the default).
bool avx2_kernels_built();
const char* isa_name(Isa isa);

// Tests: run `isa` from now on (the dispatchers read it at each call; the fragment stage at each scene). False,
// changing nothing, when that build cannot run here.
bool set_kernel_isa_for_testing(Isa isa);

}  // namespace tilevk::rast
