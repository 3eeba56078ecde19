#include "host/cpu.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

namespace tilevk::host {
namespace {

CpuFeatures detect() {
    CpuFeatures f;
#if defined(__x86_64__) || defined(__i386__)
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d)) return f;
    f.fma = c & (1u << 12);
    const bool osxsave = c & (1u << 27), avx = c & (1u << 28);
    bool ymm_saved = false;
    if (osxsave) {
        unsigned xcr0_lo, xcr0_hi;
        __asm__("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
        ymm_saved = (xcr0_lo & 0x6u) == 0x6u;
    }
    f.avx = avx && ymm_saved;
    if (__get_cpuid_count(7, 0, &a, &b, &c, &d)) {
        f.bmi1 = b & (1u << 3);
        f.avx2 = f.avx && (b & (1u << 5));
        f.bmi2 = b & (1u << 8);
    }
    if (__get_cpuid(0x80000001u, &a, &b, &c, &d)) f.lzcnt = c & (1u << 5);
#endif
    return f;
}

SimdRequest parse_simd_request() {
    const char* e = std::getenv("TILEVK_SIMD");
    if (!e || !*e || std::strcmp(e, "auto") == 0) return SimdRequest::kAuto;
    if (std::strcmp(e, "none") == 0) return SimdRequest::kNone;
    if (std::strcmp(e, "avx2") == 0) return SimdRequest::kAvx2;
    std::fprintf(stderr, "tilevk: ignoring TILEVK_SIMD=%s (want none, avx2 or auto)\n", e);
    return SimdRequest::kAuto;
}

}  // namespace

const CpuFeatures& cpu() {
    static const CpuFeatures features = detect();
    return features;
}

SimdRequest simd_request() {
    static const SimdRequest request = parse_simd_request();
    return request;
}

}  // namespace tilevk::host
