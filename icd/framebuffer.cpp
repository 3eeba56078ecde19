#include "framebuffer.h"

#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateFramebuffer(VkDevice device, const VkFramebufferCreateInfo* ci,
                                                     const VkAllocationCallbacks* pAllocator,
                                                     VkFramebuffer* pFramebuffer) {
    Device* dev = from_handle<Device>(device);
    const bool imageless = (ci->flags & VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT) != 0;
    if (imageless && !dev->enabled_features.core.v12.imagelessFramebuffer) {
        // VUID-VkFramebufferCreateInfo-flags-03189
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateFramebuffer: VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT needs the imagelessFramebuffer feature "
                    "enabled (VkPhysicalDeviceImagelessFramebufferFeatures)");
    }
    Framebuffer* fb =
        create_object<Framebuffer>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (fb == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateFramebuffer: out of host memory");
    try {
        // An imageless framebuffer's VkFramebufferAttachmentsCreateInfo describes the views to come; the views
        // themselves are checked against nothing here (as for other framebuffers, a mismatch is invalid usage).
        for (uint32_t i = 0; !imageless && i < ci->attachmentCount; ++i) {
            fb->attachments.push_back(from_handle<ImageView>(ci->pAttachments[i]));
        }
    } catch (const std::bad_alloc&) {
        destroy_object(fb);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateFramebuffer: out of host memory");
    }
    fb->imageless = imageless;
    fb->imageless_count = imageless ? ci->attachmentCount : 0;
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
