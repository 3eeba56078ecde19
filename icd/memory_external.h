// Memory shared with the world outside the device: VK_KHR_external_memory_fd (OPAQUE_FD: a memfd that tilevk maps,
// exports and imports) and VK_EXT_external_memory_host (HOST_ALLOCATION: the application's own pages used in place).
// The handle types and their properties are lavapipe 22.3.6's (lvp_device.c, lvp_formats.c); every other handle type
// is refused by name.
#pragma once
#include "memory.h"

namespace tilevk::icd {

// The application's pages must start at, and span a multiple of, this many bytes (lavapipe's value: one page).
constexpr VkDeviceSize kMinImportedHostPointerAlignment = 4096;

// What vkGet*ExternalBufferProperties / ImageFormatProperties2 answer for one handle type: OPAQUE_FD is exportable
// and importable, HOST_ALLOCATION importable; any other type has no features (`supported` false).
struct ExternalMemorySupport {
    bool supported = false;
    VkExternalMemoryProperties properties{};
};
ExternalMemorySupport external_memory_support(VkExternalMemoryHandleTypeFlagBits type);

// Gives `mem` its bytes for vkAllocateMemory: a heap block, or as the allocate info's import/export structs ask.
// On failure nothing is left to free, and an imported file descriptor still belongs to the application.
VkResult allocate_memory_backing(const VkMemoryAllocateInfo& info, DeviceMemory& mem);
void free_memory_backing(DeviceMemory& mem);

}  // namespace tilevk::icd
