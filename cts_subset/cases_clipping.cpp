// clipping.clip_distance.*, clipping.cull_distance.*: ClipDistance and CullDistance written by the vertex shader
// (features shaderClipDistance, shaderCullDistance), judged byte for byte against lavapipe, whose draw module clips
// against the user planes after the frustum planes (draw_pipe_clip.c) and culls by cull distance before that
// (draw_pipe_user_cull.c). Element k of the combined array (clip distances first) is the plane push constant p[k]
// dotted with the clip position, written out as multiplies and adds; `from_attributes` takes elements 0-2 from
// in_uv.x, in_uv.y and in_psize instead (NaN, infinite and signed-zero distances).
#include <cmath>
#include <limits>
#include <string>

#include "case.hpp"
#include "vk_context.hpp"

namespace tilevk::cts {
namespace {

struct Distances {
    int clip = 0;
    int cull = 0;
    bool from_attributes = false;
};

const char* qualifier(Interp i) {
    return i == Interp::kFlat ? "flat " : i == Interp::kNoPerspective ? "noperspective " : "";
}

std::string distance_vs(const Distances& n, Interp interp, bool point_size) {
    const std::string q = qualifier(interp);
    std::string s =
        "#version 450\n"
        "layout(location=0) in vec4 in_pos;\n"
        "layout(location=1) in vec4 in_color;\n"
        "layout(location=2) in vec2 in_uv;\n"
        "layout(location=3) in float in_psize;\n"
        "layout(location=0) " +
        q + "out vec4 v_color;\nlayout(location=1) " + q +
        "out vec2 v_uv;\n"
        "layout(push_constant) uniform P { vec4 p[8]; } pc;\n";
    if (n.clip > 0) s += "out float gl_ClipDistance[" + std::to_string(n.clip) + "];\n";
    if (n.cull > 0) s += "out float gl_CullDistance[" + std::to_string(n.cull) + "];\n";
    s += "void main() {\n  gl_Position = in_pos;\n  v_color = in_color;\n  v_uv = in_uv;\n";
    if (point_size) s += "  gl_PointSize = 4.0;\n";
    const char* attr[3] = {"in_uv.x", "in_uv.y", "in_psize"};
    for (int k = 0; k < n.clip + n.cull; ++k) {
        const std::string dst = k < n.clip ? "gl_ClipDistance[" + std::to_string(k) + "]"
                                           : "gl_CullDistance[" + std::to_string(k - n.clip) + "]";
        const std::string p = "pc.p[" + std::to_string(k) + "]";
        if (n.from_attributes && k < 3)
            s += "  " + dst + " = " + attr[k] + ";\n";
        else
            s += "  " + dst + " = " + p + ".x * in_pos.x + " + p + ".y * in_pos.y + " + p + ".z * in_pos.z + " + p +
                 ".w * in_pos.w;\n";
    }
    return s + "}\n";
}

std::string needs(const DeviceContext& c, const Distances& n) {
    if (n.clip > 0 && !c.features.shaderClipDistance) return "feature shaderClipDistance";
    if (n.cull > 0 && !c.features.shaderCullDistance) return "feature shaderCullDistance";
    if (uint32_t(n.clip + n.cull) > c.props.limits.maxCombinedClipAndCullDistances)
        return "maxCombinedClipAndCullDistances " + std::to_string(c.props.limits.maxCombinedClipAndCullDistances);
    return {};
}

Scene distance_scene(Draw d, const Distances& n, uint32_t size = 64) {
    const bool points = d.topology == VK_PRIMITIVE_TOPOLOGY_POINT_LIST || d.polygon_mode == VK_POLYGON_MODE_POINT;
    d.vertex_glsl = distance_vs(n, d.interp, points);
    d.push_constants.resize(32, 0.0f);
    Scene s = one_draw(std::move(d), size, size);
    s.unsupported = [n](const DeviceContext& c) { return needs(c, n); };
    return s;
}

void set_plane(Draw& d, int k, float a, float b, float c, float w) {
    d.push_constants.resize(32, 0.0f);
    const size_t at = 4 * size_t(k);
    d.push_constants[at] = a;
    d.push_constants[at + 1] = b;
    d.push_constants[at + 2] = c;
    d.push_constants[at + 3] = w;
}

// Two triangles covering the target, one colour per corner.
Draw full_quad() {
    Draw d;
    const Vertex a = vtxc(-1, -1, {1, 0, 0, 1}), b = vtxc(1, -1, {0, 1, 0, 1}), c = vtxc(1, 1, {0, 0, 1, 1}),
                 e = vtxc(-1, 1, {1, 1, 0, 1});
    d.vertices = {a, b, c, a, c, e};
    return d;
}

// Random primitives over and past the viewport (some vertices outside the frustum too), random w, z and colours,
// and `planes` random user planes through the middle of the target.
Draw random_draw(uint32_t seed, VkPrimitiveTopology topo, uint32_t vertices, int planes) {
    Lcg r{seed};
    Draw d;
    d.topology = topo;
    for (uint32_t i = 0; i < vertices; ++i) {
        Vertex v = vtx(r.range(-1.3f, 1.3f), r.range(-1.3f, 1.3f), r.range(-0.1f, 1.0f), r.range(0.5f, 2.0f),
                       {r.next(), r.next(), r.next(), 1.0f});
        v.uv[0] = r.range(-1, 1);
        v.uv[1] = r.range(-1, 1);
        d.vertices.push_back(v);
    }
    for (int k = 0; k < planes; ++k)
        set_plane(d, k, r.range(-1, 1), r.range(-1, 1), r.range(-0.5f, 0.5f), r.range(-0.2f, 0.6f));
    return d;
}

Scene random_scene(uint32_t seed, VkPrimitiveTopology topo, uint32_t vertices, Distances n) {
    Draw d = random_draw(seed, topo, vertices, n.clip + n.cull);
    return distance_scene(std::move(d), n);
}

void add_clip_distance_cases(CaseList& out) {
    // x >= 0 in clip space cuts the target at window x = 32: pixel 31's centre is outside, pixel 32's inside.
    out.push_back({"clipping.clip_distance.half_plane",
                   [] {
                       Draw d = full_quad();
                       for (Vertex& v : d.vertices) std::fill(std::begin(v.color), std::end(v.color), 1.0f);
                       set_plane(d, 0, 1, 0, 0, 0);
                       return distance_scene(std::move(d), {1, 0});
                   },
                   all_of({pixel_is(31, 10, 0), pixel_is(32, 10, ~0u), pixel_is(0, 60, 0), pixel_is(63, 60, ~0u)}),
                   ""});
    // Eight planes 0.8 - (cos t, sin t) . (x, y): an octagon around the centre, the corners outside.
    out.push_back({"clipping.clip_distance.octagon",
                   [] {
                       Draw d = full_quad();
                       for (int k = 0; k < 8; ++k) {
                           const float t = float(k) * 0.785398163f;
                           set_plane(d, k, -std::cos(t), -std::sin(t), 0, 0.8f);
                       }
                       return distance_scene(std::move(d), {8, 0});
                   },
                   all_of({pixel_is(0, 0, 0), pixel_is(63, 0, 0), pixel_is(0, 63, 0), pixel_is(63, 63, 0)}), ""});
    struct Row {
        const char* name;
        VkPrimitiveTopology topo;
        uint32_t vertices;
        int clip;
        uint32_t seed;
    };
    const Row rows[] = {
        {"random_tri_1", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 1, 11},
        {"random_tri_2", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 2, 12},
        {"random_tri_4", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 4, 13},
        {"random_tri_8", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 8, 14},
        {"random_strip_3", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 14, 3, 15},
        {"random_fan_5", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, 12, 5, 16},
        {"random_lines_2", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 24, 2, 17},
        {"random_line_strip_6", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 16, 6, 18},
        {"random_points_3", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 48, 3, 19},
    };
    for (const Row& row : rows)
        out.push_back({std::string("clipping.clip_distance.") + row.name,
                       [row] {
                           return random_scene(row.seed, row.topo, row.vertices, {row.clip, 0});
                       },
                       nullptr, ""});
    out.push_back({"clipping.clip_distance.wide_lines",
                   [] {
                       Draw d = random_draw(21, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 16, 2);
                       d.line_width = 3.0f;
                       return distance_scene(std::move(d), {2, 0});
                   },
                   nullptr, ""});
    out.push_back({"clipping.clip_distance.flat",
                   [] {
                       Draw d = random_draw(22, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 3);
                       d.interp = Interp::kFlat;
                       return distance_scene(std::move(d), {3, 0});
                   },
                   nullptr, ""});
    out.push_back({"clipping.clip_distance.noperspective",
                   [] {
                       Draw d = random_draw(23, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 3);
                       d.interp = Interp::kNoPerspective;
                       return distance_scene(std::move(d), {3, 0});
                   },
                   nullptr, ""});
    out.push_back({"clipping.clip_distance.depth_tested",
                   [] {
                       Scene s = random_scene(24, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {2, 0});
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       s.draws[0].depth_test = s.draws[0].depth_write = true;
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"clipping.clip_distance.cull_back",
                   [] {
                       Scene s = random_scene(25, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {2, 0});
                       s.draws[0].cull = VK_CULL_MODE_BACK_BIT;
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"clipping.clip_distance.msaa4",
                   [] {
                       Scene s = random_scene(26, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, {3, 0});
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       return s;
                   },
                   nullptr, ""});
    // polygonMode LINE / POINT: edges along a user plane are drawn (unlike the frustum planes'), and so are the
    // vertices a user plane creates; in POINT mode the x/y planes cut nothing (rast/geometry/clip.h cut_xy). Seed 41
    // has a user-plane point on the top edge that the earlier rule (x/y cuts, their corners hidden) did not draw.
    for (VkPolygonMode mode : {VK_POLYGON_MODE_LINE, VK_POLYGON_MODE_POINT})
        for (uint32_t seed : {27u, 41u, 42u}) {
            const std::string name = std::string("clipping.clip_distance.polygon_") +
                                     (mode == VK_POLYGON_MODE_LINE ? "line" : "point") +
                                     (seed == 27u ? "" : "_" + std::to_string(seed));
            out.push_back({name,
                           [mode, seed] {
                               Draw d = random_draw(seed, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 18, seed == 42u ? 4 : 2);
                               d.polygon_mode = mode;
                               return distance_scene(std::move(d), {seed == 42u ? 4 : 2, 0});
                           },
                           nullptr, ""});
        }
    // llvmpipe swallows a 9-vertex list batch whose third triangle has equal window y when the batch skipped draw's
    // pipeline (lavapipe-rules §8). glslang declares an unwritten gl_CullDistance[1] next to gl_ClipDistance; a cull
    // distance would send every batch down the pipeline, but lavapipe ignores the unwritten one: nothing is drawn.
    out.push_back({"clipping.clip_distance.nine_vertex_batch",
                   [] {
                       Draw d;
                       const float p[9][2] = {{-0.9f, -0.9f}, {0.5f, -0.8f}, {-0.7f, 0.6f}, {0.1f, 0.1f}, {0.9f, 0.2f},
                                              {0.3f, 0.9f},   {-0.5f, 0.5f}, {0.0f, 0.5f},  {0.5f, 0.5f}};
                       for (const auto& q : p) d.vertices.push_back(vtx(q[0], q[1], 0.5f, 1, {1, 0.5f, 0, 1}));
                       set_plane(d, 0, 0, 0, 0, 1);
                       return distance_scene(std::move(d), {1, 0});
                   },
                   nullptr, ""});
    // Distances straight from attributes: NaN and infinite distances drop the primitive (draw_pipe_clip.c discards
    // a non-finite plane distance); -0 is inside.
    out.push_back({"clipping.clip_distance.non_finite",
                   [] {
                       Draw d = random_draw(28, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 0);
                       const float special[] = {std::numeric_limits<float>::quiet_NaN(),
                                                std::numeric_limits<float>::infinity(),
                                                -std::numeric_limits<float>::infinity(),
                                                -0.0f,
                                                0.0f,
                                                0.25f};
                       for (size_t i = 0; i < d.vertices.size(); ++i) {
                           d.vertices[i].uv[0] = (i % 5 == 0) ? special[(i / 5) % 6] : std::fabs(d.vertices[i].uv[0]);
                           d.vertices[i].point_size = (i % 7 == 3) ? special[i % 6] : 0.5f;
                       }
                       return distance_scene(std::move(d), {3, 0, true});
                   },
                   nullptr, ""});
}

void add_cull_distance_cases(CaseList& out) {
    // Cull distance x: the quad's two triangles both have a vertex at x = 1, so neither is culled; the small
    // triangles left of x = 0 are.
    out.push_back(
        {"clipping.cull_distance.half_plane",
         [] {
             Draw d;
             d.vertices = {vtx(-0.9f, -0.9f), vtx(-0.1f, -0.9f), vtx(-0.5f, 0.9f), vtx(0.1f, -0.9f), vtx(0.9f, -0.9f),
                           vtx(0.5f, 0.9f),   vtx(-0.8f, 0.2f),  vtx(0.8f, 0.2f),  vtx(0.0f, 0.95f)};
             set_plane(d, 0, 1, 0, 0, 0);
             return distance_scene(std::move(d), {0, 1});
         },
         all_of({pixel_is(16, 50, 0), pixel_is(16, 20, 0), pixel_is(48, 50, ~0u), pixel_is(32, 45, ~0u)}), ""});
    struct Row {
        const char* name;
        VkPrimitiveTopology topo;
        uint32_t vertices;
        Distances n;
        uint32_t seed;
    };
    const Row rows[] = {
        {"random_tri_1", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {0, 1}, 31},
        {"random_tri_4", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {0, 4}, 32},
        {"random_strip_2", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 16, {0, 2}, 33},
        {"random_lines_2", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 24, {0, 2}, 34},
        {"random_points_2", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 48, {0, 2}, 35},
        {"with_clip_2_2", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {2, 2}, 36},
        {"with_clip_5_3", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {5, 3}, 37},
        {"with_clip_lines_1_3", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 16, {1, 3}, 38},
    };
    for (const Row& row : rows)
        out.push_back({std::string("clipping.cull_distance.") + row.name,
                       [row] { return random_scene(row.seed, row.topo, row.vertices, row.n); }, nullptr, ""});
    // Every batch with a CullDistance takes draw's pipeline, so its float cull of the winding applies.
    out.push_back({"clipping.cull_distance.cull_back",
                   [] {
                       Scene s = random_scene(39, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 30, {0, 2});
                       s.draws[0].cull = VK_CULL_MODE_BACK_BIT;
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"clipping.cull_distance.non_finite",
                   [] {
                       Draw d = random_draw(40, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 24, 0);
                       const float special[] = {std::numeric_limits<float>::quiet_NaN(),
                                                std::numeric_limits<float>::infinity(), -0.0f, -1.0f};
                       for (size_t i = 0; i < d.vertices.size(); ++i)
                           d.vertices[i].uv[0] = (i % 2 == 0) ? special[(i / 2) % 4] : -0.5f;
                       return distance_scene(std::move(d), {0, 1, true});
                   },
                   nullptr, ""});
}

}  // namespace

void add_clipping_cases(CaseList& out) {
    add_clip_distance_cases(out);
    add_cull_distance_cases(out);
}

}  // namespace tilevk::cts
