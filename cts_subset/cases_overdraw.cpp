// overdraw.*: full-screen layers drawn over earlier geometry. llvmpipe drops a tile's earlier commands when an
// opaque triangle covers the whole tile (lp_setup_whole_tile), and tilevk's tile loop starts at such a command
// (rast/README, "Occlusion"); these cases check that nothing visible is lost that way, and that every state which
// forbids it (blending, a write mask, discard, a scissor, a query, a depth buffer, 4x) keeps the earlier layers.
// The targets are RGBA8 (not lavapipe's linear path) of 200x150: several tiles, partial tiles at the right and
// bottom edges.
#include <random>

#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kW = 200, kH = 150;

// 60 random triangles in random colours, some across tile borders.
Draw background(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.1f, 1.1f), col(0.0f, 1.0f), off(-0.4f, 0.4f);
    Draw d;
    for (int t = 0; t < 60; ++t) {
        const float cx = pos(rng), cy = pos(rng);
        for (int k = 0; k < 3; ++k)
            d.vertices.push_back(vtxc(cx + off(rng), cy + off(rng), {col(rng), col(rng), col(rng), 1}));
    }
    return d;
}

// A full-screen quad (two triangles) with perspective (w per side) and texture coordinates over [0, 4].
Draw layer(float w_left, float w_right, Frag frag, std::array<float, 4> c = {0.9f, 0.6f, 0.3f, 0.7f}) {
    Draw d;
    d.frag = frag;
    Vertex a = vtx(-1, -1, 0, w_left, c), b = vtx(1, -1, 0, w_right, c), e = vtx(1, 1, 0, w_right, c),
           f = vtx(-1, 1, 0, w_left, c);
    a.uv[0] = 0, a.uv[1] = 0;
    b.uv[0] = 4, b.uv[1] = 0;
    e.uv[0] = 4, e.uv[1] = 4;
    f.uv[0] = 0, f.uv[1] = 4;
    d.vertices = {a, b, e, a, e, f};
    if (frag == Frag::kTexture) {
        TextureSpec t;
        t.width = t.height = 64;
        t.mip_levels = 7;
        t.pattern = TexPattern::kGradient;
        t.mag = t.min = VK_FILTER_LINEAR;
        t.mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
        d.texture = t;
    }
    return d;
}

// background, three opaque textured layers, then `last` (and small triangles over it when `tail`)
Scene layers(const Draw& last, bool tail = true) {
    Scene s = one_draw(background(11), kW, kH);
    s.draws.push_back(layer(1, 3, Frag::kTexture));
    s.draws.push_back(layer(3, 1, Frag::kColor));
    s.draws.push_back(layer(1.5f, 2, Frag::kTexture));
    s.draws.push_back(last);
    if (tail) s.draws.push_back(background(12));
    return s;
}

}  // namespace

void add_overdraw_cases(CaseList& out) {
    // Hidden: the constant layer replaces everything before it (and nothing follows).
    out.push_back({"overdraw.opaque_constant_last", [] { return layers(layer(1, 1, Frag::kConstant), false); },
                   palette_only({rgba8(128, 64, 204, 191)}), ""});
    out.push_back({"overdraw.opaque_textured", [] { return layers(layer(2, 1, Frag::kTexture)); }, nullptr, ""});
    // Not hidden: each of these keeps the earlier layers visible or counted.
    out.push_back({"overdraw.blended_last",
                   [] {
                       Draw d = layer(1, 2, Frag::kColor);
                       d.blend = alpha_over();
                       return layers(d);
                   },
                   nullptr, ""});
    out.push_back({"overdraw.write_mask_last",
                   [] {
                       Draw d = layer(1, 1, Frag::kConstant);
                       d.blend.colorWriteMask =
                           VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT;
                       return layers(d, false);
                   },
                   nullptr, ""});
    out.push_back({"overdraw.discard_last", [] { return layers(layer(1, 2, Frag::kDiscard)); }, nullptr, ""});
    out.push_back({"overdraw.scissored_last",
                   [] {
                       Draw d = layer(1, 1, Frag::kConstant);
                       d.scissor = VkRect2D{{37, 21}, {130, 100}};
                       return layers(d, false);
                   },
                   nullptr, ""});
    out.push_back({"overdraw.query_across_pass",
                   [] {
                       Scene s = layers(layer(1, 1, Frag::kConstant), false);
                       s.queries = QueryMode::kAcrossPass;
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"overdraw.with_depth_buffer",
                   [] {
                       Scene s = layers(layer(1, 1, Frag::kConstant));
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       s.draws[0].depth_test = s.draws[0].depth_write = true;
                       s.draws[0].depth_op = VK_COMPARE_OP_ALWAYS;
                       s.draws.back().depth_test = true;
                       s.draws.back().depth_op = VK_COMPARE_OP_LESS_OR_EQUAL;
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"overdraw.msaa4",
                   [] {
                       Scene s = layers(layer(1, 2, Frag::kTexture));
                       s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                       return s;
                   },
                   nullptr, ""});
}

}  // namespace tilevk::cts
