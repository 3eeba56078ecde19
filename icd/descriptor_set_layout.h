// VkDescriptorSetLayout and VkPipelineLayout: bindings flattened to descriptor slots.
#pragma once
#include <vector>

#include "object.h"

namespace tilevk::icd {

struct Sampler;

struct LayoutBinding {
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count;
    VkShaderStageFlags stages;
    uint32_t first_slot;                       // index of this binding's first descriptor in a set
    std::vector<Sampler*> immutable_samplers;  // empty or `count` entries
};

struct DescriptorSetLayout : NonDispatchableObject {
    using Handle = VkDescriptorSetLayout;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT;
    DescriptorSetLayout() : NonDispatchableObject(kType) {}
    std::vector<LayoutBinding> bindings;  // sorted by binding number
    uint32_t slot_count = 0;

    const LayoutBinding* find(uint32_t binding) const;
};

struct PipelineLayout : NonDispatchableObject {
    using Handle = VkPipelineLayout;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE_LAYOUT;
    PipelineLayout() : NonDispatchableObject(kType) {}
    std::vector<DescriptorSetLayout*> set_layouts;  // not owned: the application keeps them alive while in use
    std::vector<VkPushConstantRange> push_constants;
};

}  // namespace tilevk::icd
