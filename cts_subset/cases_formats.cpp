// format.*: colour-attachment formats beyond RGBA8 / sRGB / half / float, each compared byte for byte with
// lavapipe: a gradient background and overlapping triangles whose colours reach outside [0, 1] (so the stores'
// clamping and rounding show), with alpha blending where the format blends, at 1x and at 4x (render-pass resolve:
// an average for normalized and float formats, sample 0 for integers), with a clear colour that also reaches
// outside the range. Integer formats are written by shaders with integer outputs past each channel's range.
#include <string>

#include "case.hpp"

namespace tilevk::cts {
namespace {

enum class Kind { kNorm, kSnorm, kUint, kSint };

struct FormatCase {
    const char* name;
    VkFormat format;
    Kind kind;
    bool blend;  // the format reports COLOR_ATTACHMENT_BLEND (UNORM and float kinds)
};

const FormatCase kFormats[] = {
    // formats reported before, now also at 4x
    {"r8g8b8a8_srgb", VK_FORMAT_R8G8B8A8_SRGB, Kind::kNorm, true},
    {"b8g8r8a8_srgb", VK_FORMAT_B8G8R8A8_SRGB, Kind::kNorm, true},
    {"r16g16b16a16_sfloat", VK_FORMAT_R16G16B16A16_SFLOAT, Kind::kNorm, true},
    {"r8g8b8a8_snorm", VK_FORMAT_R8G8B8A8_SNORM, Kind::kSnorm, false},
    {"r8_snorm", VK_FORMAT_R8_SNORM, Kind::kSnorm, false},
    {"b8g8r8a8_snorm", VK_FORMAT_B8G8R8A8_SNORM, Kind::kSnorm, false},
    {"a8b8g8r8_unorm_pack32", VK_FORMAT_A8B8G8R8_UNORM_PACK32, Kind::kNorm, true},
    {"a8b8g8r8_srgb_pack32", VK_FORMAT_A8B8G8R8_SRGB_PACK32, Kind::kNorm, true},
    {"r16_unorm", VK_FORMAT_R16_UNORM, Kind::kNorm, true},
    {"r16g16_unorm", VK_FORMAT_R16G16_UNORM, Kind::kNorm, true},
    {"r16g16b16a16_unorm", VK_FORMAT_R16G16B16A16_UNORM, Kind::kNorm, true},
    {"r16_snorm", VK_FORMAT_R16_SNORM, Kind::kSnorm, false},
    {"r16g16b16a16_snorm", VK_FORMAT_R16G16B16A16_SNORM, Kind::kSnorm, false},
    {"r16_sfloat", VK_FORMAT_R16_SFLOAT, Kind::kNorm, true},
    {"r16g16_sfloat", VK_FORMAT_R16G16_SFLOAT, Kind::kNorm, true},
    {"r32g32b32_sfloat", VK_FORMAT_R32G32B32_SFLOAT, Kind::kNorm, true},
    {"r5g6b5_unorm_pack16", VK_FORMAT_R5G6B5_UNORM_PACK16, Kind::kNorm, true},
    {"b5g6r5_unorm_pack16", VK_FORMAT_B5G6R5_UNORM_PACK16, Kind::kNorm, true},
    {"r5g5b5a1_unorm_pack16", VK_FORMAT_R5G5B5A1_UNORM_PACK16, Kind::kNorm, true},
    {"b5g5r5a1_unorm_pack16", VK_FORMAT_B5G5R5A1_UNORM_PACK16, Kind::kNorm, true},
    {"a1r5g5b5_unorm_pack16", VK_FORMAT_A1R5G5B5_UNORM_PACK16, Kind::kNorm, true},
    {"b4g4r4a4_unorm_pack16", VK_FORMAT_B4G4R4A4_UNORM_PACK16, Kind::kNorm, true},
    // VK_EXT_4444_formats (the device enables formatA4R4G4B4 / formatA4B4G4R4 where offered)
    {"a4r4g4b4_unorm_pack16", VK_FORMAT_A4R4G4B4_UNORM_PACK16, Kind::kNorm, true},
    {"a4b4g4r4_unorm_pack16", VK_FORMAT_A4B4G4R4_UNORM_PACK16, Kind::kNorm, true},
    {"a2b10g10r10_unorm_pack32", VK_FORMAT_A2B10G10R10_UNORM_PACK32, Kind::kNorm, true},
    {"a2r10g10b10_unorm_pack32", VK_FORMAT_A2R10G10B10_UNORM_PACK32, Kind::kNorm, true},
    {"b10g11r11_ufloat_pack32", VK_FORMAT_B10G11R11_UFLOAT_PACK32, Kind::kNorm, true},
    {"r8g8b8a8_uint", VK_FORMAT_R8G8B8A8_UINT, Kind::kUint, false},
    {"r8g8b8a8_sint", VK_FORMAT_R8G8B8A8_SINT, Kind::kSint, false},
    {"r8_uint", VK_FORMAT_R8_UINT, Kind::kUint, false},
    {"b8g8r8a8_sint", VK_FORMAT_B8G8R8A8_SINT, Kind::kSint, false},
    {"r16g16b16a16_uint", VK_FORMAT_R16G16B16A16_UINT, Kind::kUint, false},
    {"r16g16b16a16_sint", VK_FORMAT_R16G16B16A16_SINT, Kind::kSint, false},
    {"r16g16_sint", VK_FORMAT_R16G16_SINT, Kind::kSint, false},
    {"r32_uint", VK_FORMAT_R32_UINT, Kind::kUint, false},
    {"r32g32b32a32_sint", VK_FORMAT_R32G32B32A32_SINT, Kind::kSint, false},
    {"a2b10g10r10_uint_pack32", VK_FORMAT_A2B10G10R10_UINT_PACK32, Kind::kUint, false},
    {"a2r10g10b10_uint_pack32", VK_FORMAT_A2R10G10B10_UINT_PACK32, Kind::kUint, false},
};

// The vertex shader's varyings reach the fragment shader; integer targets get their integers from them.
std::string integer_fragment(Kind k) {
    const char* head =
        "#version 450\n"
        "layout(location=0) in vec4 v_color;\n"
        "layout(location=1) in vec2 v_uv;\n";
    if (k == Kind::kUint)
        return std::string(head) +
               "layout(location=0) out uvec4 o;\n"
               "void main() { o = uvec4(max(v_color, 0.0) * vec4(300.0, 1500.0, 70000.0, 3.0e9)); }\n";
    return std::string(head) +
           "layout(location=0) out ivec4 o;\n"
           "void main() { o = ivec4((v_color - 0.5) * vec4(600.0, 3000.0, 140000.0, 2.0e9)); }\n";
}

// A background over the whole target and six triangles with colours in [-0.5, 1.5].
Scene layers(const FormatCase& f, bool blend) {
    Draw bg;
    bg.vertices = {vtx(-1, -1, 0, 1, {-0.4f, 0.9f, 0.3f, 0.2f}), vtx(3, -1, 0, 1, {0.8f, 1.4f, 0.6f, 1.0f}),
                   vtx(-1, 3, 0, 1, {0.4f, 0.5f, 1.3f, 0.6f})};
    Draw top;
    top.vertices = {
        vtx(-0.9f, -0.9f, 0, 1, {1.5f, 0.2f, -0.5f, 0.9f}), vtx(0.9f, -0.6f, 0, 1, {0.0f, 1.0f, 0.4f, 0.1f}),
        vtx(-0.5f, 0.9f, 0, 1, {0.3f, -0.2f, 1.0f, 0.5f}),  vtx(0.9f, 0.9f, 0, 1, {0.7f, 0.7f, 0.2f, 1.3f}),
        vtx(0.2f, -0.9f, 0, 1, {1.0f, 1.2f, 1.0f, 0.0f}),   vtx(-0.9f, 0.4f, 0, 1, {0.5f, 0.1f, 0.9f, -0.3f})};
    if (blend)
        top.blend = {VK_TRUE,
                     VK_BLEND_FACTOR_SRC_ALPHA,
                     VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                     VK_BLEND_OP_ADD,
                     VK_BLEND_FACTOR_ONE,
                     VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                     VK_BLEND_OP_ADD,
                     0xF};
    if (f.kind == Kind::kUint || f.kind == Kind::kSint) {
        bg.fragment_glsl = top.fragment_glsl = integer_fragment(f.kind);
    }
    Scene s = one_draw(bg);
    s.target.color = f.format;
    // Integer formats read the clear colour's bits as integers (0.1f = 0x3dcccccd: saturated by narrow channels).
    const float clear[4] = {-0.25f, 0.1f, 1.75f, 0.6f};
    for (int i = 0; i < 4; ++i) s.target.clear_color[i] = clear[i];
    // A depth attachment keeps lavapipe off its linear rasterizer for the formats it could take there.
    s.target.depth = VK_FORMAT_D32_SFLOAT;
    s.draws.push_back(top);
    return s;
}

}  // namespace

void add_format_cases(CaseList& out) {
    for (const FormatCase& f : kFormats) {
        const std::string base = std::string("format.") + f.name;
        out.push_back({base + ".draw", [f] { return layers(f, false); }, nullptr, ""});
        if (f.blend) out.push_back({base + ".blend", [f] { return layers(f, true); }, nullptr, ""});
        out.push_back({base + ".4x",
                       [f] {
                           Scene s = layers(f, f.blend);
                           s.target.samples = VK_SAMPLE_COUNT_4_BIT;
                           return s;
                       },
                       nullptr, ""});
    }
}

}  // namespace tilevk::cts
