// Renderer end to end on fragment-heavy scenes: many small triangles, and a few full-screen triangles with and
// without blending and depth, RGBA8 at 1x and 4x.  Filter with --benchmark_filter.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "bench/shader/bench_shaders.h"
#include "rast/core/thread_pool.h"
#include "rast/render/renderer.h"
#include "tests/shader/glsl.h"

namespace tilevk::rast::render {
namespace {

struct Vertex {
    float pos[4];
    float color[4];
};

constexpr int kSize = 1024;

struct Fixture {
    std::shared_ptr<const shader::Program> vs =
        shader::test::make_program(shader::Stage::Vertex, bench_shaders::kPassVs);
    std::shared_ptr<const shader::Program> fs =
        shader::test::make_program(shader::Stage::Fragment, bench_shaders::kPassFs);
    std::vector<uint8_t> rgba;
    std::vector<float> depth;
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

std::vector<Vertex> random_triangles(int n, float size) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), d(-size, size), c(0.0f, 1.0f), z(0.1f, 0.9f);
    std::vector<Vertex> v;
    for (int t = 0; t < n; ++t) {
        const float cx = u(rng), cy = u(rng), cz = z(rng);
        for (int i = 0; i < 3; ++i) v.push_back({{cx + d(rng), cy + d(rng), cz, 1}, {c(rng), c(rng), c(rng), c(rng)}});
    }
    return v;
}

std::vector<Vertex> fullscreen_triangles(int n) {
    std::vector<Vertex> v;
    for (int t = 0; t < n; ++t) {
        const float z = 0.9f - 0.1f * float(t), k = 0.2f * float(t + 1);
        v.push_back({{-1, -1, z, 1}, {k, 0.5f, 0.25f, 0.5f}});
        v.push_back({{3, -1, z, 1}, {0.1f, k, 0.75f, 0.5f}});
        v.push_back({{-1, 3, z, 1}, {0.3f, 0.6f, k, 0.5f}});
    }
    return v;
}

// args: scene (0 = 20k small triangles, 1 = 4 full-screen), blend, depth, samples
void BM_Render(benchmark::State& state) {
    const bool small = state.range(0) == 0, blend = state.range(1) != 0, depth = state.range(2) != 0;
    const int samples = int(state.range(3));
    Fixture& f = fixture();
    const std::vector<Vertex> verts = small ? random_triangles(20000, 0.03f) : fullscreen_triangles(4);
    f.rgba.assign(size_t(kSize) * kSize * 4 * samples, 0);
    f.depth.assign(size_t(kSize) * kSize * samples, 1.0f);

    PipelineState p;
    p.vertex = f.vs.get();
    p.fragment = f.fs.get();
    p.attribs = {{geometry::VertexFormat::R32G32B32A32_SFLOAT, 0, 0},
                 {geometry::VertexFormat::R32G32B32A32_SFLOAT, 0, 16}};
    p.attrib_locations = {0, 1};
    p.bindings = {{sizeof(Vertex), geometry::InputRate::kVertex}};
    p.viewport = {0, 0, float(kSize), float(kSize), 0, 1};
    p.samples = samples;
    if (blend) {
        p.blend[0].blend_enable = true;
        p.blend[0].src_color = fragment::BlendFactor::SrcAlpha;
        p.blend[0].dst_color = fragment::BlendFactor::OneMinusSrcAlpha;
    }
    if (depth) {
        p.depth_stencil.depth_test = true;
        p.depth_stencil.depth_write = true;
        p.depth_stencil.depth_compare = fragment::CompareOp::LessOrEqual;
    }
    Framebuffer fb;
    fb.width = kSize;
    fb.height = kSize;
    fb.samples = samples;
    fb.num_color = 1;
    const size_t plane = size_t(kSize) * kSize;
    fb.color[0] = {f.rgba.data(), fragment::ColorFormat::R8G8B8A8_UNORM, size_t(kSize) * 4, plane * 4};
    if (depth) {
        fb.depth_stencil.depth = reinterpret_cast<uint8_t*>(f.depth.data());
        fb.depth_stencil.format = fragment::DepthFormat::D32F;
        fb.depth_stencil.depth_row_pitch = size_t(kSize) * 4;
        fb.depth_stencil.depth_sample_stride = plane * 4;
    }
    ThreadPool pool(1);
    Renderer r(pool);
    DrawCall call;
    call.count = uint32_t(verts.size());
    call.vertex_buffers = {{reinterpret_cast<const uint8_t*>(verts.data()), uint32_t(verts.size() * sizeof(Vertex))}};
    shader::Bindings bindings;
    for (auto _ : state) {
        // Every iteration starts from the cleared depth buffer (before 2026-11-22 it kept the previous iteration's
        // depth, so only the last full-screen triangle passed LEQUAL after the first iteration).
        state.PauseTiming();
        std::fill(f.depth.begin(), f.depth.end(), 1.0f);
        state.ResumeTiming();
        r.begin(fb);
        if (!r.draw(p, call, bindings).empty()) state.SkipWithError("draw failed");
        r.end();
        benchmark::DoNotOptimize(f.rgba.data());
    }
}
BENCHMARK(BM_Render)
    ->ArgNames({"small", "blend", "depth", "samples"})
    ->Args({0, 0, 0, 1})
    ->Args({0, 1, 1, 1})
    ->Args({1, 0, 0, 1})
    ->Args({1, 1, 0, 1})
    ->Args({1, 0, 1, 1})
    ->Args({1, 1, 1, 4})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tilevk::rast::render

BENCHMARK_MAIN();
