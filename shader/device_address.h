// The interpreter's side of the device-address registry (device_address.cpp; the driver's side is in program.h).
#pragma once

#include <cstdint>
#include <shared_mutex>

namespace tilevk::shader {

// Held for one instruction's lanes: the registry cannot change while they look addresses up.
class DeviceAddressCheck {
  public:
    DeviceAddressCheck();
    ~DeviceAddressCheck();
    DeviceAddressCheck(const DeviceAddressCheck&) = delete;
    DeviceAddressCheck& operator=(const DeviceAddressCheck&) = delete;
    // `address` as a pointer when its `bytes` bytes lie inside one registered allocation, else null.
    void* find(uint64_t address, uint32_t bytes) const;

  private:
    std::shared_lock<std::shared_mutex> lock_;
};

}  // namespace tilevk::shader
