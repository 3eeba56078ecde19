// Properties beyond VkPhysicalDeviceProperties: the Vulkan 1.1-1.3 property structs (one home for every value; the
// promoted structs, VkPhysicalDeviceDriverProperties and the like, are filled from them by core_structs.cpp) and the
// pNext chains of vkGetPhysicalDevice*Properties2.
#pragma once
#include <vulkan/vulkan.h>

#include "core_structs.h"

namespace tilevk::icd {

struct PhysicalDevice;

// The values tilevk reports (the heap size comes from the physical device).
CoreProperties make_core_properties(const PhysicalDevice& pd);

// Writes tilevk's answer into one struct of a vkGetPhysicalDeviceProperties2 chain; structs tilevk does not know
// are left untouched, as the spec asks.
void write_property_struct(const PhysicalDevice& pd, VkBaseOutStructure* s);

}  // namespace tilevk::icd
