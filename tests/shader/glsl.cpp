#include "glsl.h"

#include <gtest/gtest.h>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

namespace tilevk::shader::test {

namespace {
struct GlslangInit {
    GlslangInit() { glslang::InitializeProcess(); }
    ~GlslangInit() { glslang::FinalizeProcess(); }
};
}  // namespace

std::vector<uint32_t> compile_glsl(Stage stage, const std::string& source, bool spirv_1_3) {
    static GlslangInit init;
    EShLanguage lang = stage == Stage::Vertex     ? EShLangVertex
                       : stage == Stage::Fragment ? EShLangFragment
                                                  : EShLangCompute;
    glslang::TShader shader(lang);
    const char* src = source.c_str();
    shader.setStrings(&src, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan,
                        spirv_1_3 ? glslang::EShTargetVulkan_1_1 : glslang::EShTargetVulkan_1_0);
    shader.setEnvTarget(glslang::EShTargetSpv, spirv_1_3 ? glslang::EShTargetSpv_1_3 : glslang::EShTargetSpv_1_0);
    auto msgs = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);
    if (!shader.parse(GetDefaultResources(), 450, false, msgs)) {
        ADD_FAILURE() << "GLSL compile failed: " << shader.getInfoLog();
        return {};
    }
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(msgs)) {
        ADD_FAILURE() << "GLSL link failed: " << program.getInfoLog();
        return {};
    }
    std::vector<uint32_t> spirv;
    glslang::GlslangToSpv(*program.getIntermediate(lang), spirv);
    return spirv;
}

std::shared_ptr<const Program> make_program(Stage stage, const std::string& source) {
    auto spirv = compile_glsl(stage, source);
    Result r = Program::create(spirv, stage);
    EXPECT_TRUE(r) << r.error;
    return r.program;
}

}  // namespace tilevk::shader::test
