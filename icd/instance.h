// VkInstance: owns the one physical device tilevk exposes.
#pragma once
#include "entrypoints.h"
#include "object.h"
#include "physical_device.h"

namespace tilevk::icd {

// API version tilevk implements (the manifest's api_version is generated from the same numbers).
constexpr uint32_t kApiVersion = VK_MAKE_API_VERSION(0, 1, TILEVK_API_MINOR, TILEVK_API_PATCH);

struct Instance : DispatchableObject {
    using Handle = VkInstance;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_INSTANCE;

    Instance() : DispatchableObject(kType) {}
    PhysicalDevice* physical_device = nullptr;
    uint32_t app_api_version = VK_API_VERSION_1_0;  // VkApplicationInfo::apiVersion (0 means 1.0)
    ExtensionSet enabled_extensions;                // the instance extensions the application enabled
};
TILEVK_ASSERT_DISPATCHABLE(Instance);

}  // namespace tilevk::icd
