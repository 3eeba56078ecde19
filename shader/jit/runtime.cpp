// Policy (TILEVK_JIT), CPU dispatch and the helpers the generated code calls.
#include <immintrin.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "host/cpu.h"
#include "shader/exec_libm.h"
#include "shader/jit/helpers.h"
#include "shader/jit/jit.h"
#include "shader/jit/sample_rgba8.h"

// asmjit's debug output names this instead of libc's stderr (shader/meson.build says why).
extern "C" {
FILE* tilevk_asmjit_stderr = stderr;
}

namespace tilevk::shader {

namespace {
std::atomic<int> g_jit{-1};  // -1: TILEVK_JIT not read yet
}  // namespace

void set_jit_enabled(bool on) {
    g_jit.store(on ? 1 : 0);
}

namespace jit {

bool enabled() {
    int v = g_jit.load();
    if (v < 0) {
        const char* e = std::getenv("TILEVK_JIT");
        v = (e && std::string_view(e) == "0") ? 0 : 1;
        g_jit.store(v);
    }
    return v != 0;
}

bool host_supported() {
#if defined(__x86_64__)
    return host::cpu().avx2 && host::cpu().fma;
#else
    return false;
#endif
}

bool log_enabled() {
    static const bool on = std::getenv("TILEVK_LOG_PIPELINES") != nullptr;
    return on;
}

__attribute__((target("avx"))) void run_one_instruction(Scratch::Impl* s, const Inst* code) {
    _mm256_zeroupper();
    execute_code(code, *s);
}

__attribute__((target("avx"))) void run_sample(Scratch::Impl* s, const Inst* code, uint32_t index) {
    _mm256_zeroupper();
    uint32_t* regs = s->regs.data();
    if (index < s->samples.size()) {
        BoundSample& b = s->samples[index];
        if (sample_bound(code[0], regs, b)) return;
        // first run since prepare(): bind to this run's handle (the kernel takes only one for all lanes)
        const uint32_t* handle = regs + size_t(code[0].a) * kLanes;
        if (b.state == BoundSample::State::Unbound &&
            bind_sample(code[0], handle[0], s->slots.data(), uint32_t(s->slots.size()), b) &&
            sample_bound(code[0], regs, b))
            return;
    } else if (sample_rgba8(code[0], regs, s->slots.data(), uint32_t(s->slots.size()))) {
        return;
    }
    execute_code(code, *s);
}

// exec_libm.h's lane expressions (the interpreter's kernels of the same list), for the eight lanes of one half. One
// lane at a time, each result stored before the next lane is read: d may alias a or b lane for lane.
#define TILEVK_LANES1(expr)                        \
    [](float* d, const float* a, const float*) {   \
        for (int l = 0; l < 8; ++l) d[l] = (expr); \
    }
#define TILEVK_LANES2(expr)                        \
    [](float* d, const float* a, const float* b) { \
        for (int l = 0; l < 8; ++l) d[l] = (expr); \
    }

LaneFn lane_function(Op op) {
    switch (op) {
#define TILEVK_JIT_LIBM1(op, expr) \
    case Op::op:                   \
        return TILEVK_LANES1(expr);
#define TILEVK_JIT_LIBM2(op, expr) \
    case Op::op:                   \
        return TILEVK_LANES2(expr);
        TILEVK_LIBM_OPS(TILEVK_JIT_LIBM1, TILEVK_JIT_LIBM2)
#undef TILEVK_JIT_LIBM1
#undef TILEVK_JIT_LIBM2
#define TILEVK_JIT_GALLIVM(op, fn) \
    case Op::op:                   \
        return fn;
        TILEVK_GALLIVM_OPS(TILEVK_JIT_GALLIVM)
#undef TILEVK_JIT_GALLIVM
#if !TILEVK_SIMD_AVX2
        // Without SSE4.1 the interpreter's rounding is libm's too (floorf, ceilf, truncf, nearbyintf), whose NaN
        // results are not vroundps's (a signalling NaN comes back unquieted from ceilf): the same calls here.
        case Op::Floor:
            return TILEVK_LANES1(std::floor(a[l]));
        case Op::Ceil:
            return TILEVK_LANES1(std::ceil(a[l]));
        case Op::Trunc:
            return TILEVK_LANES1(std::trunc(a[l]));
        case Op::Round:
        case Op::RoundEven:
            return TILEVK_LANES1(std::nearbyint(a[l]));  // exec_kernels.h round_even
        case Op::Fract:
            return TILEVK_LANES1(a[l] - std::floor(a[l]));
        case Op::FMod:
            return TILEVK_LANES2(a[l] - b[l] * std::floor(a[l] / b[l]));
#endif
        default:
            return nullptr;
    }
}

#undef TILEVK_LANES1
#undef TILEVK_LANES2

void count_loop_limit_hit(Scratch::Impl* s) {
    ++s->loop_limit_hits;
}

}  // namespace jit
}  // namespace tilevk::shader
