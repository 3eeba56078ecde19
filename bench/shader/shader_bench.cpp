// Shader benchmarks: lanes/second for a pass-through, a per-pixel Phong and a textured fragment shader, and
// Program::create (validate + optimize + translate) time for each.
//   ninja -C build bench/shader/shader_bench && ./build/bench/shader/shader_bench
#include <benchmark/benchmark.h>

#include <bit>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include "shader/program.h"

using namespace tilevk::shader;

namespace {

std::vector<uint32_t> compile(Stage stage, const char* source) {
    static bool init = glslang::InitializeProcess();
    (void)init;
    EShLanguage lang = stage == Stage::Vertex ? EShLangVertex : EShLangFragment;
    glslang::TShader shader(lang);
    shader.setStrings(&source, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
    auto msgs = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);
    glslang::TProgram program;
    if (!shader.parse(GetDefaultResources(), 450, false, msgs) || (program.addShader(&shader), !program.link(msgs))) {
        std::fprintf(stderr, "GLSL error: %s\n", shader.getInfoLog());
        std::abort();
    }
    std::vector<uint32_t> spirv;
    glslang::GlslangToSpv(*program.getIntermediate(lang), spirv);
    return spirv;
}

const char* kPassVs = R"(#version 450
layout(location=0) in vec4 pos; layout(location=1) in vec4 col;
layout(location=0) out vec4 ocol;
void main() { gl_Position = pos; ocol = col; })";

const char* kPassFs = R"(#version 450
layout(location=0) in vec4 col; layout(location=0) out vec4 color;
void main() { color = col; })";

const char* kPhongFs = R"(#version 450
layout(location=0) in vec3 n; layout(location=1) in vec3 wpos; layout(location=0) out vec4 color;
layout(set=0, binding=0) uniform L { vec4 light_pos; vec4 eye; vec4 diffuse; vec4 spec; } l;
void main() {
    vec3 N = normalize(n);
    vec3 Ld = normalize(l.light_pos.xyz - wpos);
    vec3 V = normalize(l.eye.xyz - wpos);
    vec3 R = reflect(-Ld, N);
    float d = max(dot(N, Ld), 0.0);
    float s = pow(max(dot(R, V), 0.0), l.spec.w);
    color = vec4(l.diffuse.rgb * d + l.spec.rgb * s + vec3(0.05), 1.0);
})";

const char* kTexFs = R"(#version 450
layout(location=0) in vec2 uv; layout(location=0) out vec4 color;
layout(set=0, binding=1) uniform sampler2D tex;
void main() { color = texture(tex, uv) * vec4(0.9, 0.9, 0.9, 1.0); })";

void BM_Create(benchmark::State& state, Stage stage, const char* src) {
    auto spirv = compile(stage, src);
    size_t insts = 0;
    for (auto _ : state) {
        Result r = Program::create(spirv, stage);
        if (!r) state.SkipWithError(r.error.c_str());
        insts = r.program ? r.program->instruction_count() : 0;
        benchmark::DoNotOptimize(r.program);
    }
    state.counters["simd_insts"] = double(insts);
}

struct Fixture {
    std::vector<uint8_t> ubo = std::vector<uint8_t>(64);
    std::vector<uint8_t> texels;
    ImageView img;
    SamplerState smp;
    Bindings b;
    Fixture() {
        float u[16] = {2, 3, 4, 1, 0, 0, 5, 1, 0.8f, 0.6f, 0.4f, 1, 0.5f, 0.5f, 0.5f, 16};
        std::memcpy(ubo.data(), u, 64);
        b.set(0, 0, 0, Descriptor{BufferView{ubo.data(), nullptr, ubo.size()}});
        // 256x256 RGBA8 with a mip chain, linear filtering
        uint32_t w = 256, off = 0, L = 0;
        for (;; ++L) {
            img.level[L] = ImageLevel{off, w * 4ull, w * w * 4ull};
            off += w * w * 4;
            if (w == 1) break;
            w /= 2;
        }
        texels.resize(off);
        for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t(i * 2654435761u >> 24);
        img.base = texels.data();
        img.format = Format::RGBA8_UNORM;
        img.width = img.height = 256;
        img.levels = L + 1;
        smp.mag_filter = smp.min_filter = Filter::Linear;
        smp.mipmap_mode = MipmapMode::Linear;
        b.set(0, 1, 0, Descriptor{{}, &img, &smp});
    }
};

void BM_Fragment(benchmark::State& state, const char* src) {
    auto spirv = compile(Stage::Fragment, src);
    Result r = Program::create(spirv, Stage::Fragment);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    Fixture fx;
    FragmentBlock fb;
    for (int l = 0; l < kLanes; ++l)
        for (int loc = 0; loc < 2; ++loc)
            for (int c = 0; c < 4; ++c)
                fb.inputs[loc][c][l] =
                    std::bit_cast<uint32_t>(0.1f * float(lane_x(l) + c) + 0.05f * float(lane_y(l) + loc));
    Scratch s;
    for (auto _ : state) {
        r.program->run_fragment(fx.b, fb, s);
        benchmark::DoNotOptimize(fb.outputs[0][0][0]);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kLanes);
    state.counters["simd_insts"] = double(r.program->instruction_count());
}

void BM_Vertex(benchmark::State& state, const char* src) {
    auto spirv = compile(Stage::Vertex, src);
    Result r = Program::create(spirv, Stage::Vertex);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    VertexBatch vb;
    Scratch s;
    for (auto _ : state) {
        r.program->run_vertex(Bindings{}, vb, s);
        benchmark::DoNotOptimize(vb.position[0][0]);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kLanes);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Create, passthrough_vs, Stage::Vertex, kPassVs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, passthrough_fs, Stage::Fragment, kPassFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, phong_fs, Stage::Fragment, kPhongFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, textured_fs, Stage::Fragment, kTexFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Vertex, passthrough_vs, kPassVs);
BENCHMARK_CAPTURE(BM_Fragment, passthrough_fs, kPassFs);
BENCHMARK_CAPTURE(BM_Fragment, phong_fs, kPhongFs);
BENCHMARK_CAPTURE(BM_Fragment, textured_fs, kTexFs);

BENCHMARK_MAIN();
