// The allocations PhysicalStorageBuffer pointers may reach (program.h register_device_memory): a map from each
// allocation's first byte to its end, read by every load, store and atomic through such a pointer (exec_pointer.h).
#include <map>
#include <mutex>
#include <shared_mutex>

#include "shader/device_address.h"
#include "shader/program.h"

namespace tilevk::shader {
namespace {

struct Range {
    uint64_t end;   // one past the last byte's address
    uint8_t* data;  // the first byte (pointers are made from it, not from the shader's integer)
};

struct Registry {
    std::shared_mutex mutex;
    std::map<uint64_t, Range> ranges;  // by the first byte's address
};

Registry& registry() {
    static Registry r;
    return r;
}

}  // namespace

void register_device_memory(const void* data, uint64_t size) {
    Registry& r = registry();
    std::unique_lock lock(r.mutex);
    const auto first = uint64_t(reinterpret_cast<uintptr_t>(data));
    // the driver's device memory, which shaders write (program.h takes it as const void* for both calls)
    r.ranges[first] = Range{first + size, static_cast<uint8_t*>(const_cast<void*>(data))};
}

void unregister_device_memory(const void* data) {
    Registry& r = registry();
    std::unique_lock lock(r.mutex);
    r.ranges.erase(uint64_t(reinterpret_cast<uintptr_t>(data)));
}

DeviceAddressCheck::DeviceAddressCheck() : lock_(registry().mutex) {}
DeviceAddressCheck::~DeviceAddressCheck() = default;

void* DeviceAddressCheck::find(uint64_t address, uint32_t bytes) const {
    const auto& ranges = registry().ranges;
    auto it = ranges.upper_bound(address);  // the first allocation starting after `address`
    if (it == ranges.begin()) return nullptr;
    --it;
    if (address + bytes < address || address + bytes > it->second.end) return nullptr;  // past its end (or wrapping)
    return it->second.data + (address - it->first);
}

}  // namespace tilevk::shader
