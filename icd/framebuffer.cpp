#include "framebuffer.h"

#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateFramebuffer(VkDevice device, const VkFramebufferCreateInfo* ci,
                                                     const VkAllocationCallbacks* pAllocator,
                                                     VkFramebuffer* pFramebuffer) {
    Device* dev = from_handle<Device>(device);
    Framebuffer* fb =
        create_object<Framebuffer>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (fb == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateFramebuffer: out of host memory");
    try {
        for (uint32_t i = 0; i < ci->attachmentCount; ++i) {
            fb->attachments.push_back(from_handle<ImageView>(ci->pAttachments[i]));
        }
    } catch (const std::bad_alloc&) {
        destroy_object(fb);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateFramebuffer: out of host memory");
    }
    fb->width = ci->width;
    fb->height = ci->height;
    fb->layers = ci->layers;
    *pFramebuffer = to_handle(fb);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyFramebuffer(VkDevice, VkFramebuffer framebuffer, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Framebuffer>(framebuffer));
}

}  // namespace tilevk::icd
