// texture.1d.*: VK_IMAGE_TYPE_1D images through 1D and 1D-array views — sampler1D / sampler1DArray with nearest and
// linear filters, every address mode, mip selection from 1D derivatives (lavapipe squares rho for 1D too),
// projection, LOD bias and explicit LOD, offsets, texelFetch inside and outside, textureSize and
// textureQueryLevels. The texels encode x, layer and level (render_objects.cpp); the targets are RGBA32F.
#include "texture_case.hpp"

namespace tilevk::cts {
namespace {

// The quad over the target; `body` computes `o_color` from `tex`.
Scene textured_1d(const TextureSpec& t, const std::string& body, const QuadUv& q) {
    return textured_nd(textured_quad(t, q), t.layers > 1 ? "sampler1DArray" : "sampler1D", body);
}

void add_filter_cases(CaseList& out) {
    for (const WrapMode& w : kWrapModes)
        for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
            const std::string fname = f == VK_FILTER_NEAREST ? "_nearest" : "_linear";
            TextureSpec t;
            t.one_d = true;
            t.width = 8;
            t.wrap = w.mode;
            t.mag = t.min = f;
            t.border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
            out.push_back(textured_case(std::string("texture.1d.wrap.") + w.name + fname, textured_1d, t,
                                        "    o_color = texture(tex, v_uv.x * 1.3 - v_uv.y);\n", {-1.25f, 2.5f}));
            TextureSpec a = t;
            a.width = 7, a.layers = 4;  // not a power of two; the layer rounds to nearest even and clamps
            out.push_back(textured_case(std::string("texture.1d.array.") + w.name + fname, textured_1d, a,
                                        "    o_color = texture(tex, vec2(v_uv.x, v_uv.y * 5.0 - 0.75));\n",
                                        {-1.25f, 2.5f}));
        }
}

void add_mip_cases(CaseList& out) {
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR})
        for (VkSamplerMipmapMode m : {VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_MIPMAP_MODE_LINEAR}) {
            TextureSpec t;
            t.one_d = true;
            t.width = 64, t.mip_levels = 7;
            t.min = t.mag = f;
            t.mip_mode = m;
            t.wrap = VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
            const std::string name = std::string("texture.1d.mipmap.min_") +
                                     (f == VK_FILTER_NEAREST ? "nearest" : "linear") + "_mip_" +
                                     (m == VK_SAMPLER_MIPMAP_MODE_NEAREST ? "nearest" : "linear");
            out.push_back(textured_case(name, textured_1d, t,
                                        "    o_color = texture(tex, v_uv.x * (1.0 + 5.0 * v_uv.y));\n",
                                        {0.0f, 1.0f, 0.4f}));
            out.push_back(textured_case(name + "_projected", textured_1d, t,
                                        "    o_color = textureProj(tex, vec2(v_uv.x * 2.0, 2.0));\n",
                                        {0.0f, 4.0f, 1.0f, true}));
            if (m == VK_SAMPLER_MIPMAP_MODE_LINEAR)  // shader bias with mip NEAREST: see texture.3d
                out.push_back(textured_case(name + "_bias", textured_1d, t,
                                            "    o_color = texture(tex, v_uv.x, v_uv.y * 3.0 - 1.2);\n",
                                            {0.0f, 1.0f, 0.6f}));
            TextureSpec a = t;
            a.layers = 3;
            a.wrap = VK_SAMPLER_ADDRESS_MODE_REPEAT;  // the 8-bit filter
            out.push_back(textured_case(name + "_array", textured_1d, a,
                                        "    o_color = texture(tex, vec2(v_uv.x * 3.0, v_uv.y * 3.0));\n",
                                        {0.0f, 1.0f, 0.4f}));
        }
}

void add_explicit_cases(CaseList& out) {
    TextureSpec t;
    t.one_d = true;
    t.width = 32, t.mip_levels = 6, t.layers = 3;
    t.min = t.mag = VK_FILTER_LINEAR;
    t.mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    t.wrap = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    out.push_back(textured_case(
        "texture.1d.array.lod_offset", textured_1d, t,
        "    o_color = textureLodOffset(tex, vec2(v_uv.x, v_uv.y * 3.0), v_uv.x * 6.0 - 1.0, -2);\n", {-0.3f, 1.4f}));
    out.push_back(textured_case("texture.1d.array.grad", textured_1d, t,
                                "    o_color = textureGrad(tex, vec2(v_uv.x, v_uv.y * 3.0), v_uv.y * 0.3, 0.02);\n"));
    out.push_back(textured_case("texture.1d.array.texel_fetch", textured_1d, t,
                                "    ivec2 f = ivec2(gl_FragCoord.xy);\n"
                                "    o_color = texelFetch(tex, ivec2(f.x % 36 - 2, f.y % 5 - 1), f.y / 16);\n"));
    // textureSize with constant LODs (see texture.3d.size_and_levels)
    out.push_back(textured_case("texture.1d.array.size_and_levels", textured_1d, t,
                                "    o_color = vec4(textureSize(tex, 2), textureQueryLevels(tex), 0.0) +"
                                " vec4(textureSize(tex, 5), 0.0, 0.0) * 100.0;\n"));
    TextureSpec one = t;
    one.layers = 1;
    // MIRRORED_REPEAT nearest exactly on texel edges (s = k/8 on 8 texels): gallivm mirrors the normalized
    // coordinate and truncates (lp_build_coord_mirror), which takes the texel after an edge the mirror maps onto
    TextureSpec edges;
    edges.one_d = true;
    edges.width = 8;
    edges.wrap = VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    out.push_back(textured_case("texture.1d.mirrored_repeat_nearest_texel_edges", textured_1d, edges,
                                "    o_color = textureLod(tex, float(int(gl_FragCoord.x) - 32) * 0.125 +"
                                " float(int(gl_FragCoord.y) / 16) * 0.0625, 0.0);\n"));
    out.push_back(textured_case("texture.1d.texel_fetch_and_size", textured_1d, one,
                                "    int x = int(gl_FragCoord.x) - 3, l = int(gl_FragCoord.y) / 12;\n"
                                "    o_color = texelFetch(tex, x, l) + vec4(textureSize(tex, 3));\n"));
}

}  // namespace

void add_texture_1d_cases(CaseList& out) {
    add_filter_cases(out);
    add_mip_cases(out);
    add_explicit_cases(out);
}

}  // namespace tilevk::cts
