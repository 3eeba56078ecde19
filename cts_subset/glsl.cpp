#include "glsl.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <map>
#include <mutex>
#include <stdexcept>

namespace tilevk::cts {

namespace {
SpirvTarget g_target = SpirvTarget::kSpirv10;
}  // namespace

void set_spirv_target(SpirvTarget target) {
    g_target = target;
}

uint32_t spirv_target_vulkan_minor() {
    switch (g_target) {
        case SpirvTarget::kSpirv10:
            return 0;
        case SpirvTarget::kSpirv13:
            return 1;
        case SpirvTarget::kSpirv15:
            return 2;
        case SpirvTarget::kSpirv16:
            break;
    }
    return 3;
}

const std::vector<uint32_t>& compile_glsl(Stage stage, const std::string& source) {
    static std::mutex mutex;
    static std::map<std::pair<int, std::string>, std::vector<uint32_t>> cache;
    static bool initialised = false;
    std::lock_guard lock(mutex);
    auto key = std::make_pair(static_cast<int>(stage), source);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    if (!initialised) initialised = glslang::InitializeProcess();

    EShLanguage lang = stage == Stage::kVertex     ? EShLangVertex
                       : stage == Stage::kFragment ? EShLangFragment
                                                   : EShLangCompute;
    glslang::TShader shader(lang);
    const char* text = source.c_str();
    shader.setStrings(&text, 1);
    const uint32_t minor = spirv_target_vulkan_minor();
    shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, minor == 0   ? glslang::EShTargetVulkan_1_0
                                                  : minor == 1 ? glslang::EShTargetVulkan_1_1
                                                  : minor == 2 ? glslang::EShTargetVulkan_1_2
                                                               : glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, minor == 0   ? glslang::EShTargetSpv_1_0
                                               : minor == 1 ? glslang::EShTargetSpv_1_3
                                               : minor == 2 ? glslang::EShTargetSpv_1_5
                                                            : glslang::EShTargetSpv_1_6);
    auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
    if (!shader.parse(GetDefaultResources(), 450, false, messages))
        throw std::runtime_error(std::string("glslang: ") + shader.getInfoLog() + "\n" + source);
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) throw std::runtime_error(std::string("glslang link: ") + program.getInfoLog());
    std::vector<uint32_t> spirv;
    glslang::GlslangToSpv(*program.getIntermediate(lang), spirv);
    return cache.emplace(key, std::move(spirv)).first->second;
}

namespace {

const char* qualifier(Interp i) {
    switch (i) {
        case Interp::kFlat:
            return "flat ";
        case Interp::kNoPerspective:
            return "noperspective ";
        default:
            return "";
    }
}

}  // namespace

std::string vertex_source(const Draw& d) {
    if (!d.vertex_glsl.empty()) return d.vertex_glsl;
    std::string q = qualifier(d.interp);
    std::string s =
        "#version 450\n"
        "layout(location=0) in vec4 in_pos;\n"
        "layout(location=1) in vec4 in_color;\n"
        "layout(location=2) in vec2 in_uv;\n"
        "layout(location=3) in float in_psize;\n"
        "layout(location=0) " +
        q +
        "out vec4 v_color;\n"
        "layout(location=1) " +
        q +
        "out vec2 v_uv;\n"
        "void main() {\n"
        "  gl_Position = in_pos;\n"
        "  v_color = in_color;\n"
        "  v_uv = in_uv;\n";
    // Only point topologies write the size: the runner does not ask other primitives to carry it.
    if (d.topology == VK_PRIMITIVE_TOPOLOGY_POINT_LIST || d.polygon_mode == VK_POLYGON_MODE_POINT)
        s += "  gl_PointSize = in_psize;\n";
    return s + "}\n";
}

std::string fragment_source(const Draw& d, bool color_output) {
    if (!d.fragment_glsl.empty()) return d.fragment_glsl;
    std::string q = qualifier(d.interp);
    std::string s =
        "#version 450\n"
        "layout(location=0) " +
        q +
        "in vec4 v_color;\n"
        "layout(location=1) " +
        q + "in vec2 v_uv;\n";
    // The inputs stay declared: they consume the vertex shader's outputs.
    if (!color_output) return s + "void main() {}\n";
    s += "layout(location=0) out vec4 o_color;\n";
    switch (d.frag) {
        case Frag::kColor:
            return s + "void main() { o_color = v_color; }\n";
        case Frag::kTexture:
            return s +
                   "layout(set=0, binding=0) uniform sampler2D tex;\n"
                   "void main() { o_color = texture(tex, v_uv); }\n";
        case Frag::kConstant:
            return s + "void main() { o_color = vec4(0.5, 0.25, 0.8, 0.75); }\n";
        case Frag::kColorRgb1:
            return s + "void main() { o_color = vec4(v_color.rgb, 1.0); }\n";
        case Frag::kColorSum:
            return s + "void main() { o_color = v_color + v_color; }\n";
        case Frag::kCount:
            return s + "void main() { o_color = vec4(1.0 / 255.0); }\n";
        case Frag::kFacing:
            return s +
                   "void main() { o_color = gl_FrontFacing ? vec4(1.0/255.0, 0, 0, 1.0/255.0)"
                   " : vec4(0, 1.0/255.0, 0, 1.0/255.0); }\n";
        case Frag::kDiscard:
            return s +
                   "void main() {\n"
                   "    if (((int(gl_FragCoord.x) + int(gl_FragCoord.y)) & 1) != 0) discard;\n"
                   "    o_color = v_color;\n"
                   "}\n";
    }
    return s;
}

}  // namespace tilevk::cts
