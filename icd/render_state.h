// Vulkan -> render-core translations shared by pipeline creation and draw execution: formats and samplers.
#pragma once
#include <vulkan/vulkan.h>

#include "rast/fragment/color.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/geometry/vertex_fetch.h"
#include "shader/program.h"

namespace tilevk::icd {

// False if the format cannot be fetched as a vertex attribute.
bool vertex_format_of(VkFormat f, rast::geometry::VertexFormat* out);
// False if the format is not a colour format the fragment stage can write.
bool color_format_of(VkFormat f, rast::fragment::ColorFormat* out);
// DepthFormat::None for formats without a depth aspect.
rast::fragment::DepthFormat depth_format_of(VkFormat f);
// Format::Undefined if the shader cannot sample the format.
shader::Format shader_format_of(VkFormat f);
shader::SamplerState sampler_state_of(const VkSamplerCreateInfo& info);

}  // namespace tilevk::icd
