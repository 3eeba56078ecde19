// The rasterization extensions lavapipe offers, judged byte for byte against it, modelled on dEQP-VK's groups:
//   rasterization.provoking_vertex.* (VK_EXT_provoking_vertex): flat inputs on every topology with the first and the
//     last vertex provoking, clipped and unfilled primitives, the 4-vertex fan and strips llvmpipe may pair into
//     rectangles; analytic colours where each primitive's provoking vertex alone has a colour;
//   clipping.depth_clip_enable.* (VK_EXT_depth_clip_enable): depthClipEnable off and on, with and without depthClamp,
//     on triangles, lines and points crossing z = 0 and z = w;
//   rasterization.line.* (VK_EXT_line_rasterization): the RECTANGULAR and BRESENHAM modes, thin and wide, lists and
//     strips.
#include <optional>
#include <string>

#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr std::array<float, 4> kRed = {1, 0, 0, 1}, kGreen = {0, 1, 0, 1}, kBlue = {0, 0, 1, 1}, kWhite = {1, 1, 1, 1};

// Random primitives of `topo` with a random colour per vertex.
Draw random_draw(VkPrimitiveTopology topo, uint32_t count, uint32_t seed, float line_width) {
    Lcg rng{seed};
    Draw d;
    d.topology = topo;
    d.line_width = line_width;
    for (uint32_t i = 0; i < count; ++i) {
        const float x = rng.range(-1.3f, 1.3f), y = rng.range(-1.3f, 1.3f);
        Vertex v = vtx(x, y, 0.0f, 1.0f, {rng.next(), rng.next(), rng.next(), 1.0f});
        v.point_size = 3.0f;
        d.vertices.push_back(v);
    }
    return d;
}

// Two triangles side by side, each with red, green, blue corners in that order: the first vertex provoking paints
// both red, the last blue (pixel (16, 48) lies in the first, (48, 48) in the second).
Scene analytic_list(bool last) {
    Draw d;
    d.interp = Interp::kFlat;
    d.provoking_last = last;
    d.vertices = {vtxc(-0.9f, 0.9f, kRed), vtxc(-0.1f, 0.9f, kGreen), vtxc(-0.5f, -0.5f, kBlue),
                  vtxc(0.1f, 0.9f, kRed),  vtxc(0.9f, 0.9f, kGreen),  vtxc(0.5f, -0.5f, kBlue)};
    return one_draw(d);
}

// A strip of four vertices coloured red, green, blue, white: triangle 0 is (v0, v1, v2), triangle 1 (v1, v2, v3)
// in some order; first-vertex: red then green; last-vertex: blue then white.
Scene analytic_strip(bool last) {
    Draw d;
    d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    d.interp = Interp::kFlat;
    d.provoking_last = last;
    d.vertices = {vtxc(-0.9f, -0.9f, kRed), vtxc(-0.9f, 0.9f, kGreen), vtxc(0.9f, -0.9f, kBlue),
                  vtxc(0.9f, 0.9f, kWhite)};
    return one_draw(d);
}

// A horizontal 3-pixel line from a red to a green vertex along row 16.
Scene analytic_lines(bool last) {
    Draw d;
    d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    d.interp = Interp::kFlat;
    d.provoking_last = last;
    d.line_width = 3.0f;
    d.vertices = {vtxc(-0.8f, -0.5f + 1.0f / 64, kRed), vtxc(0.8f, -0.5f + 1.0f / 64, kGreen)};
    return one_draw(d);
}

void add_provoking_cases(CaseList& out) {
    for (bool last : {false, true}) {
        const std::string mode = last ? "last" : "first";
        const std::string p = "rasterization.provoking_vertex." + mode + ".";
        const uint32_t a = last ? rgba8(0, 0, 255, 255) : rgba8(255, 0, 0, 255);
        out.push_back({p + "analytic_list", [last] { return analytic_list(last); },
                       all_of({pixel_is(16, 48, a), pixel_is(48, 48, a)}), ""});
        out.push_back({p + "analytic_strip", [last] { return analytic_strip(last); },
                       all_of({pixel_is(8, 32, last ? rgba8(0, 0, 255, 255) : rgba8(255, 0, 0, 255)),
                               pixel_is(56, 32, last ? rgba8(255, 255, 255, 255) : rgba8(0, 255, 0, 255))}),
                       ""});
        out.push_back({p + "analytic_line", [last] { return analytic_lines(last); },
                       pixel_is(32, 16, last ? rgba8(0, 255, 0, 255) : rgba8(255, 0, 0, 255)), ""});
        struct Row {
            const char* name;
            VkPrimitiveTopology topo;
            uint32_t count;
            float line_width;
            VkPolygonMode polygon;
        };
        // Vertices reach 1.3 past the viewport: many primitives go through draw's clipper (its fans keep the
        // provoking vertex). Twelve-vertex lists: never nine (lavapipe-rules §8).
        const Row rows[] = {
            {"triangle_list", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 12, 1, VK_POLYGON_MODE_FILL},
            {"triangle_strip", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 11, 1, VK_POLYGON_MODE_FILL},
            {"triangle_fan", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, 10, 1, VK_POLYGON_MODE_FILL},
            {"line_list", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 12, 2, VK_POLYGON_MODE_FILL},
            {"line_strip", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 10, 1, VK_POLYGON_MODE_FILL},
            {"triangle_strip_polygon_line", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 9, 1, VK_POLYGON_MODE_LINE},
            {"triangle_fan_polygon_point", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, 9, 1, VK_POLYGON_MODE_POINT},
        };
        for (const Row& r : rows)
            for (Interp interp : {Interp::kFlat, Interp::kSmooth}) {
                const std::string name = p + r.name + (interp == Interp::kFlat ? "" : "_smooth");
                out.push_back({name,
                               [r, interp, last] {
                                   Draw d = random_draw(r.topo, r.count, 4099u + r.count, r.line_width);
                                   d.interp = interp;
                                   d.polygon_mode = r.polygon;
                                   d.provoking_last = last;
                                   d.cull =
                                       r.polygon == VK_POLYGON_MODE_FILL ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
                                   // Corners inside the viewport: which corners the clipper makes lavapipe draws
                                   // as points is not fully known (rast/geometry/README.md, polygonMode POINT).
                                   if (r.polygon == VK_POLYGON_MODE_POINT)
                                       for (Vertex& v : d.vertices)
                                           for (int c = 0; c < 2; ++c) v.pos[c] *= 0.7f;
                                   return one_draw(d, 96, 80);
                               },
                               nullptr, ""});
            }
        // The 4-vertex fan llvmpipe offers to its rectangle test as (v0, v1, v2), (v0, v2, v3) whatever the
        // provoking vertex, and strips it pairs only with the first vertex provoking; B8G8R8A8 without depth lets
        // lavapipe use its linear rasterizer (docs/lavapipe-rules.md §8).
        for (bool bgra : {false, true}) {
            const std::string suffix = bgra ? "_bgra_linear" : "";
            const char* note = bgra ? "bgra-linear-path" : "";
            out.push_back({p + "fan4" + suffix,
                           [last, bgra] {
                               Draw d;
                               d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
                               d.provoking_last = last;
                               d.frag = Frag::kColorSum;
                               d.vertices = {vtxc(-0.75f, -0.5f, kRed), vtxc(0.5f, -0.5f, kGreen),
                                             vtxc(0.5f, 0.75f, {0.2f, 0.3f, 0.4f, 1}), vtxc(-0.75f, 0.75f, kBlue)};
                               Scene s = one_draw(d);
                               if (bgra) s.target.color = VK_FORMAT_B8G8R8A8_UNORM;
                               return s;
                           },
                           nullptr, note});
            out.push_back({p + "rect_strip" + suffix,
                           [last, bgra] {
                               Draw d;
                               d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
                               d.provoking_last = last;
                               d.frag = Frag::kConstant;
                               for (int i = 0; i < 6; ++i) {  // a column of axis-aligned rectangles
                                   const float y = -0.75f + 0.25f * float(i);
                                   d.vertices.push_back(vtxc(-0.5f, y, kWhite));
                                   d.vertices.push_back(vtxc(0.25f, y, kWhite));
                               }
                               Scene s = one_draw(d);
                               if (bgra) s.target.color = VK_FORMAT_B8G8R8A8_UNORM;
                               return s;
                           },
                           nullptr, note});
        }
    }
}

// A draw whose z leaves [0, w] on both sides: triangles, then lines and points (z = -0.5 .. 1.5).
Draw depth_range_draw(VkPrimitiveTopology topo, std::optional<bool> clip, bool clamp) {
    Draw d;
    d.topology = topo;
    d.depth_test = d.depth_write = true;
    d.depth_op = VK_COMPARE_OP_ALWAYS;
    d.depth_clamp = clamp;
    d.depth_clip_enable = clip;
    d.line_width = 2.0f;
    d.vertices = {vtx(-0.9f, -0.9f, -0.5f, 1, {1, 0, 0, 1}),  vtx(0.9f, -0.9f, 1.5f, 1, {0, 1, 0, 1}),
                  vtx(0.0f, 0.9f, 0.5f, 1, {0, 0, 1, 1}),     vtx(-0.9f, 0.9f, 1.2f, 2, {1, 1, 0, 1}),
                  vtx(0.9f, 0.9f, -0.2f, 0.5f, {0, 1, 1, 1}), vtx(0.5f, -0.5f, 0.3f, 1, {1, 0, 1, 1})};
    for (Vertex& v : d.vertices) v.point_size = 5.0f;
    return d;
}

// A quad entirely beyond the far plane (z = 1.5) over the left half and one before the near plane (z = -0.5) over
// the right half: clipped away with depth clipping on; drawn otherwise (its depth clamped to [0, 1]).
Scene outside_quads(bool clip, bool clamp) {
    Draw d;
    d.depth_clamp = clamp;
    d.depth_clip_enable = clip;
    for (float x0 : {-1.0f, 0.0f}) {
        const float z = x0 < 0 ? 1.5f : -0.5f;
        const auto c = x0 < 0 ? kRed : kGreen;
        d.vertices.push_back(vtx(x0, -1, z, 1, c));
        d.vertices.push_back(vtx(x0 + 1, -1, z, 1, c));
        d.vertices.push_back(vtx(x0, 1, z, 1, c));
        d.vertices.push_back(vtx(x0 + 1, -1, z, 1, c));
        d.vertices.push_back(vtx(x0 + 1, 1, z, 1, c));
        d.vertices.push_back(vtx(x0, 1, z, 1, c));
    }
    Scene s = one_draw(d);
    s.target.depth = VK_FORMAT_D32_SFLOAT;
    return s;
}

void add_depth_clip_cases(CaseList& out) {
    struct Fmt {
        const char* name;
        VkFormat format;
    };
    const Fmt fmts[] = {{"d16", VK_FORMAT_D16_UNORM}, {"d32", VK_FORMAT_D32_SFLOAT}};
    struct Topo {
        const char* name;
        VkPrimitiveTopology topo;
    };
    const Topo topos[] = {{"triangles", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST},
                          {"lines", VK_PRIMITIVE_TOPOLOGY_LINE_LIST},
                          {"points", VK_PRIMITIVE_TOPOLOGY_POINT_LIST}};
    for (bool clip : {false, true})
        for (bool clamp : {false, true}) {
            const std::string p = std::string("clipping.depth_clip_enable.") + (clip ? "clip" : "no_clip") +
                                  (clamp ? "_clamp" : "_no_clamp") + ".";
            for (const Fmt& f : fmts)
                for (const Topo& t : topos)
                    out.push_back({p + t.name + "_" + f.name,
                                   [=] {
                                       Scene s = one_draw(depth_range_draw(t.topo, clip, clamp));
                                       s.target.depth = f.format;
                                       return s;
                                   },
                                   nullptr, ""});
            const uint32_t left = clip ? 0 : rgba8(255, 0, 0, 255), right = clip ? 0 : rgba8(0, 255, 0, 255);
            out.push_back({p + "outside_quads", [=] { return outside_quads(clip, clamp); },
                           all_of({pixel_is(16, 32, left), pixel_is(48, 32, right)}), ""});
        }
}

void add_line_cases(CaseList& out) {
    struct Mode {
        const char* name;
        VkLineRasterizationModeEXT mode;
    };
    const Mode modes[] = {{"default", VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT},
                          {"rectangular", VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT},
                          {"bresenham", VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT}};
    struct Row {
        const char* name;
        VkPrimitiveTopology topo;
        float width;
    };
    const Row rows[] = {{"lines", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 1},
                        {"line_strip", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 1},
                        {"lines_wide", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 4},
                        {"line_strip_wide", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 3},
                        {"lines_width_2_5", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 2.5f}};
    for (const Mode& m : modes)
        for (const Row& r : rows)
            out.push_back({std::string("rasterization.line.") + m.name + "." + r.name,
                           [m, r] {
                               Draw d = random_draw(r.topo, 12, 7717, r.width);
                               d.line_mode = m.mode;
                               return one_draw(d, 96, 80);
                           },
                           nullptr, ""});
    // polygonMode LINE edges are lines of the pipeline's mode too; a depth-tested Bresenham line with a bias.
    for (const Mode& m : modes) {
        out.push_back({std::string("rasterization.line.") + m.name + ".polygon_line",
                       [m] {
                           Draw d = random_draw(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 12, 31, 2.0f);
                           d.polygon_mode = VK_POLYGON_MODE_LINE;
                           d.line_mode = m.mode;
                           return one_draw(d, 96, 80);
                       },
                       nullptr, ""});
        out.push_back({std::string("rasterization.line.") + m.name + ".depth_bias",
                       [m] {
                           Draw d = random_draw(VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 12, 77, 3.0f);
                           for (Vertex& v : d.vertices) v.pos[2] = 0.25f + 0.5f * v.color[0];
                           d.line_mode = m.mode;
                           d.depth_test = d.depth_write = true;
                           d.depth_bias = true;
                           d.bias_constant = 3.0f;
                           d.bias_slope = 0.5f;
                           Scene s = one_draw(d, 96, 80);
                           s.target.depth = VK_FORMAT_D32_SFLOAT;
                           return s;
                       },
                       nullptr, ""});
    }
}

}  // namespace

void add_raster_ext_cases(CaseList& out) {
    add_provoking_cases(out);
    add_depth_clip_cases(out);
    add_line_cases(out);
}

}  // namespace tilevk::cts
