// gallivm_math.h's two builds of gallivm_math_impl.h and the choice between them.
#include "shader/gallivm_math.h"

#include <immintrin.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "host/cpu.h"

namespace tilevk::shader::gallivm {
namespace {

// The portable build: one lane at a time, each operation the scalar twin of the x86 instruction LLVM emits.
template <bool kFused>
struct ScalarLanes {
    using V = float;
    using I = uint32_t;
    static V splat(float f) { return f; }
    static I isplat(int32_t i) { return uint32_t(i); }
    static V add(V a, V b) { return a + b; }
    static V sub(V a, V b) { return a - b; }
    static V mul(V a, V b) { return a * b; }
    static V div(V a, V b) { return a / b; }
    static V neg(V a) { return -a; }
    // llvm.fmuladd: fused where the CPU has FMA (fmaf runs the FMA instruction there, under the same MXCSR)
    static V mad(V a, V b, V c) {
        if constexpr (kFused)
            return std::fma(a, b, c);
        else
            return a * b + c;  // two roundings: the project builds with -ffp-contract=off
    }
    static V min(V a, V b) { return a < b ? a : b; }  // MINPS: the second operand when either is NaN
    static V max(V a, V b) { return a > b ? a : b; }  // MAXPS
    // ROUNDPS toward -Inf: under DAZ a denormal is a zero of its sign (floorf would give -1 for a negative one).
    static V floor(V a) {
        if (std::fpclassify(a) == FP_SUBNORMAL && (_mm_getcsr() & 0x40u)) return std::copysign(0.0f, a);
        return std::floor(a);
    }
    // CVTTPS2DQ: INT_MIN for NaN and out of range
    static I cvtt(V a) { return a >= -2147483648.0f && a < 2147483648.0f ? uint32_t(int32_t(a)) : 0x80000000u; }
    static V cvt(I i) { return float(int32_t(i)); }
    static I bits(V a) { return std::bit_cast<uint32_t>(a); }
    static V from_bits(I i) { return std::bit_cast<float>(i); }
    static I iadd(I a, I b) { return a + b; }
    static I isub(I a, I b) { return a - b; }
    static I iand(I a, I b) { return a & b; }
    static I iandnot(I a, I b) { return ~a & b; }
    static I ior(I a, I b) { return a | b; }
    static I ixor(I a, I b) { return a ^ b; }
    static I inot(I a) { return ~a; }
    static I shl23(I a) { return a << 23; }
    static I shl29(I a) { return a << 29; }
    static I srl23(I a) { return a >> 23; }
    static I ieq(I a, I b) { return a == b ? ~0u : 0u; }
    // unordered compares (gallivm's lp_build_cmp), as masks
    static V mask(bool m) { return from_bits(m ? ~0u : 0u); }
    static V cmp_ult(V a, V b) { return mask(!(a >= b)); }
    static V cmp_ueq(V a, V b) { return mask(!(a < b || a > b)); }
    static V cmp_uge(V a, V b) { return mask(!(a < b)); }
    static V cmp_unord(V a, V b) { return mask(std::isnan(a) || std::isnan(b)); }
    static V select(V m, V a, V b) { return bits(m) >> 31 ? a : b; }
};

namespace portable_fused {
using K = ScalarLanes<true>;
#include "shader/gallivm_math_impl.h"  // NOLINT(bugprone-suspicious-include): the algorithms, in this build
}  // namespace portable_fused
namespace portable_unfused {
using K = ScalarLanes<false>;
#include "shader/gallivm_math_impl.h"  // NOLINT(bugprone-suspicious-include,readability-duplicate-include)
}  // namespace portable_unfused

#if defined(__x86_64__)
#pragma GCC push_options
#pragma GCC target("avx2,fma")
namespace avx2 {
// Eight lanes in one YMM register; the intrinsics are the instructions LLVM selects for gallivm's IR.
struct Lanes {
    using V = __m256;
    using I = __m256i;
    static V splat(float f) { return _mm256_set1_ps(f); }
    static I isplat(int32_t i) { return _mm256_set1_epi32(i); }
    static V add(V a, V b) { return _mm256_add_ps(a, b); }
    static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
    static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
    static V div(V a, V b) { return _mm256_div_ps(a, b); }
    static V neg(V a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
    static V mad(V a, V b, V c) { return _mm256_fmadd_ps(a, b, c); }
    static V min(V a, V b) { return _mm256_min_ps(a, b); }
    static V max(V a, V b) { return _mm256_max_ps(a, b); }
    static V floor(V a) { return _mm256_round_ps(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC); }
    static I cvtt(V a) { return _mm256_cvttps_epi32(a); }
    static V cvt(I i) { return _mm256_cvtepi32_ps(i); }
    static I bits(V a) { return _mm256_castps_si256(a); }
    static V from_bits(I i) { return _mm256_castsi256_ps(i); }
    static I iadd(I a, I b) { return _mm256_add_epi32(a, b); }
    static I isub(I a, I b) { return _mm256_sub_epi32(a, b); }
    static I iand(I a, I b) { return _mm256_and_si256(a, b); }
    static I iandnot(I a, I b) { return _mm256_andnot_si256(a, b); }
    static I ior(I a, I b) { return _mm256_or_si256(a, b); }
    static I ixor(I a, I b) { return _mm256_xor_si256(a, b); }
    static I inot(I a) { return _mm256_xor_si256(a, _mm256_set1_epi32(-1)); }
    static I shl23(I a) { return _mm256_slli_epi32(a, 23); }
    static I shl29(I a) { return _mm256_slli_epi32(a, 29); }
    static I srl23(I a) { return _mm256_srli_epi32(a, 23); }
    static I ieq(I a, I b) { return _mm256_cmpeq_epi32(a, b); }
    static V cmp_ult(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_NGE_UQ); }
    static V cmp_ueq(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_EQ_UQ); }
    static V cmp_uge(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_NLT_UQ); }
    static V cmp_unord(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_UNORD_Q); }
    static V select(V m, V a, V b) { return _mm256_blendv_ps(b, a, m); }
};
using K = Lanes;
#include "shader/gallivm_math_impl.h"  // NOLINT(bugprone-suspicious-include,readability-duplicate-include)

template <V (*F)(V)>
void run1(float* d, const float* a, const float*) {
    _mm256_storeu_ps(d, F(_mm256_loadu_ps(a)));
}
template <V (*F)(V, V)>
void run2(float* d, const float* a, const float* b) {
    _mm256_storeu_ps(d, F(_mm256_loadu_ps(a), _mm256_loadu_ps(b)));
}
V sin_v(V x) {
    return sin_or_cos_v(x, false);
}
V cos_v(V x) {
    return sin_or_cos_v(x, true);
}
}  // namespace avx2
#pragma GCC pop_options
#endif

// The portable builds' eight-lane loops (operands copied first: d may be a or b).
#define TILEVK_PORTABLE_LANES(ns, expr)              \
    [](float* d, const float* a, const float* b) {   \
        float x[8], y[8];                            \
        std::memcpy(x, a, sizeof(x));                \
        std::memcpy(y, b, sizeof(y));                \
        for (int l = 0; l < 8; ++l) d[l] = ns::expr; \
    }
using Fn = void (*)(float*, const float*, const float*);
struct Table {
    const char* name;
    Fn exp2, log2, pow, exp, log, sin, cos, tan, sinh, cosh;
};
#define TILEVK_PORTABLE_TABLE(name, ns)                                                                   \
    Table {                                                                                               \
        name, TILEVK_PORTABLE_LANES(ns, exp2_v(x[l])), TILEVK_PORTABLE_LANES(ns, log2_v(x[l])),           \
            TILEVK_PORTABLE_LANES(ns, pow_v(x[l], y[l])), TILEVK_PORTABLE_LANES(ns, exp_v(x[l])),         \
            TILEVK_PORTABLE_LANES(ns, log_v(x[l])), TILEVK_PORTABLE_LANES(ns, sin_or_cos_v(x[l], false)), \
            TILEVK_PORTABLE_LANES(ns, sin_or_cos_v(x[l], true)), TILEVK_PORTABLE_LANES(ns, tan_v(x[l])),  \
            TILEVK_PORTABLE_LANES(ns, sinh_v(x[l])), TILEVK_PORTABLE_LANES(ns, cosh_v(x[l]))              \
    }
const Table kPortableFused = TILEVK_PORTABLE_TABLE("portable-fma", portable_fused);
const Table kPortable = TILEVK_PORTABLE_TABLE("portable", portable_unfused);
#undef TILEVK_PORTABLE_TABLE
#undef TILEVK_PORTABLE_LANES
#if defined(__x86_64__)
const Table kAvx2 = {"avx2-fma",
                     avx2::run1<avx2::exp2_v>,
                     avx2::run1<avx2::log2_v>,
                     avx2::run2<avx2::pow_v>,
                     avx2::run1<avx2::exp_v>,
                     avx2::run1<avx2::log_v>,
                     avx2::run1<avx2::sin_v>,
                     avx2::run1<avx2::cos_v>,
                     avx2::run1<avx2::tan_v>,
                     avx2::run1<avx2::sinh_v>,
                     avx2::run1<avx2::cosh_v>};
#endif

// The host's FMA decides whether lavapipe's multiply-adds are fused (host/cpu.h); the vector build also needs AVX2.
const Table* automatic() {
    const host::CpuFeatures& cpu = host::cpu();
    const bool portable = host::simd_request() == host::SimdRequest::kNone;
#if defined(__x86_64__)
    if (cpu.fma && cpu.avx2 && !portable) return &kAvx2;
#endif
    return cpu.fma ? &kPortableFused : &kPortable;
}

std::atomic<const Table*> g_table{nullptr};

const Table& table() {
    const Table* t = g_table.load(std::memory_order_acquire);
    if (!t) {
        t = automatic();
        g_table.store(t, std::memory_order_release);
    }
    return *t;
}

}  // namespace

void exp2(float* d, const float* a, const float* b) {
    table().exp2(d, a, b);
}
void log2(float* d, const float* a, const float* b) {
    table().log2(d, a, b);
}
void pow(float* d, const float* a, const float* b) {
    table().pow(d, a, b);
}
void exp(float* d, const float* a, const float* b) {
    table().exp(d, a, b);
}
void log(float* d, const float* a, const float* b) {
    table().log(d, a, b);
}
void sin(float* d, const float* a, const float* b) {
    table().sin(d, a, b);
}
void cos(float* d, const float* a, const float* b) {
    table().cos(d, a, b);
}
void tan(float* d, const float* a, const float* b) {
    table().tan(d, a, b);
}
void sinh(float* d, const float* a, const float* b) {
    table().sinh(d, a, b);
}
void cosh(float* d, const float* a, const float* b) {
    table().cosh(d, a, b);
}

const char* implementation_name() {
    return table().name;
}

void force_portable_for_testing(bool on, bool fused) {
    g_table.store(on ? (fused ? &kPortableFused : &kPortable) : automatic(), std::memory_order_release);
}

bool avx2_build_runs() {
#if defined(__x86_64__)
    return &table() == &kAvx2;
#else
    return false;
#endif
}

}  // namespace tilevk::shader::gallivm
