// Pipeline extensions lavapipe offers, each against lavapipe byte for byte and an analytic check:
// pipeline.color_write_enable.* (VK_EXT_color_write_enable, modelled on dEQP-VK.pipeline.*.color_write_enable) and
// draw.multi_draw.* (VK_EXT_multi_draw, modelled on dEQP-VK.draw.*.multi_draw), draw.conditional_rendering.*
// (VK_EXT_conditional_rendering, modelled on dEQP-VK.conditional_rendering.draw.*). VK_KHR_shader_non_semantic_info has
// no case here: the subset's devices are Vulkan 1.0-1.2 and lavapipe 22.3 lists the extension only as part of 1.3
// (tests/icd ApiPipelineExtensions.ShaderNonSemanticInfo compares it on a 1.3 instance).
#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kBlue = 0xFFFF0000u, kMagenta = 0xFFFF00FFu, kGreen = 0xFF00FF00u;  // RGBA8, R in the low byte

Draw full_screen(std::array<float, 4> c, float z) {
    Draw d;
    d.vertices = {vtx(-1, -1, z, 1, c), vtx(3, -1, z, 1, c), vtx(-1, 3, z, 1, c)};
    return d;
}

// Blue everywhere, then red blended ONE, ONE with attachment 0's write enable `enable` (a disabled attachment
// neither blends nor writes): all magenta when enabled, all blue when not.
Scene color_write_scene(VkBool32 enable, bool dynamic) {
    Scene s = one_draw(full_screen({0, 0, 1, 1}, 0));
    Draw top = full_screen({1, 0, 0, 1}, 0);
    top.blend = {VK_TRUE,
                 VK_BLEND_FACTOR_ONE,
                 VK_BLEND_FACTOR_ONE,
                 VK_BLEND_OP_ADD,
                 VK_BLEND_FACTOR_ONE,
                 VK_BLEND_FACTOR_ONE,
                 VK_BLEND_OP_ADD,
                 0xF};
    top.color_write_enable = enable;
    top.color_write_dynamic = dynamic;
    s.draws.push_back(top);
    return s;
}

// A disabled attachment still leaves depth written: blue at z 0.5, a disabled red square at z 0.2 over the left
// half, then green at z 0.3 with LESS: blue where the square wrote depth, green elsewhere.
Scene color_write_depth_scene(bool dynamic) {
    Draw back = full_screen({0, 0, 1, 1}, 0.5f);
    back.depth_test = back.depth_write = true;
    back.depth_op = VK_COMPARE_OP_ALWAYS;
    Draw hidden;
    const std::array<float, 4> red = {1, 0, 0, 1};
    hidden.vertices = {vtx(-1, -1, 0.2f, 1, red), vtx(0, -1, 0.2f, 1, red), vtx(-1, 1, 0.2f, 1, red),
                       vtx(0, -1, 0.2f, 1, red),  vtx(0, 1, 0.2f, 1, red),  vtx(-1, 1, 0.2f, 1, red)};
    hidden.depth_test = hidden.depth_write = true;
    hidden.depth_op = VK_COMPARE_OP_ALWAYS;
    hidden.color_write_enable = VK_FALSE;
    hidden.color_write_dynamic = dynamic;
    Draw front = full_screen({0, 1, 0, 1}, 0.3f);
    front.depth_test = true;
    front.depth_op = VK_COMPARE_OP_LESS;
    front.color_write_enable = VK_TRUE;  // an enabled attachment after a disabled one (the state does not stick)
    front.color_write_dynamic = dynamic;
    Scene s = one_draw(back);
    s.draws.push_back(hidden);
    s.draws.push_back(front);
    s.target.depth = VK_FORMAT_D32_SFLOAT;
    return s;
}

void add_color_write_cases(CaseList& out) {
    for (const bool dynamic : {false, true}) {
        const std::string kind = dynamic ? "dynamic" : "static";
        out.push_back({"pipeline.color_write_enable." + kind + "_enabled",
                       [=] { return color_write_scene(VK_TRUE, dynamic); }, palette_only({kMagenta}), ""});
        out.push_back({"pipeline.color_write_enable." + kind + "_disabled",
                       [=] { return color_write_scene(VK_FALSE, dynamic); }, palette_only({kBlue}), ""});
        out.push_back({"pipeline.color_write_enable." + kind + "_disabled_depth_write",
                       [=] { return color_write_depth_scene(dynamic); },
                       all_of({palette_only({kBlue, kGreen}), pixel_is(10, 32, kBlue), pixel_is(50, 32, kGreen)}), ""});
    }
}

// Each entry's triangles move right by 0.5 per instance and up by 0.5 per DrawIndex, and darken by 0.2 per
// DrawIndex (entry 0: white, 1: 204, 2: 153 in every colour channel; alpha from the vertex).
constexpr const char* kMultiDrawVertex = R"(#version 450
#extension GL_ARB_shader_draw_parameters : require
layout(location=0) in vec4 in_pos;
layout(location=1) in vec4 in_color;
layout(location=2) in vec2 in_uv;
layout(location=3) in float in_psize;
layout(location=0) out vec4 v_color;
layout(location=1) out vec2 v_uv;
void main() {
  gl_Position = in_pos + vec4(float(gl_InstanceIndex) * 0.5, float(gl_DrawIDARB) * -0.5, 0.0, 0.0) * in_pos.w;
  v_color = vec4(in_color.rgb * (1.0 - 0.2 * float(gl_DrawIDARB)), in_color.a);
  v_uv = in_uv;
}
)";

// A right triangle with legs `size` and corner (x, y) (NDC, y down), white with alpha `a`.
void add_corner(Draw& d, float x, float y, float size, float a) {
    const std::array<float, 4> c = {1, 1, 1, a};
    d.vertices.push_back(vtx(x, y, 0, 1, c));
    d.vertices.push_back(vtx(x + size, y, 0, 1, c));
    d.vertices.push_back(vtx(x, y + size, 0, 1, c));
}

// Three entries of one triangle each (vertices 0-2, 3-5, 6-8 at the same corner), drawn `instances` times.
// Opaque: entry i lands 0.5 above entry i-1, so each pixel has one writer (checked at the triangles' corners).
// Blended (alpha 0.5 over a grey clear, legs 1.0): instance 1 of entry 0 overlaps instance 0 of entry 1, so the
// order of lavapipe's instance loop (outside the entry loop, draw_pt.c) decides the bytes.
Draw multi_draw(uint32_t instances, bool blended, bool indexed, std::optional<int32_t> vertex_offset) {
    Draw d;
    d.vertex_glsl = kMultiDrawVertex;
    d.instances = instances;
    const float step = blended ? 0.25f : 0.0f;  // blended entries overlap partly
    for (int e = 0; e < 3; ++e)
        add_corner(d, -0.9f, 0.3f + step * float(e), blended ? 1.0f : 0.4f, blended ? 0.5f : 1.0f);
    if (blended) d.blend = alpha_over();
    if (!indexed) {
        d.multi = {{0, 3, 0}, {3, 3, 0}, {6, 3, 0}};
        return d;
    }
    // Indexed: indices 0-2 with each entry's vertexOffset selecting its triangle (3 and 6); with pVertexOffset
    // every entry reads vertices 3-5.
    d.indices = {0, 1, 2, 0, 1, 2};
    d.multi = {{0, 3, 0}, {3, 3, 3}, {0, 3, 6}};
    d.multi_vertex_offset = vertex_offset;
    return d;
}

Scene multi_draw_scene(Draw d) {
    Scene s;
    s.target.clear_color[0] = s.target.clear_color[1] = s.target.clear_color[2] = 0.25f;
    s.target.clear_color[3] = 1.0f;
    s.draws.push_back(std::move(d));
    return s;
}

void add_multi_draw_cases(CaseList& out) {
    // Opaque, one instance: entry i's triangle at y = 0.3 - 0.5 i (pixels (x, y) of a 64x64 target: NDC
    // -0.9 + 0.1 -> pixel 6, y 0.3 + 0.1 - 0.5 i -> 44.8 - 16 i).
    const uint32_t kGrey = 0xFF404040u, kWhite = 0xFFFFFFFFu, k204 = 0xFFCCCCCCu, k153 = 0xFF999999u;
    out.push_back({"draw.multi_draw.basic", [] { return multi_draw_scene(multi_draw(1, false, false, {})); },
                   all_of({palette_only({kGrey, kWhite, k204, k153}), pixel_is(6, 44, kWhite), pixel_is(6, 28, k204),
                           pixel_is(6, 12, k153), pixel_is(40, 44, kGrey)}),
                   ""});
    // Instance 1 lies 0.5 to the right (16 pixels).
    out.push_back({"draw.multi_draw.instanced", [] { return multi_draw_scene(multi_draw(2, false, false, {})); },
                   all_of({palette_only({kGrey, kWhite, k204, k153}), pixel_is(22, 44, kWhite), pixel_is(22, 28, k204),
                           pixel_is(22, 12, k153)}),
                   ""});
    out.push_back({"draw.multi_draw.instanced_blended", [] { return multi_draw_scene(multi_draw(3, true, false, {})); },
                   nullptr, ""});
    out.push_back({"draw.multi_draw.indexed", [] { return multi_draw_scene(multi_draw(2, false, true, {})); },
                   all_of({palette_only({kGrey, kWhite, k204, k153}), pixel_is(22, 44, kWhite), pixel_is(22, 28, k204),
                           pixel_is(22, 12, k153)}),
                   ""});
    out.push_back({"draw.multi_draw.indexed_blended", [] { return multi_draw_scene(multi_draw(3, true, true, {})); },
                   nullptr, ""});
    out.push_back({"draw.multi_draw.indexed_vertex_offset",
                   [] { return multi_draw_scene(multi_draw(2, true, true, 3)); }, nullptr, ""});
}

// Blue everywhere, then under a predicate (inverted or not): a vkCmdClearAttachments of pixels 8-23 to green (with
// `clear`) and a red triangle over the corner from NDC (0.5, 0.5) (pixels 48-63). The clear and the draw run when
// the 32-bit predicate is non-zero (zero when inverted) and are skipped otherwise (the spec's "Conditional
// Rendering"); the predicate values have bits only outside the low byte, so a reader of fewer bits sees zero.
Scene conditional_scene(uint32_t predicate, bool inverted, bool clear) {
    Scene s = one_draw(full_screen({0, 0, 1, 1}, 0));
    Draw d;
    d.vertices = {vtxc(0.5f, 0.5f, {1, 0, 0, 1}), vtxc(1.5f, 0.5f, {1, 0, 0, 1}), vtxc(0.5f, 1.5f, {1, 0, 0, 1})};
    d.condition = predicate;
    d.condition_inverted = inverted;
    if (clear) {
        d.clear_rect = VkRect2D{{8, 8}, {16, 16}};
        d.clear_rect_color = {0, 1, 0, 1};
    }
    s.draws.push_back(std::move(d));
    return s;
}

void add_conditional_rendering_cases(CaseList& out) {
    constexpr uint32_t kRed = 0xFF0000FFu;
    struct Row {
        const char* name;
        uint32_t predicate;
        bool inverted, clear, runs;
    };
    static const Row kRows[] = {
        {"zero_skips", 0, false, false, false},
        {"nonzero_draws", 0x100, false, false, true},
        {"inverted_zero_draws", 0, true, false, true},
        {"inverted_nonzero_skips", 0x80000000u, true, false, false},
        {"clear_attachments_zero_skips", 0, false, true, false},
        {"clear_attachments_nonzero_clears", 0x10000, false, true, true},
        {"clear_attachments_inverted_zero_clears", 0, true, true, true},
    };
    for (const Row& r : kRows) {
        const uint32_t clear_pixel = r.clear && r.runs ? kGreen : kBlue, corner = r.runs ? kRed : kBlue;
        out.push_back({std::string("draw.conditional_rendering.") + r.name,
                       [r] { return conditional_scene(r.predicate, r.inverted, r.clear); },
                       all_of({palette_only({kBlue, kGreen, kRed}), pixel_is(12, 12, clear_pixel),
                               pixel_is(23, 23, clear_pixel), pixel_is(60, 60, corner), pixel_is(52, 52, corner),
                               pixel_is(30, 30, kBlue), pixel_is(5, 60, kBlue)}),
                       ""});
    }
}

}  // namespace

void add_pipeline_ext_cases(CaseList& out) {
    add_color_write_cases(out);
    add_multi_draw_cases(out);
    add_conditional_rendering_cases(out);
}

}  // namespace tilevk::cts
