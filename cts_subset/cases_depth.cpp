// depth.*: every compare op on D16, D32 and X8_D24 (LESS on D24S8/D32S8, also at 4x), bias on each (constant, slope,
// clamp), depth clamp and near/far clipping. Colour and the depth aspect are both compared byte for byte.
#include "case.hpp"

namespace tilevk::cts {
namespace {

// A full-target plane at z=0.5, then a triangle sloping from z=0 to z=1 drawn with `op`.
Scene compare_scene(VkFormat format, VkCompareOp op) {
    Draw plane;
    plane.depth_test = plane.depth_write = true;
    plane.depth_op = VK_COMPARE_OP_ALWAYS;
    std::array<float, 4> grey = {0.25f, 0.25f, 0.25f, 1};
    plane.vertices = {vtx(-1, -1, 0.5f, 1, grey), vtx(3, -1, 0.5f, 1, grey), vtx(-1, 3, 0.5f, 1, grey)};
    Draw slope;
    slope.depth_test = slope.depth_write = true;
    slope.depth_op = op;
    slope.vertices = {vtx(-0.9f, -0.9f, 0.0f, 1, {1, 0, 0, 1}), vtx(0.9f, -0.8f, 1.0f, 1, {0, 1, 0, 1}),
                      vtx(0.0f, 0.95f, 0.5f, 1, {0, 0, 1, 1}),  vtx(-0.8f, 0.5f, 0.5f, 1, {1, 1, 0, 1}),
                      vtx(0.7f, 0.6f, 0.5f, 1, {0, 1, 1, 1}),   vtx(0.1f, -0.95f, 0.5f, 1, {1, 0, 1, 1})};
    Scene s = one_draw(plane);
    s.draws.push_back(slope);
    s.target.depth = format;
    return s;
}

Scene bias_scene(VkFormat format, float constant, float slope, float clamp) {
    Draw base;
    base.depth_test = base.depth_write = true;
    base.vertices = {vtx(-1, -1, 0.4f, 1, {0.5f, 0.5f, 0.5f, 1}), vtx(1, -1, 0.6f, 1, {0.5f, 0.5f, 0.5f, 1}),
                     vtx(-1, 1, 0.5f, 1, {0.5f, 0.5f, 0.5f, 1})};
    Draw top = base;  // the same triangle again, biased, with LESS_OR_EQUAL: the bias decides what shows
    top.depth_op = VK_COMPARE_OP_LESS_OR_EQUAL;
    top.depth_bias = true;
    top.bias_constant = constant;
    top.bias_slope = slope;
    top.bias_clamp = clamp;
    for (Vertex& v : top.vertices) v.color[0] = 1, v.color[1] = 0;
    Scene s = one_draw(base);
    s.draws.push_back(top);
    s.target.depth = format;
    return s;
}

}  // namespace

void add_depth_cases(CaseList& out) {
    struct Op {
        const char* name;
        VkCompareOp op;
    };
    const Op ops[] = {{"never", VK_COMPARE_OP_NEVER},
                      {"less", VK_COMPARE_OP_LESS},
                      {"equal", VK_COMPARE_OP_EQUAL},
                      {"less_or_equal", VK_COMPARE_OP_LESS_OR_EQUAL},
                      {"greater", VK_COMPARE_OP_GREATER},
                      {"not_equal", VK_COMPARE_OP_NOT_EQUAL},
                      {"greater_or_equal", VK_COMPARE_OP_GREATER_OR_EQUAL},
                      {"always", VK_COMPARE_OP_ALWAYS}};
    struct Fmt {
        const char* name;
        VkFormat format;
    };
    const Fmt fmts[] = {
        {"d16", VK_FORMAT_D16_UNORM}, {"d32", VK_FORMAT_D32_SFLOAT}, {"x8d24", VK_FORMAT_X8_D24_UNORM_PACK32}};
    for (const Fmt& f : fmts)
        for (const Op& o : ops)
            out.push_back({std::string("depth.compare.") + f.name + "_" + o.name,
                           [=] { return compare_scene(f.format, o.op); },
                           // NEVER: only the plane (0.25 -> unorm8 64) may show.
                           o.op == VK_COMPARE_OP_NEVER ? palette_only({rgba8(64, 64, 64, 255)}) : Check(), ""});
    out.push_back({"depth.compare.d24s8_less",
                   [] { return compare_scene(VK_FORMAT_D24_UNORM_S8_UINT, VK_COMPARE_OP_LESS); }, nullptr, ""});
    out.push_back({"depth.compare.d32s8_less",
                   [] { return compare_scene(VK_FORMAT_D32_SFLOAT_S8_UINT, VK_COMPARE_OP_LESS); }, nullptr, ""});
    // The packed depth/stencil formats at 4x (the colour resolve is compared; multisampled depth is not read back).
    const Fmt packed[] = {{"d24s8", VK_FORMAT_D24_UNORM_S8_UINT},
                          {"d32s8", VK_FORMAT_D32_SFLOAT_S8_UINT},
                          {"x8d24", VK_FORMAT_X8_D24_UNORM_PACK32}};
    for (const Fmt& f : packed)
        out.push_back({std::string("depth.compare.") + f.name + "_less_4x",
                       [=] {
                           Scene s = compare_scene(f.format, VK_COMPARE_OP_LESS);
                           s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                           return s;
                       },
                       nullptr, ""});
    struct Bias {
        const char* name;
        float constant, slope, clamp;
    };
    const Bias biases[] = {{"constant_pos", 4, 0, 0},
                           {"constant_neg", -4, 0, 0},
                           {"slope", 0, 2, 0},
                           {"slope_neg", 0, -2, 0},
                           {"clamp", -100, -4, -0.001f}};
    // Bias on the 24-bit formats (r = 2^-24) and on D32_SFLOAT_S8_UINT (r from the primitive's exponent).
    for (const Fmt& f : packed)
        for (const Bias& b : biases)
            out.push_back({std::string("depth.bias.") + f.name + "_" + b.name,
                           [=] { return bias_scene(f.format, b.constant, b.slope, b.clamp); }, nullptr, ""});
    for (const Fmt& f : fmts)
        for (const Bias& b : biases)
            out.push_back({std::string("depth.bias.") + f.name + "_" + b.name,
                           [=] { return bias_scene(f.format, b.constant, b.slope, b.clamp); }, nullptr, ""});
    // z outside [0,1]: clipped by default, clamped when depthClamp is on.
    for (bool clamp : {false, true})
        for (const Fmt& f : fmts) {
            auto scene = [=] {
                Draw d;
                d.depth_test = d.depth_write = true;
                d.depth_clamp = clamp;
                d.vertices = {vtx(-0.9f, -0.9f, -0.5f, 1, {1, 0, 0, 1}),  vtx(0.9f, -0.9f, 1.5f, 1, {0, 1, 0, 1}),
                              vtx(0.0f, 0.9f, 0.5f, 1, {0, 0, 1, 1}),     vtx(-0.9f, 0.9f, 1.2f, 2, {1, 1, 0, 1}),
                              vtx(0.9f, 0.9f, -0.2f, 0.5f, {0, 1, 1, 1}), vtx(0.5f, -0.5f, 0.3f, 1, {1, 0, 1, 1})};
                Scene s = one_draw(d);
                s.target.depth = f.format;
                return s;
            };
            out.push_back(
                {std::string("depth.") + (clamp ? "clamp_" : "near_far_clipping_") + f.name, scene, nullptr, ""});
        }
    // A depth range narrower than [0,1].
    out.push_back({"depth.viewport_depth_range_d32",
                   [] {
                       Scene s = compare_scene(VK_FORMAT_D32_SFLOAT, VK_COMPARE_OP_LESS);
                       for (Draw& d : s.draws) d.viewport = VkViewport{0, 0, 64, 64, 0.25f, 0.75f};
                       return s;
                   },
                   nullptr, ""});
}

}  // namespace tilevk::cts
