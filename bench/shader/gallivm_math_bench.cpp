// shader/gallivm_math.h against libm: 4096 lanes of pow (bases in (0, 1], specular exponents, as a lit scene's
// fragment shader calls it), exp2, log2 and sin, each as the shader tiers call it (eight lanes per call) and as the
// libm loop that the interpreter ran before (one std::pow per lane).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "shader/gallivm_math.h"

namespace {

using Fn = void (*)(float*, const float*, const float*);

struct Data {
    std::vector<float> a, b, d;
    Data() : a(4096), b(4096), d(4096) {
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        const float powers[] = {8, 16, 32, 64, 100};
        for (size_t i = 0; i < a.size(); ++i) {
            a[i] = unit(rng);
            b[i] = powers[i % 5];
        }
    }
};

void BM_Gallivm(benchmark::State& state, Fn f) {
    Data v;
    for (auto _ : state) {
        for (size_t i = 0; i < v.a.size(); i += 8) f(&v.d[i], &v.a[i], &v.b[i]);
        benchmark::DoNotOptimize(v.d.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.a.size()));
    state.SetLabel(tilevk::shader::gallivm::implementation_name());
}

template <typename F>
void BM_Libm(benchmark::State& state, F f) {
    Data v;
    for (auto _ : state) {
        for (size_t i = 0; i < v.a.size(); ++i) v.d[i] = f(v.a[i], v.b[i]);
        benchmark::DoNotOptimize(v.d.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(v.a.size()));
}

}  // namespace

BENCHMARK_CAPTURE(BM_Gallivm, pow, tilevk::shader::gallivm::pow);
BENCHMARK_CAPTURE(BM_Libm, std_pow, [](float a, float b) { return std::pow(a, b); });
BENCHMARK_CAPTURE(BM_Gallivm, exp2, tilevk::shader::gallivm::exp2);
BENCHMARK_CAPTURE(BM_Libm, std_exp2, [](float a, float) { return std::exp2(a); });
BENCHMARK_CAPTURE(BM_Gallivm, log2, tilevk::shader::gallivm::log2);
BENCHMARK_CAPTURE(BM_Libm, std_log2, [](float a, float) { return std::log2(a); });
BENCHMARK_CAPTURE(BM_Gallivm, sin, tilevk::shader::gallivm::sin);
BENCHMARK_CAPTURE(BM_Libm, std_sin, [](float a, float) { return std::sin(a); });

BENCHMARK_MAIN();
