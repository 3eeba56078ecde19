// interpolation.at.*: GLSL interpolateAtCentroid / interpolateAtSample / interpolateAtOffset (SPIR-V
// InterpolationFunction) at 1x and 4x, on perspective, noperspective and flat inputs of one to four components, with
// constant and varying offsets and sample indices, per pixel and per sample. Three overlapping triangles with
// different w are drawn into an R32G32B32A32_SFLOAT image whose every sample a compute dispatch copies out; the
// words are judged byte for byte against lavapipe. A noperspective input `pix` holds the vertex's pixel coordinates,
// so re-evaluating it at a known position gives that position: cases that read it are checked analytically too
// (offsets are added unclamped from the pixel centre; sample positions are lp_sample_pos_4x; at 1x a sample or
// centroid position is the centre).
#include <cmath>
#include <cstring>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kSize = 16;
// The 4x positions from the pixel corner (Vulkan's standard locations, lavapipe's lp_sample_pos_4x).
constexpr float kPos[4][2] = {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};
// How far a re-evaluated pixel coordinate may be from the exact position: the plane setup rounds (coordinates
// below 16, float ulps ~1e-6); an ignored offset or a wrong sample position is off by >= 1/16.
constexpr float kTolerance = 1e-3f;

std::string vertex_glsl() {
    return R"(#version 450
const vec3 kPos[9] = vec3[](vec3(-0.9, -0.8, 1.0), vec3(0.7, -0.95, 2.0), vec3(-0.2, 0.85, 0.5),
                            vec3(0.1, -0.3, 1.5), vec3(0.95, 0.6, 1.0), vec3(-0.6, 0.95, 3.0),
                            vec3(-1.0, 0.1, 1.0), vec3(1.0, 0.13, 0.75), vec3(1.0, 0.31, 1.25));
const vec4 kCol[9] = vec4[](vec4(1, 0, 0, 1), vec4(0, 1, 0, 0.5), vec4(0, 0, 1, 0.25),
                            vec4(0.3, 0.6, 0.9, 1), vec4(0.9, 0.1, 0.4, 0.75), vec4(0.2, 0.8, 0.5, 0),
                            vec4(0.5, 0.5, 0.5, 1), vec4(0.1, 0.9, 0.3, 0.6), vec4(0.7, 0.2, 0.6, 0.4));
layout(location=0) out vec4 col;
layout(location=1) noperspective out vec2 pix;
layout(location=2) flat out vec4 fl;
layout(location=3) out float s1;
layout(location=4) out vec2 s2;
layout(location=5) out vec3 s3;
layout(location=6) noperspective out vec4 np;
void main() {
    vec3 p = kPos[gl_VertexIndex];
    gl_Position = vec4(p.xy * p.z, 0.25 * p.z, p.z);
    col = kCol[gl_VertexIndex];
    pix = (p.xy + 1.0) * 8.0;  // the 16x16 viewport's pixel coordinates of the vertex
    fl = kCol[gl_VertexIndex].wzyx;
    s1 = p.z * 3.0 - 1.0;
    s2 = p.xy * 7.0;
    s3 = kCol[gl_VertexIndex].rgb * p.z;
    np = kCol[gl_VertexIndex] * 2.0 - 0.5;
}
)";
}

std::string compute_glsl(int samples) {
    if (samples == 1)
        return glsl_header(kSize, kSize) + R"(layout(binding=0) buffer B { uint w[]; };
layout(binding=1, rgba32f) uniform readonly image2D im;
void main() {
    ivec2 p = ivec2(gl_LocalInvocationID.xy);
    uvec4 b = floatBitsToUint(imageLoad(im, p));
    for (uint c = 0u; c < 4u; ++c) w[(uint(p.y) * 16u + uint(p.x)) * 4u + c] = b[c];
}
)";
    return glsl_header(kSize, kSize) + R"(layout(binding=0) buffer B { uint w[]; };
layout(binding=1) uniform sampler2DMS ms;
void main() {
    ivec2 p = ivec2(gl_LocalInvocationID.xy);
    for (int s = 0; s < 4; ++s) {
        uvec4 b = floatBitsToUint(texelFetch(ms, p, s));
        for (uint c = 0u; c < 4u; ++c) w[((uint(p.y) * 16u + uint(p.x)) * 4u + uint(s)) * 4u + c] = b[c];
    }
}
)";
}

const char* kInputs = R"(layout(location=0) in vec4 col;
layout(location=1) noperspective in vec2 pix;
layout(location=2) flat in vec4 fl;
layout(location=3) in float s1;
layout(location=4) in vec2 s2;
layout(location=5) in vec3 s3;
layout(location=6) noperspective in vec4 np;
layout(location=0) out vec4 o;
)";

// A written sample's four floats (every shader here writes alpha 1; the buffer starts as kMarker).
using TexelCheck = std::function<std::string(int samples, int sample, const float v[4])>;

Check per_sample_check(int samples, const TexelCheck& each) {
    return [samples, each](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> w = buffer_words(planes, 0);
        if (w.size() != kSize * kSize * uint32_t(samples) * 4) return "buffer0 has the wrong size";
        int written = 0;
        for (uint32_t i = 0; i < kSize * kSize * uint32_t(samples); ++i) {
            float v[4];
            std::memcpy(v, &w[i * 4], sizeof v);
            if (v[3] != 1.0f) continue;
            ++written;
            if (std::string why = each(samples, int(i % uint32_t(samples)), v); !why.empty())
                return "pixel " + std::to_string(i / uint32_t(samples)) + " sample " +
                       std::to_string(i % uint32_t(samples)) + ": " + why;
        }
        return written ? std::string() : "no sample was written";
    };
}

// Red and green (the re-evaluated `pix` minus the pixel's corner, minus any offset the shader put in blue) must be
// `want` within kTolerance.
std::string near(const float v[4], float x, float y) {
    if (std::fabs(v[0] - x) <= kTolerance && std::fabs(v[1] - y) <= kTolerance) return {};
    return "evaluated at (" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + "), expected (" + std::to_string(x) +
           ", " + std::to_string(y) + ")";
}

TexelCheck at(float x, float y) {
    return [x, y](int, int, const float v[4]) { return near(v, x, y); };
}

// Sample k's position at 4x, the centre at 1x (lavapipe adds no sample offset to single-sampled planes).
TexelCheck at_sample(int k) {
    return [k](int samples, int, const float v[4]) {
        return samples > 1 ? near(v, kPos[k][0], kPos[k][1]) : near(v, 0.5f, 0.5f);
    };
}

// Centroid: the centre, or (4x, partly covered pixels) one of the sample positions.
std::string centroid_site(int samples, int, const float v[4]) {
    if (near(v, 0.5f, 0.5f).empty()) return {};
    for (int k = 0; samples > 1 && k < 4; ++k)
        if (near(v, kPos[k][0], kPos[k][1]).empty()) return {};
    return "evaluated at (" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + "): not a centroid site";
}

struct AtCase {
    const char* name;
    const char* body;  // main()'s body; writes o with alpha 1
    TexelCheck check;
    float min_sample_shading = -1.0f;
};

Case make_case(const AtCase& ac, int samples) {
    ComputeSpec s;
    s.shaders = {compute_glsl(samples)};
    s.buffers = {ComputeBuffer{std::vector<uint32_t>(kSize * kSize * uint32_t(samples) * 4, kMarker)}};
    ComputeImage im;
    im.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    im.width = im.height = kSize;
    im.attachment = true;
    im.samples = samples > 1 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
    s.images = {im};
    s.draw.vertex_glsl = vertex_glsl();
    s.draw.fragment_glsl = std::string("#version 450\n") + kInputs + "void main() {\n" + ac.body + "\n}\n";
    s.draw.vertex_count = 9;
    s.draw.min_sample_shading = ac.min_sample_shading;
    s.steps = {draw(), dispatch(0, 1)};
    auto spec = std::make_shared<ComputeSpec>(std::move(s));
    Case c;
    c.name = std::string("interpolation.at.") + ac.name + (samples > 1 ? "_4x" : "_1x");
    c.scene = [spec] { return compute_scene(*spec); };
    if (ac.check) c.check = per_sample_check(samples, ac.check);
    return c;
}

}  // namespace

void add_interpolate_at_cases(CaseList& out) {
    // `corner` is the pixel's top-left corner; pix re-evaluated there minus corner is the position within the pixel.
#define TILEVK_CORNER "vec2 corner = floor(gl_FragCoord.xy);\n"
    const AtCase cases[] = {
        {"offset_const", TILEVK_CORNER "o = vec4(interpolateAtOffset(pix, vec2(0.25, -0.125)) - corner, 0.0, 1.0);",
         at(0.75f, 0.375f)},
        {"offset_zero", TILEVK_CORNER "o = vec4(interpolateAtOffset(pix, vec2(0.0)) - corner, col.r, 1.0);",
         at(0.5f, 0.5f)},
        // Varying offsets (per lane), subtracted again: the centre remains.
        {"offset_varying",
         TILEVK_CORNER "vec2 off = fract(gl_FragCoord.yx * vec2(0.37, 0.61)) - 0.5;\n"
                       "o = vec4(interpolateAtOffset(pix, off) - corner - off, off.x, 1.0);",
         at(0.5f, 0.5f)},
        // Outside [minInterpolationOffset, maxInterpolationOffset]: lavapipe adds it unclamped.
        {"offset_out_of_range",
         TILEVK_CORNER "o = vec4(interpolateAtOffset(pix, vec2(1.5, -1.75)) - corner, 0.0, 1.0);", at(2.0f, -1.25f)},
        {"offset_vec1_to_vec4",
         "vec2 off = vec2(0.3125, -0.4375);\n"
         "o = vec4(interpolateAtOffset(s1, off), interpolateAtOffset(s2, off).y, interpolateAtOffset(s3, off).z,"
         " 1.0);\nif (interpolateAtOffset(col, off).a > 2.0) o.r = 7.0;",
         nullptr},
        {"offset_perspective", "o = vec4(interpolateAtOffset(col, vec2(-0.375, 0.1875)).rgb, 1.0);", nullptr},
        {"offset_noperspective", "o = vec4(interpolateAtOffset(np, vec2(0.4375, 0.4375)).xyz, 1.0);", nullptr},
        {"offset_flat", "o = vec4(interpolateAtOffset(fl, vec2(0.25, 0.25)).xyz, 1.0);",
         [](int, int, const float v[4]) -> std::string {
             return v[0] == 1.0f || v[0] == 0.5f || v[0] == 0.25f || v[0] == 0.75f || v[0] == 0.0f || v[0] == 0.6f ||
                            v[0] == 0.4f
                        ? ""
                        : "flat value " + std::to_string(v[0]) + " is no vertex's";
         }},
        {"offset_component", "o = vec4(interpolateAtOffset(col.g, vec2(0.125, -0.25)), s2.x, np.w, 1.0);", nullptr},
        {"sample_const", TILEVK_CORNER "o = vec4(interpolateAtSample(pix, 2) - corner, 0.0, 1.0);", at_sample(2)},
        {"sample_varying",
         TILEVK_CORNER "int k = int(gl_FragCoord.x + gl_FragCoord.y) & 3;\n"
                       "o = vec4(interpolateAtSample(pix, k) - corner, float(k), 1.0);",
         [](int samples, int, const float v[4]) {  // blue is the lane's sample index
             const int k = int(v[2]) & 3;
             return samples > 1 ? near(v, kPos[k][0], kPos[k][1]) : near(v, 0.5f, 0.5f);
         }},
        // Whether interpolateAtSample alone makes lavapipe shade per sample: SampleMaskIn shows it (one bit per run).
        {"sample_with_mask_in",
         TILEVK_CORNER "o = vec4(interpolateAtSample(pix, 1) - corner, float(gl_SampleMaskIn[0]), 1.0);", at_sample(1)},
        {"sample_types",
         "o = vec4(interpolateAtSample(col, 1).r + interpolateAtSample(s1, 3), interpolateAtSample(s3, 0).y,"
         " interpolateAtSample(np, 2).w + interpolateAtSample(fl, 1).x, 1.0);",
         nullptr},
        {"centroid", TILEVK_CORNER "o = vec4(interpolateAtCentroid(pix) - corner, 0.0, 1.0);", centroid_site},
        {"centroid_types",
         "o = vec4(interpolateAtCentroid(col).gb, interpolateAtCentroid(s2).x + interpolateAtCentroid(fl).y, 1.0);",
         nullptr},
        // Per-sample runs: offsets still start at the pixel centre, and interpolateAtSample(gl_SampleID) is the run's
        // own sample.
        {"offset_per_sample",
         TILEVK_CORNER "o = vec4(interpolateAtOffset(pix, vec2(-0.25, 0.0625)) - corner, col.b, 1.0);",
         at(0.25f, 0.5625f), 1.0f},
        {"sample_id_per_sample", TILEVK_CORNER "o = vec4(interpolateAtSample(pix, gl_SampleID) - corner, s1, 1.0);",
         [](int samples, int s, const float v[4]) {
             return samples > 1 ? near(v, kPos[s][0], kPos[s][1]) : near(v, 0.5f, 0.5f);
         },
         1.0f},
        {"centroid_per_sample", TILEVK_CORNER "o = vec4(interpolateAtCentroid(pix) - corner, col.r, 1.0);",
         centroid_site, 1.0f},
    };
#undef TILEVK_CORNER
    for (int samples : {1, 4})
        for (const AtCase& ac : cases) out.push_back(make_case(ac, samples));
}

}  // namespace tilevk::cts
