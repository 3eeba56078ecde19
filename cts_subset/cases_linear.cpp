// linear.*: frames that put lavapipe in llvmpipe's "linear" mode (one single-sampled B8G8R8A8_UNORM colour
// attachment, no depth/stencil attachment; lavapipe-rules §0.3/§8), one feature of the mode at a time.
//
// linear.guard_band.*: in linear mode draw clips x/y against the 2x guard band |x|, |y| <= 2w instead of the
// viewport (lavapipe-rules §1). Triangles and lines crossing the viewport edges, some also crossing the guard band,
// with varying colours and w. The fragment shader is Frag::kColorSum (an fadd), which lavapipe's linear-shader analysis
// refuses, so tiles lavapipe hands to its linear rasterizer are shaded by the general shader there
// (lp_rast_linear_rect_fallback) and only the geometry is under test. Odd triangle counts keep llvmpipe's
// 6N-vertex rectangle test (lp_setup_vbuf.c) out of the unclipped batches.
#include <cstdio>
#include <functional>

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

// A vertex at window pixel (x, y) of a 128x128 target: NDC x/64 - 1 is exact for x in 1/512 steps, and so is the
// viewport transform back (fmuladd(ndc, 64, 64)), so the window coordinates are exactly the ones written here.
Vertex at(float x, float y, std::array<float, 4> c, float w = 1.0f) {
    return vtx(x / 64.0f - 1.0f, y / 64.0f - 1.0f, 0.5f, w, c);
}
// The same for a 256x256 target.
Vertex at256(float x, float y, std::array<float, 4> c) {
    return vtx(x / 128.0f - 1.0f, y / 128.0f - 1.0f, 0.5f, 1.0f, c);
}

// Colours affine in the pixel position with binary-fraction gradients: corner differences are exact, so the
// four corners of a rectangle pass do_rect_ccw's coplanarity test.
std::array<float, 4> affine(float x, float y, uint32_t k) {
    const float gx = float(1 + k % 3) / 1024.0f, gy = float(1 + k % 5) / 2048.0f;
    return {0.0625f + gx * x, 0.125f + gy * y, 0.25f - gx * 0.5f * x, 0.5f - gy * y * 0.5f};
}

// Two triangles covering the rectangle (x0, y0)-(x1, y1), in one of many vertex and triangle orders: `kind`
// picks the diagonal, the rotation of each triangle's vertices, the triangle order and (bit 5) a reversed
// winding, so all nine shared-diagonal configurations of do_rect_ccw and both windings occur.
void push_rect(Draw& d, float x0, float y0, float x1, float y1, uint32_t kind, bool coplanar, uint32_t k,
               float w = 1.0f, bool target256 = false) {
    const float xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    Vertex c[4];
    for (int i = 0; i < 4; ++i) {
        std::array<float, 4> col = affine(xs[i], ys[i], k);
        if (!coplanar && i == 2) col[1] += 1.0f / 64.0f;
        c[i] = target256 ? at256(xs[i], ys[i], col) : at(xs[i], ys[i], col, w);
    }
    const bool diag_bd = kind & 1;
    int t[2][3] = {{0, 1, 2}, {0, 2, 3}};
    if (diag_bd) t[0][0] = 1, t[0][1] = 2, t[0][2] = 3, t[1][0] = 1, t[1][1] = 3, t[1][2] = 0;
    for (int tri = 0; tri < 2; ++tri) {
        const int rot = int((kind >> (1 + tri)) % 3);
        int r[3] = {t[tri][rot], t[tri][(rot + 1) % 3], t[tri][(rot + 2) % 3]};
        if (kind & 32) std::swap(r[1], r[2]);
        std::copy(r, r + 3, t[tri]);
    }
    const int first = (kind & 8) ? 1 : 0;
    for (int tri : {first, 1 - first})
        for (int v = 0; v < 3; ++v) d.vertices.push_back(c[t[tri][v]]);
}

Scene bgra(Draw d, uint32_t w = 160, uint32_t h = 120) {
    Scene s = one_draw(std::move(d), w, h);
    s.target.color = kBgra8;
    const float clear[4] = {0.1f, 0.2f, 0.3f, 1.0f};
    std::copy(clear, clear + 4, s.target.clear_color);
    return s;
}

// linear.guard_band.*: draw's guard band (twice the viewport) instead of the viewport clip.
void add_guard_band_cases(CaseList& out) {
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
}

// linear.rect.*: llvmpipe's rectangle setup.
void add_rect_cases(CaseList& out) {
    const char* note = "bgra-linear-path";
    // linear.rect.*: llvmpipe's rectangle path (lp_setup_rect.c): 6N-vertex lists, strips and 4-vertex fans whose
    // triangle pairs form axis-aligned rectangles with equal w and coplanar attributes are set up once from three
    // corners and cover the box of their util_iround-snapped corners. Corners sit on sub-pixel offsets where
    // that box and the triangles' edge functions disagree (x.5 + 1/512: half away from zero vs half to even).
    const float offsets[] = {0.0f, 0.25f, 0.5f, 0.5f + 1.0f / 512.0f, 0.5f - 1.0f / 512.0f, 0.75f, 1.0f / 512.0f};
    for (bool coplanar : {true, false}) {
        out.push_back({std::string("linear.rect.subpixel_") + (coplanar ? "coplanar" : "not_coplanar"),
                       [=] {
                           Draw d;
                           d.frag = Frag::kColorSum;
                           uint32_t k = 0;
                           for (int j = 0; j < 7; ++j)
                               for (int i = 0; i < 7; ++i, ++k) {
                                   const float x = 2.0f + 18.0f * i + offsets[(i + j) % 7];
                                   const float y = 2.0f + 18.0f * j + offsets[(i * 3 + j) % 7];
                                   const float x1 = x + 5.0f + offsets[(i + 2 * j + 1) % 7] + float(i % 3) * 3.0f;
                                   const float y1 = y + 4.0f + offsets[(2 * i + j + 2) % 7] + float(j % 3) * 3.0f;
                                   push_rect(d, x, y, x1, y1, k * 7 + 3, coplanar, k);
                               }
                           return bgra(d, 128, 128);
                       },
                       nullptr, note});
    }
    // Every vertex/triangle order of the pair (64 kinds), one big rectangle each, drawn over each other with
    // blending so every rectangle shows; and the same under each cull mode and front face.
    const VkCullModeFlags culls[] = {VK_CULL_MODE_NONE, VK_CULL_MODE_BACK_BIT, VK_CULL_MODE_FRONT_BIT,
                                     VK_CULL_MODE_FRONT_AND_BACK};
    const char* cull_names[] = {"none", "back", "front", "both"};
    for (int c = 0; c < 4; ++c) {
        for (VkFrontFace ff : {VK_FRONT_FACE_COUNTER_CLOCKWISE, VK_FRONT_FACE_CLOCKWISE}) {
            if (c == 0 && ff == VK_FRONT_FACE_CLOCKWISE) continue;
            out.push_back(
                {std::string("linear.rect.orders_cull_") + cull_names[c] + (ff == VK_FRONT_FACE_CLOCKWISE ? "_cw" : ""),
                 [=] {
                     Scene s = bgra(Draw{}, 128, 128);
                     s.draws.clear();
                     for (uint32_t kind = 0; kind < 64; ++kind) {
                         Draw d;
                         d.frag = Frag::kColorSum;
                         d.cull = culls[c];
                         d.front_face = ff;
                         d.blend = additive();
                         const uint32_t column = kind % 8, row = kind / 8;
                         const float x = 1.5f + float(column) * 15.75f, y = 1.25f + float(row) * 15.5f;
                         push_rect(d, x, y, x + 13.5f + 1.0f / 512.0f, y + 12.5f, kind, kind % 5 != 4, kind);
                         for (Vertex& v : d.vertices)
                             for (float& ch : v.color) ch *= 0.25f;
                         s.draws.push_back(d);
                     }
                     return s;
                 },
                 nullptr, note});
        }
    }
    // Partly off-screen rectangles: their batch takes draw's pipeline (vertices outside the viewport), the
    // clipper re-emits them inside the guard band and the vbuf hands them to setup as one indexed list; those
    // crossing the guard band are cut into non-rectangles.
    for (bool cut : {false, true}) {
        out.push_back({std::string("linear.rect.off_screen") + (cut ? "_guard_band_cut" : ""),
                       [=] {
                           Draw d;
                           d.frag = Frag::kColorSum;
                           constexpr float t = 0.5f + 1.0f / 512.0f;  // a tie of the two snap roundings
                           const float r[][4] = {
                               {-20.25f, 10.0f + t, 30.0f + t, 40.5f},  {100.0f + t, -8.75f, 140.25f, 30.0f + t},
                               {60.0f + t, 110.0f + t, 90.75f, 150.5f}, {-30.0f, -20.0f, 12.0f + t, 9.0f + t},
                               {-100.0f, 60.0f, 20.0f + t, 80.0f},      {120.0f, 70.0f + t, 300.0f, 90.0f}};
                           for (uint32_t k = 0; k < (cut ? 6u : 4u); ++k)
                               push_rect(d, r[k][0], r[k][1], r[k][2], r[k][3], k * 11, true, k);
                           return bgra(d, 128, 128);
                       },
                       nullptr, note});
    }
    out.push_back({"linear.rect.off_screen_odd_count",
                   [] {
                       Draw d;
                       d.frag = Frag::kColorSum;
                       push_rect(d, -20.25f, 10.5f, 30.0f, 40.5f, 3, true, 1);
                       push_rect(d, 100.5f, 60.75f, 140.25f, 90.0f, 17, true, 2);
                       d.vertices.push_back(at(10, 100, {0.5f, 0, 0, 0.5f}));  // a lone triangle: 15 vertices
                       d.vertices.push_back(at(-30, 120, {0, 0.5f, 0, 0.5f}));
                       d.vertices.push_back(at(40, 126, {0, 0, 0.5f, 0.5f}));
                       return bgra(d, 128, 128);
                   },
                   nullptr, note});
    // Strips of rectangles (pairs of consecutive strip triangles) and 4-vertex fans.
    out.push_back({"linear.rect.strip_column",
                   [] {
                       Draw d;
                       d.frag = Frag::kColorSum;
                       d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
                       for (int i = 0; i < 9; ++i) {
                           const float y = 3.25f + 13.25f * float(i) + (i % 2 ? 0.25f + 1.0f / 512.0f : 0.0f);
                           const float x0 = 20.5f + 1.0f / 512.0f, x1 = 90.5f + 1.0f / 512.0f;
                           d.vertices.push_back(at(x0, y, affine(x0, y, 1)));
                           d.vertices.push_back(at(x1, y, affine(x1, y, 1)));
                       }
                       d.vertices[7].color[0] += 0.125f;  // one pair not coplanar: the pairing shifts by one
                       return bgra(d, 128, 128);
                   },
                   nullptr, note});
    for (int order = 0; order < 4; ++order) {
        out.push_back({"linear.rect.fan4_" + std::to_string(order),
                       [=] {
                           Draw d;
                           d.frag = Frag::kColorSum;
                           d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
                           constexpr float t = 1.0f / 512.0f;
                           const float xs[4] = {10.5f + t, 100.5f + t, 100.5f + t, 10.5f + t};
                           const float ys[4] = {20.5f + t, 20.5f + t, 90.5f + t, 90.5f + t};
                           for (int i = 0; i < 4; ++i) {
                               const int j = (order & 2) ? (order + 4 - i) % 4 : (i + order) % 4;
                               d.vertices.push_back(at(xs[j], ys[j], affine(xs[j], ys[j], uint32_t(order))));
                           }
                           return bgra(d, 128, 128);
                       },
                       nullptr, note});
    }
    // Equal w (perspective attributes divided by one w) and unequal w (not a rectangle: triangles).
    for (bool equal_w : {true, false}) {
        out.push_back({std::string("linear.rect.w_") + (equal_w ? "equal" : "unequal"),
                       [=] {
                           Draw d;
                           d.frag = Frag::kColorSum;
                           push_rect(d, 10.25f, 12.5f, 70.5f + 1.0f / 512.0f, 60.0f, 0, true, 3, 2.0f);
                           push_rect(d, 30.5f, 70.25f, 120.0f, 126.5f, 9, true, 4, 0.5f);
                           if (!equal_w) d.vertices[4].pos[3] *= 1.0f + 1.0f / 1024.0f;
                           return bgra(d, 128, 128);
                       },
                       nullptr, note});
    }
    out.push_back({"linear.rect.scissor",
                   [] {
                       Draw d;
                       d.frag = Frag::kColorSum;
                       d.scissor = VkRect2D{{13, 5}, {70, 61}};
                       push_rect(d, 2.5f, 3.75f, 120.5f + 1.0f / 512.0f, 16.5f + 1.0f / 512.0f, 5, true, 5);
                       return bgra(d, 128, 128);
                   },
                   nullptr, note});
}

// linear.shade.*: llvmpipe's 8-bit linear shading.
// A case table (over 150 lines): one entry per case, in groups under their comments, sharing the scene builders
// and constants declared at its top.
void add_shade_cases(CaseList& out) {
    const char* note = "bgra-linear-path";
    // linear.shade.*: llvmpipe's linear shading (lp_linear.c, lp_linear_interp.c) of bins holding only rectangles,
    // whole-tile triangle commands and clears, for the pass-through shader (o_color = v_color): 1.15 fixed-point
    // interpolation from each region's origin, truncated to 0.8. Where a region's colours leave [0, 1] or w varies,
    // llvmpipe falls back to its general shader; tiles with a partial triangle command use the general rasterizer.
    auto shade_case = [&](const std::string& name, std::function<Scene()> make) {
        out.push_back({"linear.shade." + name, std::move(make), nullptr, note});
    };
    shade_case("rects", [] {
        Draw d;
        uint32_t k = 0;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i, ++k) {
                const float x = 1.5f + 31.0f * i + (k % 3) * 0.25f, y = 2.25f + 30.5f * j + (k % 2) * 0.5f;
                push_rect(d, x, y, x + 9.0f + 7.5f * float(k % 4), y + 11.0f + 6.25f * float(k % 3), k * 5 + 1, true,
                          k);
            }
        push_rect(d, 20.5f, 30.25f, 110.75f, 100.5f + 1.0f / 512.0f, 3, true, 7);  // spans four tiles
        return bgra(d, 128, 128);
    });
    shade_case("rect_tiles_and_edges", [] {
        Draw d;
        // whole tiles, partial tiles and the framebuffer's partial edge tiles (160x120)
        push_rect(d, 3.25f, 5.5f, 157.5f, 117.75f, 0, true, 2);
        return bgra(d, 160, 120);
    });
    shade_case("rect_colour_out_of_range", [] {
        Draw d;
        const float xs[4] = {4.5f, 120.5f, 120.5f, 4.5f}, ys[4] = {6.5f, 6.5f, 121.5f, 121.5f};
        // red runs from -0.25 to 1.25 across the rectangle: corner checks fail in the outer tiles only
        const std::array<float, 4> c[4] = {
            {-0.25f, 0.5f, 0.25f, 1}, {1.25f, 0.5f, 0.25f, 1}, {1.25f, 0.75f, 0.25f, 1}, {-0.25f, 0.75f, 0.25f, 1}};
        for (int t : {0, 1, 2, 0, 2, 3}) d.vertices.push_back(at(xs[t], ys[t], c[t]));
        return bgra(d, 128, 128);
    });
    for (float w : {2.0f, 0.75f}) {
        for (Interp in : {Interp::kSmooth, Interp::kNoPerspective}) {
            shade_case(std::string("rect_w") + (w == 2.0f ? "2" : "0.75") +
                           (in == Interp::kSmooth ? "_perspective" : "_noperspective"),
                       [=] {
                           Draw d;
                           d.interp = in;
                           push_rect(d, 6.5f, 9.25f, 121.75f, 119.5f, 4, true, 4, w);
                           return bgra(d, 128, 128);
                       });
        }
    }
    shade_case("big_triangles", [] {
        Draw d;
        d.vertices = {at(-40.0f, -20.0f, {0.1f, 0.2f, 0.9f, 1}),   at(250.0f, 10.0f, {0.9f, 0.3f, 0.1f, 1}),
                      at(20.0f, 210.0f, {0.3f, 0.8f, 0.5f, 0.6f}), at(180.5f, 60.25f, {0.2f, 0.2f, 0.2f, 1}),
                      at(240.0f, 190.0f, {0.7f, 0.9f, 0.1f, 1}),   at(60.0f, 180.5f, {0.5f, 0.1f, 0.7f, 1})};
        return bgra(d, 256, 192);
    });
    shade_case("fullscreen_triangle", [] {
        Draw d;
        d.vertices = {vtx(-1, -1, 0.5f, 1, {0.1f, 0.2f, 0.3f, 1}), vtx(3, -1, 0.5f, 1, {0.9f, 0.2f, 0.3f, 1}),
                      vtx(-1, 3, 0.5f, 1, {0.1f, 0.8f, 0.3f, 1})};
        return bgra(d, 200, 150);
    });
    shade_case("fullscreen_strip", [] {
        Draw d;
        d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        d.vertices = {vtx(-1, -1, 0.5f, 1, {0.1f, 0.2f, 0.3f, 1}), vtx(1, -1, 0.5f, 1, {0.9f, 0.2f, 0.3f, 1}),
                      vtx(-1, 1, 0.5f, 1, {0.1f, 0.8f, 0.3f, 1}), vtx(1, 1, 0.5f, 1, {0.9f, 0.8f, 0.3f, 1})};
        return bgra(d, 200, 150);
    });
    shade_case("triangles_unequal_w", [] {
        Draw d;
        d.vertices = {vtx(-1.5f, -1.2f, 0.5f, 1.0f, {0.1f, 0.2f, 0.9f, 1}),
                      vtx(1.8f, -1.0f, 0.5f, 2.0f, {0.9f, 0.3f, 0.1f, 1}),
                      vtx(-0.2f, 1.9f, 0.5f, 1.5f, {0.3f, 0.8f, 0.5f, 1})};
        return bgra(d, 200, 150);
    });
    shade_case("scissored_triangles", [] {
        // w = 1 (a 2D scene): whole-tile commands inside the scissor, scissor planes make the tiles it cuts partial
        Draw d;
        d.vertices = {at(-30.0f, 5.0f, {0.1f, 0.2f, 0.9f, 1}),   at(240.0f, -12.0f, {0.9f, 0.3f, 0.1f, 1}),
                      at(120.0f, 200.0f, {0.3f, 0.8f, 0.5f, 1}), at(10.0f, 100.0f, {0.6f, 0.6f, 0.1f, 0.5f}),
                      at(250.0f, 130.0f, {0.2f, 0.9f, 0.9f, 1}), at(50.0f, 190.0f, {0.8f, 0.1f, 0.4f, 1})};
        d.scissor = VkRect2D{{37, 21}, {150, 140}};
        return bgra(d, 256, 192);
    });
    shade_case("rects_and_triangles", [] {
        // a rectangle over tiles that a later small triangle partly covers: those bins use the general path
        Scene s = bgra(Draw{}, 192, 128);
        s.draws.clear();
        Draw a;
        push_rect(a, 2.5f, 3.5f, 190.25f, 125.75f, 2, true, 9);
        Draw b;
        b.vertices = {at(70.0f, 70.0f, {1, 0, 0, 1}), at(90.0f, 75.0f, {0, 1, 0, 1}), at(80.0f, 100.0f, {0, 0, 1, 1})};
        Draw c;
        push_rect(c, 130.5f, 10.5f, 180.0f, 60.0f, 9, true, 3);
        s.draws = {a, b, c};
        return s;
    });
    // Blending and write masks in the linear variant: lp_build_blend_aos on the 8-bit interpolants.
    const VkPipelineColorBlendAttachmentState blends[] = {
        {VK_TRUE, VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD, VK_BLEND_FACTOR_ONE,
         VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_OP_ADD, 0xF},
        additive(),
        {VK_TRUE, VK_BLEND_FACTOR_CONSTANT_COLOR, VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR, VK_BLEND_OP_REVERSE_SUBTRACT,
         VK_BLEND_FACTOR_DST_ALPHA, VK_BLEND_FACTOR_ZERO, VK_BLEND_OP_MAX, 0xF},
        {VK_FALSE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO, VK_BLEND_OP_ADD, VK_BLEND_FACTOR_ONE,
         VK_BLEND_FACTOR_ZERO, VK_BLEND_OP_ADD, VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_B_BIT},
    };
    const char* blend_names[] = {"blend_alpha", "blend_additive", "blend_constant_revsub_max", "write_mask_rb"};
    for (int bi = 0; bi < 4; ++bi) {
        shade_case(blend_names[bi], [=] {
            // 256x256 target: a background rectangle, a blended rectangle and a blended triangle inside the guard
            // band (whole-tile commands near the origin, partial ones along its long edge)
            Scene s = bgra(Draw{}, 256, 256);
            s.draws.clear();
            Draw a;
            push_rect(a, 1.5f, 2.5f, 254.25f, 253.5f, 2, true, 6, 1.0f, true);
            Draw b;
            b.blend = blends[bi];
            b.blend_constants[0] = 0.25f;
            b.blend_constants[1] = 0.5f;
            b.blend_constants[2] = 0.75f;
            b.blend_constants[3] = 0.6f;
            push_rect(b, 20.5f, 10.25f, 210.0f, 150.5f, 5, true, 11, 1.0f, true);
            Draw c = b;
            c.vertices = {vtx(-1.9375f, -1.9375f, 0.5f, 1, {0.9f, 0.1f, 0.4f, 0.7f}),
                          vtx(1.96875f, -1.9375f, 0.5f, 1, {0.2f, 0.7f, 0.4f, 0.3f}),
                          vtx(-1.9375f, 1.9375f, 0.5f, 1, {0.5f, 0.5f, 0.9f, 0.5f})};
            s.draws = {a, b, c};
            return s;
        });
    }
    // Other members of the class: constants (float_to_ubyte) and a constant alpha. (Swizzles are not modelled:
    // lavapipe renders o = v_color.bgra as v_color.rgba there; rast/geometry/README.md.)
    const Frag frags[] = {Frag::kConstant, Frag::kColorRgb1};
    const char* frag_names[] = {"constant", "rgb1"};
    for (int fi = 0; fi < 2; ++fi) {
        shade_case(std::string("shader_") + frag_names[fi], [=] {
            Scene s = bgra(Draw{}, 256, 256);
            s.draws.clear();
            Draw a;
            a.frag = frags[fi];
            push_rect(a, 1.5f, 2.5f, 254.25f, 253.5f, 2, true, 6, 1.0f, true);
            Draw c = a;
            c.blend = blends[0];
            c.vertices = {vtx(-1.9375f, -1.9375f, 0.5f, 1, {0.9f, 0.1f, 0.4f, 0.7f}),
                          vtx(1.96875f, -1.9375f, 0.5f, 1, {0.2f, 0.7f, 0.4f, 0.3f}),
                          vtx(-1.9375f, 1.9375f, 0.5f, 1, {0.5f, 0.5f, 0.9f, 0.5f})};
            s.draws = {a, c};
            return s;
        });
    }
}

// 4-vertex fans through rect() in any mode, and a guard-band frame with depth (no linear mode).
void add_fan_cases(CaseList& out) {
    // Any mode: a non-indexed 4-vertex fan without flat inputs reaches llvmpipe's setup through rect() as
    // (v0, v1, v2), (v0, v2, v3), not in the fan's provoking order (v1, v2, v0), (v2, v3, v0): the attribute
    // planes are set up from another first vertex. With a flat input the fan order stays.
    for (Interp in : {Interp::kSmooth, Interp::kFlat}) {
        out.push_back({std::string("quirks.fan4.rgba_") + (in == Interp::kFlat ? "flat" : "smooth"),
                       [=] {
                           Draw d;
                           d.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN;
                           d.interp = in;
                           d.vertices = {at(7.3f, 11.9f, {0.91f, 0.13f, 0.27f, 1}),
                                         at(117.1f, 3.7f, {0.07f, 0.83f, 0.41f, 1}),
                                         at(121.9f, 97.3f, {0.33f, 0.29f, 0.97f, 1}),
                                         at(13.1f, 123.7f, {0.61f, 0.71f, 0.03f, 1})};
                           Scene s = one_draw(d, 128, 128);
                           return s;
                       },
                       nullptr, ""});
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

}  // namespace

void add_linear_cases(CaseList& out) {
    add_guard_band_cases(out);
    add_rect_cases(out);
    add_shade_cases(out);
    add_fan_cases(out);
}

}  // namespace tilevk::cts
