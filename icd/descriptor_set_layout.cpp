#include "descriptor_set_layout.h"

#include "render_state.h"

#include <algorithm>
#include <memory>

#include "device.h"
#include "entrypoints.h"
#include "sampler.h"

namespace tilevk::icd {

const LayoutBinding* SetLayout::find(uint32_t binding) const {
    for (const LayoutBinding& b : bindings) {
        if (b.binding == binding) return &b;
    }
    return nullptr;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateDescriptorSetLayout(VkDevice device, const VkDescriptorSetLayoutCreateInfo* ci,
                                                             const VkAllocationCallbacks* pAllocator,
                                                             VkDescriptorSetLayout* pSetLayout) {
    Device* dev = from_handle<Device>(device);
    auto* layout = create_object<DescriptorSetLayout>(pick_allocator(pAllocator, &dev->allocator),
                                                      VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (layout == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDescriptorSetLayout: out of host memory");
    try {
        auto shared = std::make_shared<SetLayout>();
        for (uint32_t i = 0; i < ci->bindingCount; ++i) {
            const VkDescriptorSetLayoutBinding& b = ci->pBindings[i];
            LayoutBinding lb{b.binding, b.descriptorType, b.descriptorCount, b.stageFlags, 0, 0, 0, {}, {}};
            const bool sampler_type = b.descriptorType == VK_DESCRIPTOR_TYPE_SAMPLER ||
                                      b.descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            if (sampler_type && b.pImmutableSamplers != nullptr) {
                for (uint32_t j = 0; j < b.descriptorCount; ++j) {
                    const Sampler* s = from_handle<Sampler>(b.pImmutableSamplers[j]);
                    lb.immutable_samplers.push_back(s != nullptr ? s->info : VkSamplerCreateInfo{});
                    // the sampler's own state: its create info no longer holds the pNext chain (custom border)
                    lb.immutable_states.push_back(s != nullptr ? s->state : sampler_state_of(VkSamplerCreateInfo{}));
                }
            }
            shared->bindings.push_back(std::move(lb));
        }
        std::sort(shared->bindings.begin(), shared->bindings.end(),
                  [](const LayoutBinding& a, const LayoutBinding& b) { return a.binding < b.binding; });
        for (LayoutBinding& b : shared->bindings) {
            b.first_slot = shared->slot_count;
            shared->slot_count += b.slots();
            if (b.inline_block()) {
                b.inline_offset = shared->inline_bytes;
                shared->inline_bytes += b.count;
            }
            if (b.dynamic()) {
                b.first_dynamic = shared->dynamic_count;
                shared->dynamic_count += b.count;
            }
        }
        layout->shared = std::move(shared);
    } catch (const std::bad_alloc&) {
        destroy_object(layout);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDescriptorSetLayout: out of host memory");
    }
    *pSetLayout = to_handle(layout);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyDescriptorSetLayout(VkDevice, VkDescriptorSetLayout layout,
                                                          const VkAllocationCallbacks*) {
    destroy_object(from_handle<DescriptorSetLayout>(layout));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreatePipelineLayout(VkDevice device, const VkPipelineLayoutCreateInfo* ci,
                                                        const VkAllocationCallbacks* pAllocator,
                                                        VkPipelineLayout* pPipelineLayout) {
    Device* dev = from_handle<Device>(device);
    auto* layout =
        create_object<PipelineLayout>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (layout == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreatePipelineLayout: out of host memory");
    try {
        for (uint32_t i = 0; i < ci->setLayoutCount; ++i) {
            const DescriptorSetLayout* set_layout = from_handle<DescriptorSetLayout>(ci->pSetLayouts[i]);
            layout->set_layouts.push_back(set_layout != nullptr ? set_layout->shared : nullptr);
        }
        layout->push_constants.assign(ci->pPushConstantRanges, ci->pPushConstantRanges + ci->pushConstantRangeCount);
    } catch (const std::bad_alloc&) {
        destroy_object(layout);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreatePipelineLayout: out of host memory");
    }
    *pPipelineLayout = to_handle(layout);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPipelineLayout(VkDevice, VkPipelineLayout layout, const VkAllocationCallbacks*) {
    destroy_object(from_handle<PipelineLayout>(layout));
}

// maintenance3: whether vkCreateDescriptorSetLayout would make this layout. Sets are arrays sized by their layout,
// so any count works (and any inline uniform block size); the descriptor types tilevk has no descriptor storage for
// are not supported.
VKAPI_ATTR void VKAPI_CALL tvk_GetDescriptorSetLayoutSupport(VkDevice, const VkDescriptorSetLayoutCreateInfo* ci,
                                                             VkDescriptorSetLayoutSupport* pSupport) {
    pSupport->supported = VK_TRUE;
    for (uint32_t i = 0; i < ci->bindingCount; ++i)
        if (ci->pBindings[i].descriptorType > VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT &&
            ci->pBindings[i].descriptorType != VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK)
            pSupport->supported = VK_FALSE;
    for (auto* s = static_cast<VkBaseOutStructure*>(pSupport->pNext); s != nullptr; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_DESCRIPTOR_SET_VARIABLE_DESCRIPTOR_COUNT_LAYOUT_SUPPORT)
            reinterpret_cast<VkDescriptorSetVariableDescriptorCountLayoutSupport*>(s)->maxVariableDescriptorCount = 0;
    }
}

}  // namespace tilevk::icd
