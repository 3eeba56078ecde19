// Cases at lavapipe's limits (lvp_device.c), each judged byte for byte against lavapipe and analytically where the
// answer is known.
// compute.limits.*: one compute stage with 32 storage buffers, 15 uniform buffers of maxUniformBufferRange (64 KiB)
// each, 64 storage images in one set. Every binding is read or written at both ends of its range, so a driver that
// drops a binding past its old limit, or clamps a uniform buffer to 16 KiB, gives other words than the analytic ones.
// rasterization.limits.varyings_128: maxVertexOutputComponents = maxFragmentInputComponents = 128, 31 varyings
// that each move the output colour.
// texture.lod_bias.*: VkSamplerCreateInfo::mipLodBias up to maxSamplerLodBias (lavapipe's 16), added to an implicit
// LOD, a shader bias and an explicit LOD.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "case.hpp"
#include "compute_case.hpp"
#include "texture_case.hpp"
#include "vk_context.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kStorageBuffers = 32, kUniformBuffers = 15, kStorageImages = 64;
constexpr uint32_t kUniformWords = 65536 / 4, kGroup = 64;

// Buffer k holds 64 words k * 1000 + i; the shader adds k + 1 to each and writes the sum of word i over all
// buffers into buffer 0's word i as well, so every binding is both read and written.
void add_storage_buffers_case(CaseList& out) {
    std::string glsl = glsl_header(kGroup);
    for (uint32_t k = 0; k < kStorageBuffers; ++k)
        glsl += "layout(std430, binding=" + std::to_string(k) + ") buffer B" + std::to_string(k) + " { uint v[]; } b" +
                std::to_string(k) + ";\n";
    glsl += "void main() { uint i = gl_GlobalInvocationID.x; uint sum = 0u;\n";
    for (uint32_t k = 1; k < kStorageBuffers; ++k) {
        const std::string b = "b" + std::to_string(k);
        glsl += "  sum += " + b + ".v[i]; " + b + ".v[i] += " + std::to_string(k + 1) + "u;\n";
    }
    glsl += "  b0.v[i] = sum; }\n";
    ComputeSpec s;
    s.shaders = {glsl};
    std::vector<std::vector<uint32_t>> want(kStorageBuffers);
    for (uint32_t k = 0; k < kStorageBuffers; ++k) {
        std::vector<uint32_t> words(kGroup);
        for (uint32_t i = 0; i < kGroup; ++i) words[i] = k * 1000 + i;
        s.buffers.push_back({k == 0 ? std::vector<uint32_t>(kGroup, kMarker) : words});
        for (uint32_t i = 0; i < kGroup; ++i) want[k].push_back(words[i] + k + 1);
    }
    want[0].assign(kGroup, 0);
    for (uint32_t k = 1; k < kStorageBuffers; ++k)
        for (uint32_t i = 0; i < kGroup; ++i) want[0][i] += k * 1000 + i;
    s.steps = {dispatch(0, 1)};
    add_compute_case(out, "limits.storage_buffers_32", std::move(s), [want](const std::vector<Plane>& planes) {
        for (uint32_t k = 0; k < kStorageBuffers; ++k)
            if (std::string why = words_are(k, want[k])(planes); !why.empty()) return why;
        return std::string();
    });
}

// Uniform buffer k (bindings 0..14) is 64 KiB of words k << 16 | w; invocation i reads word i and word
// 16383 - i of each (the last vec4 of the range included) and writes their sum over all buffers.
void add_uniform_buffers_case(CaseList& out) {
    std::string glsl = glsl_header(kGroup);
    for (uint32_t k = 0; k < kUniformBuffers; ++k)
        glsl += "layout(std140, binding=" + std::to_string(k) + ") uniform U" + std::to_string(k) + " { uvec4 v[" +
                std::to_string(kUniformWords / 4) + "]; } u" + std::to_string(k) + ";\n";
    glsl += "layout(std430, binding=" + std::to_string(kUniformBuffers) + ") buffer O { uint o[]; };\n";
    glsl += "void main() { uint i = gl_GlobalInvocationID.x, j = " + std::to_string(kUniformWords - 1) +
            "u - i; uint sum = 0u;\n";
    for (uint32_t k = 0; k < kUniformBuffers; ++k) {
        const std::string u = "u" + std::to_string(k);
        glsl += "  sum += " + u + ".v[i / 4u][i % 4u] + " + u + ".v[j / 4u][j % 4u];\n";
    }
    glsl += "  o[i] = sum; }\n";
    ComputeSpec s;
    s.shaders = {glsl};
    for (uint32_t k = 0; k < kUniformBuffers; ++k) {
        std::vector<uint32_t> words(kUniformWords);
        for (uint32_t w = 0; w < kUniformWords; ++w) words[w] = k << 16 | w;
        s.buffers.push_back({words, true, false});
    }
    s.buffers.push_back({std::vector<uint32_t>(kGroup, kMarker)});
    std::vector<uint32_t> want(kGroup, 0);
    for (uint32_t i = 0; i < kGroup; ++i)
        for (uint32_t k = 0; k < kUniformBuffers; ++k) want[i] += (k << 16 | i) + (k << 16 | (kUniformWords - 1 - i));
    s.steps = {dispatch(0, 1)};
    add_compute_case(out, "limits.uniform_buffers_15_of_64k", std::move(s), words_are(kUniformBuffers, want));
}

// 64 R32_UINT storage images of 4x4: invocation (x, y) of a 4x4 group stores image k's texel (x, y) as
// k * 100 + y * 4 + x + 1 into every image; every image is read back as its own plane.
void add_storage_images_case(CaseList& out) {
    std::string glsl = glsl_header(4, 4);
    for (uint32_t k = 0; k < kStorageImages; ++k)
        glsl +=
            "layout(binding=" + std::to_string(k) + ", r32ui) uniform writeonly uimage2D i" + std::to_string(k) + ";\n";
    glsl += "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy); uint t = uint(p.y * 4 + p.x + 1);\n";
    for (uint32_t k = 0; k < kStorageImages; ++k)
        glsl += "  imageStore(i" + std::to_string(k) + ", p, uvec4(" + std::to_string(k * 100) + "u + t));\n";
    glsl += "}\n";
    ComputeSpec s;
    s.shaders = {glsl};
    for (uint32_t k = 0; k < kStorageImages; ++k) {
        ComputeImage im;
        im.format = VK_FORMAT_R32_UINT;
        im.width = im.height = 4;
        s.images.push_back(im);
    }
    s.steps = {dispatch(0, 1)};
    add_compute_case(out, "limits.storage_images_64", std::move(s), [](const std::vector<Plane>& planes) {
        for (uint32_t k = 0; k < kStorageImages; ++k) {
            const std::string name = "image" + std::to_string(k);
            const Plane* p = nullptr;
            for (const Plane& q : planes)
                if (q.name == name) p = &q;
            if (p == nullptr || p->data.size() != 64) return name + " is missing or has the wrong size";
            for (uint32_t t = 0; t < 16; ++t) {
                uint32_t got;
                std::memcpy(&got, p->data.data() + 4 * t, 4);
                if (got != k * 100 + t + 1)
                    return name + " texel " + std::to_string(t) + " is " + std::to_string(got) + ", expected " +
                           std::to_string(k * 100 + t + 1);
            }
        }
        return std::string();
    });
}

// 128 output components as the validation layer counts them: gl_PerVertex's 7 (position, point size, one clip and
// one cull distance), 30 vec4 varyings and a float at location 30. Varying k = the vertex colour scaled by
// (k + 1) / 32 plus the position's x and y times k / 64 (each differs from the next across the triangle); the colour
// is their mean plus a sixteenth of the float, so a varying dropped or swapped with its neighbour moves every pixel.
Scene varyings_scene() {
    constexpr int kVaryings = 30;
    std::string vs =
        "#version 450\nlayout(location=0) in vec4 in_pos;\nlayout(location=1) in vec4 in_color;\n"
        "layout(location=2) in vec2 in_uv;\nlayout(location=3) in float in_psize;\n";
    std::string fs = "#version 450\nlayout(location=0) out vec4 o;\n";
    for (int k = 0; k < kVaryings; ++k) {
        vs += "layout(location=" + std::to_string(k) + ") out vec4 v" + std::to_string(k) + ";\n";
        fs += "layout(location=" + std::to_string(k) + ") in vec4 v" + std::to_string(k) + ";\n";
    }
    vs +=
        "layout(location=30) out float last;\nvoid main() {\n  gl_Position = in_pos;\n"
        "  last = in_uv.x * 0.5 + in_psize * 0.25;\n";
    fs += "layout(location=30) in float last;\nvoid main() {\n  vec4 s = vec4(0.0);\n";
    for (int k = 0; k < kVaryings; ++k) {
        const std::string v = "v" + std::to_string(k);
        vs += "  " + v + " = in_color * " + std::to_string(k + 1) + ".0 / 32.0 + vec4(in_pos.xy, in_pos.yx) * " +
              std::to_string(k) + ".0 / 64.0;\n";
        fs += "  s += " + v + (k % 2 ? ".wzyx" : "") + ";\n";
    }
    vs += "}\n";
    fs += "  o = s / 30.0 + vec4(last * 0.0625);\n}\n";
    Draw d;
    d.vertices = {vtxc(-0.9f, -0.8f, {1, 0, 0, 1}), vtxc(0.85f, -0.6f, {0, 1, 0, 0.5f}),
                  vtxc(-0.2f, 0.9f, {0, 0, 1, 0.25f})};
    d.vertex_glsl = vs;
    d.fragment_glsl = fs;
    Scene s = one_draw(std::move(d));
    s.unsupported = [](const DeviceContext& c) -> std::string {
        if (c.props.limits.maxVertexOutputComponents < 128 || c.props.limits.maxFragmentInputComponents < 128)
            return "VkPhysicalDeviceLimits::maxVertexOutputComponents or maxFragmentInputComponents below 128";
        return {};
    };
    return s;
}

// A 256x256 gradient of 9 levels, each tinted (render_objects.cpp texel), mip LINEAR or NEAREST, REPEAT: the
// level and the blend weight between two levels show in every pixel of the RGBA32F target. REPEAT on a
// power-of-two RGBA8 view is the compiled tier's sampler (shader/jit/sample_rgba8.cpp) as well as the interpreter's.
TextureSpec lod_bias_texture(float bias, VkSamplerMipmapMode mip) {
    TextureSpec t;
    t.pattern = TexPattern::kGradient;
    t.width = t.height = 256;
    t.mip_levels = 9;
    t.mag = t.min = VK_FILTER_LINEAR;
    t.mip_mode = mip;
    t.lod_bias = bias;
    return t;
}

// One textured quad of `t`, `px` pixels wide, whose implicit LOD is about `lambda` (rho = u1 * 256 / px texels a
// pixel), its right edge projected (w = 3) so that the LOD falls by log2(3) across it; `body` writes o_color.
Scene lod_bias_scene(const TextureSpec& t, float lambda, float px, const std::string& body) {
    QuadUv q;
    q.u1 = std::exp2(lambda) * px / 256.0f;
    q.x_scale = px / 64.0f;
    q.projected = true;
    return textured_nd(textured_quad(t, q), "sampler2D", body);
}

// The sampler's bias on implicit LODs that it carries to the middle of the mip chain (1.3 + bias below 0 puts
// the LOD near 1.3; a positive bias goes past the last level, where the LOD clamps to it), then on an explicit LOD
// (textureLod: lavapipe adds the sampler's bias to it, lp_build_lod_selector) so that the sum runs from -12 to 12
// across the 64 pixels, then with a
// shader bias whose sum with the sampler's passes 16 (lavapipe clamps neither the sum nor either bias, only the
// LOD to the sampler's min/max and the view's levels).
void add_lod_bias_cases(CaseList& out) {
    struct Bias {
        const char* name;
        float v;
    };
    const Bias biases[] = {{"3_5", 3.5f}, {"6_25", 6.25f},     {"minus_2_75", -2.75f}, {"minus_15_75", -15.75f},
                           {"16", 16.0f}, {"minus_16", -16.0f}};
    for (VkSamplerMipmapMode mip : {VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST}) {
        const std::string m = mip == VK_SAMPLER_MIPMAP_MODE_LINEAR ? "_mip_linear" : "_mip_nearest";
        for (const Bias& b : biases) {
            const TextureSpec t = lod_bias_texture(b.v, mip);
            // below 0: the implicit LOD that the bias brings to 1.3 (coordinates below 2^22 texels on 8 pixels)
            const float lambda = b.v < 0.0f ? 1.3f - b.v : 2.4f, px = b.v < 0.0f ? 8.0f : 64.0f;
            out.push_back({"texture.lod_bias.implicit_" + std::string(b.name) + m,
                           [=] { return lod_bias_scene(t, lambda, px, "    o_color = texture(tex, v_uv);\n"); }});
            out.push_back({"texture.lod_bias.explicit_lod_" + std::string(b.name) + m, [=] {
                               return lod_bias_scene(
                                   t, 0.0f, 64.0f,
                                   "    o_color = textureLod(tex, v_uv, gl_FragCoord.x * 0.375 - 12.0 - (" +
                                       std::to_string(b.v) + "));\n");
                           }});
        }
        // sampler bias 16 plus a shader bias of 4, and -16 plus -4 on an implicit LOD of 18.5 (the Vulkan
        // formula clamps the sum to maxSamplerLodBias: level 2.5 where lavapipe magnifies)
        out.push_back({"texture.lod_bias.sum_past_16" + m, [=] {
                           return lod_bias_scene(lod_bias_texture(16.0f, mip), -2.6f, 64.0f,
                                                 "    o_color = texture(tex, v_uv, 4.0);\n");
                       }});
        out.push_back({"texture.lod_bias.sum_past_minus_16" + m, [=] {
                           return lod_bias_scene(lod_bias_texture(-16.0f, mip), 18.5f, 8.0f,
                                                 "    o_color = texture(tex, v_uv, -4.0);\n");
                       }});
    }
}

}  // namespace

void add_compute_limit_cases(CaseList& out) {
    add_storage_buffers_case(out);
    add_uniform_buffers_case(out);
    add_storage_images_case(out);
    out.push_back({"rasterization.limits.varyings_128", [] { return varyings_scene(); }});
    add_lod_bias_cases(out);
}

}  // namespace tilevk::cts
