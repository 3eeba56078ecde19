#include "descriptor_update_template.h"

#include <cstring>
#include <new>

#include "device.h"
#include "entrypoints.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

// pData + offset need not be aligned for T.
template <class T>
T read(const uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof v);  // NOLINT(bugprone-sizeof-expression): T may be a handle (a pointer) itself
    return v;
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateDescriptorUpdateTemplate(VkDevice device,
                                                                  const VkDescriptorUpdateTemplateCreateInfo* ci,
                                                                  const VkAllocationCallbacks* pAllocator,
                                                                  VkDescriptorUpdateTemplate* pTemplate) {
    Device* dev = from_handle<Device>(device);
    const bool push = ci->templateType == VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_PUSH_DESCRIPTORS_KHR;
    if (!push && ci->templateType != VK_DESCRIPTOR_UPDATE_TEMPLATE_TYPE_DESCRIPTOR_SET) {
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDescriptorUpdateTemplate: %s is not supported",
                    vk_enum_name(ci->templateType));
    }
    auto* t = create_object<DescriptorUpdateTemplate>(pick_allocator(pAllocator, &dev->allocator),
                                                      VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (t == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDescriptorUpdateTemplate: out of host memory");
    if (push) t->bind_point = ci->pipelineBindPoint;
    try {
        t->entries.assign(ci->pDescriptorUpdateEntries, ci->pDescriptorUpdateEntries + ci->descriptorUpdateEntryCount);
    } catch (const std::bad_alloc&) {
        destroy_object(t);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDescriptorUpdateTemplate: out of host memory");
    }
    *pTemplate = to_handle(t);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyDescriptorUpdateTemplate(VkDevice,
                                                               VkDescriptorUpdateTemplate descriptorUpdateTemplate,
                                                               const VkAllocationCallbacks*) {
    destroy_object(from_handle<DescriptorUpdateTemplate>(descriptorUpdateTemplate));
}

// Each entry is one VkWriteDescriptorSet whose descriptors are read from pData at offset + i * stride (the spec's
// rule), in the shape its type uses: VkDescriptorImageInfo, VkDescriptorBufferInfo or VkBufferView.
VKAPI_ATTR void VKAPI_CALL tvk_UpdateDescriptorSetWithTemplate(VkDevice device, VkDescriptorSet descriptorSet,
                                                               VkDescriptorUpdateTemplate descriptorUpdateTemplate,
                                                               const void* pData) {
    const DescriptorUpdateTemplate* t = from_handle<DescriptorUpdateTemplate>(descriptorUpdateTemplate);
    const auto* base = static_cast<const uint8_t*>(pData);
    std::vector<VkDescriptorImageInfo> images;
    std::vector<VkDescriptorBufferInfo> buffers;
    std::vector<VkBufferView> views;
    for (const VkDescriptorUpdateTemplateEntry& e : t->entries) {
        if (e.descriptorCount == 0) continue;
        VkWriteDescriptorSet w{};
        w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        w.dstSet = descriptorSet;
        w.dstBinding = e.dstBinding;
        w.dstArrayElement = e.dstArrayElement;
        w.descriptorCount = e.descriptorCount;
        w.descriptorType = e.descriptorType;
        images.clear();
        buffers.clear();
        views.clear();
        // An inline uniform block entry: descriptorCount bytes at pData + offset (the stride is ignored).
        VkWriteDescriptorSetInlineUniformBlock block{};
        block.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_INLINE_UNIFORM_BLOCK;
        if (e.descriptorType == VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK) {
            block.dataSize = e.descriptorCount;
            block.pData = base + e.offset;
            w.pNext = &block;
            tvk_UpdateDescriptorSets(device, 1, &w, 0, nullptr);
            continue;
        }
        for (uint32_t i = 0; i < e.descriptorCount; ++i) {
            const uint8_t* p = base + e.offset + size_t(i) * e.stride;
            switch (e.descriptorType) {
                case VK_DESCRIPTOR_TYPE_SAMPLER:
                case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
                case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
                case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
                case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:
                    images.push_back(read<VkDescriptorImageInfo>(p));
                    break;
                case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
                case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
                    views.push_back(read<VkBufferView>(p));
                    break;
                default:
                    buffers.push_back(read<VkDescriptorBufferInfo>(p));
                    break;
            }
        }
        w.pImageInfo = images.empty() ? nullptr : images.data();
        w.pBufferInfo = buffers.empty() ? nullptr : buffers.data();
        w.pTexelBufferView = views.empty() ? nullptr : views.data();
        tvk_UpdateDescriptorSets(device, 1, &w, 0, nullptr);
    }
}

}  // namespace tilevk::icd
