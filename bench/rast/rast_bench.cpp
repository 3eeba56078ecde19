// Google Benchmark: triangles/s and samples/s per coverage method and triangle size (1..1024 px, full screen),
// at 1 thread and all threads; ns per tile for a full-screen triangle. Each iteration = setup + bin + rasterize.
//   build/bench/rast/rast_core_bench --benchmark_filter=...
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <thread>

#include "bench_util.h"
#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"

namespace tilevk::rast::bench {
namespace {

constexpr int kW = 1024, kH = 768;

// Minimum over repetitions: on a shared, loaded machine other jobs only ever add time, so the fastest repetition is
// the most reproducible estimate (reported next to Google Benchmark's mean/median/stddev).
double min_of(const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}

// args: method, area in px (0 = full screen), threads (0 = all), samples
void BM_Triangles(benchmark::State& state) {
    const auto method = static_cast<Method>(state.range(0));
    const int area = static_cast<int>(state.range(1));
    const unsigned threads = state.range(2) ? unsigned(state.range(2)) : std::thread::hardware_concurrency();
    const int samples = static_cast<int>(state.range(3));
    std::mt19937 rng(42);
    std::vector<TriangleInput> tris;
    if (area == 0) {
        TriangleInput a, b;
        a.x[0] = 0, a.y[0] = 0, a.x[1] = kW, a.y[1] = 0, a.x[2] = 0, a.y[2] = kH;
        b.x[0] = kW, b.y[0] = 0, b.x[1] = kW, b.y[1] = kH, b.x[2] = 0, b.y[2] = kH;
        a.common.clip = b.common.clip = {0, 0, kW, kH};
        tris = {a, b};
    } else {
        const int n = area <= 64 ? 20000 : area <= 256 ? 5000 : 1500;
        for (int i = 0; i < n; ++i) tris.push_back(triangle_of_area(rng, area, kW, kH));
    }
    for (size_t i = 0; i < tris.size(); ++i) tris[i].common.payload = uint32_t(i);
    ThreadPool pool(threads);
    Scene scene({.width = kW, .height = kH, .samples = samples, .method = method});
    CountingConsumer consumer(pool.num_workers());
    for (auto _ : state) {
        scene.reset();
        for (const TriangleInput& t : tris) scene.add_triangle(t);
        scene.rasterize(consumer, pool);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(tris.size()));
    state.counters["samples/s"] = benchmark::Counter(double(consumer.total()), benchmark::Counter::kIsRate);
    state.SetLabel(std::string(to_string(method)) + " " + (area ? std::to_string(area) + "px" : "fullscreen") + " " +
                   std::to_string(pool.num_workers()) + "T " + std::to_string(samples) + "x");
}

template <int kThreads>
void Args(benchmark::internal::Benchmark* b) {
    for (int area : {1, 4, 16, 64, 256, 1024, 0})
        for (int m : {int(Method::kReference), int(Method::kBBox), int(Method::kHier), int(Method::kFloat)})
            b->Args({m, area, kThreads, 1});
    for (int area : {4, 1024})
        for (int m : {int(Method::kBBox), int(Method::kHier)}) b->Args({m, area, kThreads, 4});
}
// One thread: rates from CPU time. All threads: rates from wall time (the main thread's CPU time would hide the
// other workers). On a shared machine wall time includes waiting for a core.
BENCHMARK(BM_Triangles)->Apply(Args<1>)->ComputeStatistics("min", min_of)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Triangles)->Apply(Args<0>)->Unit(benchmark::kMicrosecond)->UseRealTime();

// Rasterization only: the same triangles as BM_Triangles, set up and binned once; one iteration = rasterize the
// scene (all methods share setup and binning, so this is the figure that compares the rasterizers themselves).
// args: method, area in px, samples; 1 thread.
void BM_Raster(benchmark::State& state) {
    const auto method = static_cast<Method>(state.range(0));
    const int area = static_cast<int>(state.range(1));
    const int samples = static_cast<int>(state.range(2));
    std::mt19937 rng(42);
    const int n = area <= 64 ? 20000 : area <= 256 ? 5000 : 1500;
    ThreadPool pool(1);
    Scene scene({.width = kW, .height = kH, .samples = samples, .method = method});
    for (int i = 0; i < n; ++i) {
        TriangleInput t = triangle_of_area(rng, area, kW, kH);
        t.common.payload = uint32_t(i);
        scene.add_triangle(t);
    }
    CountingConsumer consumer(1);
    for (auto _ : state) scene.rasterize(consumer, pool);
    state.SetItemsProcessed(int64_t(state.iterations()) * n);
    state.counters["samples/s"] = benchmark::Counter(double(consumer.total()), benchmark::Counter::kIsRate);
    state.SetLabel(std::string(to_string(method)) + " " + std::to_string(area) + "px " + std::to_string(samples) + "x");
}
BENCHMARK(BM_Raster)
    ->ArgsProduct({{int(Method::kBBox), int(Method::kHier)}, {4, 64, 1024}, {1, 4}})
    ->ComputeStatistics("min", min_of)
    ->Unit(benchmark::kMicrosecond);

// Rasterization only (scene prepared once): ns per tile for one full-screen triangle, 1 thread.
void BM_FullScreenPerTile(benchmark::State& state) {
    const auto method = static_cast<Method>(state.range(0));
    const int samples = static_cast<int>(state.range(1));
    ThreadPool pool(1);
    Scene scene({.width = kW, .height = kH, .samples = samples, .method = method});
    TriangleInput t;  // covers the whole framebuffer with edges far outside it
    t.x[0] = -10, t.y[0] = -10, t.x[1] = 3 * kW, t.y[1] = -10, t.x[2] = -10, t.y[2] = 3 * kH;
    t.common.clip = {0, 0, kW, kH};
    scene.add_triangle(t);
    CountingConsumer consumer(1);
    for (auto _ : state) scene.rasterize(consumer, pool);
    const int64_t tiles = int64_t(scene.tiles_x()) * scene.tiles_y();
    state.counters["time_per_tile"] = benchmark::Counter(double(state.iterations() * tiles),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(std::string(to_string(method)) + " " + std::to_string(samples) + "x");
}
BENCHMARK(BM_FullScreenPerTile)
    ->ArgsProduct({{int(Method::kBBox), int(Method::kHier)}, {1, 4}})
    ->ComputeStatistics("min", min_of)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace tilevk::rast::bench

BENCHMARK_MAIN();
