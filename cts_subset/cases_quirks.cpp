// quirks.*: lavapipe behaviours that no Vulkan rule asks for but real applications run into — a zero sample
// mask, llvmpipe's 9-vertex triangle-list analysis, draw's vertex batches (which decide the clipper/float-cull
// path), and draw's pipeline stages for polygonMode LINE/POINT (clipper edge flags, offset, flatshade, point size).
// GLSL normalize() as lavapipe's SPIR-V front end writes it (a division by the length).
// Judged byte for byte against lavapipe; where an outcome is analytic (nothing drawn) it is also checked.
#include "case.hpp"

namespace tilevk::cts {
namespace {

const std::array<float, 4> kRed = {1, 0, 0, 1}, kGreen = {0, 1, 0, 1}, kBlue = {0, 0, 1, 1}, kWhite = {1, 1, 1, 1};

// Every colour pixel is the clear colour (transparent black).
Check nothing_drawn() {
    return palette_only({rgba8(0, 0, 0, 0)});
}

Draw triangle(std::array<float, 4> c = kWhite) {
    Draw d;
    d.vertices = {vtx(-0.8f, -0.7f, 0.5f, 1, kRed), vtx(0.9f, -0.5f, 0.5f, 1, kGreen), vtx(-0.2f, 0.8f, 0.5f, 1, c)};
    return d;
}

// The window-space sliver of tests/rast/geometry FloatCullOnlyOnDrawsPipelinePath on a 64x64 target: float
// det and snapped fixed-point area give it opposite orientations, so draw's float cull and llvmpipe's integer
// cull disagree about it.
void push_sliver(std::vector<Vertex>& v) {
    auto ndc = [](float wx) { return wx / 32.0f - 1.0f; };
    v.push_back(vtx(ndc(10.5f), ndc(10.5f), 0.5f, 1, kRed));
    v.push_back(vtx(ndc(30.5f), ndc(10.5017f), 0.5f, 1, kGreen));
    v.push_back(vtx(ndc(50.5f), ndc(10.503f), 0.5f, 1, kBlue));
}

// A triangle with one vertex left of the viewport (its batch takes draw's pipeline path).
void push_clipped(std::vector<Vertex>& v) {
    v.push_back(vtx(-1.5f, 0.5f, 0.5f, 1, kWhite));
    v.push_back(vtx(-0.5f, 0.9f, 0.5f, 1, kWhite));
    v.push_back(vtx(-0.6f, 0.6f, 0.5f, 1, kWhite));
}

// Zero-area filler triangles (all three vertices equal): dropped on every path, they only move batch boundaries.
void push_filler(std::vector<Vertex>& v, uint32_t triangles) {
    for (uint32_t i = 0; i < 3 * triangles; ++i) v.push_back(vtx(0.25f, 0.25f, 0.5f, 1, kWhite));
}

// The 9 vertices of the swallowed list (tests/rast/geometry NineVertexTriangleListQuirk): the third triangle's
// window y values are equal.
void push_nine(std::vector<Vertex>& v, float last_y = 0.5f) {
    const float p[9][2] = {{-0.9f, -0.9f}, {0.5f, -0.8f}, {-0.7f, 0.6f}, {0.1f, 0.1f},  {0.9f, 0.2f},
                           {0.3f, 0.9f},   {-0.5f, 0.5f}, {0.0f, 0.5f},  {0.5f, last_y}};
    const std::array<float, 4> c[3] = {kRed, kGreen, kBlue};
    for (int i = 0; i < 9; ++i) v.push_back(vtx(p[i][0], p[i][1], 0.5f, 1, c[i % 3]));
}

void add_sample_mask_cases(CaseList& out) {
    // lp_state_derived.c: sample_mask == 0 sets rasterizer_discard, at any sample count.
    out.push_back({"quirks.sample_mask.zero_1x",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0;
                       return one_draw(d);
                   },
                   nothing_drawn(), ""});
    out.push_back({"quirks.sample_mask.zero_1x_depth",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0;
                       d.depth_test = d.depth_write = true;
                       d.depth_op = VK_COMPARE_OP_ALWAYS;
                       Scene s = one_draw(d);
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   nothing_drawn(), ""});
    out.push_back({"quirks.sample_mask.zero_4x",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0;
                       Scene s = one_draw(d);
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       return s;
                   },
                   nothing_drawn(), ""});
    // Bits above the sample count: not zero, so no discard; at 1x the mask is not applied at all.
    out.push_back({"quirks.sample_mask.high_bits_1x",
                   [] {
                       Draw d = triangle();
                       d.sample_mask = 0x10;
                       return one_draw(d);
                   },
                   Check(), ""});
}

void add_nine_vertex_cases(CaseList& out) {
    // lp_setup_analysis.c lp_setup_analyse_triangles: a draw_arrays batch of exactly 9 list vertices whose last
    // triangle has equal window y is swallowed (not the "aero" rectangle).
    out.push_back({"quirks.nine_vertex.swallowed",
                   [] {
                       Draw d;
                       push_nine(d.vertices);
                       return one_draw(d);
                   },
                   nothing_drawn(), ""});
    out.push_back({"quirks.nine_vertex.ten_vertices_trimmed",
                   [] {
                       Draw d;
                       push_nine(d.vertices);
                       d.vertices.push_back(vtx(0, 0));
                       return one_draw(d);
                   },
                   nothing_drawn(), ""});
    out.push_back({"quirks.nine_vertex.control_not_flat_y",
                   [] {
                       Draw d;
                       push_nine(d.vertices, 0.6f);
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.nine_vertex.flat_input_draws",
                   [] {
                       Draw d;
                       d.interp = Interp::kFlat;
                       push_nine(d.vertices);
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.nine_vertex.clipped_vertex_draws",
                   [] {
                       Draw d;
                       push_nine(d.vertices);
                       d.vertices[0].pos[0] = -1.5f;
                       return one_draw(d);
                   },
                   Check(), ""});
    // 4095 filler vertices fill draw's first 4096-vertex batch; the 9-vertex tail is a batch of its own.
    out.push_back({"quirks.nine_vertex.tail_batch_of_4104",
                   [] {
                       Draw d;
                       push_filler(d.vertices, 1365);
                       push_nine(d.vertices);
                       return one_draw(d);
                   },
                   nothing_drawn(), ""});
}

void add_batch_cases(CaseList& out) {
    // draw_pt_fetch_shade_pipeline_llvm.c: the clipper and the float cull run per vsplit batch (non-indexed lists:
    // 4095 vertices), not per draw. The sliver alone is integer-culled; sharing a batch with a clipped triangle it
    // is float-culled.
    for (VkCullModeFlags cull : {VK_CULL_MODE_BACK_BIT, VK_CULL_MODE_FRONT_BIT}) {
        const std::string c = cull == VK_CULL_MODE_BACK_BIT ? "back" : "front";
        out.push_back({"quirks.batch.list_sliver_next_batch_cull_" + c,
                       [=] {
                           Draw d;
                           d.cull = cull;
                           push_clipped(d.vertices);
                           push_filler(d.vertices, 1364);  // vertices 3..4094: the rest of batch 0
                           push_sliver(d.vertices);        // batch 1
                           return one_draw(d);
                       },
                       Check(), ""});
        out.push_back({"quirks.batch.list_sliver_same_batch_cull_" + c,
                       [=] {
                           Draw d;
                           d.cull = cull;
                           push_clipped(d.vertices);
                           push_filler(d.vertices, 1363);
                           push_sliver(d.vertices);  // vertices 4092..4094: still batch 0
                           push_filler(d.vertices, 2);
                           return one_draw(d);
                       },
                       Check(), ""});
        // Strips: 4096-vertex segments (4094 triangles, even), the next starting 2 vertices back.
        out.push_back({"quirks.batch.strip_sliver_next_batch_cull_" + c,
                       [=] {
                           Draw d;
                           d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
                           d.cull = cull;
                           // batch 0: a clipped strip start, then degenerate repeats up to vertex 4095
                           push_clipped(d.vertices);
                           while (d.vertices.size() < 4096) d.vertices.push_back(vtx(0.25f, 0.25f, 0.5f));
                           // batch 1 = vertices 4094.. : triangle 4094 (even) is (4094, 4095, 4096)
                           d.vertices.resize(4094);
                           push_sliver(d.vertices);
                           return one_draw(d);
                       },
                       Check(), ""});
    }
}

// polygonMode LINE / POINT: draw's clipper marks the edges it creates along frustum planes as hidden and the
// vertices where a polygon leaves a plane as not drawn (draw_pipe_clip.c); offset, flatshade and the vertex's
// point size apply through draw's stages (draw_pipe_offset.c, draw_pipe_flatshade.c, lp_setup_point.c). In POINT
// mode lavapipe makes no x/y cut (rast/geometry/clip.h ClipConfig::cut_xy).

// A triangle crossing the right and the top edges of a 48x48 viewport inside the 64x64 target.
Draw unfilled_big(VkPolygonMode mode) {
    Draw d;
    d.polygon_mode = mode;
    d.vertices = {vtx(-0.8f, -0.2f, 0.5f, 1, kRed), vtx(1.7f, -0.6f, 0.5f, 1, kGreen),
                  vtx(0.3f, -1.6f, 0.5f, 1, kBlue)};
    d.viewport = VkViewport{8, 8, 48, 48, 0, 1};
    return d;
}

// A triangle whose first vertex is behind the near plane (z = -0.5).
Draw unfilled_near(VkPolygonMode mode) {
    Draw d;
    d.polygon_mode = mode;
    d.vertices = {vtx(-0.8f, -0.8f, -0.5f, 1, kRed), vtx(0.8f, -0.6f, 0.5f, 1, kGreen),
                  vtx(0.1f, 0.9f, 0.9f, 1, kBlue)};
    return d;
}

// The clipper's edge flags: clipped edges hidden, vertices the x/y planes would make not drawn.
void add_unfilled_clip_cases(CaseList& out) {
    out.push_back({"quirks.unfilled.line_clipped_edges_hidden",
                   [] {
                       Draw d = unfilled_big(VK_POLYGON_MODE_LINE);
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.unfilled.wide_line_clipped_edges_hidden",
                   [] {
                       Draw d = unfilled_big(VK_POLYGON_MODE_LINE);
                       d.line_width = 4.0f;
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.unfilled.line_near_plane_edge_hidden",
                   [] {
                       Draw d = unfilled_near(VK_POLYGON_MODE_LINE);
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.unfilled.point_clipped_vertices_size_6",
                   [] {
                       Draw d = unfilled_big(VK_POLYGON_MODE_POINT);
                       for (Vertex& v : d.vertices) v.point_size = 6.0f;
                       return one_draw(d);
                   },
                   Check(), ""});
    // A vertex the clipper makes where the polygon re-enters through the near plane is drawn (with its
    // interpolated size); the x/y planes make no vertex in POINT mode (clip.h ClipConfig::cut_xy).
    out.push_back({"quirks.unfilled.point_near_plane_vertex_drawn",
                   [] {
                       Draw d = unfilled_near(VK_POLYGON_MODE_POINT);
                       for (Vertex& v : d.vertices) v.point_size = 4.0f;
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.unfilled.point_near_plane_vertex_interpolated_size",
                   [] {
                       Draw d = unfilled_near(VK_POLYGON_MODE_POINT);
                       d.vertices[0].point_size = 2.0f;  // the new vertex halfway to v1 gets size 5
                       d.vertices[1].point_size = 8.0f;
                       d.vertices[2].point_size = 4.0f;
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.unfilled.point_right_plane_vertex_hidden",
                   [] {
                       Draw d = unfilled_big(VK_POLYGON_MODE_POINT);
                       d.viewport.reset();
                       d.vertices[2] = vtx(0.3f, 0.8f, 0.5f, 1, kBlue);
                       for (Vertex& v : d.vertices) v.point_size = 6.0f;
                       return one_draw(d);
                   },
                   Check(), ""});
    // In POINT mode a vertex outside the viewport is not cut away at x = w: lavapipe draws the part of its point
    // inside the draw region (the viewport: 6 px here, and 12 px inside a smaller viewport), where the x cut would
    // have left a corner on the edge that draw's edge flags draw (18 px) — lavapipe draws neither that nor nothing.
    // With the vertex also behind z = 0 the near plane cuts, and its coming-in vertex is drawn (18 px). Each fails
    // with x/y cuts and corners on x/y planes hidden (the rule before 2026-12-07).
    struct OutsidePoint {
        const char* name;
        float x, z;
        bool small_viewport;
    };
    for (const OutsidePoint& o : {OutsidePoint{"point_outside_vertex_partly_visible", 1.05f, 0.5f, false},
                                  OutsidePoint{"point_outside_vertex_small_viewport", 1.05f, 0.5f, true},
                                  OutsidePoint{"point_right_and_near_plane_vertex", 1.7f, -0.5f, false}})
        out.push_back({std::string("quirks.unfilled.") + o.name,
                       [=] {
                           Draw d = unfilled_big(VK_POLYGON_MODE_POINT);
                           if (!o.small_viewport) d.viewport.reset();
                           d.vertices[1].pos[0] = o.x;
                           d.vertices[1].pos[2] = o.z;
                           d.vertices[2] = vtx(0.3f, 0.8f, 0.5f, 1, kBlue);
                           for (Vertex& v : d.vertices) v.point_size = 6.0f;
                           return one_draw(d);
                       },
                       Check(), ""});
}

// What draw's stages carry from the triangle to its edges and corners: the vertex's point size, the provoking
// vertex's flat colour, the triangle's facing.
void add_unfilled_attribute_cases(CaseList& out) {
    out.push_back({"quirks.unfilled.point_size_from_shader",
                   [] {
                       Draw d = triangle(kBlue);
                       d.polygon_mode = VK_POLYGON_MODE_POINT;
                       float size = 3.0f;
                       for (Vertex& v : d.vertices) v.point_size = size, size += 2.5f;
                       return one_draw(d);
                   },
                   Check(), ""});
    out.push_back({"quirks.unfilled.line_flat_provoking_colour",
                   [] {
                       Draw d = triangle(kBlue);
                       d.polygon_mode = VK_POLYGON_MODE_LINE;
                       d.interp = Interp::kFlat;
                       d.line_width = 3.0f;
                       return one_draw(d);
                   },
                   palette_only({rgba8(0, 0, 0, 0), rgba8(255, 0, 0, 255)})});
    // gl_FrontFacing of an edge or corner is its triangle's facing (draw_pipe_unfilled.c inject_front_face_info).
    for (VkPolygonMode mode : {VK_POLYGON_MODE_LINE, VK_POLYGON_MODE_POINT}) {
        const std::string m = mode == VK_POLYGON_MODE_LINE ? "line" : "point";
        out.push_back({"quirks.unfilled." + m + "_facing_both_windings",
                       [=] {
                           Lcg rng{31};
                           Draw d;
                           d.polygon_mode = mode;
                           d.frag = Frag::kFacing;
                           d.blend = additive();
                           for (int i = 0; i < 12; ++i) {
                               Vertex v = vtx(rng.range(-1, 1), rng.range(-1, 1));
                               v.point_size = 3.0f;
                               d.vertices.push_back(v);
                           }
                           return one_draw(d);
                       },
                       Check(), ""});
    }
}

// Depth bias: draw's offset stage offsets the triangle's vertices before its edges/corners are emitted.
void add_unfilled_bias_cases(CaseList& out) {
    struct Bias {
        const char* name;
        VkFormat format;
        float constant, slope, clamp;
    };
    const Bias biases[] = {{"d16_constant", VK_FORMAT_D16_UNORM, 200.0f, 0.0f, 0.0f},
                           {"d32_constant_slope", VK_FORMAT_D32_SFLOAT, 3000.0f, 2.0f, 0.0f},
                           {"d32_clamped", VK_FORMAT_D32_SFLOAT, -5000.0f, -4.0f, -0.01f}};
    for (const Bias& b : biases) {
        for (VkPolygonMode mode : {VK_POLYGON_MODE_LINE, VK_POLYGON_MODE_POINT}) {
            const std::string m = mode == VK_POLYGON_MODE_LINE ? "line" : "point";
            out.push_back({"quirks.unfilled." + m + "_depth_bias_" + b.name,
                           [=] {
                               Draw d;
                               d.polygon_mode = mode;
                               d.line_width = 2.0f;
                               d.depth_test = d.depth_write = true;
                               d.depth_op = VK_COMPARE_OP_ALWAYS;
                               d.depth_bias = true;
                               d.bias_constant = b.constant;
                               d.bias_slope = b.slope;
                               d.bias_clamp = b.clamp;
                               d.vertices = {vtx(-0.8f, -0.7f, 0.2f, 1, kRed),  vtx(0.9f, -0.5f, 0.7f, 1, kGreen),
                                             vtx(-0.2f, 0.8f, 0.45f, 1, kBlue), vtx(0.5f, 0.9f, 0.3f, 1, kWhite),
                                             vtx(0.7f, 0.1f, 0.6f, 1, kRed),    vtx(-0.9f, 0.2f, 0.9f, 1, kGreen)};
                               for (Vertex& v : d.vertices) v.point_size = 3.0f;
                               Scene s = one_draw(d);
                               s.target.depth = b.format;
                               return s;
                           },
                           Check(), ""});
        }
    }
    // Line and point topologies never get a bias: llvmpipe's line/point setup has no offset, and draw's offset
    // stage only sees triangles.
    out.push_back({"quirks.unfilled.line_list_depth_bias_ignored",
                   [] {
                       Draw d;
                       d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
                       d.depth_test = d.depth_write = true;
                       d.depth_op = VK_COMPARE_OP_ALWAYS;
                       d.depth_bias = true;
                       d.bias_constant = 3000.0f;
                       d.bias_slope = 2.0f;
                       d.vertices = {vtx(-0.8f, -0.7f, 0.2f, 1, kRed), vtx(0.9f, -0.5f, 0.7f, 1, kGreen),
                                     vtx(-0.2f, 0.8f, 0.45f, 1, kBlue), vtx(0.5f, 0.9f, 0.3f, 1, kWhite)};
                       Scene s = one_draw(d);
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   Check(), ""});
}

// GLSL normalize(): lavapipe's SPIR-V front end divides by the length (v / sqrt(dot(v, v))); v * inversesqrt(...)
// rounds some lanes differently by an ulp (a fifth of this triangle's pixels). The fragment shader scales n by 2^20
// (exact) and keeps the fraction, so one ulp of n is ~16 units of the 8-bit output. Smooth colours give every pixel
// another vector.
Scene normalize_scene(int components) {
    static const char* const kType[] = {"", "", "vec2", "vec3", "vec4"};
    static const char* const kSwizzle[] = {"", "", ".xy", ".xyz", ""};
    static const char* const kPad[] = {"", "", ", 0.0, 1.0", ", 1.0", ""};
    const std::string body = std::string("  ") + kType[components] +
                             " n = normalize((v_color - vec4(0.5, 0.3, 0.6, 0.4))" + kSwizzle[components] +
                             ");\n  o_color = vec4(fract(n * 1048576.0)" + kPad[components] + ");\n";
    Draw d;
    d.fragment_glsl =
        "#version 450\n"
        "layout(location=0) in vec4 v_color;\n"
        "layout(location=1) in vec2 v_uv;\n"
        "layout(location=0) out vec4 o_color;\n"
        "void main() {\n" +
        body + "}\n";
    d.vertices = {vtx(-0.9f, -0.9f, 0.5f, 1, {1.0f, 0.1f, 0.2f, 0.9f}),
                  vtx(0.9f, -0.8f, 0.5f, 1, {0.0f, 0.9f, 0.4f, 0.1f}),
                  vtx(-0.1f, 0.9f, 0.5f, 1, {0.3f, 0.2f, 1.0f, 0.6f})};
    return one_draw(d);
}

void add_normalize_cases(CaseList& out) {
    for (int n : {2, 3, 4})
        out.push_back(
            {"quirks.glsl.normalize_vec" + std::to_string(n), [n] { return normalize_scene(n); }, Check(), ""});
}

}  // namespace

void add_quirk_cases(CaseList& out) {
    add_normalize_cases(out);
    add_sample_mask_cases(out);
    add_nine_vertex_cases(out);
    add_batch_cases(out);
    add_unfilled_clip_cases(out);
    add_unfilled_attribute_cases(out);
    add_unfilled_bias_cases(out);
}

}  // namespace tilevk::cts
