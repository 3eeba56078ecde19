// Features: what tilevk supports, member by member — the one home that vkGetPhysicalDeviceFeatures[2] report and
// that vkCreateDevice checks requests against — and what a device was created with.
#pragma once
#include <vulkan/vulkan.h>

#include "core_structs.h"

namespace tilevk::icd {

struct Features {
    VkPhysicalDeviceFeatures core10{};
    // Vulkan 1.1-1.3; the structs promoted into them (VkPhysicalDeviceMultiviewFeatures, ...) are read from these
    // by the generated core_structs.cpp, so the two spellings of a feature always agree.
    CoreFeatures core;
    // Feature structs of extensions that are not part of any core version.
    VkPhysicalDeviceIndexTypeUint8FeaturesEXT index_type_uint8{};
    VkPhysicalDevicePrimitiveTopologyListRestartFeaturesEXT list_restart{};
    VkPhysicalDeviceDepthClipControlFeaturesEXT depth_clip_control{};
    VkPhysicalDeviceExtendedDynamicStateFeaturesEXT extended_dynamic_state{};
    VkPhysicalDeviceExtendedDynamicState2FeaturesEXT extended_dynamic_state2{};
    VkPhysicalDeviceVertexAttributeDivisorFeaturesEXT vertex_attribute_divisor{};
    VkPhysicalDeviceColorWriteEnableFeaturesEXT color_write_enable{};
    VkPhysicalDeviceMultiDrawFeaturesEXT multi_draw{};
    VkPhysicalDeviceProvokingVertexFeaturesEXT provoking_vertex{};
    VkPhysicalDeviceDepthClipEnableFeaturesEXT depth_clip_enable{};
    VkPhysicalDeviceLineRasterizationFeaturesEXT line_rasterization{};
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{};
    VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT atomic_float2{};
    VkPhysicalDeviceCustomBorderColorFeaturesEXT custom_border_color{};
    VkPhysicalDevice4444FormatsFeaturesEXT formats_4444{};
    VkPhysicalDeviceTexelBufferAlignmentFeaturesEXT texel_buffer_alignment{};
    VkPhysicalDeviceBorderColorSwizzleFeaturesEXT border_color_swizzle{};
    VkPhysicalDeviceVertexInputDynamicStateFeaturesEXT vertex_input_dynamic_state{};
    VkPhysicalDeviceExtendedDynamicState3FeaturesEXT extended_dynamic_state3{};
    VkPhysicalDeviceConditionalRenderingFeaturesEXT conditional_rendering{};
    VkPhysicalDeviceNonSeamlessCubeMapFeaturesEXT non_seamless_cube_map{};
    VkPhysicalDeviceRobustness2FeaturesEXT robustness2{};

    Features();
    // The extension-only struct with this sType, or nullptr.
    const VkBaseOutStructure* extension_struct(VkStructureType s_type) const;
    VkBaseOutStructure* extension_struct(VkStructureType s_type);
};

// tilevk's features (icd/README.md says how each is proven).
const Features& supported_features();

// Writes tilevk's answer into one struct of a vkGetPhysicalDeviceFeatures2 chain: VkPhysicalDeviceFeatures2, any
// struct that extends it and that vk.xml lists (find_feature_struct; tilevk's values, or VK_FALSE for every member
// of a struct tilevk does not implement). Other structs are left untouched, as the spec asks.
void write_feature_struct(const Features& from, VkBaseOutStructure* s);

// vkCreateDevice: every feature requested through pEnabledFeatures or a feature struct anywhere in the pNext chain.
// VK_ERROR_FEATURE_NOT_PRESENT, with one stderr line naming the struct and member ("VkPhysicalDeviceDynamicRendering
// Features::dynamicRendering"), when tilevk does not support one; otherwise `enabled` holds every request.
VkResult enable_features(const VkDeviceCreateInfo& ci, Features* enabled);

}  // namespace tilevk::icd
