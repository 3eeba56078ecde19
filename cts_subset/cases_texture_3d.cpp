// texture.3d.*: sampler3D — nearest and trilinear filtering, the r axis's address modes (alone and mixed with
// other s/t modes, which moves lavapipe between its 8-bit and float filters), mip selection with 3D derivatives,
// LOD bias, textureLod, textureGrad, texelFetch inside and outside the levels, textureSize and textureQueryLevels
// (textureOffset on 3D is refused: shader/README.md "3D images"). The 3D texel encodes its coordinates and level
// (render_objects.cpp texel_3d); the targets are RGBA32F, so every float of the filter shows.
#include "texture_case.hpp"

namespace tilevk::cts {
namespace {

// The quad over the target with r = v_color.x across it, another plane than s's and t's; `body` computes vec4
// `o_color` from `tex` (sampler3D) and `p` = (v_uv, v_color.x).
Scene textured_3d(const TextureSpec& t, const std::string& body, const QuadUv& q) {
    const float du = q.u1 - q.u0, u0 = q.u0;
    const Draw d = textured_quad(t, q, {0.1f * du + u0, 0.8f * du + u0, -0.35f * du + u0, 0.45f * du + u0});
    return textured_nd(d, "sampler3D", "    vec3 p = vec3(v_uv, v_color.x);\n" + body);
}

void add_wrap_cases(CaseList& out) {
    for (const WrapMode& w : kWrapModes)
        for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
            const std::string fname = f == VK_FILTER_NEAREST ? "_nearest" : "_linear";
            TextureSpec t;
            t.width = 8, t.height = 8, t.depth = 8;
            t.wrap = w.mode;
            t.mag = t.min = f;
            t.border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
            out.push_back(textured_case(std::string("texture.3d.wrap.") + w.name + fname, textured_3d, t,
                                        "    o_color = texture(tex, p);\n", {-1.25f, 2.5f}));
            // the r axis alone in this mode, s and t in another (the 8-bit filter needs every axis REPEAT or
            // CLAMP_TO_EDGE); a size that is not a power of two on every axis
            TextureSpec m = t;
            m.width = 6, m.height = 5, m.depth = 3;
            m.wrap = w.mode == VK_SAMPLER_ADDRESS_MODE_REPEAT ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
                                                              : VK_SAMPLER_ADDRESS_MODE_REPEAT;
            m.wrap_w = w.mode;
            out.push_back(textured_case(std::string("texture.3d.wrap_r.") + w.name + fname + "_npot", textured_3d, m,
                                        "    o_color = texture(tex, p * 1.7 - 0.4);\n", {-1.25f, 2.5f}));
        }
}

void add_mip_cases(CaseList& out) {
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR})
        for (VkSamplerMipmapMode m : {VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_MIPMAP_MODE_LINEAR})
            for (VkSamplerAddressMode wrap :
                 {VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT}) {
                TextureSpec t;
                t.width = 32, t.height = 32, t.depth = 16;
                t.mip_levels = 6;
                t.min = t.mag = f;
                t.mip_mode = m;
                t.wrap = wrap;
                const std::string name = std::string("texture.3d.mipmap.min_") +
                                         (f == VK_FILTER_NEAREST ? "nearest" : "linear") + "_mip_" +
                                         (m == VK_SAMPLER_MIPMAP_MODE_NEAREST ? "nearest" : "linear") +
                                         (wrap == VK_SAMPLER_ADDRESS_MODE_REPEAT ? "" : "_mirrored");
                // r changing faster than s and t: the depth term decides the LOD in part of the quad
                out.push_back(textured_case(
                    name, textured_3d, t, "    o_color = texture(tex, vec3(p.xy, p.z * 9.0));\n", {0.0f, 1.0f, 0.4f}));
                out.push_back(textured_case(name + "_projected", textured_3d, t,
                                            "    o_color = textureProj(tex, vec4(p * 2.0, 2.0));\n",
                                            {0.0f, 4.0f, 1.0f, true}));
                // a shader LOD bias; with mip NEAREST lavapipe then takes fast_log2 where tilevk takes log2 (a known
                // difference of every dimension, shader/README.md), so LINEAR only
                if (m == VK_SAMPLER_MIPMAP_MODE_LINEAR)
                    out.push_back(textured_case(name + "_bias", textured_3d, t,
                                                "    o_color = texture(tex, p, v_uv.x * 3.0 - 1.2);\n",
                                                {0.0f, 1.0f, 0.6f}));
            }
}

void add_explicit_cases(CaseList& out) {
    TextureSpec t;
    t.width = 16, t.height = 8, t.depth = 32;
    t.mip_levels = 5;
    t.min = t.mag = VK_FILTER_LINEAR;
    t.mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    t.wrap = VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    t.wrap_w = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    out.push_back(
        textured_case("texture.3d.lod", textured_3d, t, "    o_color = textureLod(tex, p, v_uv.x * 5.0 - 0.5);\n"));
    out.push_back(textured_case("texture.3d.grad", textured_3d, t,
                                "    o_color = textureGrad(tex, p, vec3(v_uv.x * 0.2, 0.01, v_uv.y * 0.3),"
                                " vec3(0.02, v_uv.y * 0.1, 0.05));\n"));
    // texelFetch: levels 0..2 across the target, coordinates running past every edge of each level (outside: 0)
    out.push_back(textured_case("texture.3d.texel_fetch", textured_3d, t,
                                "    ivec2 f = ivec2(gl_FragCoord.xy);\n"
                                "    ivec3 c = ivec3(f.x % 20 - 2, f.y % 12 - 2, (f.x + 3 * f.y) % 36 - 2);\n"
                                "    o_color = texelFetch(tex, c, f.x / 24);\n"));
    // textureSize with a constant LOD: lavapipe answers a whole vector from its first lane's LOD
    // (lp_build_size_query_soa, "FIXME: this needs to honor per-element lod")
    out.push_back(textured_case("texture.3d.size_and_levels", textured_3d, t,
                                "    o_color = vec4(textureSize(tex, 1), textureQueryLevels(tex)) * 100.0 +"
                                " vec4(textureSize(tex, 4), 0.0);\n"));
}

}  // namespace

void add_texture_3d_cases(CaseList& out) {
    add_wrap_cases(out);
    add_mip_cases(out);
    add_explicit_cases(out);
}

}  // namespace tilevk::cts
