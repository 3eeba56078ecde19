// Program::create: validate (SPIRV-Tools), specialize, legalize (spirv-opt), translate (translate.cpp).
#include <atomic>
#include <chrono>
#include <cstring>
#include <unordered_map>

#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

#include "shader/ir.h"
#include "shader/jit/jit.h"

namespace tilevk::shader {

namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;

// The target environment follows the module's SPIR-V version (1.0 -> Vulkan 1.0, 1.1..1.3 -> 1.1, 1.4 -> 1.1 with
// SPIR-V 1.4, 1.5 -> 1.2, 1.6 -> 1.3).
spv_target_env target_env(uint32_t version) {
    uint32_t minor = (version >> 8) & 0xff;
    if (minor == 0) return SPV_ENV_VULKAN_1_0;
    if (minor <= 3) return SPV_ENV_VULKAN_1_1;
    if (minor == 4) return SPV_ENV_VULKAN_1_1_SPIRV_1_4;
    if (minor == 5) return SPV_ENV_VULKAN_1_2;
    return SPV_ENV_VULKAN_1_3;
}

// Passes that inline, promote memory to SSA and remove dead code. Deliberately no "simplification" or
// instruction combining: those reassociate float arithmetic and would change results.
void register_passes(spvtools::Optimizer& opt, const SpecConstants& spec) {
    std::unordered_map<uint32_t, std::vector<uint32_t>> values;
    for (const auto& s : spec) values[s.id] = s.words;
    opt.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(values));
    opt.RegisterPass(spvtools::CreateFreezeSpecConstantValuePass());
    opt.RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass());
    opt.RegisterPass(spvtools::CreateUnifyConstantPass());
    opt.RegisterPass(spvtools::CreateMergeReturnPass());  // the inliner needs single-return functions
    opt.RegisterPass(spvtools::CreateInlineExhaustivePass());
    opt.RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
    opt.RegisterPass(spvtools::CreatePrivateToLocalPass());
    opt.RegisterPass(spvtools::CreateLocalSingleBlockLoadStoreElimPass());
    opt.RegisterPass(spvtools::CreateLocalSingleStoreElimPass());
    opt.RegisterPass(spvtools::CreateScalarReplacementPass(100));
    opt.RegisterPass(spvtools::CreateLocalAccessChainConvertPass());
    opt.RegisterPass(spvtools::CreateLocalSingleBlockLoadStoreElimPass());
    opt.RegisterPass(spvtools::CreateLocalSingleStoreElimPass());
    opt.RegisterPass(spvtools::CreateSSARewritePass());
    opt.RegisterPass(spvtools::CreateCCPPass());
    opt.RegisterPass(spvtools::CreateDeadBranchElimPass());
    opt.RegisterPass(spvtools::CreateBlockMergePass());
    opt.RegisterPass(spvtools::CreateAggressiveDCEPass());
    opt.RegisterPass(spvtools::CreateCFGCleanupPass());
}

}  // namespace

void Bindings::set(uint32_t set, uint32_t binding, uint32_t element, const Descriptor& d) {
    for (auto& e : entries_) {
        if (e.set == set && e.binding == binding && e.element == element) {
            e.d = d;
            return;
        }
    }
    entries_.push_back({set, binding, element, d});
}

const Descriptor* Bindings::find(uint32_t set, uint32_t binding, uint32_t element) const {
    for (const auto& e : entries_)
        if (e.set == set && e.binding == binding && e.element == element) return &e.d;
    return nullptr;
}

Scratch::Scratch() : impl_(std::make_unique<Impl>()) {}
Scratch::~Scratch() = default;
uint64_t Scratch::loop_limit_hits() const {
    return impl_->loop_limit_hits;
}

void Scratch::set_stop_flag(const std::atomic<bool>* stop) {
    impl_->stop = stop;
}

Program::Program(std::unique_ptr<ProgramImpl> impl, ProgramInterface iface)
    : impl_(std::move(impl)), interface_(std::move(iface)), linear_(analyze_linear_shader()) {
    if (impl_->stage == Stage::Fragment) plan_fragment_io(*impl_);
}
Program::~Program() = default;
size_t Program::instruction_count() const {
    return impl_->code.size();
}
bool Program::compiled() const {
    return impl_->jit != nullptr;
}
const ProgramImpl& Program::internal() const {
    return *impl_;
}

Result Program::create(std::span<const uint32_t> spirv, Stage stage, std::string_view entry,
                       const SpecConstants& spec) {
    auto t0 = std::chrono::steady_clock::now();
    Result res;
    auto finish = [&](std::string err) {
        res.error = std::move(err);
        res.create_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return res;
    };
    if (spirv.size() < 5) return finish("invalid SPIR-V: module shorter than its 5-word header");
    if (spirv[0] != kSpirvMagic) return finish("invalid SPIR-V: bad magic number");
    uint32_t version = spirv[1];
    if (version < 0x10000 || version > 0x10600) return finish("unsupported SPIR-V version (1.0-1.6 accepted)");

    spv_target_env env = target_env(version);
    std::string messages;
    auto consumer = [&messages](spv_message_level_t level, const char*, const spv_position_t&, const char* m) {
        if (level <= SPV_MSG_ERROR && messages.size() < 2000) {
            if (!messages.empty()) messages += "; ";
            messages += m;
        }
    };
    std::vector<uint32_t> words(spirv.begin(), spirv.end());
    {
        spvtools::SpirvTools tools(env);
        tools.SetMessageConsumer(consumer);
        // Blocks may follow std430 rules in uniform buffers (uniformBufferStandardLayout, Vulkan 1.2,
        // VK_KHR_uniform_buffer_standard_layout) and scalar rules in uniform, storage and push-constant blocks
        // (scalarBlockLayout, VK_EXT_scalar_block_layout): icd/ reports both, and the translator takes every offset
        // and stride from the module's decorations and loads and stores component by component, so nothing depends
        // on std140 alignment (lavapipe does not check block layouts at all).
        spvtools::ValidatorOptions vopt;
        vopt.SetUniformBufferStandardLayout(true);
        vopt.SetScalarBlockLayout(true);
        // LocalSizeId (SPIR-V 1.2+) is valid Vulkan with maintenance4 (VK_KHR_maintenance4, which icd/ reports); the
        // translator reads its ids after specialization (translate_module.cpp). Accepted without the feature too:
        // shader/ does not know what a device enabled, and a module using it then is invalid usage anyway.
        vopt.SetAllowLocalSizeId(true);
        if (!tools.Validate(words.data(), words.size(), vopt)) return finish("invalid SPIR-V: " + messages);
    }
    std::vector<uint32_t> optimized;
    {
        spvtools::Optimizer opt(env);
        opt.SetMessageConsumer(consumer);
        register_passes(opt, spec);
        spvtools::ValidatorOptions vopt;
        spvtools::OptimizerOptions oopt;
        oopt.set_run_validator(false);
        if (!opt.Run(words.data(), words.size(), &optimized, oopt))
            return finish("SPIR-V optimization failed: " + messages);
    }
    static std::atomic<uint64_t> serial{0};
    auto impl = std::make_unique<ProgramImpl>();
    impl->serial = ++serial;
    ProgramInterface iface;
    std::string err = translate(optimized, stage, entry, *impl, iface);
    if (!err.empty()) return finish(err);
    std::string why_not;
    impl->jit = jit::compile(*impl, &why_not);  // null: the interpreter runs it (why under TILEVK_LOG_PIPELINES)
    res.program = std::make_shared<Program>(std::move(impl), std::move(iface));
    return finish("");
}

}  // namespace tilevk::shader
