// texture.bc.*: BC1-BC5 compressed textures (seeded random blocks plus hand-made ones for every mode: bc_texture.cpp)
// sampled nearest and linear, magnified (lavapipe's 8-bit filter for the UNORM formats under REPEAT /
// CLAMP_TO_EDGE, its float filter under CLAMP_TO_BORDER, and always for sRGB and SNORM), minified through a mip
// chain whose levels are not multiples of the block (22x14 down to 1x1), and every texel of every level fetched
// with texelFetch. The targets are RGBA32F, so every float of the decode and the filter shows. The textures are
// uploaded by block-granular vkCmdCopyBufferToImage (a padded bufferRowLength, a region at a block offset ending in
// a partial block).
#include "case.hpp"

namespace tilevk::cts {
namespace {

struct BcFormat {
    const char* name;
    VkFormat format;
};
const BcFormat kFormats[] = {
    {"bc1_rgb_unorm", VK_FORMAT_BC1_RGB_UNORM_BLOCK},   {"bc1_rgb_srgb", VK_FORMAT_BC1_RGB_SRGB_BLOCK},
    {"bc1_rgba_unorm", VK_FORMAT_BC1_RGBA_UNORM_BLOCK}, {"bc1_rgba_srgb", VK_FORMAT_BC1_RGBA_SRGB_BLOCK},
    {"bc2_unorm", VK_FORMAT_BC2_UNORM_BLOCK},           {"bc2_srgb", VK_FORMAT_BC2_SRGB_BLOCK},
    {"bc3_unorm", VK_FORMAT_BC3_UNORM_BLOCK},           {"bc3_srgb", VK_FORMAT_BC3_SRGB_BLOCK},
    {"bc4_unorm", VK_FORMAT_BC4_UNORM_BLOCK},           {"bc4_snorm", VK_FORMAT_BC4_SNORM_BLOCK},
    {"bc5_unorm", VK_FORMAT_BC5_UNORM_BLOCK},           {"bc5_snorm", VK_FORMAT_BC5_SNORM_BLOCK},
};

// A full-target quad with v_uv from u0 to u1; `body` computes `o_color` from `tex` and `uv`.
Scene bc_scene(const TextureSpec& t, const std::string& body, float u0, float u1) {
    Draw d;
    d.frag = Frag::kTexture;
    d.texture = t;
    Vertex a = vtx(-1, -1, 0, 1), b = vtx(1, -1, 0, 1), c = vtx(1, 1, 0, 1), e = vtx(-1, 1, 0, 1);
    a.uv[0] = u0, a.uv[1] = u0;
    b.uv[0] = u1, b.uv[1] = u0;
    c.uv[0] = u1, c.uv[1] = u1;
    e.uv[0] = u0, e.uv[1] = u1;
    d.vertices = {a, b, c, a, c, e};
    d.fragment_glsl =
        "#version 450\n"
        "layout(location=0) in vec4 v_color;\n"  // unused, declared for the interface match
        "layout(location=1) in vec2 v_uv;\n"
        "layout(location=0) out vec4 o_color;\n"
        "layout(set=0, binding=0) uniform sampler2D tex;\n"
        "void main() {\n"
        "    vec2 uv = v_uv;\n" +
        body + "}\n";
    Scene s = one_draw(d, 64, 64);
    s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
    return s;
}

TextureSpec bc_spec(VkFormat f, VkFilter filter, VkSamplerAddressMode wrap) {
    TextureSpec t;
    t.format = f;
    t.width = 22, t.height = 14, t.mip_levels = 5;  // 22x14, 11x7, 5x3, 2x1, 1x1
    t.mag = t.min = filter;
    t.mip_mode = filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    t.wrap = wrap;
    t.border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    return t;
}

}  // namespace

void add_texture_bc_cases(CaseList& out) {
    const std::string mag = "    o_color = textureLod(tex, uv, 0.0);\n";
    const std::string min = "    o_color = texture(tex, uv);\n";
    // texel (x, y) of level l: 22 columns per level, levels 0-2 side by side in the top half, 3-4 in the bottom half.
    // The level sizes are constants: lavapipe's textureSize takes one lane's LOD for a whole 8-pixel vector, so a
    // non-uniform textureSize would show that instead.
    const std::string fetch =
        "    ivec2 p = ivec2(gl_FragCoord.xy);\n"
        "    int l = p.x / 22 + (p.y >= 32 ? 3 : 0);\n"
        "    ivec2 size = max(ivec2(22, 14) >> min(l, 4), ivec2(1));\n"
        "    o_color = texelFetch(tex, ivec2(p.x % 22, p.y % 32) % size, min(l, 4));\n";
    for (const BcFormat& f : kFormats) {
        const std::string base = std::string("texture.bc.") + f.name;
        for (VkFilter filter : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
            const std::string fname = filter == VK_FILTER_NEAREST ? "nearest" : "linear";
            const TextureSpec repeat = bc_spec(f.format, filter, VK_SAMPLER_ADDRESS_MODE_REPEAT);
            const TextureSpec border = bc_spec(f.format, filter, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
            const TextureSpec edge = bc_spec(f.format, filter, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
            out.push_back(
                {base + ".mag_" + fname + "_repeat", [=] { return bc_scene(repeat, mag, -0.2f, 1.3f); }, nullptr, ""});
            out.push_back({base + ".mag_" + fname + "_clamp_to_border",
                           [=] { return bc_scene(border, mag, -0.2f, 1.3f); }, nullptr, ""});
            out.push_back(
                {base + ".min_" + fname + "_mipmap", [=] { return bc_scene(edge, min, -0.5f, 7.0f); }, nullptr, ""});
        }
        const TextureSpec t = bc_spec(f.format, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT);
        out.push_back({base + ".fetch_every_level", [=] { return bc_scene(t, fetch, 0.0f, 1.0f); }, nullptr, ""});
    }
}

}  // namespace tilevk::cts
