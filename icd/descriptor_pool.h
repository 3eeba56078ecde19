// VkDescriptorPool and VkDescriptorSet: sets are arrays of plain descriptors, owned by their pool.
#pragma once
#include <memory>
#include <vector>

#include "descriptor_set_layout.h"

namespace tilevk::icd {

struct Buffer;
struct Sampler;
struct ImageView;
struct DescriptorPool;

struct Descriptor {
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    Sampler* sampler = nullptr;
    ImageView* image_view = nullptr;
    VkImageLayout image_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    Buffer* buffer = nullptr;
    VkDeviceSize offset = 0;
    VkDeviceSize range = 0;
    VkBufferView buffer_view = VK_NULL_HANDLE;
};

struct DescriptorSet : NonDispatchableObject {
    using Handle = VkDescriptorSet;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DESCRIPTOR_SET;
    DescriptorSet() : NonDispatchableObject(kType) {}
    DescriptorPool* pool = nullptr;
    std::shared_ptr<const SetLayout> layout;  // shared with its layout object, which may be destroyed first
    std::vector<Descriptor> slots;            // layout->slot_count entries
    std::vector<uint8_t> inline_data;         // layout->inline_bytes: the contents of its inline uniform blocks
};

// A set's descriptors as its layout makes them (each slot typed, nothing written yet); throws std::bad_alloc.
void init_descriptor_set(DescriptorSet& set, const std::shared_ptr<const SetLayout>& layout);

struct DescriptorPool : NonDispatchableObject {
    using Handle = VkDescriptorPool;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_DESCRIPTOR_POOL;
    DescriptorPool() : NonDispatchableObject(kType) {}
    VkDescriptorPoolCreateFlags flags = 0;
    uint32_t max_sets = 0;
    std::vector<DescriptorSet*> sets;  // live sets
};

}  // namespace tilevk::icd
