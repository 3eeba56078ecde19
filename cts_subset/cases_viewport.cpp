// scissor.*, viewport.* and rasterization.huge.*: partial, offset and off-screen rectangles, and coordinates far past
// the viewport (clipping and guard bands).
#include <iterator>

#include "case.hpp"

namespace tilevk::cts {
namespace {

Draw colourful(uint32_t seed, int n = 12) {
    Lcg rng{seed};
    Draw d;
    for (int i = 0; i < n; ++i)
        d.vertices.push_back(
            vtx(rng.range(-1.2f, 1.2f), rng.range(-1.2f, 1.2f), 0, 1, {rng.next(), rng.next(), rng.next(), 1}));
    return d;
}

}  // namespace

// A case table (over 150 lines): one entry per case, in groups under their comments, sharing the scene builders
// and constants declared at its top.
void add_viewport_cases(CaseList& out) {
    const VkRect2D scissors[] = {
        {{10, 10}, {30, 20}}, {{0, 0}, {1, 1}}, {{40, 33}, {100, 100}}, {{63, 0}, {1, 64}}, {{0, 0}, {0, 0}}};
    const char* scissor_names[] = {"partial", "one_pixel", "past_bottom_right", "last_column", "empty"};
    for (int i = 0; i < 5; ++i) {
        VkRect2D sc = scissors[i];
        Check check = sc.extent.width == 0 ? palette_only({0}) : Check();  // an empty scissor keeps the clear
        out.push_back({std::string("scissor.") + scissor_names[i],
                       [=] {
                           Draw d = colourful(900 + i);
                           d.scissor = sc;
                           return one_draw(d);
                       },
                       check, ""});
    }
    // 4x with a scissor smaller than the target: lavapipe's scissor planes (lp_setup.c lp_setup_add_scissor_planes,
    // adj 127) pass the samples more than half a pixel into the column left of / the row above the scissor for
    // triangles and lines whose bounding box crosses that edge, when that column/row lies in a binned 64-px tile;
    // points and the right/bottom edges clip whole pixels. tilevk matches it (icd/README.md named differences).
    // Offsets: inside the first tile, on a tile boundary (64: nothing passes outside), one past it, the last
    // column; triangles, 1- and 3-px lines, 5-px points, and lines whose bounding box starts on the scissor edge.
    struct Msaa {
        const char* name;
        VkRect2D sc;
    };
    const Msaa msaa[] = {{"partial", {{10, 10}, {30, 20}}},
                         {"odd", {{5, 3}, {7, 9}}},
                         {"tile_edge", {{64, 64}, {40, 20}}},
                         {"past_tile_edge", {{65, 63}, {50, 40}}},
                         {"last_column", {{63, 0}, {1, 64}}},
                         {"one_pixel", {{33, 47}, {1, 1}}},
                         {"past_bottom_right", {{70, 40}, {200, 200}}}};
    const struct {
        const char* name;
        VkPrimitiveTopology topo;
        float width;
    } prims[] = {{"triangles", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 1.0f},
                 {"lines", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 1.0f},
                 {"wide_lines", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, 3.0f},
                 {"points", VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 1.0f}};
    for (int i = 0; i < int(std::size(msaa)); ++i) {
        for (int k = 0; k < int(std::size(prims)); ++k) {
            const Msaa m = msaa[i];
            const auto pr = prims[k];
            out.push_back({std::string("scissor.msaa4.") + m.name + "." + pr.name,
                           [=] {
                               Draw d =
                                   colourful(1300 + 7 * i + k, pr.topo == VK_PRIMITIVE_TOPOLOGY_POINT_LIST ? 60 : 24);
                               d.topology = pr.topo;
                               d.line_width = pr.width;
                               for (Vertex& v : d.vertices) v.point_size = 5.0f;
                               d.scissor = m.sc;
                               Scene s = one_draw(d, 128, 96);
                               s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                               return s;
                           },
                           nullptr, ""});
        }
    }
    // Lines whose ends sit a fraction of a pixel left of / above a whole pixel: lavapipe's line bounding box rounds
    // min up (lp_setup_line.c), so the partial column/row before it is only drawn inside the bbox's binned tiles
    // (not across a 64-px tile boundary) and gets no scissor plane when the bbox starts on the scissor edge.
    for (int scissored = 0; scissored < 2; ++scissored) {
        out.push_back({std::string("scissor.msaa4.line_box_edges") + (scissored ? ".scissored" : ".unscissored"),
                       [=] {
                           Draw d;
                           d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
                           d.line_width = 2.0f;
                           auto px = [](float x, float y, std::array<float, 4> c) {  // pixel → NDC on 128x96
                               return vtx(x / 64.0f - 1.0f, y / 48.0f - 1.0f, 0, 1, c);
                           };
                           // horizontal lines starting at 63.3..63.9 and 9.3..9.9 (x-major), vertical ones at
                           // y 63.x (y-major, the 64-row tile boundary) and 20.x
                           for (int j = 0; j < 4; ++j) {
                               const float f = 0.3f + 0.2f * float(j);
                               d.vertices.push_back(px(63.0f + f, 5.5f + 6 * j, {1, 0, 0, 1}));
                               d.vertices.push_back(px(90.0f, 7.0f + 6 * j, {0, 1, 0, 1}));
                               d.vertices.push_back(px(9.0f + f, 40.5f + 6 * j, {0, 0, 1, 1}));
                               d.vertices.push_back(px(50.0f, 42.0f + 6 * j, {1, 1, 0, 1}));
                               d.vertices.push_back(px(100.5f + 5 * j, 63.0f + f, {0, 1, 1, 1}));
                               d.vertices.push_back(px(102.0f + 5 * j, 90.0f, {1, 0, 1, 1}));
                               d.vertices.push_back(px(70.5f + 5 * j, 20.0f + f, {1, 1, 1, 1}));
                               d.vertices.push_back(px(72.0f + 5 * j, 50.0f, {0.5f, 0.2f, 0.9f, 1}));
                           }
                           if (scissored) d.scissor = VkRect2D{{10, 21}, {110, 70}};
                           Scene s = one_draw(d, 128, 96);
                           s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                           return s;
                       },
                       nullptr, ""});
    }
    const VkViewport viewports[] = {{16, 8, 32, 32, 0, 1},  {-16, -24, 64, 64, 0, 1},
                                    {40, 40, 64, 64, 0, 1}, {0.5f, 0.25f, 50.5f, 40.75f, 0, 1},
                                    {10, 10, 1, 1, 0, 1},   {-200, -200, 500, 500, 0, 1}};
    const char* vp_names[] = {"offset",    "partly_off_screen_top_left", "partly_off_screen_bottom_right", "fractional",
                              "one_pixel", "larger_than_target"};
    for (int i = 0; i < 6; ++i) {
        VkViewport vp = viewports[i];
        out.push_back({std::string("viewport.") + vp_names[i],
                       [=] {
                           Draw d = colourful(950 + i);
                           d.viewport = vp;
                           return one_draw(d);
                       },
                       nullptr, ""});
    }
    // Huge triangles: vertices hundreds to millions of viewports away; the visible part must still be exact.
    for (float far : {4.0f, 100.0f, 1e4f, 1e6f}) {
        char name[48];
        std::snprintf(name, sizeof name, "rasterization.huge.triangle_%g", far);
        out.push_back({name,
                       [=] {
                           Draw d;
                           d.vertices = {vtx(-far, -far * 0.7f, 0, 1, {1, 0, 0, 1}),
                                         vtx(far * 0.9f, -0.3f, 0, 1, {0, 1, 0, 1}),
                                         vtx(0.1f, far, 0, 1, {0, 0, 1, 1})};
                           return one_draw(d);
                       },
                       nullptr, ""});
    }
    // An edge crossing the target from a vertex far outside: shared with a second triangle, counted additively.
    for (float far : {50.0f, 5e5f}) {
        char name[48];
        std::snprintf(name, sizeof name, "rasterization.huge.shared_edge_%g", far);
        out.push_back({name,
                       [=] {
                           Draw d;
                           d.frag = Frag::kCount;
                           d.blend = additive();
                           Vertex a = vtx(-far, -0.37f * far), b = vtx(far, 0.41f * far);
                           d.vertices = {a, b, vtx(-3, 3), a, vtx(3, -3), b};
                           return one_draw(d);
                       },
                       exactly_once(0, 0, 0, 64, 64), ""});
    }
    out.push_back({"rasterization.huge.w_near_zero",
                   [] {
                       Draw d = colourful(990, 6);
                       d.vertices[0].pos[3] = 1e-3f;
                       d.vertices[4].pos[3] = 1e-5f;
                       return one_draw(d);
                   },
                   nullptr, ""});
    out.push_back({"rasterization.huge.negative_w",
                   [] {
                       Draw d = colourful(991, 6);
                       d.vertices[1].pos[3] = -0.5f;
                       return one_draw(d);
                   },
                   nullptr, ""});
    out.push_back(
        {"rasterization.huge.large_target_2048", [] { return one_draw(colourful(992), 2048, 2048); }, nullptr, ""});
}

}  // namespace tilevk::cts
