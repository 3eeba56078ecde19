// VkPrivateDataSlot (VK_EXT_private_data, core in Vulkan 1.3): 64-bit values an application attaches to any of its
// objects. Values live in one table keyed by the object's handle; destroying a tilevk object drops its values, so
// a handle that is reused later starts again at 0, as the spec's "never set" rule wants.
#pragma once
#include <cstdint>

#include "object.h"

namespace tilevk::icd {

struct PrivateDataSlot : NonDispatchableObject {
    using Handle = VkPrivateDataSlot;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PRIVATE_DATA_SLOT;
    PrivateDataSlot() : NonDispatchableObject(kType) {}
    uint64_t id = 0;  // unique for the process: a later slot at the same address never sees this one's values
};

}  // namespace tilevk::icd
