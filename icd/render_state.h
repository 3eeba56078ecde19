// Vulkan -> render-core translations shared by pipeline creation and draw execution (formats: formats.h).
#pragma once
#include <vulkan/vulkan.h>

#include "shader/program.h"

namespace tilevk::icd {

shader::SamplerState sampler_state_of(const VkSamplerCreateInfo& info);

struct ImageView;
struct BufferView;
// A sampled image view as shader/ reads it; false when the view cannot be sampled (format, samples) or its image
// has no memory yet.
bool shader_view_of(const ImageView& v, shader::ImageView* out);
// A uniform texel buffer as shader/ reads it: one row of range / texel-size texels (level 0, one layer), fetched
// with texelFetch like a 1D image; false when the view cannot be read that way.
bool texel_buffer_view_of(const BufferView& v, shader::ImageView* out);

}  // namespace tilevk::icd
