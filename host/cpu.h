// What the host CPU can run, read once with CPUID, and what TILEVK_SIMD asks for. One home for the facts that the
// SIMD kernels (rast/core/isa.h), the compiled tier (shader/jit) and the exactness rules depend on: lavapipe's LLVM
// compiles for the host CPU, so whether its multiply-adds (llvm.fmuladd) are fused is decided by `fma` alone.
#pragma once

namespace tilevk::host {

struct CpuFeatures {
    bool fma = false;
    // AVX and AVX2 count only when the OS saves the YMM state (OSXSAVE and XCR0 bits 1 and 2).
    bool avx = false;
    bool avx2 = false;
    bool bmi1 = false;
    bool bmi2 = false;
    bool lzcnt = false;
};

const CpuFeatures& cpu();

// Whether a multiply-add that lavapipe emits as llvm.fmuladd is one fused operation on this host.
inline bool has_fma() {
    return cpu().fma;
}

// TILEVK_SIMD: `none` runs the portable kernels and the portable transcendentals everywhere; `avx2` and `auto` (or
// unset) take the AVX2 builds where the CPU runs them. Any other value is reported once on stderr and means auto.
enum class SimdRequest { kAuto, kNone, kAvx2 };
SimdRequest simd_request();

}  // namespace tilevk::host
