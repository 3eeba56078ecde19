// The fragment stage's fast path (DrawPlan: declared inputs only, SIMD interpolation, depth kernel, fused RGBA8
// store, one shader run per flat primitive) must write exactly the bytes of its reference path. Random scenes —
// sizes that are not multiples of 4 or 64, 1x and 4x, RGBA8 / BGRA8 / RGBA16F, no depth / D16 / D32F, stencil,
// every depth compare, clamp, blending, write masks, alpha to coverage, perspective and flat inputs, discard,
// FragCoord, FragDepth, FrontFacing — are rendered both ways and compared byte for byte (colour, depth, stencil).
#include <gtest/gtest.h>
#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "rast/core/cpu.h"
#include "rast/core/thread_pool.h"
#include "rast/render/fragment_stage.h"
#include "rast/render/renderer.h"
#include "tests/shader/glsl.h"

namespace tilevk::rast::render {
namespace {

using shader::Stage;

constexpr const char* kVs = R"(#version 450
layout(location = 0) in vec4 pos;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 v_color;
layout(location = 1) out vec2 v_uv;
void main() { gl_Position = pos; v_color = color; v_uv = pos.xy * 0.5 + 0.5; })";

// Fragment shaders: the first three take the uniform (once per primitive) path.
const char* const kFs[] = {
    R"(#version 450
layout(location = 0) flat in vec4 c;
layout(location = 1) flat in vec2 uv;
layout(location = 0) out vec4 o;
void main() { o = c; })",
    R"(#version 450
layout(location = 0) flat in vec4 c;
layout(location = 0) out vec4 o;
void main() { o = gl_FrontFacing ? c : c.bgra * 0.5; })",
    R"(#version 450
layout(location = 0) flat in vec4 c;
layout(location = 0) out vec4 o;
layout(location = 1) out vec4 o1;
void main() { o = c * c - 0.25; o1 = c.wzyx; })",
    R"(#version 450
layout(location = 0) in vec4 c;
layout(location = 1) in vec2 uv;
layout(location = 0) out vec4 o;
void main() { o = c; })",
    R"(#version 450
layout(location = 0) in vec4 c;
layout(location = 0) out vec4 o;
void main() { if (c.a < 0.3) discard; o = c; })",
    R"(#version 450
layout(location = 0) in vec4 c;
layout(location = 0) out vec4 o;
void main() { o = vec4(fract(gl_FragCoord.xy / 16.0), gl_FragCoord.z, c.a * gl_FragCoord.w); })",
    R"(#version 450
layout(location = 0) in vec4 c;
layout(location = 0) out vec4 o;
void main() { gl_FragDepth = c.r; o = c; })",
    R"(#version 450
layout(location = 0) noperspective in vec4 c;
layout(location = 1) in vec2 uv;
layout(location = 0) out vec4 o;
void main() { o = vec4(c.rg * 2.0 - 0.5, uv); })",
    R"(#version 450
layout(location = 0) flat in vec4 c;
layout(location = 1) in vec2 uv;
layout(location = 0) out vec4 o;
void main() { o = vec4(c.rg, dFdx(uv.x) * 64.0, uv.y); })",
};
constexpr int kNumFs = sizeof(kFs) / sizeof(kFs[0]);
constexpr int kCopyFs = 3;  // kFs[3]: a plain copy of a perspective vec4
// A plain copy of a noperspective vec4 (not in kFs: the random scenes keep their shader sequence).
constexpr const char* kCopyNoPerspectiveFs = R"(#version 450
layout(location = 0) noperspective in vec4 c;
layout(location = 0) out vec4 o;
void main() { o = c; })";

// Shaders the fragment stage runs directly (DrawPlan::direct: inputs written into the program's local words, no
// FragmentBlock copies), with push constants so that each draw's own bindings show in its pixels; the second
// declares an input it never reads, and both read gl_FrontFacing.
const char* const kPushFs[] = {
    R"(#version 450
layout(push_constant) uniform P { vec4 tint; vec4 add; } pc;
layout(location = 0) in vec4 c;
layout(location = 0) out vec4 o;
void main() { o = (gl_FrontFacing ? c : c.bgra) * pc.tint + pc.add; })",
    R"(#version 450
layout(push_constant) uniform P { vec4 tint; vec4 add; } pc;
layout(location = 0) in vec4 c;
layout(location = 1) in vec2 uv;
layout(location = 0) out vec4 o;
void main() { o = gl_FrontFacing ? vec4(uv * pc.tint.xy, pc.add.zw) : pc.tint; })",
};

struct Vertex {
    float pos[4];
    float color[4];
};

struct Targets {
    std::vector<uint8_t> color0, color1, depth, stencil;
    std::vector<uint64_t> passed;  // occlusion count per draw (DrawCall::samples_passed)
};

struct SceneDesc {
    int width, height, samples;
    fragment::ColorFormat format0;
    fragment::DepthFormat depth;
    bool stencil;
    std::vector<PipelineState> pipes;
    std::vector<int> shaders;  // kFs index per pipe (-1: kCopyNoPerspectiveFs)
    std::vector<std::vector<Vertex>> draws;
    std::vector<std::array<float, 8>> push;  // per draw, when not empty: its push constants
    size_t split = 0;                        // > 0: the draws from this one on are a second scene of the renderer
    bool queries = true;                     // false: no draw counts samples (DrawCall::samples_passed null)
};

// A failing scene, readably.
std::string describe(const SceneDesc& d) {
    std::string s = std::to_string(d.width) + "x" + std::to_string(d.height) + " samples " + std::to_string(d.samples) +
                    " format " + std::to_string(int(d.format0)) + " depth " + std::to_string(int(d.depth)) +
                    (d.stencil ? " +stencil" : "");
    for (size_t i = 0; i < d.pipes.size(); ++i) {
        const PipelineState& p = d.pipes[i];
        const fragment::DepthStencilState& z = p.depth_stencil;
        s += "\n  draw " + std::to_string(i) + ": fs " + std::to_string(d.shaders[i]) + " depth test " +
             std::to_string(z.depth_test) + " write " + std::to_string(z.depth_write) + " op " +
             std::to_string(int(z.depth_compare)) + " clamp " + std::to_string(p.depth_clamp) + " stencil " +
             std::to_string(z.stencil_test) + " a2c " + std::to_string(p.alpha_to_coverage) + " blend0 " +
             std::to_string(p.blend[0].blend_enable) + "/" + std::to_string(p.blend[0].write_mask) + " blend1 " +
             std::to_string(p.blend[1].blend_enable) + "/" + std::to_string(p.blend[1].write_mask) + " tris " +
             std::to_string(d.draws[i].size() / 3);
    }
    return s;
}

class FragmentStageTest : public ::testing::Test {
  protected:
    void SetUp() override {
        vs_ = shader::test::make_program(Stage::Vertex, kVs);
        for (const char* src : kFs) fs_.push_back(shader::test::make_program(Stage::Fragment, src));
        copy_noperspective_ = shader::test::make_program(Stage::Fragment, kCopyNoPerspectiveFs);
        for (const char* src : kPushFs) push_fs_.push_back(shader::test::make_program(Stage::Fragment, src));
    }
    void TearDown() override { set_fragment_fast_paths(true); }

    SceneDesc random_scene(std::mt19937& rng, int iter) {
        SceneDesc d;
        const int sizes[][2] = {{67, 45}, {130, 75}, {64, 64}, {200, 131}};
        d.width = sizes[iter % 4][0];
        d.height = sizes[iter % 4][1];
        d.samples = (iter % 5 == 4) ? 4 : 1;
        const fragment::ColorFormat formats[] = {fragment::ColorFormat::R8G8B8A8_UNORM,
                                                 fragment::ColorFormat::B8G8R8A8_UNORM,
                                                 fragment::ColorFormat::R16G16B16A16_SFLOAT};
        d.format0 = formats[rng() % 3];
        const fragment::DepthFormat depths[] = {fragment::DepthFormat::None, fragment::DepthFormat::D16,
                                                fragment::DepthFormat::D32F, fragment::DepthFormat::D32F};
        d.depth = depths[rng() % 4];
        d.stencil = d.depth != fragment::DepthFormat::None && rng() % 4 == 0;
        std::uniform_real_distribution<float> u(-1.2f, 1.2f), c(-0.1f, 1.1f), zr(-0.1f, 1.1f), wr(0.5f, 2.0f);
        const int num_draws = 1 + int(rng() % 4);
        d.pipes.resize(size_t(num_draws));
        for (int i = 0; i < num_draws; ++i) {
            PipelineState& p = d.pipes[size_t(i)];
            p.vertex = vs_.get();
            d.shaders.push_back(int(rng() % kNumFs));
            p.fragment = fs_[size_t(d.shaders.back())].get();
            p.attribs = {{geometry::VertexFormat::R32G32B32A32_SFLOAT, 0, 0},
                         {geometry::VertexFormat::R32G32B32A32_SFLOAT, 0, 16}};
            p.attrib_locations = {0, 1};
            p.bindings = {{sizeof(Vertex), geometry::InputRate::kVertex}};
            p.viewport = {0, 0, float(d.width), float(d.height), 0, 1};
            p.samples = d.samples;
            p.cull = CullMode(rng() % 2 ? 0 : 2);
            p.alpha_to_coverage = rng() % 6 == 0;
            p.depth_clamp = rng() % 5 == 0;
            fragment::DepthStencilState& ds = p.depth_stencil;
            ds.depth_test = rng() % 4 != 0;
            ds.depth_write = rng() % 3 != 0;
            ds.depth_compare = fragment::CompareOp(rng() % 8);
            if (rng() % 2) ds.depth_compare = fragment::CompareOp::LessOrEqual;
            ds.stencil_test = d.stencil && rng() % 2;
            ds.front.compare_op = fragment::CompareOp(rng() % 8);
            ds.front.pass_op = fragment::StencilOp(rng() % 8);
            ds.front.fail_op = fragment::StencilOp(rng() % 8);
            ds.front.depth_fail_op = fragment::StencilOp(rng() % 8);
            ds.front.reference = uint8_t(rng());
            ds.back = ds.front;
            for (int t = 0; t < 2; ++t) {
                fragment::BlendAttachment& a = p.blend[t];
                const int kind = int(rng() % 4);
                a.blend_enable = kind >= 2;
                a.write_mask = kind == 1 ? uint8_t(rng() % 16) : 0xf;
                if (kind == 2) {
                    a.src_color = fragment::BlendFactor::SrcAlpha;
                    a.dst_color = fragment::BlendFactor::OneMinusSrcAlpha;
                } else if (kind == 3) {
                    a.src_color = fragment::BlendFactor(rng() % 15);
                    a.dst_color = fragment::BlendFactor(rng() % 15);
                    a.src_alpha = fragment::BlendFactor(rng() % 15);
                    a.dst_alpha = fragment::BlendFactor(rng() % 15);
                    a.color_op = fragment::BlendOp(rng() % 5);
                }
            }
            // Only kFs[2] writes location 1; an unwritten output's bytes are undefined (the reference path writes
            // whatever the previous block left there), so the other shaders mask attachment 1 off.
            if (d.shaders.back() != 2) p.blend[1].write_mask = 0;
            std::vector<Vertex> v;
            const int tris = 1 + int(rng() % 40);
            const float size = (rng() % 3 == 0) ? 2.0f : 0.3f;
            for (int t = 0; t < tris; ++t) {
                const float cx = u(rng), cy = u(rng);
                for (int k = 0; k < 3; ++k) {
                    const float w = (rng() % 2) ? wr(rng) : 1.0f;
                    Vertex vx{{(cx + size * u(rng)) * w, (cy + size * u(rng)) * w, zr(rng) * w, w},
                              {c(rng), c(rng), c(rng), c(rng)}};
                    v.push_back(vx);
                }
            }
            d.draws.push_back(std::move(v));
        }
        return d;
    }

    Targets render(const SceneDesc& d, bool fast, unsigned threads) {
        set_fragment_fast_paths(fast);
        Targets t;
        const size_t plane = size_t(d.width) * d.height;
        const size_t bytes0 = fragment::format_info(d.format0).bytes;
        t.color0.assign(plane * bytes0 * d.samples, 0x35);
        t.color1.assign(plane * 4 * d.samples, 0x9a);
        const size_t zbytes = depth_bytes(d.depth);
        t.depth.assign(plane * zbytes * d.samples, 0);
        for (size_t i = 0; i + zbytes <= t.depth.size() && zbytes; i += zbytes) {
            // a stored depth of ~0.7 with varied low bits
            const float z = 0.7f + float(i % 97) * 1e-4f;
            const uint32_t v = d.depth == fragment::DepthFormat::D16 ? uint32_t(z * 65535.0f) : 0;
            if (d.depth == fragment::DepthFormat::D16)
                std::memcpy(&t.depth[i], &v, 2);
            else
                std::memcpy(&t.depth[i], &z, 4);
        }
        t.stencil.assign(plane * d.samples, 0x11);
        Framebuffer fb;
        fb.width = d.width;
        fb.height = d.height;
        fb.samples = d.samples;
        fb.num_color = 2;
        fb.color[0] = {t.color0.data(), d.format0, size_t(d.width) * bytes0, plane * bytes0};
        fb.color[1] = {t.color1.data(), fragment::ColorFormat::R8G8B8A8_UNORM, size_t(d.width) * 4, plane * 4};
        if (d.depth != fragment::DepthFormat::None) {
            fb.depth_stencil.depth = t.depth.data();
            fb.depth_stencil.format = d.depth;
            fb.depth_stencil.depth_row_pitch = size_t(d.width) * zbytes;
            fb.depth_stencil.depth_sample_stride = plane * zbytes;
        }
        if (d.stencil) {
            fb.depth_stencil.stencil = t.stencil.data();
            fb.depth_stencil.stencil_row_pitch = size_t(d.width);
            fb.depth_stencil.stencil_sample_stride = plane;
        }
        ThreadPool pool(threads);
        Renderer r(pool);
        r.begin(fb);
        t.passed.assign(d.pipes.size(), 0);
        for (size_t i = 0; i < d.pipes.size(); ++i) {
            if (d.split && i == d.split) {  // the same renderer and workers render a second scene
                r.end();
                r.begin(fb);
            }
            DrawCall call;
            call.samples_passed = d.queries ? &t.passed[i] : nullptr;
            call.count = uint32_t(d.draws[i].size());
            call.vertex_buffers = {
                {reinterpret_cast<const uint8_t*>(d.draws[i].data()), uint32_t(d.draws[i].size() * sizeof(Vertex))}};
            shader::Bindings bindings;
            if (!d.push.empty()) bindings.push_constants = std::as_bytes(std::span(d.push[i]));
            EXPECT_EQ(r.draw(d.pipes[i], call, bindings), "");
        }
        r.end();
        return t;
    }

    // A random scene turned into what the fused square kernel takes (fragment_plan.h SquarePlan): 1x, no depth,
    // a copy shader, colour 0 RGBA8/BGRA8 opaque or SRC_ALPHA/ONE_MINUS_SRC_ALPHA (any write mask), and large
    // triangles (whole 64x64 tiles and 16x16 squares), some with one w for all vertices (a constant 1/w).
    SceneDesc square_scene(std::mt19937& rng, int iter) {
        SceneDesc d = random_scene(rng, iter);
        d.samples = 1;
        d.depth = fragment::DepthFormat::None;
        d.stencil = false;
        d.format0 = rng() % 2 ? fragment::ColorFormat::R8G8B8A8_UNORM : fragment::ColorFormat::B8G8R8A8_UNORM;
        std::uniform_real_distribution<float> u(-1.0f, 1.0f), c(-0.1f, 1.1f), wr(0.5f, 2.0f);
        for (size_t i = 0; i < d.pipes.size(); ++i) {
            PipelineState& p = d.pipes[i];
            const bool noperspective = rng() % 3 == 0;
            d.shaders[i] = noperspective ? -1 : kCopyFs;
            p.fragment = noperspective ? copy_noperspective_.get() : fs_[kCopyFs].get();
            p.samples = 1;
            p.cull = CullMode(0);
            p.alpha_to_coverage = false;
            p.depth_stencil = {};
            fragment::BlendAttachment& a = p.blend[0];
            a = {};
            a.blend_enable = rng() % 4 != 0;
            a.src_color = a.src_alpha = fragment::BlendFactor::SrcAlpha;
            a.dst_color = a.dst_alpha = fragment::BlendFactor::OneMinusSrcAlpha;
            a.write_mask = a.blend_enable && rng() % 3 == 0 ? uint8_t(1 + rng() % 15) : 0xf;
            p.blend[1].write_mask = 0;
            std::vector<Vertex>& v = d.draws[i];
            v.clear();
            const bool one_w = rng() % 2;
            const float w_all = rng() % 2 ? 1.0f : wr(rng);
            for (int t = 0; t < 1 + int(rng() % 3); ++t)
                for (int k = 0; k < 3; ++k) {
                    const float w = one_w ? w_all : wr(rng);
                    // corners well outside the viewport: every tile has whole squares
                    const float x = (k == 1 ? 3.0f : -1.2f) + 0.2f * u(rng),
                                y = (k == 2 ? 3.0f : -1.2f) + 0.2f * u(rng);
                    v.push_back({{x * w, y * w, 0.5f * w, w}, {c(rng), c(rng), c(rng), c(rng)}});
                }
        }
        return d;
    }

    // Renders `d` on the reference path (which must draw something), then on the fast path under the AVX2 and the
    // portable kernels where this CPU runs them (1 or 2 threads by `iter`), and hands `check` the kernel's name, the
    // fast render and the reference. The kernel ISA in force before is restored.
    template <class Check>
    void expect_fast_isas_match(const SceneDesc& d, int iter, Check&& check) {
        const Isa before = kernel_isa();
        const Targets ref = render(d, false, 1);
        ASSERT_TRUE(ref.color0 != std::vector<uint8_t>(ref.color0.size(), 0x35)) << "nothing drawn, iter " << iter;
        for (const Isa isa : {Isa::kAvx2, Isa::kPortable}) {
            if (!set_kernel_isa_for_testing(isa)) continue;
            const Targets fast = render(d, true, 1 + unsigned(iter % 2));
            check(isa == Isa::kAvx2 ? "avx2" : "portable", fast, ref);
        }
        set_kernel_isa_for_testing(before);
    }

    std::shared_ptr<const shader::Program> vs_;
    std::vector<std::shared_ptr<const shader::Program>> fs_;
    std::shared_ptr<const shader::Program> copy_noperspective_;
    std::vector<std::shared_ptr<const shader::Program>> push_fs_;
};

TEST_F(FragmentStageTest, FastPathWritesTheReferenceBytes) {
    std::mt19937 rng(2024);
    int changed = 0;
    long counted = 0;  // draws whose count is not zero
    for (int iter = 0; iter < 300; ++iter) {
        const SceneDesc d = random_scene(rng, iter);
        const Targets ref = render(d, false, 1);
        const Targets fast = render(d, true, 1 + unsigned(iter % 2));
        ASSERT_TRUE(fast.color0 == ref.color0) << "colour 0, iter " << iter << ": " << describe(d);
        ASSERT_TRUE(fast.color1 == ref.color1) << "colour 1, iter " << iter << ": " << describe(d);
        ASSERT_TRUE(fast.depth == ref.depth) << "depth, iter " << iter << ": " << describe(d);
        ASSERT_TRUE(fast.stencil == ref.stencil) << "stencil, iter " << iter << ": " << describe(d);
        // Occlusion counts: the same on both paths and any thread count (per (draw, worker) counters).
        ASSERT_TRUE(fast.passed == ref.passed) << "samples passed, iter " << iter << ": " << describe(d);
        counted += std::count_if(ref.passed.begin(), ref.passed.end(), [](uint64_t n) { return n != 0; });
        // the scenes must draw something, or the comparison proves nothing
        changed += ref.color0 != std::vector<uint8_t>(ref.color0.size(), 0x35);
    }
    EXPECT_GT(changed, 200);
    EXPECT_GT(counted, 300);
}

// The portable and the AVX2/FMA builds of the kernels (rast/core/cpu.h: tile set-up and coverage, the fast block
// pipeline, the RGBA8 blend) write the same bytes, and both those of the reference path.
TEST_F(FragmentStageTest, BothInstructionSetsWriteTheSameBytes) {
    const Isa before = kernel_isa();
    if (!set_kernel_isa_for_testing(Isa::kAvx2)) GTEST_SKIP() << "the AVX2/FMA build cannot run here";
    std::mt19937 rng(77);
    int changed = 0;
    for (int iter = 0; iter < 150; ++iter) {
        const SceneDesc d = random_scene(rng, iter);
        ASSERT_TRUE(set_kernel_isa_for_testing(Isa::kAvx2));
        const Targets avx2 = render(d, true, 1 + unsigned(iter % 2));
        ASSERT_TRUE(set_kernel_isa_for_testing(Isa::kPortable));
        const Targets portable = render(d, true, 1 + unsigned(iter % 2));
        const Targets ref = render(d, false, 1);
        for (const Targets* t : {&avx2, &portable}) {
            const char* name = t == &avx2 ? "avx2" : "portable";
            ASSERT_TRUE(t->color0 == ref.color0) << name << " colour 0, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(t->color1 == ref.color1) << name << " colour 1, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(t->depth == ref.depth) << name << " depth, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(t->stencil == ref.stencil) << name << " stencil, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(t->passed == ref.passed) << name << " samples passed, iter " << iter << ": " << describe(d);
        }
        changed += ref.color0 != std::vector<uint8_t>(ref.color0.size(), 0x35);
    }
    set_kernel_isa_for_testing(before);
    EXPECT_GT(changed, 100);
}

// Whole squares of copy-shader draws take the fused square kernel (fragment_square.cpp) in the AVX2 build: the
// same bytes and occlusion counts as the reference path, at 1 and 2 threads, and as the portable build.
TEST_F(FragmentStageTest, SquareKernelWritesTheReferenceBytes) {
    std::mt19937 rng(4242);
    for (int iter = 0; iter < 80; ++iter) {
        const SceneDesc d = square_scene(rng, iter);
        expect_fast_isas_match(d, iter, [&](const char* name, const Targets& fast, const Targets& ref) {
            ASSERT_TRUE(fast.color0 == ref.color0) << name << " colour 0, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(fast.passed == ref.passed) << name << " samples passed, iter " << iter << ": " << describe(d);
        });
        if (HasFatalFailure()) return;
    }
}

// 4x draws of a uniform shader into one opaque RGBA8 or BGRA8 target, without depth, stencil, queries or alpha to
// coverage, store the primitive's colour under each sample's raster mask (DrawPlan::uniform_store_4x in the AVX2
// build): the reference bytes at 1 and 2 threads, and the portable build's. The framebuffer sizes that are not
// multiples of 4 keep their edge blocks on the general path, next to blocks of the store.
TEST_F(FragmentStageTest, UniformStore4xWritesTheReferenceBytes) {
    std::mt19937 rng(4711);
    for (int iter = 0; iter < 60; ++iter) {
        SceneDesc d = random_scene(rng, iter);
        d.samples = 4;
        d.depth = fragment::DepthFormat::None;
        d.stencil = false;
        d.queries = false;
        d.format0 = rng() % 2 ? fragment::ColorFormat::R8G8B8A8_UNORM : fragment::ColorFormat::B8G8R8A8_UNORM;
        for (size_t i = 0; i < d.pipes.size(); ++i) {
            PipelineState& p = d.pipes[i];
            d.shaders[i] = int(rng() % 2);  // kFs[0] and kFs[1]: uniform, colour 0 only
            p.fragment = fs_[size_t(d.shaders[i])].get();
            p.samples = 4;
            p.alpha_to_coverage = false;
            p.depth_stencil = {};
            p.blend[0] = {};  // opaque, every channel written
            p.blend[1].write_mask = 0;
        }
        expect_fast_isas_match(d, iter, [&](const char* name, const Targets& fast, const Targets& ref) {
            ASSERT_TRUE(fast.color0 == ref.color0) << name << " colour 0, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(fast.color1 == ref.color1) << name << " colour 1, iter " << iter << ": " << describe(d);
        });
        if (HasFatalFailure()) return;
    }
}

// 1x draws of a uniform shader or a copy shader (perspective and noperspective) into one opaque RGBA8 or BGRA8
// target, without queries, stencil or alpha to coverage, with no depth buffer or D16/D32F under random depth states,
// take the fused 1x block kernel in the AVX2 build (DrawPlan::block1x): the reference bytes (colour and depth) at 1
// and 2 threads, and the portable build's. Depth states with a late test (writes off but the test on) or none at all
// sit beside the kernel's early ones, and edge blocks beside inside ones.
TEST_F(FragmentStageTest, Block1xWritesTheReferenceBytes) {
    const Isa before = kernel_isa();
    std::mt19937 rng(1111);
    int changed = 0;  // the depth states may reject every fragment of a scene, but not of most scenes
    for (int iter = 0; iter < 80; ++iter) {
        SceneDesc d = random_scene(rng, iter);
        d.samples = 1;
        d.stencil = false;
        d.queries = false;
        d.format0 = rng() % 2 ? fragment::ColorFormat::R8G8B8A8_UNORM : fragment::ColorFormat::B8G8R8A8_UNORM;
        for (size_t i = 0; i < d.pipes.size(); ++i) {
            PipelineState& p = d.pipes[i];
            const int kinds[] = {0, 1, kCopyFs, -1};  // uniform, uniform with FrontFacing, copies
            d.shaders[i] = kinds[rng() % 4];
            p.fragment = d.shaders[i] < 0 ? copy_noperspective_.get() : fs_[size_t(d.shaders[i])].get();
            p.samples = 1;
            p.alpha_to_coverage = false;
            p.depth_stencil.stencil_test = false;
            p.blend[0] = {};  // opaque, every channel written
            p.blend[1].write_mask = 0;
        }
        const Targets ref = render(d, false, 1);
        changed += ref.color0 != std::vector<uint8_t>(ref.color0.size(), 0x35);
        for (const Isa isa : {Isa::kAvx2, Isa::kPortable}) {
            if (!set_kernel_isa_for_testing(isa)) continue;
            const Targets fast = render(d, true, 1 + unsigned(iter % 2));
            const char* name = isa == Isa::kAvx2 ? "avx2" : "portable";
            ASSERT_TRUE(fast.color0 == ref.color0) << name << " colour 0, iter " << iter << ": " << describe(d);
            ASSERT_TRUE(fast.depth == ref.depth) << name << " depth, iter " << iter << ": " << describe(d);
        }
        set_kernel_isa_for_testing(before);
    }
    EXPECT_GT(changed, 60);
}

// Direct runs bind each draw's descriptors once per worker and scene (Program::bind_fragment): draws of one scene
// with other push constants, and a second scene of the same renderer whose draw records (and their bindings) take
// the first scene's places, must still see their own. Random scenes whose draws take kPushFs shaders or kFs ones
// (discard, noperspective, derivatives: direct as well), each with its own push constants, at 1 and 2 threads.
TEST_F(FragmentStageTest, DirectRunsUseEachDrawsOwnBindings) {
    std::mt19937 rng(1357);
    std::uniform_real_distribution<float> u(-0.5f, 1.5f);
    int direct_draws = 0;
    for (int iter = 0; iter < 120; ++iter) {
        SceneDesc d = random_scene(rng, iter);
        if (d.pipes.size() < 2) {  // at least one draw per scene
            d.pipes.push_back(d.pipes[0]);
            d.shaders.push_back(d.shaders[0]);
            d.draws.push_back(d.draws[0]);
        }
        for (size_t i = 0; i < d.pipes.size(); ++i) {
            if (rng() % 3 != 0) {
                const size_t k = rng() % std::size(kPushFs);
                d.pipes[i].fragment = push_fs_[k].get();
                d.shaders[i] = 100 + int(k);
                d.pipes[i].blend[1].write_mask = 0;
            }
            std::array<float, 8> pc;
            for (float& v : pc) v = u(rng);
            d.push.push_back(pc);
            if (d.shaders[i] >= 100) ++direct_draws;
        }
        d.split = iter % 2 ? 1 + rng() % (d.pipes.size() - 1) : 0;
        const Targets ref = render(d, false, 1);
        const Targets fast = render(d, true, 1 + unsigned(iter % 2));
        const std::string what = "iter " + std::to_string(iter) + " split " + std::to_string(d.split) + ": ";
        ASSERT_TRUE(fast.color0 == ref.color0) << "colour 0, " << what << describe(d);
        ASSERT_TRUE(fast.color1 == ref.color1) << "colour 1, " << what << describe(d);
        ASSERT_TRUE(fast.depth == ref.depth) << "depth, " << what << describe(d);
        ASSERT_TRUE(fast.passed == ref.passed) << "samples passed, " << what << describe(d);
    }
    EXPECT_GT(direct_draws, 150);
}

TEST_F(FragmentStageTest, SwitchReadsBack) {
    set_fragment_fast_paths(false);
    EXPECT_FALSE(fragment_fast_paths());
    set_fragment_fast_paths(true);
    EXPECT_TRUE(fragment_fast_paths());
}

}  // namespace
}  // namespace tilevk::rast::render
