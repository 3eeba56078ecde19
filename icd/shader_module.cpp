#include "shader_module.h"

#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {

constexpr uint32_t kSpirvMagic = 0x07230203;

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateShaderModule(VkDevice device, const VkShaderModuleCreateInfo* ci,
                                                      const VkAllocationCallbacks* pAllocator,
                                                      VkShaderModule* pShaderModule) {
    Device* dev = from_handle<Device>(device);
    // Only the framing is checked here; the module's contents are validated by shader/ at pipeline creation.
    if (ci->codeSize < 20 || ci->codeSize % 4 != 0 || ci->pCode == nullptr || ci->pCode[0] != kSpirvMagic) {
        return fail(VK_ERROR_INVALID_SHADER_NV, "vkCreateShaderModule: not SPIR-V (size %zu, first word 0x%08x)",
                    ci->codeSize, ci->pCode != nullptr && ci->codeSize >= 4 ? ci->pCode[0] : 0u);
    }
    ShaderModule* m =
        create_object<ShaderModule>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (m == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateShaderModule: out of host memory");
    try {
        m->words.assign(ci->pCode, ci->pCode + ci->codeSize / 4);
    } catch (const std::bad_alloc&) {
        destroy_object(m);
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateShaderModule: out of host memory");
    }
    *pShaderModule = to_handle(m);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyShaderModule(VkDevice, VkShaderModule shaderModule,
                                                   const VkAllocationCallbacks*) {
    destroy_object(from_handle<ShaderModule>(shaderModule));
}

}  // namespace tilevk::icd
