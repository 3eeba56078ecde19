#include "rast/core/cpu.h"

#include <atomic>
#include <cstdio>

#include "host/cpu.h"

namespace tilevk::rast {
namespace {

Isa choose() {
    const host::SimdRequest request = host::simd_request();
    if (request == host::SimdRequest::kNone) return Isa::kPortable;
    const bool runnable = avx2_kernels_built() && cpu_has_avx2_kernels();
    if (request == host::SimdRequest::kAvx2 && !runnable)
        std::fprintf(stderr, "tilevk: TILEVK_SIMD=avx2: %s; running the portable kernels\n",
                     avx2_kernels_built() ? "this CPU lacks AVX2/FMA/BMI2/LZCNT" : "not built with AVX2 kernels");
    return runnable ? Isa::kAvx2 : Isa::kPortable;
}

}  // namespace

bool cpu_has_avx2_kernels() {
    const host::CpuFeatures& f = host::cpu();
    return f.fma && f.avx2 && f.bmi1 && f.bmi2 && f.lzcnt;
}

bool avx2_kernels_built() {
#if TILEVK_AVX2_VARIANT
    return true;
#else
    return false;
#endif
}

namespace {
std::atomic<Isa>& chosen() {
    static std::atomic<Isa> value{choose()};
    return value;
}
}  // namespace

Isa kernel_isa() {
    return chosen().load(std::memory_order_relaxed);
}

bool set_kernel_isa_for_testing(Isa isa) {
    if (isa == Isa::kAvx2 && !(avx2_kernels_built() && cpu_has_avx2_kernels())) return false;
    chosen().store(isa, std::memory_order_relaxed);
    return true;
}

const char* isa_name(Isa isa) {
    return isa == Isa::kAvx2 ? "avx2" : "portable";
}

}  // namespace tilevk::rast
