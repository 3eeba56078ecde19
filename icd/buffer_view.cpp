// vkCreateBufferView / vkDestroyBufferView.
#include "buffer_view.h"

#include <cinttypes>

#include "device.h"
#include "entrypoints.h"
#include "formats.h"
#include "render_state.h"
#include "vk_names.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateBufferView(VkDevice device, const VkBufferViewCreateInfo* pCreateInfo,
                                                    const VkAllocationCallbacks* pAllocator, VkBufferView* pView) {
    Device* dev = from_handle<Device>(device);
    Buffer* buf = from_handle<Buffer>(pCreateInfo->buffer);
    if (buf == nullptr || pCreateInfo->offset >= buf->size)
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY,  // invalid usage: the closest code vkCreateBufferView may return
                    "vkCreateBufferView: offset %" PRIu64 " lies outside the buffer", uint64_t(pCreateInfo->offset));
    // The view's format must have the texel-buffer feature of each texel-buffer usage of the buffer: uniform texel
    // buffers are read by shader/ (texelFetch), storage ones read, written and used by atomics (imageBuffer).
    const FormatInfo* f = find_format(pCreateInfo->format);
    const VkFormatFeatureFlags have = f != nullptr ? VkFormatFeatureFlags(f->buffer) : 0;
    if ((buf->usage & VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT) && !(have & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT))
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                    "vkCreateBufferView: %s has no VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT (the buffer's usage has "
                    "VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT)",
                    vk_enum_name(pCreateInfo->format));
    if ((buf->usage & VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT) && !(have & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT))
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                    "vkCreateBufferView: %s has no VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT (the buffer's usage has "
                    "VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT)",
                    vk_enum_name(pCreateInfo->format));
    BufferView* view =
        create_object<BufferView>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (view == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateBufferView: out of host memory");
    view->buffer = buf;
    view->format = pCreateInfo->format;
    view->offset = pCreateInfo->offset;
    view->range = pCreateInfo->range == VK_WHOLE_SIZE ? buf->size - pCreateInfo->offset : pCreateInfo->range;
    if (buf->data() != nullptr) {  // bound already (Vulkan requires it for a non-sparse buffer)
        view->texel_ok = texel_buffer_view_of(*view, &view->texel);
        view->texel_memory = buf->data();
    }
    *pView = to_handle(view);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyBufferView(VkDevice, VkBufferView bufferView, const VkAllocationCallbacks*) {
    destroy_object(from_handle<BufferView>(bufferView));
}

}  // namespace tilevk::icd
