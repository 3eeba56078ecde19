// The extensions tilevk exposes (listed in icd/extensions.txt, tables generated into entrypoints.h): how they are
// enumerated, enabled at vkCreateInstance/vkCreateDevice, and which commands they make visible.
#pragma once
#include "entrypoints.h"

namespace tilevk::icd {

// vkEnumerate{Instance,Device}ExtensionProperties: the exposed extensions of one kind, with the count/array
// protocol of the spec (VK_INCOMPLETE when the array is too short).
VkResult enumerate_extensions(bool device, uint32_t* count, VkExtensionProperties* properties);

// Parses the names an application enables. Returns VK_ERROR_EXTENSION_NOT_PRESENT (and says which name, for
// `command`) when one is not an exposed extension of that kind.
VkResult enable_extensions(const char* command, bool device, uint32_t name_count, const char* const* names,
                           ExtensionSet* enabled);

// Whether a command is visible to an application that asked for `api_version` and enabled `instance_extensions`
// and `device_extensions` (nullptr: any exposed device extension counts, as for vkGetInstanceProcAddr). Names of a
// newer core version or of an extension not enabled are NULL (Vulkan spec, "Command Function Pointers").
bool entry_point_enabled(const EntryPoint& e, uint32_t api_version, const ExtensionSet& instance_extensions,
                         const ExtensionSet* device_extensions);

}  // namespace tilevk::icd
