// api.smoke.*: the smallest frames that exercise the whole path (clear, one draw, read-back).
#include "case.hpp"

namespace tilevk::cts {

void add_api_cases(CaseList& out) {
    constexpr std::array<float, 4> kMagenta = {1, 0, 1, 1};
    // The CTS smoke triangle: magenta on (0.125, 0.25, 0.75); unorm8 of those is round(v*255) = 32, 64, 191.
    auto smoke = [=](VkFormat format) {
        Draw d;
        d.vertices = {vtxc(-0.5f, -0.5f, kMagenta), vtxc(0.5f, -0.5f, kMagenta), vtxc(0.0f, 0.5f, kMagenta)};
        Scene s = one_draw(d, 256, 256);
        s.target.color = format;
        float clear[4] = {0.125f, 0.25f, 0.75f, 1.0f};
        std::copy(clear, clear + 4, s.target.clear_color);
        return s;
    };
    uint32_t clear = rgba8(32, 64, 191, 255), magenta = rgba8(255, 0, 255, 255);
    out.push_back({"api.smoke.triangle", [=] { return smoke(VK_FORMAT_R8G8B8A8_UNORM); },
                   all_of({palette_only({clear, magenta}), pixel_is(128, 128, magenta), pixel_is(4, 4, clear),
                           band_of([=] { return smoke(VK_FORMAT_R8G8B8A8_UNORM); })}),
                   ""});
    // B8G8R8A8 with no depth attachment: lavapipe's linear rasterizer (lavapipe-rules §0.3/§8) may take this frame.
    out.push_back({"api.smoke.triangle_bgra_linear", [=] { return smoke(VK_FORMAT_B8G8R8A8_UNORM); },
                   all_of({palette_only({rgba8(191, 64, 32, 255), magenta}), pixel_is(128, 128, magenta)}),
                   "bgra-linear-path"});
    out.push_back({"api.smoke.clear_only",
                   [] {
                       Scene s;
                       float c[4] = {0.5f, 0.25f, 1.0f, 0.0f};
                       std::copy(c, c + 4, s.target.clear_color);
                       return s;
                   },
                   palette_only({rgba8(128, 64, 255, 0)}), ""});
    // An axis-aligned rectangle of constant 0.5: lavapipe's linear path shades it 127, the general path 128.
    auto rect = [](VkFormat format) {
        std::array<float, 4> half = {0.5f, 0.5f, 0.5f, 1.0f};
        Draw d;
        d.vertices = {vtxc(-0.5f, -0.5f, half), vtxc(0.5f, -0.5f, half), vtxc(0.5f, 0.5f, half),
                      vtxc(-0.5f, -0.5f, half), vtxc(0.5f, 0.5f, half),  vtxc(-0.5f, 0.5f, half)};
        Scene s = one_draw(d, 128, 128);
        s.target.color = format;
        return s;
    };
    out.push_back({"api.smoke.rect_rgba", [=] { return rect(VK_FORMAT_R8G8B8A8_UNORM); },
                   all_of({palette_only({0, rgba8(128, 128, 128, 255)}), pixel_is(64, 64, rgba8(128, 128, 128, 255))}),
                   ""});
    out.push_back(
        {"api.smoke.rect_bgra_linear", [=] { return rect(VK_FORMAT_B8G8R8A8_UNORM); }, nullptr, "bgra-linear-path"});
    out.push_back({"api.smoke.two_draws",
                   [] {
                       Draw a, b;
                       a.vertices = {vtxc(-1, -1, {1, 0, 0, 1}), vtxc(1, -1, {0, 1, 0, 1}), vtxc(-1, 1, {0, 0, 1, 1})};
                       b.vertices = {vtxc(1, 1, {1, 1, 0, 1}), vtxc(-1, 1, {0, 1, 1, 1}), vtxc(1, -1, {1, 0, 1, 1})};
                       Scene s = one_draw(a);
                       s.draws.push_back(b);
                       return s;
                   },
                   nullptr, ""});
    out.push_back({"api.smoke.depth_only",
                   [] {
                       Draw d;
                       d.depth_test = d.depth_write = true;
                       d.vertices = {vtx(-0.9f, -0.9f, 0.1f), vtx(0.9f, -0.7f, 0.5f), vtx(0.0f, 0.9f, 0.9f)};
                       Scene s = one_draw(d);
                       s.target.color = VK_FORMAT_UNDEFINED;
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   nullptr, ""});
}

}  // namespace tilevk::cts
