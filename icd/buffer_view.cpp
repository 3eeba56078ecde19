// vkCreateBufferView / vkDestroyBufferView.
#include "buffer_view.h"

#include <cinttypes>

#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateBufferView(VkDevice device, const VkBufferViewCreateInfo* pCreateInfo,
                                                    const VkAllocationCallbacks* pAllocator, VkBufferView* pView) {
    Device* dev = from_handle<Device>(device);
    Buffer* buf = from_handle<Buffer>(pCreateInfo->buffer);
    if (buf == nullptr || pCreateInfo->offset >= buf->size)
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY,  // invalid usage: the closest code vkCreateBufferView may return
                    "vkCreateBufferView: offset %" PRIu64 " lies outside the buffer", uint64_t(pCreateInfo->offset));
    // The format would need UNIFORM/STORAGE_TEXEL_BUFFER features, which no format has: the view can be made (and
    // written into descriptor sets) but no pipeline can read it — shader/ refuses texel-buffer images.
    BufferView* view =
        create_object<BufferView>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (view == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateBufferView: out of host memory");
    view->buffer = buf;
    view->format = pCreateInfo->format;
    view->offset = pCreateInfo->offset;
    view->range = pCreateInfo->range == VK_WHOLE_SIZE ? buf->size - pCreateInfo->offset : pCreateInfo->range;
    *pView = to_handle(view);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyBufferView(VkDevice, VkBufferView bufferView, const VkAllocationCallbacks*) {
    destroy_object(from_handle<BufferView>(bufferView));
}

}  // namespace tilevk::icd
