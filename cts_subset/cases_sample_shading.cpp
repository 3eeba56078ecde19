// multisample.sample_shading.*: fragment shaders run once per sample (sampleShadingEnable with minSampleShading, or
// a shader that reads SampleId / SamplePosition or has a Sample-decorated input) and Centroid inputs at 4x. Three
// overlapping triangles with different w (perspective) are drawn into a 4x R32G32B32A32_SFLOAT image, whose every
// sample a compute dispatch copies out with texelFetch(sampler2DMS); the words are judged byte for byte against
// lavapipe, and where the answer is known (the sample positions of lp_sample_pos_4x, SampleId, SampleMaskIn's one
// bit per run, minSampleShading's threshold) analytically too.
#include <cmath>
#include <cstring>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kSize = 16;
constexpr uint32_t kWords = kSize * kSize * 4 * 4;  // pixel, sample, component
// The 4x positions from the pixel corner (Vulkan's standard locations, lavapipe's lp_sample_pos_4x).
constexpr float kPos[4][2] = {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};

std::string vertex_glsl() {
    return R"(#version 450
const vec3 kPos[9] = vec3[](vec3(-0.9, -0.8, 1.0), vec3(0.7, -0.95, 2.0), vec3(-0.2, 0.85, 0.5),
                            vec3(0.1, -0.3, 1.5), vec3(0.95, 0.6, 1.0), vec3(-0.6, 0.95, 3.0),
                            vec3(-1.0, 0.1, 1.0), vec3(1.0, 0.13, 0.75), vec3(1.0, 0.31, 1.25));
const vec4 kCol[9] = vec4[](vec4(1, 0, 0, 1), vec4(0, 1, 0, 0.5), vec4(0, 0, 1, 0.25),
                            vec4(0.3, 0.6, 0.9, 1), vec4(0.9, 0.1, 0.4, 0.75), vec4(0.2, 0.8, 0.5, 0),
                            vec4(0.5, 0.5, 0.5, 1), vec4(0.1, 0.9, 0.3, 0.6), vec4(0.7, 0.2, 0.6, 0.4));
layout(location=0) out vec4 col;
void main() {
    vec3 p = kPos[gl_VertexIndex];
    gl_Position = vec4(p.xy * p.z, 0.25 * p.z, p.z);
    col = kCol[gl_VertexIndex];
}
)";
}

std::string compute_glsl() {
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

// A sample's four floats; `written`: the draw wrote it (every shader here writes alpha 1, the clear is zero).
struct Texel {
    float v[4];
    bool written() const { return v[3] == 1.0f; }
};
using TexelCheck = std::function<std::string(int sample, const Texel& t)>;

// Runs `each` on every written sample; fails when none is written.
Check per_sample_check(const TexelCheck& each) {
    return [each](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> w = buffer_words(planes, 0);
        if (w.size() != kWords) return "buffer0 has the wrong size";
        int written = 0;
        for (uint32_t i = 0; i < kSize * kSize * 4; ++i) {
            Texel t;
            std::memcpy(t.v, &w[i * 4], sizeof t.v);
            if (!t.written()) continue;
            ++written;
            if (std::string why = each(int(i % 4), t); !why.empty())
                return "pixel " + std::to_string(i / 4) + " sample " + std::to_string(i % 4) + ": " + why;
        }
        return written ? std::string() : "no sample was written";
    };
}

// Red and green are the position the shader ran at within its pixel: the sample's, or the centre.
TexelCheck at_sample_positions(bool per_sample) {
    return [per_sample](int s, const Texel& t) -> std::string {
        const float x = per_sample ? kPos[s][0] : 0.5f, y = per_sample ? kPos[s][1] : 0.5f;
        if (t.v[0] != x || t.v[1] != y)
            return "ran at (" + std::to_string(t.v[0]) + ", " + std::to_string(t.v[1]) + "), expected (" +
                   std::to_string(x) + ", " + std::to_string(y) + ")";
        return {};
    };
}

struct ShadingCase {
    const char* name;
    const char* fragment;  // the body of main(); `col` is the input, `o` the output
    const char* input = "layout(location=0) in vec4 col;";
    float min_sample_shading = -1.0f;
    bool alpha_to_coverage = false;
    TexelCheck check;
};

Case make_case(const ShadingCase& sc) {
    ComputeSpec s;
    s.shaders = {compute_glsl()};
    s.buffers = {ComputeBuffer{std::vector<uint32_t>(kWords, kMarker)}};
    ComputeImage im;
    im.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    im.width = im.height = kSize;
    im.attachment = true;
    im.samples = VK_SAMPLE_COUNT_4_BIT;
    s.images = {im};
    s.draw.vertex_glsl = vertex_glsl();
    s.draw.fragment_glsl = std::string("#version 450\n") + sc.input +
                           "\nlayout(location=0) out vec4 o;\nvoid main() {\n" + sc.fragment + "\n}\n";
    s.draw.vertex_count = 9;
    s.draw.min_sample_shading = sc.min_sample_shading;
    s.draw.alpha_to_coverage = sc.alpha_to_coverage;
    s.steps = {draw(), dispatch(0, 1)};
    return compute_case(std::string("multisample.sample_shading.") + sc.name, std::move(s),
                        sc.check ? per_sample_check(sc.check) : Check{});
}

}  // namespace

void add_sample_shading_cases(CaseList& out) {
    // fract(FragCoord.xy) is where the run was: per sample once ceil(4 * minSampleShading) > 1 (lvp_execute.c
    // update_samples), so 0.25 still shades per pixel.
    const char* where = "o = vec4(fract(gl_FragCoord.xy), col.b, 1.0);";
    const struct {
        const char* name;
        float min;
        bool per_sample;
    } mins[] = {{"min_off", -1.0f, false}, {"min_0_00", 0.0f, false}, {"min_0_25", 0.25f, false},
                {"min_0_26", 0.26f, true}, {"min_0_50", 0.5f, true},  {"min_1_00", 1.0f, true}};
    for (const auto& m : mins) {
        ShadingCase sc{m.name, where};
        sc.min_sample_shading = m.min;
        sc.check = at_sample_positions(m.per_sample);
        out.push_back(make_case(sc));
    }
    // Reading SampleId or SamplePosition shades per sample without sampleShadingEnable (force_min_sample).
    ShadingCase id{"sample_id_and_position", "o = vec4(gl_SamplePosition, float(gl_SampleID), 1.0);"};
    id.check = [](int s, const Texel& t) -> std::string {
        if (t.v[2] != float(s)) return "SampleId " + std::to_string(t.v[2]);
        return at_sample_positions(true)(s, t);
    };
    out.push_back(make_case(id));
    ShadingCase frag_id{"frag_coord_with_sample_id",
                        "o = vec4(fract(gl_FragCoord.xy), gl_FragCoord.z + float(gl_SampleID), 1.0);"};
    frag_id.check = at_sample_positions(true);
    out.push_back(make_case(frag_id));
    // One bit per run: the run's own sample, when that sample is covered.
    ShadingCase mask_in{"sample_mask_in", "o = vec4(float(gl_SampleMaskIn[0]), float(gl_SampleID), col.r, 1.0);"};
    mask_in.min_sample_shading = 1.0f;
    mask_in.check = [](int s, const Texel& t) -> std::string {
        if (t.v[0] != float(1 << s)) return "SampleMaskIn " + std::to_string(t.v[0]);
        return {};
    };
    out.push_back(make_case(mask_in));
    ShadingCase mask_in_pixel{"sample_mask_in_per_pixel", "o = vec4(float(gl_SampleMaskIn[0]), col.gb, 1.0);"};
    out.push_back(make_case(mask_in_pixel));
    // A Sample-decorated input: interpolated at each sample and shades per sample by itself; perspective inputs take
    // 1/w at the pixel centre.
    ShadingCase qualified{"sample_input", "o = vec4(col.rgb, 1.0);", "layout(location=0) sample in vec4 col;"};
    out.push_back(make_case(qualified));
    ShadingCase qualified_np{"sample_input_noperspective", "o = vec4(col.rgb, 1.0);",
                             "layout(location=0) sample noperspective in vec4 col;"};
    out.push_back(make_case(qualified_np));
    // Centroid at 4x: the centre where every sample (or none) is covered, else the lowest covered sample.
    ShadingCase centroid{"centroid_input", "o = vec4(col.rgb, 1.0);", "layout(location=0) centroid in vec4 col;"};
    out.push_back(make_case(centroid));
    ShadingCase centroid_ps{"centroid_input_per_sample", "o = vec4(col.rg, fract(gl_FragCoord.x), 1.0);",
                            "layout(location=0) centroid in vec4 col;"};
    centroid_ps.min_sample_shading = 1.0f;
    out.push_back(make_case(centroid_ps));
    ShadingCase plain{"centre_input_per_sample", "o = vec4(col.rgb, 1.0);"};
    plain.min_sample_shading = 1.0f;
    out.push_back(make_case(plain));
    // Discard in some runs only, derivatives per run, and a shader-written sample mask per run.
    ShadingCase kill{"discard_per_sample",
                     "if (gl_SampleID == 2 || (gl_SampleID == 1 && col.r > 0.4)) discard;\n"
                     "o = vec4(dFdx(col.r), dFdy(fract(gl_FragCoord.y)), float(gl_SampleID), 1.0);"};
    kill.check = [](int s, const Texel&) -> std::string { return s == 2 ? "a discarded sample was written" : ""; };
    out.push_back(make_case(kill));
    ShadingCase mask_out{"sample_mask_out", "gl_SampleMask[0] = gl_SampleID == 3 ? 0 : 0xB;\no = vec4(col.rgb, 1.0);"};
    mask_out.min_sample_shading = 1.0f;
    mask_out.check = [](int s, const Texel&) -> std::string {
        return s == 2 || s == 3 ? "a sample outside the written mask was written" : "";
    };
    out.push_back(make_case(mask_out));
    // Alpha to coverage with every run's alpha applied to every sample's mask, in lavapipe's order.
    ShadingCase a2c{"alpha_to_coverage", "o = vec4(col.rgb, fract(gl_FragCoord.x * 0.37 + gl_FragCoord.y * 0.21));"};
    a2c.min_sample_shading = 1.0f;
    a2c.alpha_to_coverage = true;
    out.push_back(make_case(a2c));
}

}  // namespace tilevk::cts
