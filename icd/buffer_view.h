// VkBufferView: a typed view of a buffer range. No format reports UNIFORM/STORAGE_TEXEL_BUFFER features (shader/
// has no texel-buffer access: no Buffer-dimension images), so no shader can read one; the object only holds what
// it was created with, for vkUpdateDescriptorSets.
#pragma once
#include "buffer.h"

namespace tilevk::icd {

struct BufferView : NonDispatchableObject {
    using Handle = VkBufferView;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_BUFFER_VIEW;
    BufferView() : NonDispatchableObject(kType) {}
    Buffer* buffer = nullptr;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkDeviceSize offset = 0, range = 0;  // range resolved from VK_WHOLE_SIZE
};

}  // namespace tilevk::icd
