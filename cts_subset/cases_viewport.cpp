// scissor.*, viewport.* and rasterization.huge.*: partial, offset and off-screen rectangles, and coordinates far past
// the viewport (clipping and guard bands).
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
