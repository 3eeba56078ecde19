// Interpreter kernels: loads, stores and atomics through PhysicalStorageBuffer pointers (buffer device addresses).
//
// A pointer is two registers, the address's low and high words (translate_pointer.cpp). Every access looks its
// bytes up in the device-address registry (device_address.h): outside the allocations the driver registered, a
// load gives 0 and a store or atomic does nothing (the address is the application's bug; the driver's and the
// application's other memory stay untouched, where a GPU would fault or read garbage).
#pragma once

#include <cstring>

#include "shader/device_address.h"
#include "shader/exec_atomic.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

inline uint64_t lane_address(const Inst& in, const uint32_t* lo, const uint32_t* hi, int l) {
    return ((uint64_t(hi[l]) << 32) | lo[l]) + in.extra;
}

// d = the word at address (a, b) + extra in the lanes of mask c; 0 elsewhere and outside registered memory.
[[gnu::always_inline]] inline void op_load_ptr(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *b = B, *c = C;
    const DeviceAddressCheck check;
    for (int l = 0; l < kLanes; ++l) {
        uint32_t v = 0;
        if (c[l] != 0) {
            if (const void* p = check.find(lane_address(in, a, b, l), 4)) std::memcpy(&v, p, 4);
        }
        d[l] = v;
    }
}

// The word at address (a, b) + extra = c in the lanes of mask d, in lane order.
[[gnu::always_inline]] inline void op_store_ptr(const Inst& in, Machine& mc) {
    const uint32_t *m = D, *a = A, *b = B, *c = C;
    const DeviceAddressCheck check;
    for (int l = 0; l < kLanes; ++l) {
        if (m[l] == 0) continue;
        if (void* p = check.find(lane_address(in, a, b, l), 4)) std::memcpy(p, &c[l], 4);
    }
}

// d = atomic pad:AtomicOp on the word at (a, b) + extra, value c, comparator d, in the lanes of mask n (a
// register), lanes in order; other lanes, misaligned words and words outside registered memory: nothing, d = 0.
// With kAtomicWide: a 64-bit doubleword, c, d register pairs (exec_atomic.h).
[[gnu::always_inline]] inline void op_atomic_ptr(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *b = B, *c = C;
    const uint32_t* m = mc.R + size_t(in.n) * kLanes;
    const auto op = AtomicOp(in.pad & ~kAtomicWide);
    const bool wide = (in.pad & kAtomicWide) != 0;
    const size_t bytes = wide ? 8 : 4;
    const DeviceAddressCheck check;
    for (int l = 0; l < kLanes; ++l) {
        const uint64_t cmp = wide ? pair_lane(d, l) : d[l];
        if (wide) set_pair_lane(d, l, 0);
        d[l] = 0;
        if (m[l] == 0) continue;
        void* p = check.find(lane_address(in, a, b, l), bytes);
        if (p == nullptr || reinterpret_cast<uintptr_t>(p) % bytes != 0) continue;
        if (wide)
            set_pair_lane(d, l, atomic_on_dword(op, static_cast<uint64_t*>(p), pair_lane(c, l), cmp));
        else
            d[l] = atomic_on_word(op, static_cast<uint32_t*>(p), c[l], uint32_t(cmp));
    }
}

#define TILEVK_EXEC_POINTER_OPS(X) \
    X(LoadPtr, op_load_ptr)        \
    X(StorePtr, op_store_ptr)      \
    X(AtomicPtr, op_atomic_ptr)

}  // namespace
}  // namespace tilevk::shader::exec
