#include "descriptor_pool.h"

#include <algorithm>
#include <cstring>

#include "buffer.h"
#include "device.h"
#include "entrypoints.h"
#include "image_view.h"
#include "sampler.h"

namespace tilevk::icd {
namespace {

void free_set(DescriptorSet* set) {
    destroy_object(set);
}

// Slot of array element `element` of `binding`, following Vulkan's rule that an update running past the end of a
// binding continues into the next binding(s) in binding order.
Descriptor* slot_of(DescriptorSet* set, uint32_t binding, uint32_t element) {
    const LayoutBinding* b = set->layout->find(binding);
    if (b == nullptr) return nullptr;
    uint32_t slot = b->first_slot + element;
    return slot < set->slots.size() ? &set->slots[slot] : nullptr;
}

// Bytes [offset, offset + size) of inline uniform block `binding` of `set` (VK_EXT_inline_uniform_block: the array
// element and count of a write or copy are byte offset and size), or null when the binding is not an inline block
// or the range leaves it.
uint8_t* inline_bytes(DescriptorSet* set, uint32_t binding, uint32_t offset, uint32_t size) {
    const LayoutBinding* b = set != nullptr ? set->layout->find(binding) : nullptr;
    if (b == nullptr || !b->inline_block() || offset > b->count || size > b->count - offset) return nullptr;
    return set->inline_data.data() + b->inline_offset + offset;
}

void write_inline(DescriptorSet* set, const VkWriteDescriptorSet& w) {
    const VkWriteDescriptorSetInlineUniformBlock* data = nullptr;
    for (auto* s = static_cast<const VkBaseInStructure*>(w.pNext); s != nullptr; s = s->pNext)
        if (s->sType == VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_INLINE_UNIFORM_BLOCK)
            data = reinterpret_cast<const VkWriteDescriptorSetInlineUniformBlock*>(s);
    uint8_t* to = inline_bytes(set, w.dstBinding, w.dstArrayElement, w.descriptorCount);
    if (data == nullptr || data->dataSize != w.descriptorCount || to == nullptr) {
        log_error(
            "vkUpdateDescriptorSets: inline uniform block write of %u bytes at %u into binding %u without a "
            "VkWriteDescriptorSetInlineUniformBlock of that size, or outside the block",
            w.descriptorCount, w.dstArrayElement, w.dstBinding);
        return;
    }
    std::memcpy(to, data->pData, w.descriptorCount);
}

// A copy between inline uniform blocks copies bytes; false when the source is not one.
bool copy_inline(const VkCopyDescriptorSet& c) {
    DescriptorSet* src = from_handle<DescriptorSet>(c.srcSet);
    const LayoutBinding* b = src != nullptr ? src->layout->find(c.srcBinding) : nullptr;
    if (b == nullptr || !b->inline_block()) return false;
    const uint8_t* from = inline_bytes(src, c.srcBinding, c.srcArrayElement, c.descriptorCount);
    uint8_t* to =
        inline_bytes(from_handle<DescriptorSet>(c.dstSet), c.dstBinding, c.dstArrayElement, c.descriptorCount);
    if (from == nullptr || to == nullptr)
        log_error("vkUpdateDescriptorSets: inline uniform block copy of %u bytes runs outside a block",
                  c.descriptorCount);
    else
        std::memmove(to, from, c.descriptorCount);
    return true;
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateDescriptorPool(VkDevice device, const VkDescriptorPoolCreateInfo* ci,
                                                        const VkAllocationCallbacks* pAllocator,
                                                        VkDescriptorPool* pDescriptorPool) {
    Device* dev = from_handle<Device>(device);
    auto* pool =
        create_object<DescriptorPool>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (pool == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDescriptorPool: out of host memory");
    pool->flags = ci->flags;
    pool->max_sets = ci->maxSets;
    *pDescriptorPool = to_handle(pool);
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_ResetDescriptorPool(VkDevice, VkDescriptorPool descriptorPool,
                                                       VkDescriptorPoolResetFlags) {
    DescriptorPool* pool = from_handle<DescriptorPool>(descriptorPool);
    for (DescriptorSet* set : pool->sets) free_set(set);
    pool->sets.clear();
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyDescriptorPool(VkDevice device, VkDescriptorPool descriptorPool,
                                                     const VkAllocationCallbacks*) {
    DescriptorPool* pool = from_handle<DescriptorPool>(descriptorPool);
    if (pool == nullptr) return;
    tvk_ResetDescriptorPool(device, descriptorPool, 0);
    destroy_object(pool);
}

void init_descriptor_set(DescriptorSet& set, const std::shared_ptr<const SetLayout>& layout) {
    set.layout = layout;
    set.slots.assign(layout->slot_count, Descriptor{});
    set.inline_data.assign(layout->inline_bytes, 0);
    for (const LayoutBinding& b : layout->bindings) {
        for (uint32_t j = 0; j < b.slots(); ++j) set.slots[b.first_slot + j].type = b.type;
    }
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_AllocateDescriptorSets(VkDevice device, const VkDescriptorSetAllocateInfo* ai,
                                                          VkDescriptorSet* pDescriptorSets) {
    DescriptorPool* pool = from_handle<DescriptorPool>(ai->descriptorPool);
    for (uint32_t i = 0; i < ai->descriptorSetCount; ++i) pDescriptorSets[i] = VK_NULL_HANDLE;
    for (uint32_t i = 0; i < ai->descriptorSetCount; ++i) {
        const std::shared_ptr<const SetLayout>& layout = from_handle<DescriptorSetLayout>(ai->pSetLayouts[i])->shared;
        DescriptorSet* set = create_object<DescriptorSet>(pool->allocator, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
        bool ok = set != nullptr;
        if (ok) {
            set->pool = pool;
            try {
                init_descriptor_set(*set, layout);
                pool->sets.push_back(set);
            } catch (const std::bad_alloc&) {
                destroy_object(set);
                ok = false;
            }
        }
        if (!ok) {
            // All or nothing: free what this call allocated.
            VkDescriptorSet done[1];
            for (uint32_t j = 0; j < i; ++j) {
                done[0] = pDescriptorSets[j];
                DescriptorSet* s = from_handle<DescriptorSet>(done[0]);
                pool->sets.erase(std::find(pool->sets.begin(), pool->sets.end(), s));
                free_set(s);
                pDescriptorSets[j] = VK_NULL_HANDLE;
            }
            return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkAllocateDescriptorSets: out of host memory");
        }
        pDescriptorSets[i] = to_handle(set);
    }
    (void)device;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_FreeDescriptorSets(VkDevice, VkDescriptorPool descriptorPool, uint32_t count,
                                                      const VkDescriptorSet* pDescriptorSets) {
    DescriptorPool* pool = from_handle<DescriptorPool>(descriptorPool);
    for (uint32_t i = 0; i < count; ++i) {
        DescriptorSet* set = from_handle<DescriptorSet>(pDescriptorSets[i]);
        if (set == nullptr) continue;
        auto it = std::find(pool->sets.begin(), pool->sets.end(), set);
        if (it != pool->sets.end()) pool->sets.erase(it);
        free_set(set);
    }
    return VK_SUCCESS;
}

namespace {

// The VUID a write of VK_NULL_HANDLE breaks when the nullDescriptor feature (VK_EXT_robustness2) is not enabled, or
// null when element j of the write names an object (or the feature is enabled). Samplers are never null descriptors.
const char* refused_null_descriptor(const Device& dev, const VkWriteDescriptorSet& w, uint32_t j) {
    if (dev.enabled_features.robustness2.nullDescriptor) return nullptr;
    switch (w.descriptorType) {
        case VK_DESCRIPTOR_TYPE_SAMPLER:
        case VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK:
            return nullptr;
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:
            return w.pImageInfo[j].imageView == VK_NULL_HANDLE ? "VUID-VkWriteDescriptorSet-descriptorType-02997"
                                                               : nullptr;
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
            return w.pTexelBufferView[j] == VK_NULL_HANDLE ? "VUID-VkWriteDescriptorSet-descriptorType-02995" : nullptr;
        default:
            return w.pBufferInfo[j].buffer == VK_NULL_HANDLE ? "VUID-VkDescriptorBufferInfo-buffer-02998" : nullptr;
    }
}

}  // namespace

VKAPI_ATTR void VKAPI_CALL tvk_UpdateDescriptorSets(VkDevice device, uint32_t writeCount,
                                                    const VkWriteDescriptorSet* writes, uint32_t copyCount,
                                                    const VkCopyDescriptorSet* copies) {
    const Device* dev = from_handle<Device>(device);
    for (uint32_t i = 0; i < writeCount; ++i) {
        const VkWriteDescriptorSet& w = writes[i];
        DescriptorSet* set = from_handle<DescriptorSet>(w.dstSet);
        if (w.descriptorType == VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK) {
            write_inline(set, w);
            continue;
        }
        for (uint32_t j = 0; j < w.descriptorCount; ++j) {
            Descriptor* d = slot_of(set, w.dstBinding, w.dstArrayElement + j);
            if (d == nullptr) {
                log_error("vkUpdateDescriptorSets: binding %u element %u is outside the set", w.dstBinding,
                          w.dstArrayElement + j);
                break;
            }
            if (const char* vuid = refused_null_descriptor(*dev, w, j)) {
                log_error(
                    "vkUpdateDescriptorSets: binding %u element %u: VK_NULL_HANDLE needs the nullDescriptor "
                    "feature of VkPhysicalDeviceRobustness2FeaturesEXT enabled (%s); the descriptor is left as "
                    "it was",
                    w.dstBinding, w.dstArrayElement + j, vuid);
                continue;
            }
            d->type = w.descriptorType;
            switch (w.descriptorType) {
                case VK_DESCRIPTOR_TYPE_SAMPLER:
                case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
                case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
                case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
                case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT: {
                    const VkDescriptorImageInfo& ii = w.pImageInfo[j];
                    const bool has_sampler = w.descriptorType == VK_DESCRIPTOR_TYPE_SAMPLER ||
                                             w.descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
                    // Immutable samplers stay (the draw takes them from the layout); otherwise the written sampler is
                    // used.
                    const LayoutBinding* b = set->layout->find(w.dstBinding);
                    if (has_sampler && (b == nullptr || b->immutable_samplers.empty())) {
                        d->sampler = from_handle<Sampler>(ii.sampler);
                    }
                    if (w.descriptorType != VK_DESCRIPTOR_TYPE_SAMPLER) {
                        d->image_view = from_handle<ImageView>(ii.imageView);
                        d->image_layout = ii.imageLayout;
                    }
                    break;
                }
                case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
                case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
                    d->buffer_view = w.pTexelBufferView[j];
                    break;
                default: {
                    const VkDescriptorBufferInfo& bi = w.pBufferInfo[j];
                    d->buffer = from_handle<Buffer>(bi.buffer);
                    d->offset = bi.offset;
                    d->range =
                        bi.range == VK_WHOLE_SIZE && d->buffer != nullptr ? d->buffer->size - bi.offset : bi.range;
                    break;
                }
            }
        }
    }
    for (uint32_t i = 0; i < copyCount; ++i) {
        const VkCopyDescriptorSet& c = copies[i];
        if (copy_inline(c)) continue;
        DescriptorSet* src = from_handle<DescriptorSet>(c.srcSet);
        DescriptorSet* dst = from_handle<DescriptorSet>(c.dstSet);
        for (uint32_t j = 0; j < c.descriptorCount; ++j) {
            Descriptor* s = slot_of(src, c.srcBinding, c.srcArrayElement + j);
            Descriptor* d = slot_of(dst, c.dstBinding, c.dstArrayElement + j);
            if (s == nullptr || d == nullptr) {
                log_error("vkUpdateDescriptorSets: copy %u runs outside a set", i);
                break;
            }
            *d = *s;
        }
    }
}

}  // namespace tilevk::icd
