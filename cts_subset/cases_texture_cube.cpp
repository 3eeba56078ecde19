// texture.cube.*: cube and cube-array textures sampled in fragment shaders. Six panels, one per face, each a quad
// whose corner directions lean 1.3 past the face's edges, so that every panel crosses into the four neighbouring
// faces and reaches the cube's corners (where three faces meet): face selection, the seamless filter across edges
// and corners, the per-pixel LOD of cube maps, bias, explicit LOD and gradients, depth comparison, cube arrays and
// the size queries. The targets are RGBA32F, so the shaders' float results are compared bit for bit.
#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kPanel = 32;  // each panel is kPanel x kPanel pixels, three across, two down

const char* const kVertex = R"(#version 450
layout(location=0) in vec4 in_pos;
layout(location=1) in vec4 in_color;
layout(location=2) in vec2 in_uv;
layout(location=3) in float in_psize;
layout(location=0) out vec3 v_dir;
layout(location=1) out vec2 v_uv;
void main() { gl_Position = in_pos; gl_PointSize = in_psize; v_dir = in_color.xyz; v_uv = in_uv; }
)";

// The fragment shader around `body`, which sets `vec4 o` from `tex`, the direction `d` and `uv` in [0, 1].
std::string fragment(const std::string& sampler, const std::string& body) {
    return "#version 450\nlayout(set=0, binding=0) uniform " + sampler +
           " tex;\nlayout(location=0) in vec3 v_dir;\nlayout(location=1) in vec2 v_uv;\n"
           "layout(location=0) out vec4 o_color;\nvoid main() {\n    vec3 d = v_dir;\n    vec2 uv = v_uv;\n"
           "    vec4 o;\n    " +
           body + "\n    o_color = o;\n}\n";
}

// The panel of face f (0..5 = +X, -X, +Y, -Y, +Z, -Z): the major axis fixed at +-1, the two others from -1.3 to 1.3
// across the panel, at pixel rectangle (col, row).
Draw panel(uint32_t f, const TextureSpec& t, const std::string& frag) {
    Draw d;
    d.texture = t;
    d.vertex_glsl = kVertex;
    d.fragment_glsl = frag;
    const uint32_t col = f % 3, row = f / 3;
    const float x0 = -1.0f + 2.0f * float(col * kPanel) / float(3 * kPanel);
    const float x1 = -1.0f + 2.0f * float((col + 1) * kPanel) / float(3 * kPanel);
    const float y0 = -1.0f + float(row), y1 = float(row);
    const uint32_t axis = f / 2;
    const float sign = (f & 1) ? -1.0f : 1.0f;
    // corners (a, b) in {-1.3, 1.3}: the direction has sign on `axis` and a, b on the other two axes; the small
    // offsets keep the panel's centre off exact ties between faces
    const auto corner = [&](float px, float py, float a, float b, float u, float v) {
        Vertex vx = vtx(px, py, 0, 1);
        float dir[3];
        dir[axis] = sign;
        dir[(axis + 1) % 3] = a + 0.013f;
        dir[(axis + 2) % 3] = b - 0.021f;
        for (int i = 0; i < 3; ++i) vx.color[i] = dir[i];
        vx.color[3] = 1.0f;
        vx.uv[0] = u, vx.uv[1] = v;
        return vx;
    };
    const Vertex a = corner(x0, y0, -1.3f, -1.3f, 0, 0), b = corner(x1, y0, 1.3f, -1.3f, 1, 0);
    const Vertex c = corner(x1, y1, 1.3f, 1.3f, 1, 1), e = corner(x0, y1, -1.3f, 1.3f, 0, 1);
    d.vertices = {a, b, c, a, c, e};
    return d;
}

Scene panels(const TextureSpec& t, const std::string& frag) {
    Scene s;
    s.target.width = 3 * kPanel;
    s.target.height = 2 * kPanel;
    s.target.color = VK_FORMAT_R32G32B32A32_SFLOAT;
    for (uint32_t f = 0; f < 6; ++f) s.draws.push_back(panel(f, t, frag));
    return s;
}

TextureSpec cube(uint32_t size, uint32_t levels, VkFilter filter, VkSamplerMipmapMode mip) {
    TextureSpec t;
    t.cube_layers = 6;
    t.width = t.height = size;
    t.mip_levels = levels;
    t.min = t.mag = filter;
    t.mip_mode = mip;
    t.wrap = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    t.max_lod = VK_LOD_CLAMP_NONE;
    return t;
}

void add(CaseList& out, const std::string& name, const TextureSpec& t, const std::string& sampler,
         const std::string& body) {
    const std::string frag = fragment(sampler, body);
    out.push_back({"texture.cube." + name, [=] { return panels(t, frag); }, nullptr, ""});
}

// texture.cube.non_seamless.*: samplers with VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT. Each face is filtered
// alone, clamped at its edges: the RGBA8 cubes through lavapipe's 8-bit filter, the depth cube in float; REPEAT,
// which lavapipe clamps too.
void add_non_seamless_cases(CaseList& out) {
    const auto ns = [](TextureSpec t) {
        t.non_seamless = true;
        return t;
    };
    const std::string kSample = "o = texture(tex, d);";
    const std::string p = "non_seamless.";
    add(out, p + "mag_linear", ns(cube(8, 1, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST)), "samplerCube",
        kSample);
    add(out, p + "mag_nearest", ns(cube(8, 1, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST)), "samplerCube",
        kSample);
    TextureSpec repeat = ns(cube(8, 1, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST));
    repeat.wrap = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    add(out, p + "mag_linear_repeat", repeat, "samplerCube", kSample);
    for (VkSamplerMipmapMode m : {VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_MIPMAP_MODE_LINEAR}) {
        const std::string mname = m == VK_SAMPLER_MIPMAP_MODE_NEAREST ? "nearest" : "linear";
        add(out, p + "min_linear_mip_" + mname, ns(cube(64, 7, VK_FILTER_LINEAR, m)), "samplerCube", kSample);
    }
    const TextureSpec trilinear = ns(cube(64, 7, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR));
    add(out, p + "lod", trilinear, "samplerCube", "o = textureLod(tex, d, uv.y * 7.0 - 1.0);");
    add(out, p + "grad", trilinear, "samplerCube",
        "o = textureGrad(tex, d, vec3(0.02, 0.01, -0.03) * uv.x, vec3(-0.01, 0.04, 0.02) * uv.y);");
    // one level and an implicit LOD: one LOD per quad, so lavapipe still takes the 8-bit path, choosing the filter
    // per quad (about 1.3 texels per pixel: some quads minify, some magnify)
    TextureSpec mixed = ns(cube(32, 1, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST));
    mixed.mag = VK_FILTER_NEAREST;
    add(out, p + "min_linear_mag_nearest", mixed, "samplerCube", kSample);
    TextureSpec shadow = ns(cube(16, 1, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST));
    shadow.format = VK_FORMAT_D32_SFLOAT;
    shadow.compare = true;
    shadow.compare_op = VK_COMPARE_OP_LESS;
    add(out, p + "shadow_linear", shadow, "samplerCubeShadow", "o = vec4(texture(tex, vec4(d, uv.x)), 0.0, 0.0, 1.0);");
    TextureSpec arr = ns(cube(16, 5, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR));
    arr.cube_layers = 18;
    add(out, p + "array_linear", arr, "samplerCubeArray", "o = texture(tex, vec4(d, uv.x * 3.6 - 0.7));");
}

}  // namespace

void add_texture_cube_cases(CaseList& out) {
    const std::string kSample = "o = texture(tex, d);";
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
        const std::string fname = f == VK_FILTER_NEAREST ? "nearest" : "linear";
        // magnified (8 texels across a face, ~0.3 texels per pixel): edges and corners at level 0
        add(out, "mag_" + fname, cube(8, 1, f, VK_SAMPLER_MIPMAP_MODE_NEAREST), "samplerCube", kSample);
        for (VkSamplerMipmapMode m : {VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_MIPMAP_MODE_LINEAR}) {
            const std::string mname = m == VK_SAMPLER_MIPMAP_MODE_NEAREST ? "nearest" : "linear";
            // minified (64 texels, ~2.5 texels per pixel): the per-pixel LOD of cube maps between levels 1 and 2
            add(out, "min_" + fname + "_mip_" + mname, cube(64, 7, f, m), "samplerCube", kSample);
        }
    }
    const TextureSpec trilinear = cube(64, 7, VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR);
    add(out, "bias", trilinear, "samplerCube", "o = texture(tex, d, uv.x * 3.0 - 1.0);");
    TextureSpec sampler_bias = trilinear;
    sampler_bias.lod_bias = 0.75f;
    add(out, "sampler_bias", sampler_bias, "samplerCube", kSample);
    add(out, "lod", trilinear, "samplerCube", "o = textureLod(tex, d, uv.y * 7.0 - 1.0);");
    add(out, "lod_nearest", cube(64, 7, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST), "samplerCube",
        "o = textureLod(tex, d, uv.y * 7.0 - 1.0);");
    add(out, "grad", trilinear, "samplerCube",
        "o = textureGrad(tex, d, vec3(0.02, 0.01, -0.03) * uv.x, vec3(-0.01, 0.04, 0.02) * uv.y);");
    // the sizes and level count, as numbers
    add(out, "queries", cube(16, 5, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST), "samplerCube",
        "o = vec4(textureSize(tex, 0), textureSize(tex, 2).x, textureQueryLevels(tex));");
    for (VkFilter f : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
        TextureSpec shadow = cube(16, 1, f, VK_SAMPLER_MIPMAP_MODE_NEAREST);
        shadow.format = VK_FORMAT_D32_SFLOAT;
        shadow.compare = true;
        shadow.compare_op = VK_COMPARE_OP_LESS;
        add(out, std::string("shadow_") + (f == VK_FILTER_NEAREST ? "nearest" : "linear"), shadow, "samplerCubeShadow",
            "o = vec4(texture(tex, vec4(d, uv.x)), 0.0, 0.0, 1.0);");
        TextureSpec arr = cube(16, 5, f, VK_SAMPLER_MIPMAP_MODE_LINEAR);
        arr.cube_layers = 18;
        // the layer runs from -0.7 to 2.9: rounded to even, clamped to the 3 cubes
        add(out, std::string("array_") + (f == VK_FILTER_NEAREST ? "nearest" : "linear"), arr, "samplerCubeArray",
            "o = texture(tex, vec4(d, uv.x * 3.6 - 0.7));");
    }
    add_non_seamless_cases(out);
    TextureSpec arr_queries = cube(16, 5, VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST);
    arr_queries.cube_layers = 18;
    add(out, "array_queries", arr_queries, "samplerCubeArray",
        "o = vec4(textureSize(tex, 1), textureQueryLevels(tex));");
}

}  // namespace tilevk::cts
