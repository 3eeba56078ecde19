// Shader benchmarks: lanes/second of typical shaders (bench_shaders.h) in the interpreter and in the compiled tier,
// Program::create (validate + optimize + translate + compile) time, and the compiled tier's code generation alone.
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

#include "bench/shader/bench_shaders.h"
#include "shader/ir.h"
#include "shader/jit/jit.h"
#if TILEVK_LLVM_PROBE
#include "bench/shader/llvm_probe.h"
#endif
#include "shader/program.h"

using namespace tilevk::shader;
using namespace tilevk::bench_shaders;

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
    std::vector<uint8_t> ubo = std::vector<uint8_t>(256);
    std::vector<uint8_t> texels;
    ImageView img;
    SamplerState smp;
    Bindings b;
    Fixture() {
        float u[16] = {2, 3, 4, 1, 0, 0, 5, 1, 0.8f, 0.6f, 0.4f, 1, 0.5f, 0.5f, 0.5f, 16};
        std::memcpy(ubo.data(), u, 64);
        for (size_t i = 64; i < ubo.size(); i += 4) {  // mesh_vs's model matrix and light: small floats
            float x = 0.01f * float(i % 37) - 0.1f;
            std::memcpy(&ubo[i], &x, 4);
        }
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
        img.format = Format::R8G8B8A8_UNORM;
        img.width = img.height = 256;
        img.levels = L + 1;
        prepare_view(img);
        smp.mag_filter = smp.min_filter = Filter::Linear;
        smp.mipmap_mode = MipmapMode::Linear;
        b.set(0, 1, 0, Descriptor{{}, &img, &smp});
    }
};

// The compiled tier's share of Program::create: code generation for the translated program.
void BM_Compile(benchmark::State& state, Stage stage, const char* src) {
    auto spirv = compile(stage, src);
    Result r = Program::create(spirv, stage);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    size_t bytes = 0;
    for (auto _ : state) {
        std::string why;
        auto code = jit::compile(r.program->internal(), &why);
        if (!code) state.SkipWithError(why.c_str());
        bytes = code ? code->code_bytes : 0;
        benchmark::DoNotOptimize(code);
    }
    state.counters["code_bytes"] = double(bytes);
    state.counters["simd_insts"] = double(r.program->instruction_count());
}

// `compiled`: the program runs in the compiled tier, else in the interpreter.
Result create_in_tier(const std::vector<uint32_t>& spirv, Stage stage, bool compiled) {
    set_jit_enabled(compiled);
    Result r = Program::create(spirv, stage);
    set_jit_enabled(true);
    if (r && r.program->compiled() != compiled) return Result{nullptr, "the compiled tier is not available here"};
    return r;
}

// Two vec4 inputs that differ per lane and location.
FragmentBlock fragment_inputs() {
    FragmentBlock fb;
    for (int l = 0; l < kLanes; ++l)
        for (int loc = 0; loc < 2; ++loc)
            for (int c = 0; c < 4; ++c)
                fb.inputs[loc][c][l] =
                    std::bit_cast<uint32_t>(0.1f * float(lane_x(l) + c) + 0.05f * float(lane_y(l) + loc));
    return fb;
}

// The timed loop of the fragment benchmarks: one 16-lane block per iteration.
void time_fragment(benchmark::State& state, const Program& program, const Bindings& b, FragmentBlock& fb, Scratch& s) {
    for (auto _ : state) {
        program.run_fragment(b, fb, s);
        benchmark::DoNotOptimize(fb.outputs[0][0][0]);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kLanes);
}

void BM_Fragment(benchmark::State& state, const char* src, bool compiled) {
    auto spirv = compile(Stage::Fragment, src);
    Result r = create_in_tier(spirv, Stage::Fragment, compiled);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    Fixture fx;
    FragmentBlock fb = fragment_inputs();
    Scratch s;
    time_fragment(state, *r.program, fx.b, fb, s);
    state.counters["simd_insts"] = double(r.program->instruction_count());
}

void BM_Vertex(benchmark::State& state, const char* src, bool compiled) {
    auto spirv = compile(Stage::Vertex, src);
    Result r = create_in_tier(spirv, Stage::Vertex, compiled);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    Fixture fx;
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l)
        for (int loc = 0; loc < 3; ++loc)
            for (int c = 0; c < 4; ++c)
                vb.inputs[loc][c][l] = std::bit_cast<uint32_t>(0.1f * float(l + c) - 0.3f * loc);
    Scratch s;
    for (auto _ : state) {
        r.program->run_vertex(fx.b, vb, s);
        benchmark::DoNotOptimize(vb.position[0][0]);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kLanes);
}

#if TILEVK_LLVM_PROBE
// The same program compiled by LLVM (llvm_probe.cpp) instead of asmjit.
void BM_LlvmCompile(benchmark::State& state, Stage stage, const char* src, int opt) {
    auto spirv = compile(stage, src);
    Result r = Program::create(spirv, stage);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    state.counters["init_ms"] = tilevk::bench_probe::llvm_init_ms();
    for (auto _ : state) {
        std::string why;
        auto code = tilevk::bench_probe::llvm_compile(r.program->internal(), opt, &why);
        if (!code) state.SkipWithError(why.c_str());
        benchmark::DoNotOptimize(code);
    }
}

// Runs with LLVM's code installed in place of asmjit's.
Result create_with_llvm(const std::vector<uint32_t>& spirv, Stage stage, int opt) {
    Result r = Program::create(spirv, stage);
    if (!r) return r;
    std::string why;
    auto code = tilevk::bench_probe::llvm_compile(r.program->internal(), opt, &why);
    if (!code) return Result{nullptr, why};
    const_cast<ProgramImpl&>(r.program->internal()).jit = code;
    return r;
}

void BM_LlvmFragment(benchmark::State& state, const char* src, int opt) {
    auto spirv = compile(Stage::Fragment, src);
    Result r = create_with_llvm(spirv, Stage::Fragment, opt);
    if (!r) {
        state.SkipWithError(r.error.c_str());
        return;
    }
    Fixture fx;
    FragmentBlock fb = fragment_inputs();
    Scratch s;
    {  // the probe's code must give the interpreter's bits, or its speed means nothing
        Result ref = create_in_tier(spirv, Stage::Fragment, false);
        FragmentBlock a = fb, b = fb;
        Scratch sr;
        r.program->run_fragment(fx.b, a, s);
        ref.program->run_fragment(fx.b, b, sr);
        if (std::memcmp(&a, &b, sizeof a) != 0) {
            state.SkipWithError("LLVM's code gives other bits than the interpreter");
            return;
        }
    }
    time_fragment(state, *r.program, fx.b, fb, s);
}
#endif

}  // namespace

#if TILEVK_LLVM_PROBE
BENCHMARK_CAPTURE(BM_LlvmCompile, passthrough_fs_O2, Stage::Fragment, kPassFs, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LlvmCompile, phong_fs_O1, Stage::Fragment, kPhongFs, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LlvmCompile, phong_fs_O2, Stage::Fragment, kPhongFs, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LlvmCompile, textured_fs_O2, Stage::Fragment, kTexFs, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LlvmCompile, loop_fs_O2, Stage::Fragment, kLoopFs, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_LlvmFragment, passthrough_fs_llvm_O2, kPassFs, 2);
BENCHMARK_CAPTURE(BM_LlvmFragment, phong_fs_llvm_O1, kPhongFs, 1);
BENCHMARK_CAPTURE(BM_LlvmFragment, phong_fs_llvm_O2, kPhongFs, 2);
BENCHMARK_CAPTURE(BM_LlvmFragment, textured_fs_llvm_O2, kTexFs, 2);
BENCHMARK_CAPTURE(BM_LlvmFragment, loop_fs_llvm_O2, kLoopFs, 2);
#endif

BENCHMARK_CAPTURE(BM_Create, passthrough_vs, Stage::Vertex, kPassVs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, passthrough_fs, Stage::Fragment, kPassFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, phong_fs, Stage::Fragment, kPhongFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, textured_fs, Stage::Fragment, kTexFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, mesh_vs, Stage::Vertex, kMeshVs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Create, loop_fs, Stage::Fragment, kLoopFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compile, passthrough_vs, Stage::Vertex, kPassVs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compile, passthrough_fs, Stage::Fragment, kPassFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compile, phong_fs, Stage::Fragment, kPhongFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compile, textured_fs, Stage::Fragment, kTexFs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compile, mesh_vs, Stage::Vertex, kMeshVs)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compile, loop_fs, Stage::Fragment, kLoopFs)->Unit(benchmark::kMicrosecond);
// Interpreter and compiled tier next to each other, per program.
BENCHMARK_CAPTURE(BM_Vertex, passthrough_vs_interpreter, kPassVs, false);
BENCHMARK_CAPTURE(BM_Vertex, passthrough_vs_compiled, kPassVs, true);
BENCHMARK_CAPTURE(BM_Vertex, mesh_vs_interpreter, kMeshVs, false);
BENCHMARK_CAPTURE(BM_Vertex, mesh_vs_compiled, kMeshVs, true);
BENCHMARK_CAPTURE(BM_Fragment, passthrough_fs_interpreter, kPassFs, false);
BENCHMARK_CAPTURE(BM_Fragment, passthrough_fs_compiled, kPassFs, true);
BENCHMARK_CAPTURE(BM_Fragment, phong_fs_interpreter, kPhongFs, false);
BENCHMARK_CAPTURE(BM_Fragment, phong_fs_compiled, kPhongFs, true);
BENCHMARK_CAPTURE(BM_Fragment, textured_fs_interpreter, kTexFs, false);
BENCHMARK_CAPTURE(BM_Fragment, textured_fs_compiled, kTexFs, true);
BENCHMARK_CAPTURE(BM_Fragment, loop_fs_interpreter, kLoopFs, false);
BENCHMARK_CAPTURE(BM_Fragment, loop_fs_compiled, kLoopFs, true);

BENCHMARK_MAIN();
