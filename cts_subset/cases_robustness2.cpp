// compute.robustness2.* (VK_EXT_robustness2): null descriptors of every buffer and image kind, a null vertex buffer,
// robustBufferAccess2's exact bounds and robustImageAccess2's out-of-view loads. Every case is compared with the
// reference byte for byte and checked against the answer computed here from the rules (docs/lavapipe-rules.md
// "Buffer bounds" and "Null descriptors").
#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

ComputeBuffer buffer_of(std::vector<uint32_t> words) {
    ComputeBuffer b;
    b.words = std::move(words);
    return b;
}

ComputeBuffer null_buffer(std::vector<uint32_t> words, bool uniform, VkFormat texel_format = VK_FORMAT_UNDEFINED) {
    ComputeBuffer b = buffer_of(std::move(words));
    b.uniform = uniform;
    b.texel_format = texel_format;
    b.null_descriptor = true;
    return b;
}

std::vector<uint32_t> counting(uint32_t n, uint32_t first) {
    std::vector<uint32_t> w(n);
    for (uint32_t i = 0; i < n; ++i) w[i] = first + i;
    return w;
}

// Loads through a null storage buffer, uniform buffer and storage texel buffer read 0 (a null texel has no alpha
// 1: llvmpipe's format-NONE texture returns all zeros), stores and atomics through them do nothing and atomics
// return 0, sizes are 0. The buffers behind the bindings are never touched. The load comes before the store: lavapipe's
// NIR forwards a store to a later load of the same invocation (nir_opt_copy_prop_vars), so it would read the 7 back.
void add_null_buffers_case(CaseList& out) {
    ComputeSpec s;
    s.buffers = {buffer_of(std::vector<uint32_t>(16 * 8, kMarker)), null_buffer(counting(16, 1), false),
                 null_buffer(counting(16, 100), true), null_buffer(counting(16, 200), false, VK_FORMAT_R32_UINT)};
    s.shaders = {glsl_header(16) +
                 "layout(std430, binding=0) buffer R { uint res[]; };\n"
                 "layout(std430, binding=1) buffer N { uint v[]; } nb;\n"
                 "layout(std140, binding=2) uniform U { uvec4 u[4]; } nu;\n"
                 "layout(binding=3, r32ui) uniform uimageBuffer nt;\n"
                 "void main() {\n"
                 "  uint i = gl_LocalInvocationID.x;\n"
                 "  res[i * 8u] = nb.v[i];\n"
                 "  nb.v[i] = 7u;\n"
                 "  res[i * 8u + 1u] = atomicAdd(nb.v[i], 5u);\n"
                 "  res[i * 8u + 2u] = nu.u[i & 3u].x + nu.u[i & 3u].w;\n"
                 "  uvec4 t = imageLoad(nt, int(i));\n"
                 "  res[i * 8u + 3u] = t.x;\n"
                 "  res[i * 8u + 4u] = t.w;\n"
                 "  imageStore(nt, int(i), uvec4(9u));\n"
                 "  res[i * 8u + 5u] = uint(imageSize(nt));\n"
                 "  res[i * 8u + 6u] = imageAtomicAdd(nt, int(i), 3u);\n"
                 "  res[i * 8u + 7u] = uint(nb.v.length());\n"
                 "}\n"};
    add_compute_case(out, "robustness2.null_buffers", std::move(s),
                     all_of({words_are(0, std::vector<uint32_t>(16 * 8, 0)), words_are(1, counting(16, 1)),
                             words_are(2, counting(16, 100)), words_are(3, counting(16, 200))}));
}

// A null storage image and a null combined image sampler: loads, fetches and samples read (0, 0, 0, 0) whatever
// the format (no alpha 1), sizes and level counts are 0, stores do nothing.
void add_null_images_case(CaseList& out) {
    ComputeSpec s;
    s.buffers = {buffer_of(std::vector<uint32_t>(16 * 16, kMarker))};
    ComputeImage storage;
    storage.null_descriptor = true;
    ComputeImage sampled;
    sampled.format = VK_FORMAT_R8_UNORM;  // a format without alpha: a null view still gives alpha 0
    sampled.sampled = true;
    sampled.null_descriptor = true;
    s.images = {storage, sampled};
    s.shaders = {glsl_header(16) +
                 "layout(std430, binding=0) buffer R { uint res[]; };\n"
                 "layout(binding=1, rgba8) uniform image2D ni;\n"
                 "layout(binding=2) uniform sampler2D ns;\n"
                 "void main() {\n"
                 "  uint i = gl_LocalInvocationID.x;\n"
                 "  ivec2 p = ivec2(i, i / 4u);\n"
                 "  imageStore(ni, p, vec4(1.0));\n"
                 "  uint o = i * 16u;\n"
                 "  vec4 a = imageLoad(ni, p);\n"
                 "  vec4 b = textureLod(ns, vec2(float(i) / 16.0, 0.5), 0.0);\n"
                 "  vec4 c = texelFetch(ns, p, 0);\n"
                 "  for (uint k = 0u; k < 4u; ++k) {\n"
                 "    res[o + k] = floatBitsToUint(a[k]);\n"
                 "    res[o + 4u + k] = floatBitsToUint(b[k]);\n"
                 "    res[o + 8u + k] = floatBitsToUint(c[k]);\n"
                 "  }\n"
                 "  ivec2 s1 = imageSize(ni);\n"
                 "  res[o + 12u] = uint(s1.x) + uint(s1.y);\n"
                 "  ivec2 s2 = textureSize(ns, 0);\n"
                 "  res[o + 13u] = uint(s2.x);\n"
                 "  res[o + 14u] = uint(s2.y);\n"
                 "  res[o + 15u] = uint(textureQueryLevels(ns));\n"
                 "}\n"};
    add_compute_case(out, "robustness2.null_images", std::move(s), words_are(0, std::vector<uint32_t>(16 * 16, 0)));
}

// robustBufferAccess2 with ranges of 18 bytes: a storage buffer holds range >> 2 = 4 words (loads past them 0,
// stores dropped, atomics 0, length() 4); a uniform buffer DIV_ROUND_UP(18, 4) = 5 words (the word straddling the
// end is read whole), as llvmpipe bounds them (robustStorage/UniformBufferAccessSizeAlignment 1).
void add_tight_bounds_case(CaseList& out) {
    ComputeSpec s;
    ComputeBuffer storage = buffer_of(counting(8, 1));
    storage.range = 18;
    ComputeBuffer uniform = buffer_of(counting(8, 100));
    uniform.uniform = true;
    uniform.range = 18;
    s.buffers = {buffer_of(std::vector<uint32_t>(25, kMarker)), storage, uniform};
    s.shaders = {glsl_header(1) +
                 "layout(std430, binding=0) buffer R { uint res[]; };\n"
                 "layout(std430, binding=1) buffer S { uint v[]; } sb;\n"
                 "layout(std140, binding=2) uniform U { uvec4 u[2]; } ub;\n"
                 "void main() {\n"
                 "  for (uint k = 0u; k < 8u; ++k) res[k] = sb.v[k];\n"
                 "  for (uint k = 0u; k < 8u; ++k) res[8u + k] = ub.u[k / 4u][k % 4u];\n"
                 "  res[16] = uint(sb.v.length());\n"
                 "  for (uint k = 0u; k < 8u; ++k) sb.v[k] = 50u + k;\n"
                 "  for (uint k = 0u; k < 8u; ++k) res[17u + k] = atomicAdd(sb.v[k], 1u);\n"
                 "}\n"};
    std::vector<uint32_t> want = {1, 2, 3, 4, 0, 0, 0, 0, 100, 101, 102, 103, 104, 0, 0, 0, 4};
    for (uint32_t k = 0; k < 8; ++k) want.push_back(k < 4 ? 50 + k : 0);
    add_compute_case(
        out, "robustness2.tight_bounds", std::move(s),
        all_of({words_are(0, want), words_are(1, {51, 52, 53, 54, 5, 6, 7, 8}), words_are(2, counting(8, 100))}));
}

// robustImageAccess2: loads outside a storage image and texel fetches outside a sampled one give (0, 0, 0, 0),
// alpha 1 (the integer 1 for integer formats) when the format has no alpha.
void add_image_out_of_bounds_case(CaseList& out) {
    ComputeSpec s;
    s.buffers = {buffer_of(std::vector<uint32_t>(4 * 12, kMarker))};
    ComputeImage rgba;
    rgba.init = std::vector<uint8_t>(16 * 16 * 4, 0x80);
    ComputeImage r32;
    r32.format = VK_FORMAT_R32_UINT;
    r32.init = std::vector<uint8_t>(16 * 16 * 4, 0x11);
    ComputeImage r8;
    r8.format = VK_FORMAT_R8_UNORM;
    r8.sampled = true;
    r8.init = std::vector<uint8_t>(16 * 16, 0x40);
    s.images = {rgba, r32, r8};
    s.shaders = {glsl_header(4) +
                 "layout(std430, binding=0) buffer R { uint res[]; };\n"
                 "layout(binding=1, rgba8) uniform readonly image2D a;\n"
                 "layout(binding=2, r32ui) uniform readonly uimage2D b;\n"
                 "layout(binding=3) uniform sampler2D c;\n"
                 "const ivec2 kOut[4] = ivec2[](ivec2(-1, 0), ivec2(16, 0), ivec2(0, 16), ivec2(3, -7));\n"
                 "void main() {\n"
                 "  uint i = gl_LocalInvocationID.x;\n"
                 "  vec4 x = imageLoad(a, kOut[i]);\n"
                 "  uvec4 y = imageLoad(b, kOut[i]);\n"
                 "  vec4 z = texelFetch(c, kOut[i], 0);\n"
                 "  for (uint k = 0u; k < 4u; ++k) {\n"
                 "    res[i * 12u + k] = floatBitsToUint(x[k]);\n"
                 "    res[i * 12u + 4u + k] = y[k];\n"
                 "    res[i * 12u + 8u + k] = floatBitsToUint(z[k]);\n"
                 "  }\n"
                 "}\n"};
    std::vector<uint32_t> want;
    for (uint32_t i = 0; i < 4; ++i) {
        const std::vector<uint32_t> lane = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, fbits(1.0f)};
        want.insert(want.end(), lane.begin(), lane.end());
    }
    add_compute_case(out, "robustness2.image_out_of_bounds", std::move(s), words_are(0, want));
}

// A null vertex buffer (nullDescriptor): the attribute reads (0, 0, 0, 0) for R32G32B32A32_SFLOAT, whose alpha is
// a channel of the format (draw's fetch of a binding without bytes).
void add_null_vertex_buffer_case(CaseList& out) {
    constexpr uint32_t kVertices = 6;
    ComputeSpec s;
    s.buffers = {buffer_of(std::vector<uint32_t>(kVertices * 4, kMarker)),
                 null_buffer(counting(kVertices * 4, 1), false)};
    ComputeImage target;
    target.width = target.height = 32;
    target.attachment = true;
    s.images = {target};
    s.draw = {
        "#version 450\n"
        "layout(location=0) in vec4 attr;\n"
        "layout(std430, binding=0) buffer R { uint res[]; };\n"
        "void main() {\n"
        "  uint i = uint(gl_VertexIndex);\n"
        "  for (uint k = 0u; k < 4u; ++k) res[i * 4u + k] = floatBitsToUint(attr[k]);\n"
        "  gl_Position = vec4(float(i % 3u) * 0.5 - 0.8 + attr.x, float(i / 3u) * 0.8 - 0.8, attr.z, 1.0);\n"
        "}\n",
        "#version 450\nlayout(location=0) out vec4 o;\nvoid main() { o = vec4(0.25, 0.5, 1.0, 1.0); }\n", kVertices, 1};
    s.steps = {draw()};
    add_compute_case(
        out, "robustness2.null_vertex_buffer", std::move(s),
        all_of({words_are(0, std::vector<uint32_t>(kVertices * 4, 0)), words_are(1, counting(kVertices * 4, 1))}));
}

}  // namespace

void add_compute_robustness2_cases(CaseList& out) {
    add_null_buffers_case(out);
    add_null_images_case(out);
    add_tight_bounds_case(out);
    add_image_out_of_bounds_case(out);
    add_null_vertex_buffer_case(out);
}

}  // namespace tilevk::cts
