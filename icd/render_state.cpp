#include "render_state.h"

namespace tilevk::icd {

using rast::geometry::VertexFormat;

bool vertex_format_of(VkFormat f, VertexFormat* out) {
    switch (f) {
#define TVK_VF(vk, rf)           \
    case VK_FORMAT_##vk:         \
        *out = VertexFormat::rf; \
        return true;
        TVK_VF(R32_SFLOAT, kR32Float)
        TVK_VF(R32G32_SFLOAT, kR32G32Float)
        TVK_VF(R32G32B32_SFLOAT, kR32G32B32Float)
        TVK_VF(R32G32B32A32_SFLOAT, kR32G32B32A32Float)
        TVK_VF(R16_SFLOAT, kR16Float)
        TVK_VF(R16G16_SFLOAT, kR16G16Float)
        TVK_VF(R16G16B16_SFLOAT, kR16G16B16Float)
        TVK_VF(R16G16B16A16_SFLOAT, kR16G16B16A16Float)
        TVK_VF(R8_UNORM, kR8Unorm)
        TVK_VF(R8G8_UNORM, kR8G8Unorm)
        TVK_VF(R8G8B8_UNORM, kR8G8B8Unorm)
        TVK_VF(R8G8B8A8_UNORM, kR8G8B8A8Unorm)
        TVK_VF(B8G8R8A8_UNORM, kB8G8R8A8Unorm)
        TVK_VF(R8_SNORM, kR8Snorm)
        TVK_VF(R8G8_SNORM, kR8G8Snorm)
        TVK_VF(R8G8B8_SNORM, kR8G8B8Snorm)
        TVK_VF(R8G8B8A8_SNORM, kR8G8B8A8Snorm)
        TVK_VF(R16_UNORM, kR16Unorm)
        TVK_VF(R16G16_UNORM, kR16G16Unorm)
        TVK_VF(R16G16B16_UNORM, kR16G16B16Unorm)
        TVK_VF(R16G16B16A16_UNORM, kR16G16B16A16Unorm)
        TVK_VF(R16_SNORM, kR16Snorm)
        TVK_VF(R16G16_SNORM, kR16G16Snorm)
        TVK_VF(R16G16B16_SNORM, kR16G16B16Snorm)
        TVK_VF(R16G16B16A16_SNORM, kR16G16B16A16Snorm)
        TVK_VF(R8_UINT, kR8Uint)
        TVK_VF(R8G8_UINT, kR8G8Uint)
        TVK_VF(R8G8B8_UINT, kR8G8B8Uint)
        TVK_VF(R8G8B8A8_UINT, kR8G8B8A8Uint)
        TVK_VF(R8_SINT, kR8Sint)
        TVK_VF(R8G8_SINT, kR8G8Sint)
        TVK_VF(R8G8B8_SINT, kR8G8B8Sint)
        TVK_VF(R8G8B8A8_SINT, kR8G8B8A8Sint)
        TVK_VF(R16_UINT, kR16Uint)
        TVK_VF(R16G16_UINT, kR16G16Uint)
        TVK_VF(R16G16B16_UINT, kR16G16B16Uint)
        TVK_VF(R16G16B16A16_UINT, kR16G16B16A16Uint)
        TVK_VF(R16_SINT, kR16Sint)
        TVK_VF(R16G16_SINT, kR16G16Sint)
        TVK_VF(R16G16B16_SINT, kR16G16B16Sint)
        TVK_VF(R16G16B16A16_SINT, kR16G16B16A16Sint)
        TVK_VF(R32_UINT, kR32Uint)
        TVK_VF(R32G32_UINT, kR32G32Uint)
        TVK_VF(R32G32B32_UINT, kR32G32B32Uint)
        TVK_VF(R32G32B32A32_UINT, kR32G32B32A32Uint)
        TVK_VF(R32_SINT, kR32Sint)
        TVK_VF(R32G32_SINT, kR32G32Sint)
        TVK_VF(R32G32B32_SINT, kR32G32B32Sint)
        TVK_VF(R32G32B32A32_SINT, kR32G32B32A32Sint)
        TVK_VF(A2B10G10R10_UNORM_PACK32, kA2B10G10R10Unorm)
        TVK_VF(A2B10G10R10_SNORM_PACK32, kA2B10G10R10Snorm)
        TVK_VF(A2B10G10R10_UINT_PACK32, kA2B10G10R10Uint)
        TVK_VF(A2B10G10R10_SINT_PACK32, kA2B10G10R10Sint)
#undef TVK_VF
        default:
            return false;
    }
}

bool color_format_of(VkFormat f, rast::fragment::ColorFormat* out) {
    using rast::fragment::ColorFormat;
    switch (f) {
#define TVK_CF(name)              \
    case VK_FORMAT_##name:        \
        *out = ColorFormat::name; \
        return true;
        TVK_CF(R8G8B8A8_UNORM)
        TVK_CF(B8G8R8A8_UNORM)
        TVK_CF(R8G8B8A8_SRGB)
        TVK_CF(B8G8R8A8_SRGB)
        TVK_CF(R8_UNORM)
        TVK_CF(R8G8_UNORM)
        TVK_CF(R16G16B16A16_SFLOAT)
        TVK_CF(R32_SFLOAT)
        TVK_CF(R32G32_SFLOAT)
        TVK_CF(R32G32B32A32_SFLOAT)
#undef TVK_CF
        default:
            return false;
    }
}

rast::fragment::DepthFormat depth_format_of(VkFormat f) {
    using rast::fragment::DepthFormat;
    switch (f) {
        case VK_FORMAT_D16_UNORM:
            return DepthFormat::D16;
        case VK_FORMAT_D32_SFLOAT:
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
            return DepthFormat::D32F;
        case VK_FORMAT_D24_UNORM_S8_UINT:
            return DepthFormat::X8D24;
        default:
            return DepthFormat::None;
    }
}

shader::Format shader_format_of(VkFormat f) {
    using shader::Format;
    switch (f) {
        case VK_FORMAT_R8G8B8A8_UNORM:
            return Format::RGBA8_UNORM;
        case VK_FORMAT_R8G8B8A8_SRGB:
            return Format::RGBA8_SRGB;
        case VK_FORMAT_B8G8R8A8_UNORM:
            return Format::BGRA8_UNORM;
        case VK_FORMAT_B8G8R8A8_SRGB:
            return Format::BGRA8_SRGB;
        case VK_FORMAT_R8_UNORM:
            return Format::R8_UNORM;
        case VK_FORMAT_R8G8_UNORM:
            return Format::RG8_UNORM;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
            return Format::RGBA16F;
        case VK_FORMAT_R32_SFLOAT:
            return Format::R32F;
        case VK_FORMAT_R32G32_SFLOAT:
            return Format::RG32F;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return Format::RGBA32F;
        case VK_FORMAT_D16_UNORM:
            return Format::D16_UNORM;
        case VK_FORMAT_D32_SFLOAT:
            return Format::D32_SFLOAT;
        default:
            return Format::Undefined;
    }
}

shader::SamplerState sampler_state_of(const VkSamplerCreateInfo& in) {
    shader::SamplerState s;
    // VkFilter, VkSamplerMipmapMode, VkSamplerAddressMode and VkCompareOp number their values as shader/ does.
    s.mag_filter = in.magFilter == VK_FILTER_LINEAR ? shader::Filter::Linear : shader::Filter::Nearest;
    s.min_filter = in.minFilter == VK_FILTER_LINEAR ? shader::Filter::Linear : shader::Filter::Nearest;
    s.mipmap_mode =
        in.mipmapMode == VK_SAMPLER_MIPMAP_MODE_LINEAR ? shader::MipmapMode::Linear : shader::MipmapMode::Nearest;
    s.address_u = shader::AddressMode(in.addressModeU);
    s.address_v = shader::AddressMode(in.addressModeV);
    s.address_w = shader::AddressMode(in.addressModeW);
    s.mip_lod_bias = in.mipLodBias;
    s.min_lod = in.minLod;
    s.max_lod = in.maxLod;
    switch (in.borderColor) {
        case VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK:
        case VK_BORDER_COLOR_INT_OPAQUE_BLACK:
            s.border = shader::BorderColor::OpaqueBlack;
            break;
        case VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE:
        case VK_BORDER_COLOR_INT_OPAQUE_WHITE:
            s.border = shader::BorderColor::OpaqueWhite;
            break;
        default:
            s.border = shader::BorderColor::TransparentBlack;
    }
    s.unnormalized = in.unnormalizedCoordinates;
    s.compare_enable = in.compareEnable;
    s.compare_op = shader::CompareOp(in.compareOp);
    return s;
}

}  // namespace tilevk::icd
