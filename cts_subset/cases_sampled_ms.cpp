// multisample.sampled_ms.*: a 4x colour image rendered by a draw (three overlapping triangles, so that edge pixels
// hold different samples), then read by a compute dispatch with texelFetch(sampler2DMS, p, sample) for every pixel
// and sample, textureSamples and textureSize, and fetches outside the samples and the image; the words are judged
// byte for byte against lavapipe, and the queries and outside fetches against their known values.
#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kSize = 16;                           // the 4x image is kSize x kSize
constexpr uint32_t kTexels = kSize * kSize * 4;          // pixel-sample pairs
constexpr uint32_t kWordsPerFetch = 4;                   // a fetch's four components as 32-bit words
constexpr uint32_t kQueryAt = kTexels * kWordsPerFetch;  // textureSamples, textureSize.x, .y
constexpr uint32_t kOutsideAt = kQueryAt + 3;            // four outside fetches
constexpr uint32_t kOutsideFetches = 4;

struct MsFormat {
    VkFormat format;
    const char* name;
    const char* prefix;   // "", "u", "i": sampler2DMS / usampler2DMS / isampler2DMS
    const char* output;   // the fragment output type
    const char* convert;  // the interpolated colour `col` as that type
    const char* bits;     // a fetched texel `t` as uvec4
};

// The integer outputs convert clamped or signed values: at 4x a pixel centre outside the triangle extrapolates the
// colour below 0, and a negative float's conversion to uint is undefined in GLSL.
const MsFormat kFormats[] = {
    {VK_FORMAT_R8G8B8A8_UNORM, "rgba8_unorm", "", "vec4", "col", "floatBitsToUint(t)"},
    {VK_FORMAT_R16G16B16A16_SFLOAT, "rgba16_sfloat", "", "vec4", "col * 3.0 - 1.0", "floatBitsToUint(t)"},
    {VK_FORMAT_R32G32B32A32_SFLOAT, "rgba32_sfloat", "", "vec4", "col * 7.0 - 2.0", "floatBitsToUint(t)"},
    {VK_FORMAT_R8G8B8A8_UINT, "rgba8_uint", "u", "uvec4", "uvec4(clamp(col, 0.0, 1.0) * 250.0)", "t"},
    {VK_FORMAT_R32G32B32A32_SINT, "rgba32_sint", "i", "ivec4", "ivec4(col * 1000.0) - 300", "uvec4(t)"},
};

std::string vertex_glsl() {
    return R"(#version 450
const vec2 kPos[9] = vec2[](vec2(-0.9, -0.8), vec2(0.7, -0.95), vec2(-0.2, 0.85),
                            vec2(0.1, -0.3), vec2(0.95, 0.6), vec2(-0.6, 0.95),
                            vec2(-1.0, 0.1), vec2(1.0, 0.13), vec2(1.0, 0.31));
const vec4 kCol[9] = vec4[](vec4(1, 0, 0, 1), vec4(0, 1, 0, 0.5), vec4(0, 0, 1, 0.25),
                            vec4(0.3, 0.6, 0.9, 1), vec4(0.9, 0.1, 0.4, 0.75), vec4(0.2, 0.8, 0.5, 0),
                            vec4(0.5, 0.5, 0.5, 1), vec4(0.1, 0.9, 0.3, 0.6), vec4(0.7, 0.2, 0.6, 0.4));
layout(location=0) out vec4 col;
void main() { gl_Position = vec4(kPos[gl_VertexIndex], 0.0, 1.0); col = kCol[gl_VertexIndex]; }
)";
}

std::string fragment_glsl(const MsFormat& f) {
    return std::string("#version 450\nlayout(location=0) in vec4 col;\nlayout(location=0) out ") + f.output +
           " o;\nvoid main() { o = " + f.convert + "; }\n";
}

std::string compute_glsl(const MsFormat& f) {
    const std::string put = std::string("void put(uint at, ") + f.prefix + "vec4 t) { uvec4 b = " + f.bits +
                            "; for (uint c = 0u; c < 4u; ++c) w[at + c] = b[c]; }\n";
    return glsl_header(kSize, kSize) + "layout(binding=0) buffer B { uint w[]; };\nlayout(binding=1) uniform " +
           f.prefix + "sampler2DMS ms;\n" + put + R"(void main() {
    ivec2 p = ivec2(gl_LocalInvocationID.xy);
    for (int s = 0; s < 4; ++s) put(((uint(p.y) * 16u + uint(p.x)) * 4u + uint(s)) * 4u, texelFetch(ms, p, s));
    if (p == ivec2(0)) {
        const uint q = )" +
           std::to_string(kQueryAt) +
           R"(u;
        w[q] = uint(textureSamples(ms));
        w[q + 1u] = uint(textureSize(ms).x);
        w[q + 2u] = uint(textureSize(ms).y);
        put(q + 3u, texelFetch(ms, ivec2(3, 3), 4));
        put(q + 7u, texelFetch(ms, ivec2(3, 3), -1));
        put(q + 11u, texelFetch(ms, ivec2(16, 0), 0));
        put(q + 15u, texelFetch(ms, ivec2(0, -1), 1));
    }
}
)";
}

// The queries say 4 samples of 16x16, the outside fetches return zeros (every format here has alpha), some pixel's
// samples differ (the draw's edges cross pixels, so a fetch that ignored the sample index would fail here) and some
// pixel's four samples are all the cleared zero.
Check sampled_ms_check() {
    return [](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> w = buffer_words(planes, 0);
        if (w.size() != kOutsideAt + kOutsideFetches * kWordsPerFetch) return "buffer0 has the wrong size";
        if (w[kQueryAt] != 4) return "textureSamples is " + std::to_string(w[kQueryAt]) + ", expected 4";
        if (w[kQueryAt + 1] != kSize || w[kQueryAt + 2] != kSize) return "textureSize is not 16x16";
        for (uint32_t k = kOutsideAt; k < w.size(); ++k)
            if (w[k] != 0) return "outside fetch word " + std::to_string(k - kOutsideAt) + " is not 0";
        bool differing = false, cleared = false;
        for (uint32_t px = 0; px < kSize * kSize; ++px) {
            const uint32_t* t = &w[px * 4 * kWordsPerFetch];
            bool all_zero = true, all_same = true;
            for (uint32_t k = 0; k < 4 * kWordsPerFetch; ++k) {
                all_zero = all_zero && t[k] == 0;
                all_same = all_same && t[k] == t[k % kWordsPerFetch];
            }
            differing = differing || !all_same;
            cleared = cleared || all_zero;
        }
        if (!differing) return "no pixel has samples that differ";
        if (!cleared) return "no pixel is left cleared";
        return {};
    };
}

}  // namespace

void add_sampled_ms_cases(CaseList& out) {
    for (const MsFormat& f : kFormats) {
        ComputeSpec s;
        s.shaders = {compute_glsl(f)};
        s.buffers = {ComputeBuffer{std::vector<uint32_t>(kOutsideAt + kOutsideFetches * kWordsPerFetch, kMarker)}};
        ComputeImage im;
        im.format = f.format;
        im.width = im.height = kSize;
        im.attachment = true;
        im.samples = VK_SAMPLE_COUNT_4_BIT;
        s.images = {im};
        s.draw.vertex_glsl = vertex_glsl();
        s.draw.fragment_glsl = fragment_glsl(f);
        s.draw.vertex_count = 9;
        s.steps = {draw(), dispatch(0, 1)};
        out.push_back(compute_case(std::string("multisample.sampled_ms.fetch_every_sample_") + f.name, std::move(s),
                                   sampled_ms_check()));
    }
}

}  // namespace tilevk::cts
