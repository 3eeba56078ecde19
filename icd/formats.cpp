#include "formats.h"

namespace tilevk::icd {
namespace {

constexpr VkFormatFeatureFlags kTransfer = VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
// vkCmdBlitImage (execute_blit.cpp): every colour format (NEAREST and LINEAR) and D16/D32 (NEAREST only).
constexpr VkFormatFeatureFlags kBlit = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT;
// Colour formats: drawn and blended by rast/fragment, sampled (nearest and linear) by shader/.
constexpr VkFormatFeatureFlags kColor =
    kTransfer | kBlit | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
    VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
constexpr VkFormatFeatureFlags kDepth = kTransfer | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
// D16 and D32 are also sampled (shadow samplers); D32_S8's 8-byte texel is not a layout shader/ reads.
constexpr VkFormatFeatureFlags kDepthSampled = kDepth | kBlit | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
constexpr VkFormatFeatureFlags kVertex = VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT;
// Uniform texel buffers: texelFetch through shader/'s texture decode (the linear colour formats it reads).
constexpr VkFormatFeatureFlags kVertexTexel = kVertex | VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT;
constexpr VkImageAspectFlags kC = VK_IMAGE_ASPECT_COLOR_BIT;

// Colour image formats of issue 5, the depth formats, and the vertex-only formats.
constexpr FormatInfo kFormats[] = {
    {VK_FORMAT_R8_UNORM, 1, 1, false, PackKind::kUnorm8, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_R8G8_UNORM, 2, 2, false, PackKind::kUnorm8, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_R8G8B8A8_UNORM, 4, 4, false, PackKind::kUnorm8, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_B8G8R8A8_UNORM, 4, 4, true, PackKind::kUnorm8, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_R8G8B8A8_SRGB, 4, 4, false, PackKind::kSrgb8, kC, kColor, kColor, 0},
    {VK_FORMAT_B8G8R8A8_SRGB, 4, 4, true, PackKind::kSrgb8, kC, kColor, kColor, 0},
    {VK_FORMAT_R16G16B16A16_SFLOAT, 8, 4, false, PackKind::kFloat16, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_R32_SFLOAT, 4, 1, false, PackKind::kFloat32, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_R32G32_SFLOAT, 8, 2, false, PackKind::kFloat32, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_R32G32B32A32_SFLOAT, 16, 4, false, PackKind::kFloat32, kC, kColor, kColor, kVertexTexel},
    {VK_FORMAT_D16_UNORM, 2, 1, false, PackKind::kD16, VK_IMAGE_ASPECT_DEPTH_BIT, kDepthSampled, 0, 0},
    {VK_FORMAT_D32_SFLOAT, 4, 1, false, PackKind::kD32F, VK_IMAGE_ASPECT_DEPTH_BIT, kDepthSampled, 0, 0},
    {VK_FORMAT_D32_SFLOAT_S8_UINT, 8, 2, false, PackKind::kD32FS8,
     VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT, kDepth, 0, 0},
    {VK_FORMAT_D24_UNORM_S8_UINT, 4, 2, false, PackKind::kD24S8,
     VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT, kDepth, 0, 0},
    // Vertex attribute formats only (no image support).
    {VK_FORMAT_R32G32B32_SFLOAT, 12, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16_SFLOAT, 2, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16_SFLOAT, 4, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16_SFLOAT, 6, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8_UNORM, 3, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8_SNORM, 3, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8_UINT, 3, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8_SINT, 3, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16_UNORM, 6, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16_SNORM, 6, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16_UINT, 6, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16_SINT, 6, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_A2B10G10R10_SNORM_PACK32, 4, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_A2B10G10R10_UINT_PACK32, 4, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8_SNORM, 1, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8_SNORM, 2, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8A8_SNORM, 4, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8_UINT, 1, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8_UINT, 2, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8A8_UINT, 4, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8_SINT, 1, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8_SINT, 2, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R8G8B8A8_SINT, 4, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16_UNORM, 2, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16_UNORM, 4, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16A16_UNORM, 8, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16_SNORM, 2, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16_SNORM, 4, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16A16_SNORM, 8, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16_UINT, 2, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16_UINT, 4, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16A16_UINT, 8, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16_SINT, 2, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16_SINT, 4, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R16G16B16A16_SINT, 8, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32_UINT, 4, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32G32_UINT, 8, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32G32B32_UINT, 12, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32G32B32A32_UINT, 16, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32_SINT, 4, 1, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32G32_SINT, 8, 2, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32G32B32_SINT, 12, 3, false, PackKind::kNone, 0, 0, 0, kVertex},
    {VK_FORMAT_R32G32B32A32_SINT, 16, 4, false, PackKind::kNone, 0, 0, 0, kVertex},
};

}  // namespace

const FormatInfo* find_format(VkFormat format) {
    for (const FormatInfo& f : kFormats) {
        if (f.format == format) return &f;
    }
    return nullptr;
}

bool format_supports_msaa(const FormatInfo& f) {
    switch (f.pack) {
        case PackKind::kUnorm8:
        case PackKind::kFloat32:
        case PackKind::kD16:
        case PackKind::kD32F:
        case PackKind::kD32FS8:
        case PackKind::kD24S8:
            return true;
        default:
            return false;
    }
}

uint32_t buffer_texel_bytes(const FormatInfo& f, VkImageAspectFlags aspect) {
    if (f.pack == PackKind::kD32FS8 || f.pack == PackKind::kD24S8) return aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? 1 : 4;
    return f.texel_bytes;
}

uint32_t aspect_offset(const FormatInfo& f, VkImageAspectFlags aspect) {
    if (aspect != VK_IMAGE_ASPECT_STENCIL_BIT) return 0;
    return f.pack == PackKind::kD32FS8 ? 4 : f.pack == PackKind::kD24S8 ? 3 : 0;
}

}  // namespace tilevk::icd
