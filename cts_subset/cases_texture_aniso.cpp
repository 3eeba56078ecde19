// texture.aniso.*: samplerAnisotropy, judged byte for byte against lavapipe's elliptical filter
// (docs/lavapipe-rules.md §10 "Anisotropy"): textured quads squeezed or tilted so that the footprint is an ellipse,
// with several maxAnisotropy values (lavapipe's filter depends on it only through "above 1"), one level or a mip
// chain, NEAREST and LINEAR filters (the probes are nearest lookups either way), into a float target.
#include "texture_case.hpp"

namespace tilevk::cts {

namespace {

TextureSpec aniso_texture(float max_aniso, VkFilter f, bool mips, TexPattern p) {
    TextureSpec t;
    t.pattern = p;
    t.width = t.height = 64;
    t.mip_levels = mips ? 7 : 1;
    t.mag = t.min = f;
    t.mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    t.max_anisotropy = max_aniso;
    return t;
}

Scene quad(const TextureSpec& t, const QuadUv& q) {
    Scene s = one_draw(textured_quad(t, q), 64, 64);
    s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
    return s;
}

// One textured quad whose fragment shader runs `body` on sampler2D `tex` (textureLod, textureGrad, bias, gather).
Scene quad_body(const TextureSpec& t, const std::string& body, const QuadUv& q) {
    return textured_nd(textured_quad(t, q), "sampler2D", body);
}

}  // namespace

void add_texture_aniso_cases(CaseList& out) {
    struct Shape {
        const char* name;
        QuadUv q;
    };
    // squeezed: u and v both run 0..2 over a quad 0.3 wide, so d/dx is 3.3 times d/dy; tilted: the perspective quad
    // (right edge w = 3) over 0..4 repeats, footprints stretched along its depth
    const Shape shapes[] = {{"squeezed", {0.0f, 2.0f, 0.3f, false}}, {"tilted", {0.0f, 4.0f, 1.0f, true}}};
    for (float n : {2.0f, 4.0f, 16.0f})
        for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR})
            for (bool mips : {false, true})
                for (const Shape& sh : shapes) {
                    const TextureSpec t = aniso_texture(n, f, mips, TexPattern::kGradient);
                    const std::string name = "texture.aniso.x" + std::to_string(int(n)) +
                                             (f == VK_FILTER_NEAREST ? "_nearest" : "_linear") +
                                             (mips ? "_mips_" : "_one_level_") + sh.name;
                    out.push_back({name, [=] { return quad(t, sh.q); }, nullptr, ""});
                }
    // the checker under the address modes (probes past the edge wrap or read the border like any nearest lookup),
    // at maxAnisotropy 2.5, which lavapipe truncates to 2, and at 1.5, truncated to 1: no anisotropy at all
    for (const WrapMode& w : kWrapModes) {
        TextureSpec t = aniso_texture(2.5f, VK_FILTER_LINEAR, true, TexPattern::kChecker);
        t.wrap = w.mode;
        t.border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
        out.push_back({std::string("texture.aniso.x2_5_checker_") + w.name,
                       [=] {
                           return quad(t, {-0.7f, 2.6f, 1.0f, true});
                       },
                       nullptr, ""});
    }
    const TextureSpec t15 = aniso_texture(1.5f, VK_FILTER_LINEAR, true, TexPattern::kChecker);
    out.push_back({"texture.aniso.x1_5_is_not_anisotropic",
                   [=] {
                       return quad(t15, {-0.7f, 2.6f, 1.0f, true});
                   },
                   nullptr, ""});
    // the LOD operands: explicit (the filter still takes the quad's differences), bias, gradients, and a gather
    // (lavapipe's anisotropic filter replaces it, at the first level)
    struct Body {
        const char* name;
        const char* glsl;
    };
    const Body bodies[] = {{"lod", "o_color = textureLod(tex, v_uv, 1.7);\n"},
                           {"bias", "o_color = texture(tex, v_uv, -1.3);\n"},
                           {"grad", "o_color = textureGrad(tex, v_uv, vec2(0.05, 0.0), vec2(0.0, 0.01));\n"},
                           {"gather", "o_color = textureGather(tex, v_uv, 1);\n"}};
    for (const Body& b : bodies) {
        const TextureSpec t = aniso_texture(8.0f, VK_FILTER_LINEAR, true, TexPattern::kGradient);
        out.push_back(
            textured_case(std::string("texture.aniso.x8_") + b.name, quad_body, t, b.glsl, {0.0f, 4.0f, 1.0f, true}));
    }
}

}  // namespace tilevk::cts
