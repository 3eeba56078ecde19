// Interpreter kernels: local (SoA) memory and bounds-checked buffer access.
#pragma once

#include "shader/exec_kernels.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

[[gnu::always_inline]] inline void op_load_local(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES {
        uint64_t w = std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1);  // clamp to the variable
        d[l] = mc.M[w * kLanes + l];
    }
}

[[gnu::always_inline]] inline void op_store_local(const Inst& in, Machine& mc) {
    const uint32_t* __restrict a = A, * __restrict b = B, * __restrict c = C;
    LANES {
        uint64_t w = std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1);
        if (c[l]) mc.M[w * kLanes + l] = b[l];
    }
}

[[gnu::always_inline]] inline void op_load_buf(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A, * __restrict b = B;
    LANES {
        uint32_t v = 0;
        if (a[l] < in.n && in.imm + a[l] < mc.num_slots) {
            const Descriptor* desc = mc.slots[in.imm + a[l]];
            uint64_t off = uint64_t(b[l]) + in.extra;
            if (desc && desc->buffer.data && off + 4 <= desc->buffer.size)
                std::memcpy(&v, static_cast<const uint8_t*>(desc->buffer.data) + off, 4);
        }
        d[l] = v;
    }
}

[[gnu::always_inline]] inline void op_load_buf_uniform(const Inst& in, Machine& mc) {
    // constant element and offset: one bounds-checked read, broadcast
    uint32_t v = 0;
    if (in.imm < mc.num_slots) {
        const Descriptor* desc = mc.slots[in.imm];
        uint64_t off = in.extra;
        if (desc && desc->buffer.data && off + 4 <= desc->buffer.size)
            std::memcpy(&v, static_cast<const uint8_t*>(desc->buffer.data) + off, 4);
    }
    uint32_t* __restrict d = D;
    LANES d[l] = v;
}

[[gnu::always_inline]] inline void op_store_buf(const Inst& in, Machine& mc) {
    const uint32_t *m = D, *a = A, *b = B, *c = C;
    LANES {
        if (!m[l] || a[l] >= in.n || in.imm + a[l] >= mc.num_slots) continue;
        const Descriptor* desc = mc.slots[in.imm + a[l]];
        uint64_t off = uint64_t(b[l]) + in.extra;
        if (desc && desc->buffer.writable && off + 4 <= desc->buffer.size)
            std::memcpy(static_cast<uint8_t*>(desc->buffer.writable) + off, &c[l], 4);
    }
}

[[gnu::always_inline]] inline void op_buf_array_length(const Inst& in, Machine& mc) {
    // runtime array length = (buffer size - member offset) / stride, 0 when missing or too small
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A, * __restrict b = B;
    LANES {
        uint32_t v = 0;
        if (a[l] < in.n && in.imm + a[l] < mc.num_slots && b[l]) {
            const Descriptor* desc = mc.slots[in.imm + a[l]];
            if (desc && desc->buffer.data && desc->buffer.size > in.extra)
                v = uint32_t(std::min<uint64_t>((desc->buffer.size - in.extra) / b[l], 0xFFFFFFFFu));
        }
        d[l] = v;
    }
}

#define TILEVK_EXEC_MEMORY_OPS(X)          \
    X(LoadLocal, op_load_local)            \
    X(StoreLocal, op_store_local)          \
    X(LoadBuf, op_load_buf)                \
    X(LoadBufUniform, op_load_buf_uniform) \
    X(StoreBuf, op_store_buf)              \
    X(BufArrayLength, op_buf_array_length)

}  // namespace
}  // namespace tilevk::shader::exec
