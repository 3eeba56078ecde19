#include "descriptor_set_layout.h"

#include <algorithm>

#include "device.h"
#include "entrypoints.h"
#include "sampler.h"

namespace tilevk::icd {

const LayoutBinding* DescriptorSetLayout::find(uint32_t binding) const {
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
        for (uint32_t i = 0; i < ci->bindingCount; ++i) {
            const VkDescriptorSetLayoutBinding& b = ci->pBindings[i];
            LayoutBinding lb{b.binding, b.descriptorType, b.descriptorCount, b.stageFlags, 0, {}};
            const bool sampler_type = b.descriptorType == VK_DESCRIPTOR_TYPE_SAMPLER ||
                                      b.descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            if (sampler_type && b.pImmutableSamplers != nullptr) {
                for (uint32_t j = 0; j < b.descriptorCount; ++j) {
                    lb.immutable_samplers.push_back(from_handle<Sampler>(b.pImmutableSamplers[j]));
                }
            }
            layout->bindings.push_back(std::move(lb));
        }
        std::sort(layout->bindings.begin(), layout->bindings.end(),
                  [](const LayoutBinding& a, const LayoutBinding& b) { return a.binding < b.binding; });
        for (LayoutBinding& b : layout->bindings) {
            b.first_slot = layout->slot_count;
            layout->slot_count += b.count;
        }
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
            layout->set_layouts.push_back(from_handle<DescriptorSetLayout>(ci->pSetLayouts[i]));
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

}  // namespace tilevk::icd
