// blend.*: every blend factor (as source and as destination), every op, the constant colour and write masks.
// The destination is a smooth gradient; the blended triangles carry varying colour and alpha.
#include "case.hpp"

namespace tilevk::cts {
namespace {

Scene blend_scene(VkPipelineColorBlendAttachmentState b) {
    Draw bg;
    bg.vertices = {vtx(-1, -1, 0, 1, {0.1f, 0.9f, 0.3f, 0.2f}), vtx(3, -1, 0, 1, {0.8f, 0.2f, 0.6f, 1.0f}),
                   vtx(-1, 3, 0, 1, {0.4f, 0.5f, 1.0f, 0.6f})};
    Draw top;
    top.blend = b;
    float constants[4] = {0.25f, 0.5f, 0.75f, 0.6f};
    std::copy(constants, constants + 4, top.blend_constants);
    top.vertices = {
        vtx(-0.9f, -0.9f, 0, 1, {1.0f, 0.2f, 0.0f, 0.9f}), vtx(0.9f, -0.6f, 0, 1, {0.0f, 1.0f, 0.4f, 0.1f}),
        vtx(-0.5f, 0.9f, 0, 1, {0.3f, 0.0f, 1.0f, 0.5f}),  vtx(0.9f, 0.9f, 0, 1, {0.7f, 0.7f, 0.2f, 0.3f}),
        vtx(0.2f, -0.9f, 0, 1, {1.0f, 1.0f, 1.0f, 0.0f}),  vtx(-0.9f, 0.4f, 0, 1, {0.5f, 0.1f, 0.9f, 1.0f})};
    Scene s = one_draw(bg);
    s.draws.push_back(top);
    return s;
}

VkPipelineColorBlendAttachmentState blend(VkBlendFactor src, VkBlendFactor dst, VkBlendOp op = VK_BLEND_OP_ADD,
                                          uint32_t mask = 0xF) {
    return {VK_TRUE, src, dst, op, src, dst, op, mask};
}

}  // namespace

void add_blend_cases(CaseList& out) {
    struct Factor {
        const char* name;
        VkBlendFactor f;
    };
    const Factor factors[] = {{"zero", VK_BLEND_FACTOR_ZERO},
                              {"one", VK_BLEND_FACTOR_ONE},
                              {"src_color", VK_BLEND_FACTOR_SRC_COLOR},
                              {"one_minus_src_color", VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR},
                              {"dst_color", VK_BLEND_FACTOR_DST_COLOR},
                              {"one_minus_dst_color", VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR},
                              {"src_alpha", VK_BLEND_FACTOR_SRC_ALPHA},
                              {"one_minus_src_alpha", VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA},
                              {"dst_alpha", VK_BLEND_FACTOR_DST_ALPHA},
                              {"one_minus_dst_alpha", VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA},
                              {"constant_color", VK_BLEND_FACTOR_CONSTANT_COLOR},
                              {"one_minus_constant_color", VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR},
                              {"constant_alpha", VK_BLEND_FACTOR_CONSTANT_ALPHA},
                              {"one_minus_constant_alpha", VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_ALPHA},
                              {"src_alpha_saturate", VK_BLEND_FACTOR_SRC_ALPHA_SATURATE}};
    // Each factor as the source factor (destination ONE_MINUS_SRC_ALPHA), then as the destination (source ONE).
    for (const Factor& f : factors) {
        auto b = blend(f.f, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
        out.push_back({std::string("blend.src_factor.") + f.name, [=] { return blend_scene(b); }, nullptr, ""});
    }
    for (const Factor& f : factors) {
        if (f.f == VK_BLEND_FACTOR_SRC_ALPHA_SATURATE) continue;
        auto b = blend(VK_BLEND_FACTOR_ONE, f.f);
        out.push_back({std::string("blend.dst_factor.") + f.name, [=] { return blend_scene(b); }, nullptr, ""});
    }
    struct Op {
        const char* name;
        VkBlendOp op;
    };
    const Op ops[] = {{"add", VK_BLEND_OP_ADD},
                      {"subtract", VK_BLEND_OP_SUBTRACT},
                      {"reverse_subtract", VK_BLEND_OP_REVERSE_SUBTRACT},
                      {"min", VK_BLEND_OP_MIN},
                      {"max", VK_BLEND_OP_MAX}};
    for (const Op& o : ops) {
        auto b = blend(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR, o.op);
        out.push_back({std::string("blend.op.") + o.name, [=] { return blend_scene(b); }, nullptr, ""});
    }
    // Separate colour and alpha equations.
    VkPipelineColorBlendAttachmentState sep = {VK_TRUE,
                                               VK_BLEND_FACTOR_SRC_ALPHA,
                                               VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                                               VK_BLEND_OP_ADD,
                                               VK_BLEND_FACTOR_DST_ALPHA,
                                               VK_BLEND_FACTOR_CONSTANT_ALPHA,
                                               VK_BLEND_OP_REVERSE_SUBTRACT,
                                               0xF};
    out.push_back({"blend.separate_alpha", [=] { return blend_scene(sep); }, nullptr, ""});
    for (uint32_t mask : {0x0u, 0x1u, 0x2u, 0x4u, 0x8u, 0x5u, 0xAu, 0x7u}) {
        auto plain = blend(VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO, VK_BLEND_OP_ADD, mask);
        plain.blendEnable = VK_FALSE;
        out.push_back({"blend.write_mask." + std::to_string(mask), [=] { return blend_scene(plain); }, nullptr, ""});
    }
    auto masked = blend(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD, 0x6);
    out.push_back({"blend.write_mask.6_blended", [=] { return blend_scene(masked); }, nullptr, ""});
}

}  // namespace tilevk::cts
