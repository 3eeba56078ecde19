// Interpreter kernels of 8- and 16-bit values (shader/README.md "8- and 16-bit types"): buffer loads and stores of
// one or two bytes, and the float16 <-> float conversions of 16-bit storage. A register holds the value
// zero-extended; the arithmetic is 32-bit IR the translator wraps (translate_narrow.cpp).
#pragma once

#include "format/texel_codec.h"
#include "shader/exec_kernels.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

// As lavapipe's emit_load_mem / emit_store_mem with a 16- or 8-bit type: the offset counts elements of that size,
// so an element is inside when all of its bytes are.
[[gnu::always_inline]] inline void op_load_buf_n(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A, * __restrict b = B;
    const uint32_t bytes = in.pad;
    LANES {
        uint32_t v = 0;
        if (a[l] < in.n && in.imm + a[l] < mc.num_slots) {
            const Descriptor* desc = mc.slots[in.imm + a[l]];
            const uint64_t off = uint64_t(b[l]) + in.extra;
            if (desc && desc->buffer.data && off + bytes <= desc->buffer.size)
                std::memcpy(&v, static_cast<const uint8_t*>(desc->buffer.data) + off, bytes);  // little endian
        }
        d[l] = v;
    }
}

[[gnu::always_inline]] inline void op_store_buf_n(const Inst& in, Machine& mc) {
    const uint32_t *m = D, *a = A, *b = B, *c = C;
    const uint32_t bytes = in.pad;
    LANES {
        if (!m[l] || a[l] >= in.n || in.imm + a[l] >= mc.num_slots) continue;
        const Descriptor* desc = mc.slots[in.imm + a[l]];
        const uint64_t off = uint64_t(b[l]) + in.extra;
        if (desc && desc->buffer.writable && off + bytes <= desc->buffer.size)
            std::memcpy(static_cast<uint8_t*>(desc->buffer.writable) + off, &c[l], bytes);
    }
}

// lavapipe's f2f16 (LLVM's fptrunc): to nearest even, overflow to infinity; a NaN becomes the quiet NaN 0x7E00 with
// its sign, its payload dropped (measured with quiet and signalling NaNs: cts types.storage.layouts_and_halves).
// Float denormals give a signed zero with or without DAZ.
inline uint32_t float_to_half_fptrunc(float f) {
    const uint32_t x = std::bit_cast<uint32_t>(f);
    if ((x & 0x7fffffffu) > 0x7f800000u) return ((x >> 16) & 0x8000u) | 0x7e00u;
    return float_to_half(f);
}

[[gnu::always_inline]] inline void op_half_to_float(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES d[l] = std::bit_cast<uint32_t>(format::half_to_float(uint16_t(a[l])));
}

[[gnu::always_inline]] inline void op_float_to_half(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES d[l] = float_to_half_fptrunc(std::bit_cast<float>(a[l]));
}

#define TILEVK_EXEC_NARROW_OPS(X)    \
    X(LoadBufN, op_load_buf_n)       \
    X(StoreBufN, op_store_buf_n)     \
    X(HalfToFloat, op_half_to_float) \
    X(FloatToHalf, op_float_to_half)

}  // namespace
}  // namespace tilevk::shader::exec
