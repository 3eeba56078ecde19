// rasterization.fill_rules.*: shared edges drawn with additive counting; every pixel is covered at most once,
// and where the geometry tiles the whole target, exactly once (the top-left rule, as the CTS fill_rules judge).
#include <cmath>

#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kSize = 64;

Draw counting_draw() {
    Draw d;
    d.frag = Frag::kCount;
    d.blend = additive();
    return d;
}

// A quad of two triangles sharing the diagonal; `reverse` flips both windings.
Draw quad(float x0, float y0, float x1, float y1, bool reverse, float w0 = 1, float w1 = 1) {
    Draw d = counting_draw();
    Vertex a = vtx(x0, y0, 0, w0), b = vtx(x1, y0, 0, w1), c = vtx(x1, y1, 0, w1), e = vtx(x0, y1, 0, w0);
    d.vertices = reverse ? std::vector<Vertex>{a, c, b, a, e, c} : std::vector<Vertex>{a, b, c, a, c, e};
    return d;
}

// An n x n grid of cells over [-1.5,1.5]^2 (so it covers the whole target), each split into two triangles; every
// interior vertex is moved by `jitter` pixels times a pseudo-random factor plus `offset` pixels (sub-pixel steps).
Draw grid(int n, float offset_px, float jitter_px, uint32_t seed, bool alternate_diagonal) {
    Lcg rng{seed};
    const float px = 2.0f / kSize;  // one pixel in NDC
    std::vector<float> xs((n + 1) * (n + 1)), ys((n + 1) * (n + 1));
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            bool border = i == 0 || j == 0 || i == n || j == n;
            float jx = border ? 0 : (rng.range(-1, 1) * jitter_px + offset_px) * px;
            float jy = border ? 0 : (rng.range(-1, 1) * jitter_px + offset_px) * px;
            xs[j * (n + 1) + i] = -1.5f + 3.0f * i / n + jx;
            ys[j * (n + 1) + i] = -1.5f + 3.0f * j / n + jy;
        }
    Draw d = counting_draw();
    auto v = [&](int i, int j) { return vtx(xs[j * (n + 1) + i], ys[j * (n + 1) + i]); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            bool flip = alternate_diagonal && (i + j) % 2;
            if (flip) {
                for (auto p : {v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)})
                    d.vertices.push_back(p);
            } else {
                for (auto p : {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)})
                    d.vertices.push_back(p);
            }
        }
    return d;
}

// A fan around a (sub-pixel placed) centre, reaching past the target on every side.
Draw fan(float cx_px, float cy_px, int spokes) {
    Draw d = counting_draw();
    d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
    const float px = 2.0f / kSize;
    d.vertices.push_back(vtx(-1 + cx_px * px, -1 + cy_px * px));
    for (int i = 0; i <= spokes; ++i) {
        float a = 6.2831853f * float(i % spokes) / float(spokes) + 0.1f;
        d.vertices.push_back(vtx(3.0f * std::cos(a), 3.0f * std::sin(a)));
    }
    return d;
}

}  // namespace

void add_fill_rule_cases(CaseList& out) {
    const std::string g = "rasterization.fill_rules.";
    const int S = int(kSize);
    // Quads whose corners are off pixel centres, on screen: each pixel at most once.
    auto basic = [] { return one_draw(quad(-0.53f, -0.61f, 0.47f, 0.39f, false)); };
    out.push_back({g + "basic_quad", basic, all_of({exactly_once(0), band_of(basic)}), ""});
    auto reverse = [] { return one_draw(quad(-0.53f, -0.61f, 0.47f, 0.39f, true)); };
    out.push_back({g + "basic_quad_reverse", reverse, all_of({exactly_once(0), band_of(reverse)}), ""});
    out.push_back({g + "clipped_full", [] { return one_draw(quad(-1.5f, -1.5f, 1.5f, 1.5f, false)); },
                   exactly_once(0, 0, 0, S, S), ""});
    out.push_back(
        {g + "clipped_partly", [] { return one_draw(quad(-0.3f, -1.6f, 1.7f, 0.45f, false)); }, exactly_once(0), ""});
    auto projected = [] { return one_draw(quad(-0.8f, -0.7f, 0.6f, 0.9f, false, 1.0f, 3.0f)); };
    out.push_back({g + "projected", projected, all_of({exactly_once(0), band_of(projected)}), ""});
    out.push_back({g + "basic_quad_bgra_linear",
                   [] {
                       Scene s = one_draw(quad(-0.53f, -0.61f, 0.47f, 0.39f, false));
                       s.target.color = VK_FORMAT_B8G8R8A8_UNORM;
                       return s;
                   },
                   exactly_once(0), "bgra-linear-path"});
    // Shared edges with every interior vertex shifted by k/256 pixel (the 8-bit sub-pixel grid).
    for (int k : {0, 1, 2, 64, 127, 128, 129, 255}) {
        out.push_back({g + "shared_edges_offset_" + std::to_string(k),
                       [=] { return one_draw(grid(7, float(k) / 256.0f, 0.0f, 1, k % 2 == 1)); },
                       exactly_once(0, 0, 0, S, S), ""});
    }
    for (uint32_t seed = 1; seed <= 4; ++seed)
        out.push_back({g + "shared_edges_jitter_" + std::to_string(seed),
                       [=] { return one_draw(grid(9, 0.0f, 2.5f, seed, seed % 2 == 0)); }, exactly_once(0, 0, 0, S, S),
                       ""});
    // Fans whose centre sits on a pixel centre, a pixel corner, and between.
    const float centres[][2] = {{32.5f, 32.5f}, {32.0f, 32.0f}, {20.25f, 40.75f}, {10.5f, 50.0f}};
    for (int i = 0; i < 4; ++i)
        out.push_back({g + "fan_centre_" + std::to_string(i),
                       [=] { return one_draw(fan(centres[i][0], centres[i][1], 11 + i)); }, exactly_once(0, 0, 0, S, S),
                       ""});
}

}  // namespace tilevk::cts
