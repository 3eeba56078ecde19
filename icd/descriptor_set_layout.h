// VkDescriptorSetLayout and VkPipelineLayout: bindings flattened to descriptor slots.
//
// Object Lifetime lets a descriptor set layout be destroyed while the sets allocated with it and the pipeline
// layouts made from it live on (they may still be bound, drawn with, copied and freed). So what a layout says is a
// SetLayout shared (reference-counted) by the layout object, its sets and its pipeline layouts; destroying the
// object drops one reference. Immutable samplers are copied into it for the same reason.
#pragma once
#include <memory>
#include <vector>

#include "object.h"
#include "shader/program.h"

namespace tilevk::icd {

struct LayoutBinding {
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count;
    VkShaderStageFlags stages;
    uint32_t first_slot;     // index of this binding's first descriptor in a set
    uint32_t first_dynamic;  // dynamic bindings: index of its first dynamic offset within the set (binding order)
    uint32_t inline_offset = 0;  // inline uniform blocks: where its `count` bytes start in the set's inline bytes
    std::vector<VkSamplerCreateInfo> immutable_samplers;  // empty or `count` copies (pNext cleared)
    std::vector<shader::SamplerState> immutable_states;   // the same, translated for shader/ once

    // An inline uniform block (VK_EXT_inline_uniform_block) is one descriptor whose `count` is its size in bytes.
    bool inline_block() const { return type == VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK; }
    uint32_t slots() const { return inline_block() ? 1 : count; }
    bool dynamic() const {
        return type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC || type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC;
    }
};

struct SetLayout {
    std::vector<LayoutBinding> bindings;  // sorted by binding number
    uint32_t slot_count = 0;
    uint32_t dynamic_count = 0;  // dynamic buffer descriptors in the set
    uint32_t inline_bytes = 0;   // the bytes of all its inline uniform blocks

    const LayoutBinding* find(uint32_t binding) const;
};

struct DescriptorSetLayout : NonDispatchableObject {
    using Handle = VkDescriptorSetLayout;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT;
    DescriptorSetLayout() : NonDispatchableObject(kType) {}
    std::shared_ptr<const SetLayout> shared;
};

struct PipelineLayout : NonDispatchableObject {
    using Handle = VkPipelineLayout;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE_LAYOUT;
    PipelineLayout() : NonDispatchableObject(kType) {}
    std::vector<std::shared_ptr<const SetLayout>> set_layouts;  // shared: the set layouts may be destroyed first
    std::vector<VkPushConstantRange> push_constants;
};

}  // namespace tilevk::icd
