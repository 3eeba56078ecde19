// Helpers shared by the texture case tables (cases_texture*.cpp): the textured quad and the address-mode table.
#pragma once

#include <array>
#include <string>

#include "case.hpp"

namespace tilevk::cts {

// Where the quad stands and what it samples: v_uv runs from u0 to u1 in both directions over [-x_scale, x_scale]^2;
// `projected` gives its right edge w = 3, a perspective tilt that makes the derivatives vary across it.
struct QuadUv {
    float u0 = 0.0f, u1 = 1.0f, x_scale = 1.0f;
    bool projected = false;
};

// The quad as two triangles (a b c, a c e) drawing `t` with the texture fragment stage; `color_x` is v_color.x at
// the corners a, b, c, e (bottom left, bottom right, top right, top left).
inline Draw textured_quad(const TextureSpec& t, const QuadUv& q, std::array<float, 4> color_x = {1, 1, 1, 1}) {
    Draw d;
    d.frag = Frag::kTexture;
    d.texture = t;
    const float s = q.x_scale, wl = 1.0f, wr = q.projected ? 3.0f : 1.0f;
    Vertex a = vtx(-s, -s, 0, wl), b = vtx(s, -s, 0, wr), c = vtx(s, s, 0, wr), e = vtx(-s, s, 0, wl);
    a.uv[0] = q.u0, a.uv[1] = q.u0;
    b.uv[0] = q.u1, b.uv[1] = q.u0;
    c.uv[0] = q.u1, c.uv[1] = q.u1;
    e.uv[0] = q.u0, e.uv[1] = q.u1;
    a.color[0] = color_x[0], b.color[0] = color_x[1], c.color[0] = color_x[2], e.color[0] = color_x[3];
    d.vertices = {a, b, c, a, c, e};
    return d;
}

// One draw of `d` into a 64x64 RGBA32F target (every float of the filter shows) with a fragment shader whose
// `main` is `body`, reading `tex`, a uniform of GLSL type `sampler` at set 0, binding 0.
inline Scene textured_nd(Draw d, const char* sampler, const std::string& body) {
    d.fragment_glsl = std::string(
                          "#version 450\n"
                          "layout(location=0) in vec4 v_color;\n"
                          "layout(location=1) in vec2 v_uv;\n"
                          "layout(location=0) out vec4 o_color;\n"
                          "layout(set=0, binding=0) uniform ") +
                      sampler + " tex;\nvoid main() {\n" + body + "}\n";
    Scene s = one_draw(d, 64, 64);
    s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
    return s;
}

// A case of the scene `build(t, body, q)`: one textured quad whose fragment shader runs `body`.
using TexturedScene = Scene (*)(const TextureSpec& t, const std::string& body, const QuadUv& q);
inline Case textured_case(std::string name, TexturedScene build, const TextureSpec& t, const std::string& body,
                          QuadUv q = {}) {
    return {std::move(name), [=] { return build(t, body, q); }, nullptr, ""};
}

// The address modes every texture dimension takes (texture.wrap.* adds MIRROR_CLAMP_TO_EDGE).
struct WrapMode {
    const char* name;
    VkSamplerAddressMode mode;
};
inline constexpr WrapMode kWrapModes[] = {{"repeat", VK_SAMPLER_ADDRESS_MODE_REPEAT},
                                          {"mirrored_repeat", VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT},
                                          {"clamp_to_edge", VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE},
                                          {"clamp_to_border", VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER}};

}  // namespace tilevk::cts
