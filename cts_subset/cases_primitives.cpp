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

}  // namespace

void add_primitive_cases(CaseList& out) {
    struct Row {
        const char* name;
        VkPrimitiveTopology topo;
        uint32_t count;
        float line_width, psize;
    };
    // Twelve-vertex lists: never nine (lavapipe's 9-vertex rectangle analysis, notes §8).
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
