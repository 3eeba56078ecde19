#include "rast/core/cpu.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

namespace tilevk::rast {
namespace {

bool detect_avx2_kernels() {
#if defined(__x86_64__) || defined(__i386__)
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
    const bool fma = c & (1u << 12), osxsave = c & (1u << 27), avx = c & (1u << 28);
    if (!fma || !osxsave || !avx) return false;
    // The OS saves XMM and YMM state (XCR0 bits 1 and 2).
    unsigned xcr0_lo, xcr0_hi;
    __asm__("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
    if ((xcr0_lo & 0x6u) != 0x6u) return false;
    if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return false;
    const bool bmi1 = b & (1u << 3), avx2 = b & (1u << 5), bmi2 = b & (1u << 8);
    if (!__get_cpuid(0x80000001u, &a, &b, &c, &d)) return false;
    const bool lzcnt = c & (1u << 5);
    return avx2 && bmi1 && bmi2 && lzcnt;
#else
    return false;
#endif
}

Isa choose() {
    const char* e = std::getenv("TILEVK_SIMD");
    if (e && *e && std::strcmp(e, "auto") != 0) {
        if (std::strcmp(e, "none") == 0) return Isa::kPortable;
        if (std::strcmp(e, "avx2") != 0)
            std::fprintf(stderr, "tilevk: ignoring TILEVK_SIMD=%s (want none, avx2 or auto)\n", e);
        else if (!avx2_kernels_built() || !cpu_has_avx2_kernels())
            std::fprintf(stderr, "tilevk: TILEVK_SIMD=avx2: %s; running the portable kernels\n",
                         avx2_kernels_built() ? "this CPU lacks AVX2/FMA/BMI2/LZCNT" : "not built with AVX2 kernels");
    }
    return avx2_kernels_built() && cpu_has_avx2_kernels() ? Isa::kAvx2 : Isa::kPortable;
}

}  // namespace

bool cpu_has_avx2_kernels() {
    static const bool value = detect_avx2_kernels();
    return value;
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
