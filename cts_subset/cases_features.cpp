// feature.*: pipeline-level features and extensions beyond Vulkan 1.0's minimum, each compared byte for byte with
// lavapipe: logic ops (every op; UNORM8, sRGB, float and R8 targets, 4x, write masks), alpha to one (with blending,
// with alpha to coverage, at 4x), multiViewport (16 viewports, viewport 0 used), negative viewport heights
// (VK_KHR_maintenance1), 8-bit indices (VK_EXT_index_type_uint8), primitive restart on list topologies
// (VK_EXT_primitive_topology_list_restart), clip-space depth in [-w, w] (VK_EXT_depth_clip_control) and dual-source
// blending (dualSrcBlend).
#include <iterator>

#include "case.hpp"

namespace tilevk::cts {
namespace {

// A gradient background and six overlapping colourful triangles on top (colours with fractional bits, so that
// the logic ops see every bit pattern).
Scene two_layers(const Draw& top_state, VkFormat format = VK_FORMAT_R8G8B8A8_UNORM) {
    Draw bg;
    bg.vertices = {vtx(-1, -1, 0, 1, {0.1f, 0.9f, 0.3f, 0.2f}), vtx(3, -1, 0, 1, {0.8f, 0.2f, 0.6f, 1.0f}),
                   vtx(-1, 3, 0, 1, {0.4f, 0.5f, 1.0f, 0.6f})};
    Draw top = top_state;
    top.vertices = {
        vtx(-0.9f, -0.9f, 0, 1, {1.0f, 0.2f, 0.0f, 0.9f}), vtx(0.9f, -0.6f, 0, 1, {0.0f, 1.0f, 0.4f, 0.1f}),
        vtx(-0.5f, 0.9f, 0, 1, {0.3f, 0.0f, 1.0f, 0.5f}),  vtx(0.9f, 0.9f, 0, 1, {0.7f, 0.7f, 0.2f, 0.3f}),
        vtx(0.2f, -0.9f, 0, 1, {1.0f, 1.0f, 1.0f, 0.0f}),  vtx(-0.9f, 0.4f, 0, 1, {0.5f, 0.1f, 0.9f, 1.0f})};
    Scene s = one_draw(bg);
    s.target.color = format;
    s.draws.push_back(top);
    return s;
}

VkPipelineColorBlendAttachmentState blend_on(VkBlendFactor src, VkBlendFactor dst, uint32_t mask = 0xF) {
    return {VK_TRUE, src, dst, VK_BLEND_OP_ADD, src, dst, VK_BLEND_OP_ADD, mask};
}

// Triangles, lines or points from an index list over a 4x3 grid of vertices, drawn with `index_type`.
Draw grid_draw(VkPrimitiveTopology topo, std::vector<uint32_t> indices, VkIndexType index_type, bool restart) {
    Draw d;
    d.topology = topo;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            d.vertices.push_back(vtx(-0.85f + 0.55f * float(x) + 0.07f * float(y), -0.8f + 0.75f * float(y), 0, 1,
                                     {0.2f + 0.25f * float(x), 0.3f * float(y), 1.0f - 0.2f * float(x), 1}));
    for (Vertex& v : d.vertices) v.point_size = 4.0f;
    d.indices = std::move(indices);
    d.index_type = index_type;
    d.primitive_restart = restart;
    return d;
}

void add_logic_op_cases(CaseList& out) {
    const struct {
        const char* name;
        VkLogicOp op;
    } ops[] = {{"clear", VK_LOGIC_OP_CLEAR},
               {"and", VK_LOGIC_OP_AND},
               {"and_reverse", VK_LOGIC_OP_AND_REVERSE},
               {"copy", VK_LOGIC_OP_COPY},
               {"and_inverted", VK_LOGIC_OP_AND_INVERTED},
               {"no_op", VK_LOGIC_OP_NO_OP},
               {"xor", VK_LOGIC_OP_XOR},
               {"or", VK_LOGIC_OP_OR},
               {"nor", VK_LOGIC_OP_NOR},
               {"equivalent", VK_LOGIC_OP_EQUIVALENT},
               {"invert", VK_LOGIC_OP_INVERT},
               {"or_reverse", VK_LOGIC_OP_OR_REVERSE},
               {"copy_inverted", VK_LOGIC_OP_COPY_INVERTED},
               {"or_inverted", VK_LOGIC_OP_OR_INVERTED},
               {"nand", VK_LOGIC_OP_NAND},
               {"set", VK_LOGIC_OP_SET}};
    for (const auto& o : ops) {
        Draw d;
        d.logic_op = o.op;
        out.push_back({std::string("feature.logic_op.") + o.name, [=] { return two_layers(d); }, nullptr, ""});
    }
    // Blending is ignored while the logic op is on; write masks still apply.
    Draw blended;
    blended.logic_op = VK_LOGIC_OP_XOR;
    blended.blend = blend_on(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, 0x5);
    out.push_back({"feature.logic_op.xor_blend_ignored_mask_5", [=] { return two_layers(blended); }, nullptr, ""});
    // Formats: R8 and BGRA8 (UNORM8: combined), sRGB and float (Vulkan: no logic op; the source is written).
    const struct {
        const char* name;
        VkFormat f;
    } formats[] = {{"r8_unorm", VK_FORMAT_R8_UNORM},
                   {"b8g8r8a8_unorm_depth", VK_FORMAT_B8G8R8A8_UNORM},
                   {"r8g8b8a8_srgb", VK_FORMAT_R8G8B8A8_SRGB},
                   {"r32g32b32a32_sfloat", VK_FORMAT_R32G32B32A32_SFLOAT},
                   {"r16g16b16a16_sfloat", VK_FORMAT_R16G16B16A16_SFLOAT}};
    for (const auto& f : formats) {
        Draw d;
        d.logic_op = VK_LOGIC_OP_OR_REVERSE;
        const bool depth = std::string(f.name).find("depth") != std::string::npos;
        out.push_back({std::string("feature.logic_op.or_reverse.") + f.name,
                       [=] {
                           Scene s = two_layers(d, f.f);
                           if (depth) s.target.depth = VK_FORMAT_D32_SFLOAT;  // off llvmpipe's linear path
                           return s;
                       },
                       nullptr, ""});
    }
    Draw msaa;
    msaa.logic_op = VK_LOGIC_OP_EQUIVALENT;
    out.push_back({"feature.logic_op.equivalent_4x",
                   [=] {
                       Scene s = two_layers(msaa);
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       return s;
                   },
                   nullptr, ""});
    // B8G8R8A8 without depth: a logic op keeps lavapipe off its linear rasterizer (lp_state_fs.c linear_pipeline).
    Draw linear;
    linear.logic_op = VK_LOGIC_OP_NAND;
    out.push_back({"feature.logic_op.nand_bgra_no_depth", [=] { return two_layers(linear, VK_FORMAT_B8G8R8A8_UNORM); },
                   nullptr, "bgra-linear-path"});
}

void add_alpha_to_one_cases(CaseList& out) {
    Draw blended;
    blended.alpha_to_one = true;
    blended.blend = blend_on(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
    out.push_back({"feature.alpha_to_one.blend_src_alpha", [=] { return two_layers(blended); }, nullptr, ""});
    Draw plain;
    plain.alpha_to_one = true;
    out.push_back({"feature.alpha_to_one.float_target",
                   [=] { return two_layers(plain, VK_FORMAT_R32G32B32A32_SFLOAT); }, nullptr, ""});
    // With alpha to coverage: the coverage comes from the shader's alpha, the written alpha is 1.
    for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT}) {
        Draw a2c = blended;
        a2c.alpha_to_coverage = true;
        out.push_back({std::string("feature.alpha_to_one.with_coverage_") + (samples == 1 ? "1x" : "4x"),
                       [=] {
                           Scene s = two_layers(a2c);
                           s.target.samples = samples;
                           return s;
                       },
                       nullptr, ""});
    }
    out.push_back({"feature.alpha_to_one.bgra_no_depth", [=] { return two_layers(plain, VK_FORMAT_B8G8R8A8_UNORM); },
                   nullptr, "bgra-linear-path"});
}

void add_viewport_feature_cases(CaseList& out) {
    // 16 viewports and scissors in the pipeline (all the same); every primitive uses viewport 0.
    Draw many;
    many.viewport_count = 16;
    many.viewport = VkViewport{4, 6, 50, 40, 0, 1};
    many.scissor = VkRect2D{{8, 2}, {40, 50}};
    out.push_back({"feature.multi_viewport.count_16", [=] { return two_layers(many); }, nullptr, ""});
    // maintenance1: negative heights flip the image; partial and offset viewports too.
    const VkViewport flips[] = {{0, 64, 64, -64, 0, 1}, {5, 50.5f, 40, -37.25f, 0.2f, 0.9f}, {-10, 80, 90, -100, 0, 1}};
    const char* names[] = {"full", "partial", "past_edges"};
    for (int i = 0; i < 3; ++i) {
        Draw d;
        d.viewport = flips[i];
        d.depth_test = d.depth_write = true;
        out.push_back({std::string("viewport.negative_height.") + names[i],
                       [=] {
                           Scene s = two_layers(d);
                           s.target.depth = VK_FORMAT_D32_SFLOAT;
                           s.draws[1].vertices[1].pos[2] = 0.7f;
                           return s;
                       },
                       nullptr, ""});
    }
}

void add_index_cases(CaseList& out) {
    // 8-bit indices: a list, a strip with restart (0xFF), and indices near 255 (the vertex count allows them).
    out.push_back({"feature.index_uint8.triangle_list",
                   [] {
                       return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                                                 {0, 1, 4, 5, 4, 1, 6, 7, 10, 11, 10, 7, 2, 3, 6},
                                                 VK_INDEX_TYPE_UINT8_EXT, false));
                   },
                   nullptr, ""});
    out.push_back({"feature.index_uint8.strip_restart",
                   [] {
                       return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP,
                                                 {0, 4, 1, 5, 2, 6, 0xFF, 5, 9, 6, 10, 7, 11}, VK_INDEX_TYPE_UINT8_EXT,
                                                 true));
                   },
                   nullptr, ""});
    out.push_back({"feature.index_uint8.line_strip",
                   [] {
                       return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, {0, 5, 2, 7, 11, 6, 8},
                                                 VK_INDEX_TYPE_UINT8_EXT, false));
                   },
                   nullptr, ""});
    // Restart off: the all-ones index is an ordinary index, far past the vertex buffer (robustBufferAccess: the
    // vertex reads zeros). A strip through it keeps going.
    for (VkIndexType t : {VK_INDEX_TYPE_UINT32, VK_INDEX_TYPE_UINT16}) {
        const uint32_t ones = t == VK_INDEX_TYPE_UINT16 ? 0xFFFF : ~0u;
        const char* tn = t == VK_INDEX_TYPE_UINT16 ? "uint16" : "uint32";
        out.push_back({std::string("feature.index_no_restart.strip_") + tn,
                       [=] {
                           return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP,
                                                     {0, 4, 1, 5, 2, 6, ones, 5, 9, 6, 10, 7, 11}, t, false));
                       },
                       nullptr, ""});
        out.push_back({std::string("feature.index_no_restart.list_") + tn,
                       [=] {
                           return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                                                     {0, 1, 4, 5, ones, 1, 2, 5, 6, 7, 10, 11}, t, false));
                       },
                       nullptr, ""});
        out.push_back(
            {std::string("feature.index_no_restart.line_strip_") + tn,
             [=] {
                 return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, {0, 5, 2, ones, 7, 11, 6, 8}, t, false));
             },
             nullptr, ""});
        out.push_back(
            {std::string("feature.index_no_restart.points_") + tn,
             [=] {
                 return one_draw(grid_draw(VK_PRIMITIVE_TOPOLOGY_POINT_LIST, {0, 5, 2, ones, 7, 11, 6, 8}, t, false));
             },
             nullptr, ""});
    }
    // Restart on list topologies: the list starts again after each restart index; an incomplete primitive before
    // it is dropped.
    const struct {
        const char* name;
        VkPrimitiveTopology topo;
        std::vector<uint32_t> idx;
    } lists[] = {{"triangle_list",
                  VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                  {0, 1, 4, 5, 0xFFFFFFFF, 1, 2, 5, 6, 7, 10, 0xFFFFFFFF, 3, 7, 11, 0xFFFFFFFF, 8}},
                 {"line_list", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, {0, 5, 1, 0xFFFFFFFF, 2, 7, 3, 6, 0xFFFFFFFF, 8, 11}},
                 {"point_list", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, {0, 2, 0xFFFFFFFF, 5, 7, 9, 0xFFFFFFFF, 11}}};
    for (const auto& l : lists) {
        for (VkIndexType t : {VK_INDEX_TYPE_UINT32, VK_INDEX_TYPE_UINT16, VK_INDEX_TYPE_UINT8_EXT}) {
            std::vector<uint32_t> idx = l.idx;
            const uint32_t restart = t == VK_INDEX_TYPE_UINT8_EXT ? 0xFF : t == VK_INDEX_TYPE_UINT16 ? 0xFFFF : ~0u;
            for (uint32_t& i : idx)
                if (i == 0xFFFFFFFF) i = restart;
            const char* tn = t == VK_INDEX_TYPE_UINT8_EXT ? "uint8" : t == VK_INDEX_TYPE_UINT16 ? "uint16" : "uint32";
            const VkPrimitiveTopology topo = l.topo;
            out.push_back({std::string("feature.list_restart.") + l.name + "." + tn,
                           [=] { return one_draw(grid_draw(topo, idx, t, true)); }, nullptr, ""});
        }
    }
}

void add_depth_clip_control_cases(CaseList& out) {
    // Clip-space z in [-w, w]: triangles crossing z = -w and z = w are clipped there (not at 0), the depth buffer
    // gets (z/w + 1)/2 scaled into the viewport's range.
    const struct {
        const char* name;
        float min_depth, max_depth;
        bool clamp;
    } ranges[] = {{"full_range", 0, 1, false},
                  {"partial_range", 0.25f, 0.75f, false},
                  {"reversed_range", 1, 0, false},
                  {"clamped", 0.1f, 0.9f, true}};
    for (const auto& r : ranges) {
        out.push_back({std::string("feature.depth_clip_control.") + r.name,
                       [=] {
                           Draw d;
                           d.negative_one_to_one = true;
                           d.depth_test = d.depth_write = true;
                           d.depth_op = VK_COMPARE_OP_LESS_OR_EQUAL;
                           d.depth_clamp = r.clamp;
                           d.viewport = VkViewport{0, 0, 64, 64, r.min_depth, r.max_depth};
                           Lcg rng{uint32_t(r.min_depth * 1000 + r.max_depth * 10 + (r.clamp ? 7 : 3))};
                           for (int i = 0; i < 24; ++i) {
                               const float w = rng.range(0.5f, 2.0f);
                               d.vertices.push_back(vtx(rng.range(-1.1f, 1.1f), rng.range(-1.1f, 1.1f),
                                                        rng.range(-1.6f, 1.6f), w,
                                                        {rng.next(), rng.next(), rng.next(), 1}));
                           }
                           Scene s = one_draw(d);
                           s.target.depth = VK_FORMAT_D32_SFLOAT;
                           s.target.clear_depth = 1.0f;
                           return s;
                       },
                       nullptr, ""});
    }
    // Vulkan's [0, w] with depth clamp on a partial range: llvmpipe clamps to translate and fl(translate + scale)
    // (util_viewport_zmin_zmax), an ulp below maxDepth for [0.04, 0.2], not to the viewport's values.
    out.push_back({"depth.clamp.partial_range_ulp",
                   [] {
                       Draw d;
                       d.depth_test = d.depth_write = true;
                       d.depth_op = VK_COMPARE_OP_ALWAYS;
                       d.depth_clamp = true;
                       d.viewport = VkViewport{0, 0, 64, 64, 0.04f, 0.2f};
                       d.vertices = {vtx(-1, -1, 1.5f), vtx(3, -1, 1.5f), vtx(-1, 3, -0.5f)};
                       Scene s = one_draw(d);
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"feature.depth_clip_control.lines_points_d16",
                   [] {
                       Draw lines;
                       lines.negative_one_to_one = true;
                       lines.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
                       lines.line_width = 3.0f;
                       lines.depth_test = lines.depth_write = true;
                       Lcg rng{4242};
                       for (int i = 0; i < 20; ++i)
                           lines.vertices.push_back(vtx(rng.range(-1, 1), rng.range(-1, 1), rng.range(-1.4f, 1.4f), 1,
                                                        {rng.next(), rng.next(), rng.next(), 1}));
                       Draw points = lines;
                       points.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
                       for (Vertex& v : points.vertices) v.point_size = 6.0f;
                       Scene s = one_draw(lines);
                       s.draws.push_back(points);
                       s.target.depth = VK_FORMAT_D16_UNORM;
                       return s;
                   },
                   nullptr, ""});
}

// The top layer's shader writes a second colour (Location 0, Index 1) that differs from the first in every channel.
Draw dual_source_draw(VkPipelineColorBlendAttachmentState blend) {
    Draw d;
    d.blend = blend;
    const float constants[4] = {0.25f, 0.5f, 0.75f, 0.6f};
    std::copy(constants, constants + 4, d.blend_constants);
    d.fragment_glsl =
        "#version 450\n"
        "layout(location=0) in vec4 v_color;\n"
        "layout(location=1) in vec2 v_uv;\n"
        "layout(location=0, index=0) out vec4 o_color;\n"
        "layout(location=0, index=1) out vec4 o_second;\n"
        "void main() {\n"
        "  o_color = v_color;\n"
        "  o_second = vec4(v_color.gbr * 0.8 + vec3(0.1, 0.3, 0.05), 1.0 - v_color.a * 0.7);\n"
        "}\n";
    return d;
}

// dualSrcBlend: each SRC1 factor as source and as destination, the complementary pairs lavapipe turns into a lerp,
// separate alpha, alpha to one, on UNORM8 (RGBA, BGRA, R8, 565 without alpha), 16-bit UNORM, 10-bit, sRGB, half and
// float targets and at 4x.
void add_dual_source_cases(CaseList& out) {
    struct Pair {
        const char* name;
        VkBlendFactor src, dst;
    };
    const Pair pairs[] = {
        {"one_src1_color", VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_SRC1_COLOR},
        {"src1_color_one_minus_src1_color", VK_BLEND_FACTOR_SRC1_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR},
        {"src1_alpha_one_minus_src1_alpha", VK_BLEND_FACTOR_SRC1_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA},
        {"one_minus_src1_alpha_src1_alpha", VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA, VK_BLEND_FACTOR_SRC1_ALPHA},
        {"one_minus_src1_color_dst_color", VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR, VK_BLEND_FACTOR_DST_COLOR}};
    for (const Pair& p : pairs) {
        const Draw d = dual_source_draw(blend_on(p.src, p.dst));
        out.push_back({std::string("feature.dual_src_blend.") + p.name, [=] { return two_layers(d); }, nullptr, ""});
    }
    VkPipelineColorBlendAttachmentState sep = {VK_TRUE,
                                               VK_BLEND_FACTOR_SRC1_COLOR,
                                               VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                                               VK_BLEND_OP_SUBTRACT,
                                               VK_BLEND_FACTOR_ONE,
                                               VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA,
                                               VK_BLEND_OP_REVERSE_SUBTRACT,
                                               0xF};
    const Draw separate = dual_source_draw(sep);
    out.push_back({"feature.dual_src_blend.separate_alpha", [=] { return two_layers(separate); }, nullptr, ""});
    Draw to_one = dual_source_draw(blend_on(VK_BLEND_FACTOR_SRC1_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR));
    to_one.alpha_to_one = true;
    out.push_back({"feature.dual_src_blend.alpha_to_one", [=] { return two_layers(to_one); }, nullptr, ""});
    const Draw masked =
        dual_source_draw(blend_on(VK_BLEND_FACTOR_SRC1_COLOR, VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA, 0xB));
    out.push_back({"feature.dual_src_blend.write_mask_b", [=] { return two_layers(masked); }, nullptr, ""});
    const struct {
        const char* name;
        VkFormat f;
    } formats[] = {{"b8g8r8a8_unorm", VK_FORMAT_B8G8R8A8_UNORM},
                   {"r8_unorm", VK_FORMAT_R8_UNORM},
                   {"r5g6b5_unorm", VK_FORMAT_R5G6B5_UNORM_PACK16},
                   {"r16g16b16a16_unorm", VK_FORMAT_R16G16B16A16_UNORM},
                   {"a2b10g10r10_unorm", VK_FORMAT_A2B10G10R10_UNORM_PACK32},
                   {"r8g8b8a8_srgb", VK_FORMAT_R8G8B8A8_SRGB},
                   {"r16g16b16a16_sfloat", VK_FORMAT_R16G16B16A16_SFLOAT},
                   {"r32g32b32a32_sfloat", VK_FORMAT_R32G32B32A32_SFLOAT},
                   {"r32_sfloat", VK_FORMAT_R32_SFLOAT}};
    for (const auto& f : formats)
        for (const Pair& p : {pairs[0], pairs[1], pairs[4]}) {
            const Draw d = dual_source_draw(blend_on(p.src, p.dst));
            out.push_back({std::string("feature.dual_src_blend.") + f.name + "." + p.name,
                           [=] { return two_layers(d, f.f); }, nullptr, ""});
        }
    const Draw msaa = dual_source_draw(blend_on(VK_BLEND_FACTOR_SRC1_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA));
    out.push_back({"feature.dual_src_blend.4x",
                   [=] {
                       Scene s = two_layers(msaa);
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       return s;
                   },
                   nullptr, ""});
}

}  // namespace

void add_feature_cases(CaseList& out) {
    add_logic_op_cases(out);
    add_dual_source_cases(out);
    add_alpha_to_one_cases(out);
    add_viewport_feature_cases(out);
    add_index_cases(out);
    add_depth_clip_control_cases(out);
}

}  // namespace tilevk::cts
