#include "private_data.h"

#include <atomic>
#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

#include "device.h"
#include "entrypoints.h"

namespace tilevk::icd {
namespace {

// handle -> (slot id, value) pairs. One table for the process: handles are unique while their objects live.
struct Table {
    std::mutex mutex;
    std::unordered_map<uint64_t, std::vector<std::pair<uint64_t, uint64_t>>> values;
};

Table& table() {
    static Table* t = new Table;  // never destroyed: objects may be destroyed from static destructors
    return *t;
}

std::atomic<bool> g_in_use{false};  // no lookup on destroy until some value was ever set
std::atomic<uint64_t> g_next_slot{1};

}  // namespace

void forget_private_data(const void* handle) {
    if (!g_in_use.load(std::memory_order_relaxed)) return;
    Table& t = table();
    std::lock_guard lock(t.mutex);
    t.values.erase(reinterpret_cast<uint64_t>(handle));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreatePrivateDataSlot(VkDevice device, const VkPrivateDataSlotCreateInfo*,
                                                         const VkAllocationCallbacks* pAllocator,
                                                         VkPrivateDataSlot* pSlot) {
    Device* dev = from_handle<Device>(device);
    auto* slot =
        create_object<PrivateDataSlot>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (slot == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreatePrivateDataSlot: out of host memory");
    slot->id = g_next_slot.fetch_add(1);
    *pSlot = to_handle(slot);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPrivateDataSlot(VkDevice, VkPrivateDataSlot slot, const VkAllocationCallbacks*) {
    // Values stored under this slot stay until their objects are destroyed; no later slot has the same id.
    destroy_object(from_handle<PrivateDataSlot>(slot));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_SetPrivateData(VkDevice, VkObjectType, uint64_t objectHandle,
                                                  VkPrivateDataSlot privateDataSlot, uint64_t data) {
    const uint64_t id = from_handle<PrivateDataSlot>(privateDataSlot)->id;
    Table& t = table();
    std::lock_guard lock(t.mutex);
    g_in_use.store(true);
    try {
        auto& entries = t.values[objectHandle];
        for (auto& e : entries) {
            if (e.first == id) {
                e.second = data;
                return VK_SUCCESS;
            }
        }
        entries.emplace_back(id, data);
    } catch (const std::bad_alloc&) {
        return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkSetPrivateData: out of host memory");
    }
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetPrivateData(VkDevice, VkObjectType, uint64_t objectHandle,
                                              VkPrivateDataSlot privateDataSlot, uint64_t* pData) {
    const uint64_t id = from_handle<PrivateDataSlot>(privateDataSlot)->id;
    *pData = 0;
    Table& t = table();
    std::lock_guard lock(t.mutex);
    auto it = t.values.find(objectHandle);
    if (it == t.values.end()) return;
    for (const auto& e : it->second)
        if (e.first == id) *pData = e.second;
}

}  // namespace tilevk::icd
