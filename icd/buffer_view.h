// VkBufferView: a typed view of a buffer range. Uniform texel buffers are read by texelFetch as a one-row image
// (execute_draw.cpp texel_buffer_of); no format reports STORAGE_TEXEL_BUFFER (shader/ has no imageLoad/imageStore).
#pragma once
#include "buffer.h"
#include "shader/program.h"

namespace tilevk::icd {

struct BufferView : NonDispatchableObject {
    using Handle = VkBufferView;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_BUFFER_VIEW;
    BufferView() : NonDispatchableObject(kType) {}
    Buffer* buffer = nullptr;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkDeviceSize offset = 0, range = 0;  // range resolved from VK_WHOLE_SIZE
    // The view as shader/ reads a uniform texel buffer (render_state.h texel_buffer_view_of), translated at
    // vkCreateBufferView; `texel_memory` is the buffer memory it was made for (null: none yet).
    shader::ImageView texel{};
    bool texel_ok = false;
    const void* texel_memory = nullptr;
};

}  // namespace tilevk::icd
