// Interpreter kernels: compute's Workgroup (shared) memory and the OpAtomic* family: 32-bit integers, 32-bit floats
// (Load, Store, Exchange, OpAtomicFAddEXT, OpAtomicFMinEXT / FMaxEXT) and 64-bit integers (kAtomicWide).
//
// Shared memory is one flat block per workgroup (not SoA: every lane of every batch sees the same word). A workgroup
// runs wholly on one thread, so its shared words need no atomic instructions; storage buffers are shared by all the
// workgroups of a dispatch, which run on several threads, so buffer atomics are std::atomic_ref operations. Within
// a batch the lanes apply their operations in lane order, so a batch's results are deterministic.
#pragma once

#include <atomic>
#include <bit>

#include <xmmintrin.h>

#include "shader/exec_kernels.h"

// Internal linkage: one translation unit (exec.cpp) uses these.
namespace tilevk::shader::exec {
namespace {

// The value an integer atomic leaves in memory, given the old one, the operand v and the comparator: on U (uint32_t,
// or uint64_t for kAtomicWide), S its signed twin.
template <class U, class S>
inline U integer_atomic_result(AtomicOp op, U old, U v, U cmp) {
    switch (op) {
        case AtomicOp::Load:
            return old;
        case AtomicOp::Store:
        case AtomicOp::Exchange:
            return v;
        case AtomicOp::CompareExchange:
            return old == cmp ? v : old;
        case AtomicOp::IAdd:
            return old + v;
        case AtomicOp::SMin:
            return S(v) < S(old) ? v : old;
        case AtomicOp::SMax:
            return S(v) > S(old) ? v : old;
        case AtomicOp::UMin:
            return std::min(old, v);
        case AtomicOp::UMax:
            return std::max(old, v);
        case AtomicOp::And:
            return old & v;
        case AtomicOp::Or:
            return old | v;
        case AtomicOp::Xor:
            return old ^ v;
        default:  // the float operations: 32-bit only (atomic_result; translate_atomic.cpp refuses the rest)
            return old;
    }
}

// The value a 32-bit atomic leaves in memory: the integer ones, and the float add, min and max.
inline uint32_t atomic_result(AtomicOp op, uint32_t old, uint32_t v, uint32_t cmp) {
    switch (op) {
        case AtomicOp::FAdd: {  // LLVM's atomicrmw fadd: old + v under the run's MXCSR, retried by compare-exchange
            // ADDSS with old first, as the compiled tier's (memory_ops.cpp), whichever NaN the compiler would pick
            const __m128 sum = _mm_add_ss(_mm_set_ss(std::bit_cast<float>(old)), _mm_set_ss(std::bit_cast<float>(v)));
            return std::bit_cast<uint32_t>(_mm_cvtss_f32(sum));
        }
        case AtomicOp::FMin:    // LLVM 15's minnum on x86: MINSS(v, old) — old when either is NaN or both are
        case AtomicOp::FMax: {  // zeros — then v when old is NaN; the compare sees the run's DAZ (lavapipe-rules)
            const __m128 o = _mm_set_ss(std::bit_cast<float>(old)), x = _mm_set_ss(std::bit_cast<float>(v));
            const __m128 m = op == AtomicOp::FMin ? _mm_min_ss(x, o) : _mm_max_ss(x, o);
            return (old & 0x7FFFFFFFu) > 0x7F800000u ? v : std::bit_cast<uint32_t>(_mm_cvtss_f32(m));
        }
        default:
            return integer_atomic_result<uint32_t, int32_t>(op, old, v, cmp);
    }
}

// One 64-bit atomic on a buffer doubleword other threads may be changing: returns the value before the operation.
inline uint64_t atomic_on_dword(AtomicOp op, uint64_t* word, uint64_t v, uint64_t cmp) {
    std::atomic_ref<uint64_t> ref(*word);
    if (op == AtomicOp::Store) {
        ref.store(v);
        return 0;
    }
    uint64_t old = ref.load();
    while (op != AtomicOp::Load &&
           !ref.compare_exchange_weak(old, integer_atomic_result<uint64_t, int64_t>(op, old, v, cmp))) {
    }
    return old;
}

// A register pair's lane l as one 64-bit value (low word at r, high word one register later).
inline uint64_t pair_lane(const uint32_t* r, int l) {
    return uint64_t(r[l]) | uint64_t(r[l + kLanes]) << 32;
}
inline void set_pair_lane(uint32_t* r, int l, uint64_t v) {
    r[l] = uint32_t(v);
    r[l + kLanes] = uint32_t(v >> 32);
}

// One atomic on a buffer word other threads may be changing: returns the value before the operation.
inline uint32_t atomic_on_word(AtomicOp op, uint32_t* word, uint32_t v, uint32_t cmp) {
    std::atomic_ref<uint32_t> ref(*word);
    switch (op) {
        case AtomicOp::Load:
            return ref.load();
        case AtomicOp::Store:
            ref.store(v);
            return 0;
        case AtomicOp::Exchange:
            return ref.exchange(v);
        case AtomicOp::CompareExchange: {
            uint32_t expected = cmp;
            ref.compare_exchange_strong(expected, v);
            return expected;  // the old value, whether it was replaced or not
        }
        case AtomicOp::IAdd:
            return ref.fetch_add(v);
        case AtomicOp::And:
            return ref.fetch_and(v);
        case AtomicOp::Or:
            return ref.fetch_or(v);
        case AtomicOp::Xor:
            return ref.fetch_xor(v);
        default: {  // min / max: no fetch_min in C++20; float add: no fetch_add on a float's bits
            uint32_t old = ref.load();
            while (!ref.compare_exchange_weak(old, atomic_result(op, old, v, cmp))) {
            }
            return old;
        }
    }
}

[[gnu::always_inline]] inline void op_load_shared(const Inst& in, Machine& mc) {
    uint32_t* __restrict d = D;
    const uint32_t* __restrict a = A;
    LANES d[l] = mc.S[std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1)];  // clamped to the variable
}

[[gnu::always_inline]] inline void op_store_shared(const Inst& in, Machine& mc) {
    const uint32_t *a = A, *b = B, *c = C;
    for (int l = 0; l < kLanes; ++l)  // in lane order: when lanes write one word, the last one wins
        if (c[l]) mc.S[std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1)] = b[l];
}

[[gnu::always_inline]] inline void op_atomic_shared(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    const auto op = AtomicOp(in.pad & ~kAtomicWide);
    if (in.pad & kAtomicWide) {  // two words, low first, each clamped to the variable as a load of them would be
        for (int l = 0; l < kLanes; ++l) {
            if (a[l] == kNoReg) {
                set_pair_lane(d, l, 0);
                continue;
            }
            uint32_t& lo = mc.S[std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1)];
            uint32_t& hi = mc.S[std::min<uint64_t>(uint64_t(in.imm) + a[l] + 1, in.n - 1)];
            const uint64_t old = uint64_t(lo) | uint64_t(hi) << 32;
            const uint64_t now = integer_atomic_result<uint64_t, int64_t>(op, old, pair_lane(c, l), pair_lane(d, l));
            lo = uint32_t(now), hi = uint32_t(now >> 32);
            set_pair_lane(d, l, old);
        }
        return;
    }
    for (int l = 0; l < kLanes; ++l) {
        if (a[l] == kNoReg) {  // inactive lane
            d[l] = 0;
            continue;
        }
        uint32_t& w = mc.S[std::min<uint64_t>(uint64_t(in.imm) + a[l], in.n - 1)];
        const uint32_t old = w;
        w = atomic_result(op, old, c[l], d[l]);
        d[l] = old;
    }
}

[[gnu::always_inline]] inline void op_atomic_buf(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *b = B, *c = C;
    const auto op = AtomicOp(in.pad & ~kAtomicWide);
    const bool wide = (in.pad & kAtomicWide) != 0;
    const uint64_t bytes = wide ? 8 : 4;
    for (int l = 0; l < kLanes; ++l) {
        const uint64_t cmp = wide ? pair_lane(d, l) : d[l];
        if (wide) set_pair_lane(d, l, 0);
        d[l] = 0;
        if (a[l] >= in.n || in.imm + a[l] >= mc.num_slots) continue;  // inactive lane or outside the array
        const Descriptor* desc = mc.slots[in.imm + a[l]];
        const uint64_t off = uint64_t(b[l]) + in.extra;
        // out of bounds, read-only or misaligned (invalid usage): nothing is done, the result is 0
        if (desc == nullptr || desc->buffer.writable == nullptr || off + bytes > desc->buffer.size) continue;
        auto* word = static_cast<uint8_t*>(desc->buffer.writable) + off;
        if (reinterpret_cast<uintptr_t>(word) % bytes != 0) continue;
        if (wide)
            set_pair_lane(d, l, atomic_on_dword(op, reinterpret_cast<uint64_t*>(word), pair_lane(c, l), cmp));
        else
            d[l] = atomic_on_word(op, reinterpret_cast<uint32_t*>(word), c[l], uint32_t(cmp));
    }
}

// Image atomics: the texel's word found by texture.cpp (bounds, format, writability), then as on a buffer.
[[gnu::always_inline]] inline void op_atomic_image(const Inst& in, Machine& mc) {
    uint32_t* d = D;
    const uint32_t *a = A, *c = C;
    const uint32_t* x = mc.R + size_t(in.b) * kLanes;
    const uint32_t* y = x + kLanes;
    const uint32_t* layer = (in.imm & kSampleArray) ? y + kLanes : nullptr;
    const auto op = AtomicOp(in.pad);
    for (int l = 0; l < kLanes; ++l) {
        const uint32_t cmp = d[l];
        d[l] = 0;
        if (a[l] == kNoReg) continue;  // inactive lane
        uint32_t* word = storage_image_word(mc.slots, mc.num_slots, a[l], x[l], y[l], layer ? layer[l] : 0u);
        if (word != nullptr) d[l] = atomic_on_word(op, word, c[l], cmp);
    }
}

#define TILEVK_EXEC_SHARED_OPS(X)     \
    X(LoadShared, op_load_shared)     \
    X(StoreShared, op_store_shared)   \
    X(AtomicShared, op_atomic_shared) \
    X(AtomicBuf, op_atomic_buf)       \
    X(AtomicImage, op_atomic_image)

}  // namespace
}  // namespace tilevk::shader::exec
