// linear.*: frames that put lavapipe in llvmpipe's "linear" mode (one single-sampled B8G8R8A8_UNORM colour
// attachment, no depth/stencil attachment; notes §0.3/§8), one feature of the mode at a time.
//
// linear.guard_band.*: in linear mode draw clips x/y against the 2x guard band |x|, |y| <= 2w instead of the
// viewport (notes §1). Triangles and lines crossing the viewport edges, some also crossing the guard band, with
// varying colours and w. The fragment shader is Frag::kColorSum (an fadd), which lavapipe's linear-shader
// analysis refuses, so tiles lavapipe hands to its linear rasterizer are shaded by the general shader there
// (lp_rast_linear_rect_fallback) and only the geometry is under test. Odd triangle counts keep llvmpipe's
// 6N-vertex rectangle test (lp_setup_vbuf.c) out of the unclipped batches.
#include <cstdio>

#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr VkFormat kBgra8 = VK_FORMAT_B8G8R8A8_UNORM;

std::array<float, 4> dim_colour(Lcg& rng) {
    // below 0.5 so that v + v stays in [0, 1]
    return {rng.range(0, 0.5f), rng.range(0, 0.5f), rng.range(0, 0.5f), rng.range(0.25f, 0.5f)};
}

// `n` vertices with NDC x, y in [-reach, reach] and w in [0.6, 1.8].
Draw edge_crossing(uint32_t seed, int n, float reach, VkPrimitiveTopology topo) {
    Lcg rng{seed};
    Draw d;
    d.topology = topo;
    d.frag = Frag::kColorSum;
    for (int i = 0; i < n; ++i)
        d.vertices.push_back(
            vtx(rng.range(-reach, reach), rng.range(-reach, reach), 0.5f, rng.range(0.6f, 1.8f), dim_colour(rng)));
    return d;
}

Scene bgra(Draw d, uint32_t w = 160, uint32_t h = 120) {
    Scene s = one_draw(std::move(d), w, h);
    s.target.color = kBgra8;
    const float clear[4] = {0.1f, 0.2f, 0.3f, 1.0f};
    std::copy(clear, clear + 4, s.target.clear_color);
    return s;
}

}  // namespace

void add_linear_cases(CaseList& out) {
    const char* note = "bgra-linear-path";
    // 45 triangles (135 vertices): reach 1.6 stays inside the guard band, 3.5 crosses it.
    for (uint32_t seed : {1u, 2u, 3u}) {
        for (float reach : {1.6f, 3.5f}) {
            char name[64];
            std::snprintf(name, sizeof name, "linear.guard_band.triangles_reach%g_s%u", reach, seed);
            out.push_back({name,
                           [=] {
                               return bgra(edge_crossing(4100 + seed * 7 + uint32_t(reach * 10), 45 * 3, reach,
                                                         VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST));
                           },
                           nullptr, note});
        }
    }
    out.push_back({"linear.guard_band.strip",
                   [] { return bgra(edge_crossing(4200, 41, 2.6f, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP)); }, nullptr,
                   note});
    out.push_back({"linear.guard_band.fan",
                   [] { return bgra(edge_crossing(4210, 9, 2.6f, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN)); }, nullptr,
                   note});
    out.push_back({"linear.guard_band.lines",
                   [] {
                       Draw d = edge_crossing(4220, 60, 3.0f, VK_PRIMITIVE_TOPOLOGY_LINE_LIST);
                       d.line_width = 2.0f;
                       return bgra(d);
                   },
                   nullptr, note});
    // Viewports inside, across and larger than the target: the guard band scales with the viewport.
    const VkViewport viewports[] = {
        {12, 9, 60, 44, 0, 1}, {3.5f, 2.25f, 70.5f, 50.75f, 0, 1}, {-30, -20, 100, 80, 0, 1}};
    const char* vp_names[] = {"viewport_inside", "viewport_fractional", "viewport_off_screen"};
    for (int i = 0; i < 3; ++i) {
        const VkViewport vp = viewports[i];
        out.push_back({std::string("linear.guard_band.") + vp_names[i],
                       [=] {
                           Draw d = edge_crossing(4300 + i, 45 * 3, 2.8f, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST);
                           d.viewport = vp;
                           return bgra(d);
                       },
                       nullptr, note});
    }
    // The same frame with a depth attachment is not in linear mode (draw clips at the viewport): both must match.
    out.push_back({"linear.guard_band.with_depth_is_not_linear",
                   [] {
                       Scene s = bgra(edge_crossing(4101, 45 * 3, 3.5f, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST));
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   nullptr, ""});
}

}  // namespace tilevk::cts
