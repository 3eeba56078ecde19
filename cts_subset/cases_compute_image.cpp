// compute.image.* (imageLoad / imageStore / imageSize over the 16 storage formats Vulkan requires and the 23 of
// shaderStorageImageExtendedFormats) and
// compute.sync.* (a dispatch's writes seen by a later transfer, draw or dispatch in the same command buffer, and the
// reverse), judged byte for byte and, where the answer is known, against it.
#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

struct StorageFormat {
    VkFormat format;
    const char* name;       // case name
    const char* qualifier;  // GLSL format layout qualifier
    const char* prefix;     // "", "u", "i": image2D / uimage2D / iimage2D
    uint32_t texel_bytes;
};

const StorageFormat kFormats[] = {
    {VK_FORMAT_R8G8B8A8_UNORM, "rgba8_unorm", "rgba8", "", 4},
    {VK_FORMAT_R8G8B8A8_SNORM, "rgba8_snorm", "rgba8_snorm", "", 4},
    {VK_FORMAT_R8G8B8A8_UINT, "rgba8_uint", "rgba8ui", "u", 4},
    {VK_FORMAT_R8G8B8A8_SINT, "rgba8_sint", "rgba8i", "i", 4},
    {VK_FORMAT_R16G16B16A16_UINT, "rgba16_uint", "rgba16ui", "u", 8},
    {VK_FORMAT_R16G16B16A16_SINT, "rgba16_sint", "rgba16i", "i", 8},
    {VK_FORMAT_R16G16B16A16_SFLOAT, "rgba16_sfloat", "rgba16f", "", 8},
    {VK_FORMAT_R32_UINT, "r32_uint", "r32ui", "u", 4},
    {VK_FORMAT_R32_SINT, "r32_sint", "r32i", "i", 4},
    {VK_FORMAT_R32_SFLOAT, "r32_sfloat", "r32f", "", 4},
    {VK_FORMAT_R32G32_UINT, "rg32_uint", "rg32ui", "u", 8},
    {VK_FORMAT_R32G32_SINT, "rg32_sint", "rg32i", "i", 8},
    {VK_FORMAT_R32G32_SFLOAT, "rg32_sfloat", "rg32f", "", 8},
    {VK_FORMAT_R32G32B32A32_UINT, "rgba32_uint", "rgba32ui", "u", 16},
    {VK_FORMAT_R32G32B32A32_SINT, "rgba32_sint", "rgba32i", "i", 16},
    {VK_FORMAT_R32G32B32A32_SFLOAT, "rgba32_sfloat", "rgba32f", "", 16},
    // shaderStorageImageExtendedFormats
    {VK_FORMAT_R16G16_SFLOAT, "rg16_sfloat", "rg16f", "", 4},
    {VK_FORMAT_B10G11R11_UFLOAT_PACK32, "b10g11r11_ufloat", "r11f_g11f_b10f", "", 4},
    {VK_FORMAT_R16_SFLOAT, "r16_sfloat", "r16f", "", 2},
    {VK_FORMAT_R16G16B16A16_UNORM, "rgba16_unorm", "rgba16", "", 8},
    {VK_FORMAT_A2B10G10R10_UNORM_PACK32, "a2b10g10r10_unorm", "rgb10_a2", "", 4},
    {VK_FORMAT_R16G16_UNORM, "rg16_unorm", "rg16", "", 4},
    {VK_FORMAT_R8G8_UNORM, "rg8_unorm", "rg8", "", 2},
    {VK_FORMAT_R16_UNORM, "r16_unorm", "r16", "", 2},
    {VK_FORMAT_R8_UNORM, "r8_unorm", "r8", "", 1},
    {VK_FORMAT_R16G16B16A16_SNORM, "rgba16_snorm", "rgba16_snorm", "", 8},
    {VK_FORMAT_R16G16_SNORM, "rg16_snorm", "rg16_snorm", "", 4},
    {VK_FORMAT_R8G8_SNORM, "rg8_snorm", "rg8_snorm", "", 2},
    {VK_FORMAT_R16_SNORM, "r16_snorm", "r16_snorm", "", 2},
    {VK_FORMAT_R8_SNORM, "r8_snorm", "r8_snorm", "", 1},
    {VK_FORMAT_R16G16_SINT, "rg16_sint", "rg16i", "i", 4},
    {VK_FORMAT_R8G8_SINT, "rg8_sint", "rg8i", "i", 2},
    {VK_FORMAT_R16_SINT, "r16_sint", "r16i", "i", 2},
    {VK_FORMAT_R8_SINT, "r8_sint", "r8i", "i", 1},
    {VK_FORMAT_A2B10G10R10_UINT_PACK32, "a2b10g10r10_uint", "rgb10_a2ui", "u", 4},
    {VK_FORMAT_R16G16_UINT, "rg16_uint", "rg16ui", "u", 4},
    {VK_FORMAT_R8G8_UINT, "rg8_uint", "rg8ui", "u", 2},
    {VK_FORMAT_R16_UINT, "r16_uint", "r16ui", "u", 2},
    {VK_FORMAT_R8_UINT, "r8_uint", "r8ui", "u", 1},
    // Storage formats lavapipe offers beyond Vulkan's lists: GLSL has no qualifier of their own, the shaders declare
    // the RGBA8 one and the view's format converts.
    {VK_FORMAT_B8G8R8A8_UNORM, "bgra8_unorm", "rgba8", "", 4},
    {VK_FORMAT_A8B8G8R8_UNORM_PACK32, "abgr8_unorm", "rgba8", "", 4},
    {VK_FORMAT_A8B8G8R8_SNORM_PACK32, "abgr8_snorm", "rgba8_snorm", "", 4},
    {VK_FORMAT_A8B8G8R8_UINT_PACK32, "abgr8_uint", "rgba8ui", "u", 4},
    {VK_FORMAT_A8B8G8R8_SINT_PACK32, "abgr8_sint", "rgba8i", "i", 4},
};

bool is_half(VkFormat f) {
    return f == VK_FORMAT_R16G16B16A16_SFLOAT || f == VK_FORMAT_R16G16_SFLOAT || f == VK_FORMAT_R16_SFLOAT;
}
bool is_snorm(VkFormat f) {
    return f == VK_FORMAT_R8G8B8A8_SNORM || f == VK_FORMAT_R16G16B16A16_SNORM || f == VK_FORMAT_R16G16_SNORM ||
           f == VK_FORMAT_R8G8_SNORM || f == VK_FORMAT_R16_SNORM || f == VK_FORMAT_R8_SNORM ||
           f == VK_FORMAT_A8B8G8R8_SNORM_PACK32;
}
uint32_t snorm_bits(VkFormat f) {
    return f == VK_FORMAT_R8G8B8A8_SNORM || f == VK_FORMAT_R8G8_SNORM || f == VK_FORMAT_R8_SNORM ||
                   f == VK_FORMAT_A8B8G8R8_SNORM_PACK32
               ? 8
               : 16;
}

// Texels every format represents exactly: random bytes, except that float formats get finite values (halves with
// exponents below 30, floats of at most 24 significant bits, B10G11R11 fields with exponents below 31) so that no
// NaN payload is at the drivers' mercy.
std::vector<uint8_t> texels(const StorageFormat& f, uint32_t n, uint32_t seed) {
    Lcg g{seed};
    std::vector<uint8_t> b(size_t(n) * f.texel_bytes);
    if (f.format == VK_FORMAT_B10G11R11_UFLOAT_PACK32) {
        for (size_t i = 0; i + 3 < b.size(); i += 4) {
            const auto field = [&](uint32_t mbits) {
                return uint32_t(g.next() * 31.0f) << mbits | uint32_t(g.next() * float(1u << mbits));
            };
            const uint32_t w = field(6) | field(6) << 11 | field(5) << 22;
            std::memcpy(&b[i], &w, 4);
        }
    } else if (is_half(f.format)) {
        for (size_t i = 0; i + 1 < b.size(); i += 2) {
            const uint16_t h = uint16_t(uint32_t(g.next() * 2.0f) << 15 | uint32_t(g.next() * 30.0f) << 10 |
                                        uint32_t(g.next() * 1024.0f));
            std::memcpy(&b[i], &h, 2);
        }
    } else if (f.format == VK_FORMAT_R32_SFLOAT || f.format == VK_FORMAT_R32G32_SFLOAT ||
               f.format == VK_FORMAT_R32G32B32A32_SFLOAT) {
        for (size_t i = 0; i + 3 < b.size(); i += 4) {
            const uint32_t w = fbits((g.next() - 0.5f) * 1000.0f);
            std::memcpy(&b[i], &w, 4);
        }
    } else {
        for (uint8_t& x : b) x = uint8_t(g.next() * 256.0f);
    }
    return b;
}

// imageLoad from image 0, imageStore mirrored in x into image 1, imageSize into buffer 0. A load and store of the
// same format gives back the texel's bytes, except SNORM -2^(n-1), which reads as -1.0 and is written back as
// -(2^(n-1) - 1). `linear`: both images have VK_IMAGE_TILING_LINEAR (image.linear.*).
void add_copy_case(CaseList& out, const StorageFormat& f, bool linear) {
    constexpr uint32_t kW = 19, kH = 11;  // not a multiple of the 4x4 blocks, partly covered workgroups
    const std::string type = std::string(f.prefix) + "image2D";
    ComputeSpec s;
    s.shaders = {glsl_header(8, 4) + "layout(binding=1, " + f.qualifier + ") readonly uniform " + type +
                 " src;\n"
                 "layout(binding=2, " +
                 f.qualifier + ") writeonly uniform " + type +
                 " dst;\n"
                 "layout(std430, binding=0) buffer S { ivec2 size; };\n"
                 "void main() {\n"
                 "  ivec2 p = ivec2(gl_GlobalInvocationID.xy), sz = imageSize(src);\n"
                 "  if (p == ivec2(0)) size = sz;\n"
                 "  if (p.x < sz.x && p.y < sz.y) imageStore(dst, ivec2(sz.x - 1 - p.x, p.y), imageLoad(src, p));\n"
                 "}\n"};
    const std::vector<uint8_t> in = texels(f, kW * kH, uint32_t(f.format));
    s.buffers = {{{kMarker, kMarker}}};
    s.images = {{f.format, kW, kH, in}, {f.format, kW, kH, {}}};
    for (ComputeImage& im : s.images) im.linear = linear;
    s.steps = {dispatch(0, (kW + 7) / 8, (kH + 3) / 4)};
    std::vector<uint8_t> want(in.size());
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x)
            std::memcpy(&want[(y * kW + kW - 1 - x) * f.texel_bytes], &in[(y * kW + x) * f.texel_bytes], f.texel_bytes);
    if (is_snorm(f.format) && snorm_bits(f.format) == 8)
        for (uint8_t& b : want) b = b == 0x80 ? 0x81 : b;
    if (is_snorm(f.format) && snorm_bits(f.format) == 16)
        for (size_t i = 0; i + 1 < want.size(); i += 2)
            if (want[i] == 0x00 && want[i + 1] == 0x80) want[i] = 0x01;
    Check check = [want](const std::vector<Plane>& planes) -> std::string {
        for (const Plane& p : planes) {
            if (p.name != "image1") continue;
            for (size_t i = 0; i < want.size(); ++i)
                if (p.data[i] != want[i]) return "image1 byte " + std::to_string(i) + " differs from the source's";
            return {};
        }
        return "no plane image1";
    };
    add_compute_case(out, std::string(linear ? "image.linear.load_store." : "image.load_store.") + f.name, std::move(s),
                     all_of({words_are(0, {kW, kH}), check}));
}

// The same copy through storage texel buffers: 64 texels loaded from texel buffer 0 and stored mirrored into texel
// buffer 1 of the same format, and the loaded values' bits (floatBitsToUint for float formats) into buffer 2.
void add_texel_buffer_copy_case(CaseList& out, const StorageFormat& f) {
    constexpr uint32_t kN = 64;
    const std::string type = std::string(f.prefix) + "imageBuffer";
    const std::string bits = std::string(f.prefix).empty() ? "floatBitsToUint" : "uvec4";
    ComputeSpec s;
    s.shaders = {glsl_header(kN) + "layout(binding=0, " + f.qualifier + ") readonly uniform " + type +
                 " src;\n"
                 "layout(binding=1, " +
                 f.qualifier + ") writeonly uniform " + type +
                 " dst;\n"
                 "layout(std430, binding=2) buffer B { uvec4 loaded[]; };\n"
                 "void main() {\n"
                 "  int i = int(gl_GlobalInvocationID.x);\n"
                 "  imageStore(dst, " +
                 std::to_string(kN - 1) + " - i, imageLoad(src, i));\n  loaded[i] = " + bits +
                 "(imageLoad(src, i));\n"
                 "}\n"};
    const std::vector<uint8_t> in = texels(f, kN, uint32_t(f.format) + 1000u);
    std::vector<uint32_t> words((in.size() + 3) / 4, 0);
    std::memcpy(words.data(), in.data(), in.size());
    s.buffers = {{words, false, true, f.format},
                 {std::vector<uint32_t>(words.size(), kMarker), false, true, f.format},
                 {std::vector<uint32_t>(kN * 4, kMarker)}};
    s.steps = {dispatch(0, 1)};
    std::vector<uint8_t> want(in.size());
    for (uint32_t i = 0; i < kN; ++i)
        std::memcpy(&want[(kN - 1 - i) * f.texel_bytes], &in[i * f.texel_bytes], f.texel_bytes);
    if (is_snorm(f.format) && snorm_bits(f.format) == 8)
        for (uint8_t& b : want) b = b == 0x80 ? 0x81 : b;
    if (is_snorm(f.format) && snorm_bits(f.format) == 16)
        for (size_t i = 0; i + 1 < want.size(); i += 2)
            if (want[i] == 0x00 && want[i + 1] == 0x80) want[i] = 0x01;
    std::vector<uint32_t> want_words(words.size(), 0);
    std::memcpy(want_words.data(), want.data(), want.size());
    add_compute_case(out, std::string("texel_buffer.load_store.") + f.name, std::move(s), words_are(1, want_words));
}

// imageStore of values computed from the invocation (conversions, rounding and clamping of out-of-range values
// in the format's direction): byte comparison only. Without `declared`, the image has no format qualifier
// (shaderStorageImageWriteWithoutFormat: the view's format converts).
void add_store_case(CaseList& out, const StorageFormat& f, bool declared) {
    constexpr uint32_t kW = 16, kH = 16;
    const std::string type = std::string(f.prefix) + "image2D";
    const std::string value =
        std::string(f.prefix) == "u"   ? "uvec4(p.x * 37u + p.y * 4099u, p.y * 0x10001u, ~p.x, 0xFFFFFFFFu - p.y)"
        : std::string(f.prefix) == "i" ? "ivec4(int(p.x) * 37 - 300, -int(p.y) * 70001, int(p.x * p.y) - 128, "
                                         "int(0x80000000u + p.x))"
                                       : "vec4(float(p.x) / 7.0 - 1.1, float(p.y) / 3.0, -float(p.x * p.y) / 100.0, "
                                         "float(p.x) * 4099.5 - 1.0e4)";
    ComputeSpec s;
    const std::string qualifier = declared ? std::string(", ") + f.qualifier : std::string();
    s.shaders = {glsl_header(4, 4) + "layout(binding=0" + qualifier + ") writeonly uniform " + type +
                 " dst;\n"
                 "void main() { uvec2 p = gl_GlobalInvocationID.xy; imageStore(dst, ivec2(p), " +
                 value + "); }\n"};
    s.images = {{f.format, kW, kH, {}}};
    s.steps = {dispatch(0, kW / 4, kH / 4)};
    add_compute_case(out, std::string(declared ? "image.store_converted." : "image.store_without_format.") + f.name,
                     std::move(s), nullptr);
}

// --- compute.sync ---

// The words of the buffer after `doubled(i)` = 2 * (i + 1) written by a dispatch of 4 x 64.
const std::string kWriteDoubled = glsl_header(64) +
                                  "layout(std430, binding=0) buffer A { uint a[]; };\n"
                                  "void main() { uint i = gl_GlobalInvocationID.x; a[i] = 2u * (i + 1u); }\n";

std::vector<uint32_t> iota_doubled(uint32_t n) {
    std::vector<uint32_t> w(n);
    for (uint32_t i = 0; i < n; ++i) w[i] = 2 * (i + 1);
    return w;
}

void add_sync_cases(CaseList& out) {
    {  // compute -> transfer (buffer copy)
        ComputeSpec s;
        s.shaders = {kWriteDoubled};
        s.buffers = {{std::vector<uint32_t>(256, kMarker), false, false}, {std::vector<uint32_t>(256, kMarker)}};
        s.steps = {dispatch(0, 4), copy_buffer(0, 1)};
        add_compute_case(out, "sync.compute_to_transfer", std::move(s), words_are(1, iota_doubled(256)));
    }
    {  // transfer (fill) -> compute -> transfer (copy) -> compute: each stage reads what the one before wrote
        ComputeSpec s;
        s.shaders = {glsl_header(64) +
                     "layout(std430, binding=0) buffer A { uint a[]; };\n"
                     "void main() { uint i = gl_GlobalInvocationID.x; a[i] = a[i] * 3u + i; }\n"};
        s.buffers = {{std::vector<uint32_t>(256, kMarker)}, {std::vector<uint32_t>(256, 0), false, false}};
        s.steps = {fill(0, 5), dispatch(0, 4), copy_buffer(0, 1), fill(0, 1), copy_buffer(1, 0), dispatch(0, 4)};
        std::vector<uint32_t> want(256);
        for (uint32_t i = 0; i < 256; ++i) want[i] = (5 * 3 + i) * 3 + i;
        add_compute_case(out, "sync.transfer_to_compute", std::move(s), words_are(0, want));
    }
    {  // compute -> transfer (image to buffer) and transfer (buffer to image) -> compute
        ComputeSpec s;
        s.shaders = {glsl_header(8, 8) +
                     "layout(binding=2, r32ui) uniform uimage2D img;\n"
                     "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                     "  imageStore(img, p, imageLoad(img, p) + uvec4(p.x * 100 + p.y)); }\n"};
        std::vector<uint32_t> seed(256), want(256);
        for (uint32_t i = 0; i < 256; ++i) {
            seed[i] = i * 11;
            want[i] = seed[i] + 2 * ((i % 16) * 100 + i / 16);
        }
        s.buffers = {{seed, false, false}, {std::vector<uint32_t>(256, kMarker)}};
        s.images = {{VK_FORMAT_R32_UINT, 16, 16, {}}};
        s.steps = {copy_buffer_to_image(0, 0), dispatch(0, 2, 2), dispatch(0, 2, 2), copy_image_to_buffer(0, 1)};
        add_compute_case(out, "sync.image_transfer_compute_transfer", std::move(s), words_are(1, want));
    }
    const std::string fullscreen_vs =
        "#version 450\n"
        "void main() { vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);\n"
        "  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n";
    {  // compute -> draw: a dispatch writes the vertex buffer and a colour the fragment shader reads
        ComputeSpec s;
        s.shaders = {glsl_header(3) +
                     "layout(std430, binding=0) buffer V { vec4 v[3]; };\n"
                     "layout(std430, binding=1) buffer C { vec4 color; };\n"
                     "void main() { uint i = gl_LocalInvocationIndex;\n"
                     "  v[i] = vec4(i == 1u ? 3.0 : -1.0, i == 2u ? 3.0 : -1.0, 0.0, 1.0);\n"
                     "  if (i == 0u) color = vec4(0.0, 1.0, 0.0, 1.0); }\n"};
        s.buffers = {{std::vector<uint32_t>(12, 0), false, false}, {std::vector<uint32_t>(4, 0), false, false}};
        s.images = {{VK_FORMAT_R8G8B8A8_UNORM, 32, 32, std::vector<uint8_t>(32 * 32 * 4, 0x40), true}};
        s.draw = {"#version 450\nlayout(location=0) in vec4 pos;\nvoid main() { gl_Position = pos; }\n",
                  "#version 450\nlayout(std430, binding=1) readonly buffer C { vec4 color; };\n"
                  "layout(location=0) out vec4 o;\nvoid main() { o = color; }\n",
                  3, 0};
        s.steps = {dispatch(0, 1), draw()};
        add_compute_case(out, "sync.compute_to_draw", std::move(s), [](const std::vector<Plane>& planes) {
            for (const Plane& p : planes)
                if (p.name == "image0") {
                    for (size_t i = 0; i < p.data.size(); i += 4)
                        if (p.data[i] != 0 || p.data[i + 1] != 255 || p.data[i + 2] != 0 || p.data[i + 3] != 255)
                            return "image0 texel " + std::to_string(i / 4) + " is not the dispatch's green";
                    return std::string();
                }
            return std::string("no plane image0");
        });
    }
    {  // draw -> compute: the draw's colour attachment is read by a dispatch as a storage image
        ComputeSpec s;
        s.shaders = {glsl_header(8, 8) +
                     "layout(binding=1, rgba8) readonly uniform image2D img;\n"
                     "layout(std430, binding=0) buffer O { uint o[]; };\n"
                     "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                     "  o[p.y * 32 + p.x] = packUnorm4x8(imageLoad(img, p)); }\n"};
        s.buffers = {{std::vector<uint32_t>(32 * 32, kMarker)}};
        s.images = {{VK_FORMAT_R8G8B8A8_UNORM, 32, 32, {}, true}};
        s.draw = {fullscreen_vs,
                  "#version 450\nlayout(location=0) out vec4 o;\n"
                  "void main() { o = vec4(floor(gl_FragCoord.xy) / 255.0, 0.2, 1.0); }\n",
                  3, -1};
        s.steps = {draw(), dispatch(0, 4, 4)};
        std::vector<uint32_t> want(32 * 32);
        for (uint32_t y = 0; y < 32; ++y)
            for (uint32_t x = 0; x < 32; ++x) want[y * 32 + x] = x | y << 8 | 51u << 16 | 255u << 24;
        add_compute_case(out, "sync.draw_to_compute", std::move(s), words_are(0, want));
    }
}

}  // namespace

void add_compute_image_cases(CaseList& out) {
    for (const StorageFormat& f : kFormats) add_copy_case(out, f, false);
    for (const StorageFormat& f : kFormats) add_copy_case(out, f, true);
    for (const StorageFormat& f : kFormats) add_store_case(out, f, true);
    for (const StorageFormat& f : kFormats) add_store_case(out, f, false);
    for (const StorageFormat& f : kFormats) add_texel_buffer_copy_case(out, f);
    add_sync_cases(out);
}

}  // namespace tilevk::cts
