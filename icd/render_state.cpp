#include "render_state.h"

#include <algorithm>
#include <cstring>

#include "buffer_view.h"
#include "formats.h"
#include "image_view.h"
#include "memory.h"
#include "physical_device.h"
#include "rast/fragment/block.h"

namespace tilevk::icd {

static_assert(int(shader::Reduction::WeightedAverage) == VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE &&
              int(shader::Reduction::Min) == VK_SAMPLER_REDUCTION_MODE_MIN &&
              int(shader::Reduction::Max) == VK_SAMPLER_REDUCTION_MODE_MAX);

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
        case VK_BORDER_COLOR_FLOAT_CUSTOM_EXT:
        case VK_BORDER_COLOR_INT_CUSTOM_EXT: {
            // VK_EXT_custom_border_color: the colour's bits as lavapipe stores them (vk_sampler_border_color_value),
            // the format member unused (customBorderColorWithoutFormat); shader/ clamps them to the view's format.
            s.border = shader::BorderColor::Custom;
            const auto* cb = find_in_chain<VkSamplerCustomBorderColorCreateInfoEXT>(
                in.pNext, VK_STRUCTURE_TYPE_SAMPLER_CUSTOM_BORDER_COLOR_CREATE_INFO_EXT);
            if (cb != nullptr) std::memcpy(s.custom_border.data(), cb->customBorderColor.uint32, 16);
            break;
        }
        default:
            s.border = shader::BorderColor::TransparentBlack;
    }
    s.integer_border = in.borderColor == VK_BORDER_COLOR_INT_TRANSPARENT_BLACK ||
                       in.borderColor == VK_BORDER_COLOR_INT_OPAQUE_BLACK ||
                       in.borderColor == VK_BORDER_COLOR_INT_OPAQUE_WHITE;
    // samplerFilterMinmax: VkSamplerReductionMode numbers its values as shader::Reduction
    if (const auto* rm = find_in_chain<VkSamplerReductionModeCreateInfo>(
            in.pNext, VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO);
        rm != nullptr && rm->reductionMode <= VK_SAMPLER_REDUCTION_MODE_MAX)
        s.reduction = shader::Reduction(rm->reductionMode);
    s.unnormalized = in.unnormalizedCoordinates;
    s.compare_enable = in.compareEnable;
    s.compare_op = shader::CompareOp(in.compareOp);
    // lvp_CreateSampler stores maxAnisotropy into pipe_sampler_state's 5-bit unsigned max_anisotropy: truncated,
    // so 1.5 is 1 (no anisotropy) and 2.9 is 2
    s.max_anisotropy = in.anisotropyEnable ? float(uint32_t(std::clamp(in.maxAnisotropy, 0.0f, 31.0f))) : 1.0f;
    // VK_EXT_non_seamless_cube_map, as lavapipe's seamless_cube_map (lvp_device.c lvp_CreateSampler)
    s.seamless_cube = (in.flags & VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT) == 0;
    return s;
}

bool shader_view_of(const ImageView& v, shader::ImageView* out) {
    if (v.image == nullptr || v.image->memory == nullptr) return false;
    const Image& img = *v.image;
    // A multisampled image is only ever a sampled image (physical_device.cpp: no 4x with STORAGE or
    // INPUT_ATTACHMENT usage), read by texelFetch with a sample index: one level, its sample planes.
    if (!(image_features(*v.format) & (format::kSampledImage | format::kStorageImage)) ||
        (img.samples != 1 && (img.samples != uint32_t(rast::fragment::kMaxSamples) || img.mip_levels != 1)))
        return false;
    out->format = v.format->id;
    const uint32_t b = v.range.baseMipLevel;
    out->base = img.memory->data + img.memory_offset;
    out->width = img.level_width(b);
    out->height = img.level_height(b);
    out->depth = img.level_depth(b);  // 1 but for a 3D view (whose layer_pitch below is the depth pitch)
    out->base_level = b;
    out->width0 = img.level_width(0);
    out->height0 = img.level_height(0);
    out->levels = std::min<uint32_t>(v.range.levelCount, uint32_t(out->level.size()));
    out->layers = v.range.layerCount;
    out->samples = img.samples;
    out->sample_pitch = img.samples > 1 ? img.layout.sample_pitch[b] : 0;
    const VkComponentSwizzle mapping[4] = {v.components.r, v.components.g, v.components.b, v.components.a};
    for (uint8_t c = 0; c < 4; ++c) {
        switch (mapping[c]) {
            case VK_COMPONENT_SWIZZLE_ZERO:
                out->swizzle[c] = shader::kSwizzleZero;
                break;
            case VK_COMPONENT_SWIZZLE_ONE:
                out->swizzle[c] = shader::kSwizzleOne;
                break;
            case VK_COMPONENT_SWIZZLE_R:
            case VK_COMPONENT_SWIZZLE_G:
            case VK_COMPONENT_SWIZZLE_B:
            case VK_COMPONENT_SWIZZLE_A:
                out->swizzle[c] = uint8_t(mapping[c] - VK_COMPONENT_SWIZZLE_R);
                break;
            default:  // IDENTITY
                out->swizzle[c] = c;
                break;
        }
    }
    for (uint32_t i = 0; i < out->levels; ++i) {
        out->level[i].offset =
            img.layout.level_offset[b + i] + VkDeviceSize(v.range.baseArrayLayer) * img.layout.layer_pitch[b + i];
        out->level[i].row_pitch = img.layout.row_pitch[b + i];
        out->level[i].layer_pitch = img.layout.layer_pitch[b + i];
    }
    shader::prepare_view(*out);
    return true;
}

bool texel_buffer_view_of(const BufferView& v, shader::ImageView* out) {
    if (v.buffer == nullptr || v.buffer->data() == nullptr) return false;
    const FormatInfo* f = find_format(v.format);
    if (f == nullptr || !(f->buffer & (format::kUniformTexelBuffer | format::kStorageTexelBuffer))) return false;
    if (v.offset > v.buffer->size) return false;
    const VkDeviceSize range = std::min(v.range, v.buffer->size - v.offset);
    const VkDeviceSize texels = std::min<VkDeviceSize>(range / f->bytes, kMaxTexelBufferElements);
    if (texels == 0) return false;
    out->format = f->id;
    out->base = v.buffer->data() + v.offset;
    out->width = uint32_t(texels);
    out->height = 1;
    out->levels = 1;
    out->layers = 1;
    out->level[0].offset = 0;
    out->level[0].row_pitch = texels * f->bytes;
    out->level[0].layer_pitch = out->level[0].row_pitch;
    return true;
}

}  // namespace tilevk::icd
