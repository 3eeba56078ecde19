// VkDescriptorUpdateTemplate (VK_KHR_descriptor_update_template, core in Vulkan 1.1): the template's entries;
// vkUpdateDescriptorSetWithTemplate (and vkCmdPushDescriptorSetWithTemplateKHR) turn them into the
// VkWriteDescriptorSets vkUpdateDescriptorSets applies.
#pragma once
#include <vector>

#include "object.h"

namespace tilevk::icd {

struct DescriptorUpdateTemplate : NonDispatchableObject {
    using Handle = VkDescriptorUpdateTemplate;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DESCRIPTOR_UPDATE_TEMPLATE;
    DescriptorUpdateTemplate() : NonDispatchableObject(kType) {}
    std::vector<VkDescriptorUpdateTemplateEntry> entries;
    // Push-descriptor templates (VK_KHR_push_descriptor): the bind point vkCmdPushDescriptorSetWithTemplateKHR binds
    // at.
    VkPipelineBindPoint bind_point = VK_PIPELINE_BIND_POINT_GRAPHICS;
};

}  // namespace tilevk::icd
