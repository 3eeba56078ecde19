// The frame benchmark's scenes (bench/frame/README.md lists them with what each one stresses).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "frame_scene.h"
#include "lit_shader.h"
#include "mesh.hpp"

namespace tilevk::bench {
namespace {

// Deterministic pseudo-random numbers (the same scene on every run and for both drivers).
struct Lcg {
    uint64_t s;
    float next() {  // [0, 1)
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return float(uint32_t(s >> 40)) / float(1u << 24);
    }
    float range(float a, float b) { return a + (b - a) * next(); }
};

constexpr const char* kVertexHeader = R"(#version 450
layout(location = 0) in vec4 a_pos;
layout(location = 1) in vec4 a_color;
layout(location = 2) in vec2 a_uv;
layout(push_constant) uniform Push { vec4 offset; vec4 tint; } pc;
)";

// Flat colour: one colour per triangle (the provoking vertex's).
const std::string kFlatVs = std::string(kVertexHeader) + R"(
layout(location = 0) flat out vec4 v_color;
void main() { gl_Position = a_pos + pc.offset * a_pos.w; v_color = a_color * pc.tint; }
)";
constexpr const char* kFlatFs = R"(#version 450
layout(location = 0) flat in vec4 v_color;
layout(location = 0) out vec4 o_color;
void main() { o_color = v_color; }
)";

// Smooth colour, perspective-correct.
const std::string kSmoothVs = std::string(kVertexHeader) + R"(
layout(location = 0) out vec4 v_color;
void main() { gl_Position = a_pos + pc.offset * a_pos.w; v_color = a_color * pc.tint; }
)";
constexpr const char* kSmoothFs = R"(#version 450
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o_color;
void main() { o_color = v_color; }
)";

// Textured and tinted by the vertex colour.
const std::string kTexturedVs = std::string(kVertexHeader) + R"(
layout(location = 0) out vec4 v_color;
layout(location = 1) out vec2 v_uv;
void main() { gl_Position = a_pos + pc.offset * a_pos.w; v_color = a_color * pc.tint; v_uv = a_uv; }
)";
constexpr const char* kTexturedFs = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D u_tex;
layout(location = 0) in vec4 v_color;
layout(location = 1) in vec2 v_uv;
layout(location = 0) out vec4 o_color;
void main() { o_color = texture(u_tex, v_uv) * v_color; }
)";

// Lit and textured: the colour attribute carries the normal; diffuse + ambient light times the texture.
const std::string kLitVs = std::string(kVertexHeader) + R"(
layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec2 v_uv;
void main() { gl_Position = a_pos + pc.offset * a_pos.w; v_normal = a_color.xyz; v_uv = a_uv; }
)";

enum class Shading { kFlat, kSmooth, kDepth };

uint32_t g_small_triangles = 100000;  // set_small_triangle_count

BenchScene sized(uint32_t width, uint32_t height) {
    BenchScene s;
    s.width = width;
    s.height = height;
    return s;
}

BenchPipeline flat_pipeline() {
    return {kFlatVs, kFlatFs};
}

// n triangles of `area` pixels each (legs of a right triangle, random rotation) at random positions in the target.
// Smooth triangles get random vertex colours and w in [1, 3] (perspective-correct interpolation matters);
// depth triangles a random z per triangle.
void add_triangles(BenchScene& s, uint32_t n, float area, Shading shading, uint64_t seed) {
    Lcg rng{seed};
    const float leg = std::sqrt(2.0f * area);
    const uint32_t first = uint32_t(s.vertices.size());
    for (uint32_t t = 0; t < n; ++t) {
        const float cx = rng.range(0, float(s.width)), cy = rng.range(0, float(s.height));
        const float a = rng.range(0, 6.2831853f), ca = std::cos(a), sa = std::sin(a);
        const float px[3] = {0, leg, 0}, py[3] = {0, 0, leg};
        const float z = shading == Shading::kDepth ? rng.next() : 0.5f;
        const float tc[4] = {rng.next(), rng.next(), rng.next(), 1.0f};
        for (int k = 0; k < 3; ++k) {
            const float x = cx + ca * px[k] - sa * py[k], y = cy + sa * px[k] + ca * py[k];
            const float w = shading == Shading::kSmooth ? rng.range(1.0f, 3.0f) : 1.0f;
            BenchVertex v;
            v.pos[0] = (x / float(s.width) * 2.0f - 1.0f) * w;
            v.pos[1] = (y / float(s.height) * 2.0f - 1.0f) * w;
            v.pos[2] = z * w;
            v.pos[3] = w;
            for (int c = 0; c < 4; ++c) v.color[c] = shading == Shading::kSmooth && c < 3 ? rng.next() : tc[c];
            s.vertices.push_back(v);
        }
    }
    BenchDraw d;
    d.first_vertex = first;
    d.vertex_count = 3 * n;
    s.draws.push_back(d);
}

BenchScene small_triangles(uint32_t w, uint32_t h, uint32_t area, Shading shading) {
    BenchScene s = sized(w, h);
    const char* kind = shading == Shading::kFlat ? "flat" : shading == Shading::kSmooth ? "smooth" : "depth";
    s.description = std::to_string(g_small_triangles) + " triangles of " + std::to_string(area) + " px, " +
                    (shading == Shading::kFlat     ? std::string("flat colour")
                     : shading == Shading::kSmooth ? std::string("perspective-correct smooth colour")
                                                   : std::string("flat colour, D32 LESS + write"));
    s.name = "tri" + std::to_string(area) + "_" + kind;
    s.pipelines.push_back(shading == Shading::kSmooth ? BenchPipeline{kSmoothVs, kSmoothFs} : flat_pipeline());
    if (shading == Shading::kDepth) {
        s.depth = VK_FORMAT_D32_SFLOAT;
        s.pipelines[0].depth_test = s.pipelines[0].depth_write = true;
    }
    add_triangles(s, g_small_triangles, float(area), shading, 1000 + area);
    return s;
}

// A full-screen quad (two triangles) at depth z with per-corner colours.
void add_quad(BenchScene& s, float z, const float colors[4][4], float w_left = 1, float w_right = 1) {
    const float xy[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const int order[6] = {0, 1, 2, 0, 2, 3};
    BenchDraw d;
    d.first_vertex = uint32_t(s.vertices.size());
    d.vertex_count = 6;
    for (int k : order) {
        BenchVertex v;
        const float w = xy[k][0] < 0 ? w_left : w_right;
        v.pos[0] = xy[k][0] * w;
        v.pos[1] = xy[k][1] * w;
        v.pos[2] = z * w;
        v.pos[3] = w;
        for (int c = 0; c < 4; ++c) v.color[c] = colors[k][c];
        v.uv[0] = uv[k][0] * 4.0f;
        v.uv[1] = uv[k][1] * 4.0f;
        s.vertices.push_back(v);
    }
    s.draws.push_back(d);
}

BenchScene blended_layers(uint32_t w, uint32_t h) {
    BenchScene s = sized(w, h);
    s.name = "blend16";
    s.description = "16 alpha-blended full-screen layers (smooth colour, SRC_ALPHA / ONE_MINUS_SRC_ALPHA)";
    BenchPipeline p{kSmoothVs, kSmoothFs};
    p.blend = true;
    s.pipelines.push_back(p);
    Lcg rng{16};
    for (int layer = 0; layer < 16; ++layer) {
        float c[4][4];
        for (auto& corner : c) {
            for (int k = 0; k < 3; ++k) corner[k] = rng.next();
            corner[3] = rng.range(0.2f, 0.6f);
        }
        add_quad(s, 0.5f, c);
    }
    return s;
}

BenchScene msaa_triangles(uint32_t w, uint32_t h) {
    BenchScene s = small_triangles(w, h, 16, Shading::kFlat);
    s.name = "msaa4_tri16";
    s.description =
        std::to_string(g_small_triangles) + " triangles of 16 px, flat colour, 4x MSAA resolved in the render pass";
    s.samples = VK_SAMPLE_COUNT_4_BIT;
    return s;
}

// The assimp meshes side by side (normalised by mesh.cpp, aspect-corrected here), lit and textured, D32 LESS.
BenchScene lit_meshes(uint32_t w, uint32_t h) {
    BenchScene s = sized(w, h);
    s.name = "meshes_lit";
    s.description =
        "assimp meshes (Wuson PLY and OBJ, spider, sphere with hole), per-pixel diffuse + specular light, "
        "trilinear-filtered texture, D32 LESS";
    s.depth = VK_FORMAT_D32_SFLOAT;
    BenchPipeline p{kLitVs, kLitFs};
    p.depth_test = p.depth_write = true;
    p.textured = true;
    s.pipelines.push_back(p);
    s.textures.push_back({512, 3});
    struct Placement {
        const char* file;
        float yaw, pitch, cx, cy, scale;
    };
    const Placement meshes[] = {{"PLY/Wuson.ply", 0.5f, 0.2f, -0.5f, -0.45f, 0.5f},
                                {"OBJ/spider.obj", 0.4f, 0.7f, 0.5f, -0.45f, 0.5f},
                                {"OBJ/WusonOBJ.obj", -0.6f, 0.3f, -0.5f, 0.5f, 0.5f},
                                {"STL/sphereWithHole.stl", 0.2f, 0.3f, 0.5f, 0.5f, 0.45f}};
    const float aspect = float(s.height) / float(s.width);
    for (const Placement& m : meshes) {
        const cts::Mesh mesh = cts::load_mesh(cts::model_dir() + "/" + m.file, m.yaw, m.pitch);
        BenchDraw d;
        d.texture = 0;
        d.first_vertex = uint32_t(s.vertices.size());
        for (size_t t = 0; t < mesh.normals.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const auto& p3 = mesh.triangles[t * 3 + k];
                BenchVertex v;
                v.pos[0] = m.cx + p3[0] * m.scale * aspect;
                v.pos[1] = m.cy + p3[1] * m.scale;
                v.pos[2] = p3[2];
                for (int c = 0; c < 3; ++c) v.color[c] = mesh.normals[t][c];
                v.uv[0] = p3[0] * 2.0f + p3[2];
                v.uv[1] = p3[1] * 2.0f - p3[2];
                s.vertices.push_back(v);
            }
        d.vertex_count = uint32_t(s.vertices.size()) - d.first_vertex;
        s.draws.push_back(d);
    }
    return s;
}

// A patch of nx x ny quads of `cell` pixels whose corner is at the origin (moved by the draw's push offset).
void add_patch(BenchScene& s, int nx, int ny, float cell, Lcg& rng, bool smooth_alpha) {
    const float sx = 2.0f * cell / float(s.width), sy = 2.0f * cell / float(s.height);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const float x0 = -1 + i * sx, y0 = -1 + j * sy;
            const float corners[4][2] = {{x0, y0}, {x0 + sx, y0}, {x0 + sx, y0 + sy}, {x0, y0 + sy}};
            const int order[6] = {0, 1, 2, 0, 2, 3};
            for (int k : order) {
                BenchVertex v;
                v.pos[0] = corners[k][0];
                v.pos[1] = corners[k][1];
                v.pos[2] = 0.0f;
                for (int c = 0; c < 3; ++c) v.color[c] = rng.range(0.3f, 1.0f);
                v.color[3] = smooth_alpha ? rng.range(0.3f, 0.8f) : 1.0f;
                v.uv[0] = (corners[k][0] + 1) * 4;
                v.uv[1] = (corners[k][1] + 1) * 4;
                s.vertices.push_back(v);
            }
        }
}

// 1000 draws cycling through four pipelines (flat, textured, blended, lit), two textures, per-draw push constants
// and scissors: the per-draw cost of state changes.
BenchScene many_draws(uint32_t w, uint32_t h) {
    BenchScene s = sized(w, h);
    s.name = "draws1000";
    s.description =
        "1000 draws of 64 triangles (~16x16 px cells): 4 pipelines, 2 textures, push constants and "
        "a scissor per draw, D32 LESS";
    s.depth = VK_FORMAT_D32_SFLOAT;
    BenchPipeline flat = flat_pipeline(), tex{kTexturedVs, kTexturedFs}, blend{kSmoothVs, kSmoothFs},
                  lit{kLitVs, kLitFs};
    flat.depth_test = flat.depth_write = tex.depth_test = tex.depth_write = lit.depth_test = lit.depth_write = true;
    blend.depth_test = true;
    blend.blend = true;
    tex.textured = lit.textured = true;
    s.pipelines = {flat, tex, blend, lit};
    s.textures = {{128, 5}, {256, 6}};
    Lcg rng{1000};
    uint32_t patch_first[4], patch_count[4];
    for (int p = 0; p < 4; ++p) {
        patch_first[p] = uint32_t(s.vertices.size());
        add_patch(s, 8, 4, 16.0f, rng, p == 2);
        patch_count[p] = uint32_t(s.vertices.size()) - patch_first[p];
    }
    for (int i = 0; i < 1000; ++i) {
        BenchDraw d;
        d.pipeline = uint32_t(i % 4);
        d.first_vertex = patch_first[d.pipeline];
        d.vertex_count = patch_count[d.pipeline];
        d.texture = (d.pipeline == 1 || d.pipeline == 3) ? (i / 4) % 2 : -1;
        const float ox = rng.range(0, 2.0f - 2.0f * 128 / float(s.width));
        const float oy = rng.range(0, 2.0f - 2.0f * 64 / float(s.height));
        const float z = rng.range(0.05f, 0.95f);
        const float tint[4] = {rng.range(0.5f, 1), rng.range(0.5f, 1), rng.range(0.5f, 1), 1};
        d.push[0] = ox;
        d.push[1] = oy;
        d.push[2] = z;
        d.push[3] = 0;
        for (int c = 0; c < 4; ++c) d.push[4 + c] = tint[c];
        if (i % 3 == 0) {
            d.scissor = {{int32_t(rng.range(0, float(s.width) / 2)), int32_t(rng.range(0, float(s.height) / 2))},
                         {s.width / 2, s.height / 2}};
        }
        s.draws.push_back(d);
    }
    return s;
}

// Three overlapping full-screen quads with perspective (w from 1 to 3 across the screen), a 1024x1024 trilinear
// texture: large triangles, every pixel textured three times.
BenchScene large_textured(uint32_t w, uint32_t h) {
    BenchScene s = sized(w, h);
    s.name = "large_textured";
    s.description = "3 overlapping full-screen perspective quads (6 large triangles), 1024x1024 trilinear texture";
    BenchPipeline p{kTexturedVs, kTexturedFs};
    p.textured = true;
    s.pipelines.push_back(p);
    s.textures.push_back({1024, 7});
    const float white[4][4] = {{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}};
    const float layer_w[3][2] = {{1, 3}, {3, 1}, {1.5f, 2}};
    for (auto& ww : layer_w) {
        add_quad(s, 0.5f, white, ww[0], ww[1]);
        s.draws.back().texture = 0;
    }
    return s;
}

struct Entry {
    const char* name;
    BenchScene (*make)(uint32_t width, uint32_t height);
};

const Entry kScenes[] = {
    {"tri4_flat", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 4, Shading::kFlat); }},
    {"tri16_flat", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 16, Shading::kFlat); }},
    {"tri64_flat", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 64, Shading::kFlat); }},
    {"tri4_smooth", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 4, Shading::kSmooth); }},
    {"tri16_smooth", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 16, Shading::kSmooth); }},
    {"tri64_smooth", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 64, Shading::kSmooth); }},
    {"tri4_depth", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 4, Shading::kDepth); }},
    {"tri16_depth", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 16, Shading::kDepth); }},
    {"tri64_depth", [](uint32_t w, uint32_t h) { return small_triangles(w, h, 64, Shading::kDepth); }},
    {"blend16", blended_layers},
    {"msaa4_tri16", msaa_triangles},
    {"meshes_lit", lit_meshes},
    {"draws1000", many_draws},
    {"large_textured", large_textured},
};

}  // namespace

void set_small_triangle_count(uint32_t n) {
    g_small_triangles = n;
}

std::vector<std::string> scene_names() {
    std::vector<std::string> out;
    for (const Entry& e : kScenes) out.emplace_back(e.name);
    return out;
}

BenchScene make_scene(const std::string& spec) {
    std::string name = spec;
    uint32_t width = 1920, height = 1080;
    if (const size_t at = spec.find('@'); at != std::string::npos) {
        name = spec.substr(0, at);
        if (std::sscanf(spec.c_str() + at + 1, "%ux%u", &width, &height) != 2 || width == 0 || height == 0 ||
            width > 4096 || height > 4096)
            throw std::runtime_error("bad target size in scene name '" + spec + "' (NAME@WIDTHxHEIGHT)");
    }
    for (const Entry& e : kScenes) {
        if (name != e.name) continue;
        BenchScene s = e.make(width, height);
        if (width != 1920 || height != 1080) s.name += "@" + std::to_string(width) + "x" + std::to_string(height);
        return s;
    }
    throw std::runtime_error("unknown scene '" + name + "'");
}

}  // namespace tilevk::bench
