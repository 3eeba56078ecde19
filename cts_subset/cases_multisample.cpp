// multisample.*: 4x coverage, sample masks, alpha to coverage and resolve (the colour is resolved, then compared).
#include "case.hpp"

namespace tilevk::cts {
namespace {

Scene ms_scene(Draw d) {
    Scene s = one_draw(std::move(d));
    s.target.samples = VK_SAMPLE_COUNT_4_BIT;
    return s;
}

Draw random_triangles(uint32_t seed, VkPrimitiveTopology topo = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, int n = 12) {
    Lcg rng{seed};
    Draw d;
    d.topology = topo;
    for (int i = 0; i < n; ++i)
        d.vertices.push_back(vtx(rng.range(-1.1f, 1.1f), rng.range(-1.1f, 1.1f), 0, 1,
                                 {rng.next(), rng.next(), rng.next(), rng.next()}));
    return d;
}

// Short width-1 lines whose x extent (y extent for the vertical ones; both for the tiny diagonals) lies inside one
// pixel column (row), between two pixel boundaries, yet over a sample: lavapipe's line bbox (min rounded up, max
// rounded up minus one) is then empty and u_rect_test_intersection drops the whole line, samples and all. The fifth
// horizontal and vertical segments cross a pixel boundary instead and are drawn by both. Coordinates are window
// pixels.
Scene subpixel_lines() {
    Draw d;
    d.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    auto ndc = [](float x, float y) { return vtx(x / 32.0f - 1.0f, y / 32.0f - 1.0f); };
    const float starts[] = {0.30f, 0.20f, 0.55f, 0.05f, 0.80f};   // fraction where the segment starts
    const float lengths[] = {0.20f, 0.45f, 0.40f, 0.30f, 0.35f};  // the last one ends past the pixel boundary
    for (int i = 0; i < 5; ++i) {
        const float x = 4.0f + 7.0f * i + starts[i], y = 6.0f + 0.1f * i;
        d.vertices.push_back(ndc(x, y));  // horizontal, near a row boundary
        d.vertices.push_back(ndc(x + lengths[i], y + 0.02f));
        d.vertices.push_back(ndc(4.0f + 0.1f * i, 20.0f + 7.0f * i + starts[i]));  // vertical
        d.vertices.push_back(ndc(4.0f + 0.1f * i - 0.03f, 20.0f + 7.0f * i + starts[i] + lengths[i]));
        d.vertices.push_back(ndc(40.0f + starts[i], 30.0f + 7.0f * i + 0.5f));  // diagonal, inside one pixel
        d.vertices.push_back(ndc(40.0f + starts[i] + 0.1f, 30.0f + 7.0f * i + 0.6f));
    }
    return ms_scene(d);
}

}  // namespace

void add_sampled_ms_cases(CaseList& out);      // cases_sampled_ms.cpp
void add_sample_shading_cases(CaseList& out);  // cases_sample_shading.cpp

void add_multisample_cases(CaseList& out) {
    const std::string g = "multisample.";
    add_sampled_ms_cases(out);
    add_sample_shading_cases(out);
    out.push_back({g + "coverage_4x_triangles", [] { return ms_scene(random_triangles(11)); }, nullptr, ""});
    out.push_back({g + "coverage_4x_triangle_strip",
                   [] { return ms_scene(random_triangles(12, VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 10)); }, nullptr,
                   ""});
    out.push_back({g + "coverage_4x_lines",
                   [] { return ms_scene(random_triangles(13, VK_PRIMITIVE_TOPOLOGY_LINE_LIST)); }, nullptr, ""});
    out.push_back({g + "subpixel_lines_4x", subpixel_lines, nullptr, ""});
    out.push_back({g + "coverage_4x_points",
                   [] {
                       Draw d = random_triangles(14, VK_PRIMITIVE_TOPOLOGY_POINT_LIST, 16);
                       for (Vertex& v : d.vertices) v.point_size = 3.5f;
                       return ms_scene(d);
                   },
                   nullptr, ""});
    // With white geometry, a pixel fully covered by k of the 4 samples resolves to round(255*k/4).
    for (uint32_t mask : {0x0u, 0x1u, 0x3u, 0x5u, 0xAu, 0xEu, 0xFu}) {
        char name[32];
        std::snprintf(name, sizeof name, "sample_mask_0x%x", mask);
        auto scene = [=] {
            Draw d;
            d.sample_mask = mask;
            d.vertices = {vtx(-1.5f, -1.5f), vtx(5.0f, -1.5f), vtx(-1.5f, 5.0f)};  // covers every pixel
            return ms_scene(d);
        };
        int k = __builtin_popcount(mask);
        uint32_t v = uint32_t(255.0 * k / 4.0 + 0.5);  // the average of k white and 4-k black samples
        out.push_back({g + name, scene, palette_only({rgba8(v, v, v, v)}), ""});
    }
    for (float alpha : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        auto scene = [=] {
            Draw d;
            d.alpha_to_coverage = true;
            d.vertices = {vtx(-1.5f, -1.5f, 0, 1, {1, 1, 1, alpha}), vtx(5.0f, -1.5f, 0, 1, {1, 1, 1, alpha}),
                          vtx(-1.5f, 5.0f, 0, 1, {1, 1, 1, alpha})};
            return ms_scene(d);
        };
        out.push_back({g + "alpha_to_coverage_" + std::to_string(int(alpha * 100)), scene, nullptr, ""});
    }
    out.push_back({g + "alpha_to_coverage_gradient",
                   [] {
                       Draw d;
                       d.alpha_to_coverage = true;
                       d.vertices = {vtx(-1, -1, 0, 1, {1, 0, 0, 0}),   vtx(1, -1, 0, 1, {0, 1, 0, 1}),
                                     vtx(-1, 1, 0, 1, {0, 0, 1, 0.5f}), vtx(1, -1, 0, 1, {0, 1, 0, 1}),
                                     vtx(1, 1, 0, 1, {1, 1, 1, 0.25f}), vtx(-1, 1, 0, 1, {0, 0, 1, 0.5f})};
                       return ms_scene(d);
                   },
                   nullptr, ""});
    out.push_back({g + "resolve_clear_only",
                   [] {
                       Scene s;
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       float c[4] = {0.2f, 0.4f, 0.6f, 0.8f};
                       std::copy(c, c + 4, s.target.clear_color);
                       return s;
                   },
                   palette_only({rgba8(51, 102, 153, 204)}), ""});
    out.push_back({g + "resolve_blend",
                   [] {
                       Draw a = random_triangles(21), b = random_triangles(22);
                       b.blend = alpha_over();
                       Scene s = ms_scene(a);
                       s.draws.push_back(b);
                       return s;
                   },
                   nullptr, ""});
    // With sample shading (every sample its own run: depth, blend and store per sample, cases_sample_shading.cpp).
    for (float min_sample_shading : {-1.0f, 1.0f})
        out.push_back({g + (min_sample_shading < 0 ? "depth_test_4x" : "sample_shading.depth_test_blend"),
                       [=] {
                           Draw a = random_triangles(31), b = random_triangles(32);
                           for (Draw* d : {&a, &b}) {
                               d->depth_test = d->depth_write = true;
                               d->min_sample_shading = min_sample_shading;
                               Lcg rng{77};
                               for (Vertex& v : d->vertices) v.pos[2] = rng.next();
                           }
                           if (min_sample_shading >= 0) b.blend = alpha_over();
                           Scene s = ms_scene(a);
                           s.draws.push_back(b);
                           s.target.depth = VK_FORMAT_D32_SFLOAT;
                           return s;
                       },
                       nullptr, ""});
}

}  // namespace tilevk::cts
