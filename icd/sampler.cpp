#include "sampler.h"

#include "device.h"
#include "entrypoints.h"
#include "render_state.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateSampler(VkDevice device, const VkSamplerCreateInfo* ci,
                                                 const VkAllocationCallbacks* pAllocator, VkSampler* pSampler) {
    Device* dev = from_handle<Device>(device);
    Sampler* s = create_object<Sampler>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (s == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSampler: out of host memory");
    s->state = sampler_state_of(*ci);  // with its pNext chain (custom border colour)
    s->info = *ci;
    s->info.pNext = nullptr;
    *pSampler = to_handle(s);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroySampler(VkDevice, VkSampler sampler, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Sampler>(sampler));
}

// Vulkan 1.1 core commands of the optional samplerYcbcrConversion feature, which tilevk does not support: valid
// usage never calls them; a call is refused by name and no object exists to destroy.
VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateSamplerYcbcrConversion(VkDevice, const VkSamplerYcbcrConversionCreateInfo*,
                                                                const VkAllocationCallbacks*,
                                                                VkSamplerYcbcrConversion* pYcbcrConversion) {
    *pYcbcrConversion = VK_NULL_HANDLE;
    return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                "vkCreateSamplerYcbcrConversion: the samplerYcbcrConversion feature is not supported by tilevk");
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroySamplerYcbcrConversion(VkDevice, VkSamplerYcbcrConversion,
                                                             const VkAllocationCallbacks*) {}

}  // namespace tilevk::icd
