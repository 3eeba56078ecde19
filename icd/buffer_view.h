// VkBufferView: a typed view of a buffer range. Uniform texel buffers are read by texelFetch as a one-row image
// (execute_draw.cpp texel_buffer_of); no format reports STORAGE_TEXEL_BUFFER (shader/ has no imageLoad/imageStore).
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
