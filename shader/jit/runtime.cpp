// Policy (TILEVK_JIT), CPU dispatch and the helpers the generated code calls.
#include <immintrin.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string_view>

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
    // libgcc checks the OS saves the YMM state (XGETBV) before it reports AVX2
    static const bool ok = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return ok;
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

__attribute__((target("avx"))) void run_sample(Scratch::Impl* s, const Inst* code) {
    _mm256_zeroupper();
    if (!sample_rgba8(code[0], s->regs.data(), s->slots.data(), uint32_t(s->slots.size()))) execute_code(code, *s);
}

void count_loop_limit_hit(Scratch::Impl* s) {
    ++s->loop_limit_hits;
}

}  // namespace jit
}  // namespace tilevk::shader
