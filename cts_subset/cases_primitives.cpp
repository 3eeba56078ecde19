// rasterization.primitives.*: every topology with random primitives, and points of several sizes.
#include "case.hpp"

namespace tilevk::cts {
namespace {

Scene random_primitives(VkPrimitiveTopology topo, uint32_t count, uint32_t seed, float line_width, float psize) {
    Lcg rng{seed};
    Draw d;
    d.topology = topo;
    d.line_width = line_width;
    for (uint32_t i = 0; i < count; ++i) {
        Vertex v = vtx(rng.range(-1.1f, 1.1f), rng.range(-1.1f, 1.1f), 0.0f, 1.0f, {1, 1, 1, 1});
        v.point_size = psize;
        d.vertices.push_back(v);
    }
    return one_draw(d, 128, 128);
}

// gl_PointCoord (found by cases_random.cpp: tilevk's shaders read 0 for it). One size-8 point centred on pixel
// corner (32,32) at w = 1, then perspective points (w != 1) of several sizes, all writing vec4(gl_PointCoord, 0, 1).
Scene point_coord_scene(VkSampleCountFlagBits samples) {
    Draw d;
    d.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    d.vertex_glsl =
        "#version 450\n"
        "layout(location=0) in vec4 in_pos;\n"
        "layout(location=1) in vec4 in_color;\n"  // every attribute of the runner's layout is consumed
        "layout(location=2) in vec2 in_uv;\n"
        "layout(location=3) in float in_psize;\n"
        "void main() { gl_Position = in_pos; gl_PointSize = in_psize; }\n";
    d.fragment_glsl =
        "#version 450\n"
        "layout(location=0) out vec4 o_color;\n"
        "void main() { o_color = vec4(gl_PointCoord, 0.0, 1.0); }\n";
    Vertex centre = vtx(0, 0);
    centre.point_size = 8;
    d.vertices.push_back(centre);
    Lcg rng{4242};
    for (int i = 0; i < 10; ++i) {  // right of x = 42 px: clear of the first point
        Vertex v = vtx(rng.range(0.5f, 1.0f), rng.range(-1.0f, 1.0f), 0.5f, rng.range(0.5f, 3.0f));
        v.point_size = rng.range(1.0f, 12.0f);
        d.vertices.push_back(v);
    }
    Scene s = one_draw(d);
    s.target.samples = samples;
    return s;
}

}  // namespace

void add_primitive_cases(CaseList& out) {
    // 1x: the size-8 point covers pixels 28..35; PointCoord at pixel 28's centre is 0.5/8 (unorm8 16), at pixel 35's
    // 7.5/8 (239), origin upper-left. At 4x lavapipe's point planes keep the 1x half-pixel offset (lavapipe-rules §6),
    // so only the comparison judges it.
    out.push_back({"rasterization.primitives.point_coord", [] { return point_coord_scene(VK_SAMPLE_COUNT_1_BIT); },
                   all_of({pixel_is(28, 28, rgba8(16, 16, 0, 255)), pixel_is(35, 28, rgba8(239, 16, 0, 255)),
                           pixel_is(28, 35, rgba8(16, 239, 0, 255)), pixel_is(35, 35, rgba8(239, 239, 0, 255)),
                           pixel_is(27, 28, 0), pixel_is(36, 35, 0)}),
                   ""});
    out.push_back({"rasterization.primitives.point_coord_msaa4",
                   [] { return point_coord_scene(VK_SAMPLE_COUNT_4_BIT); }, nullptr, ""});
    struct Row {
        const char* name;
        VkPrimitiveTopology topo;
        uint32_t count;
        float line_width, psize;
    };
    // Twelve-vertex lists: never nine (lavapipe's 9-vertex rectangle analysis, lavapipe-rules §8).
    const Row rows[] = {
        {"triangles", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 12, 1, 1},
        {"triangle_strip", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 10, 1, 1},
        {"triangle_fan", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, 10, 1, 1},
        {"lines", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 12, 1, 1},
        {"line_strip", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 10, 1, 1},
        {"lines_wide", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 12, 4, 1},
        {"line_strip_wide", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, 10, 3, 1},
        {"points", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 24, 1, 1},
        {"points_size_2", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 24, 1, 2},
        {"points_size_3", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 24, 1, 3},
        {"points_size_8", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 16, 1, 8},
        {"points_size_31_5", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 8, 1, 31.5f},
        {"points_size_128", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 4, 1, 128},
    };
    for (const Row& r : rows)
        for (uint32_t seed = 1; seed <= 2; ++seed) {
            std::string name = std::string("rasterization.primitives.") + r.name + (seed == 1 ? "" : "_seed2");
            auto make = [=] { return random_primitives(r.topo, r.count, seed * 7919, r.line_width, r.psize); };
            bool filled = r.topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST ||
                          r.topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP ||
                          r.topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
            Check palette = palette_only({0, rgba8(255, 255, 255, 255)});
            out.push_back({name, make, filled ? all_of({palette, band_of(make)}) : palette, ""});
        }
}

}  // namespace tilevk::cts
