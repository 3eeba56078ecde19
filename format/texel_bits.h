// Bit-level helpers the texel codec's files share (texel_codec.cpp, texel_codec_channels.cpp): float bits, SSE
// min/max semantics, and reading/writing a channel's bits in a texel read as a little-endian integer.
#pragma once

#include <cstdint>
#include <cstring>

namespace tilevk::format::bits {

inline uint32_t of(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
inline float to_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
// MINPS / MAXPS: the second operand when either is NaN (gallivm's lp_build_min / lp_build_max on x86).
inline float sse_min(float a, float b) {
    return a < b ? a : b;
}
inline float sse_max(float a, float b) {
    return a > b ? a : b;
}

// Bits [shift, shift + count) of the texel read as a little-endian integer (count <= 32).
inline uint32_t extract(const uint8_t* texel, uint32_t shift, uint32_t count) {
    const uint8_t* p = texel + shift / 8;
    const uint32_t bytes = (shift % 8 + count + 7) / 8;
    uint64_t v = 0;
    for (uint32_t i = 0; i < bytes; ++i) v |= uint64_t(p[i]) << (8 * i);
    v >>= shift % 8;
    return count >= 32 ? uint32_t(v) : uint32_t(v & ((1ull << count) - 1));
}
// Writes the low `count` bits of `value` at bit `shift`, keeping every other bit of the texel.
inline void insert(uint8_t* texel, uint32_t shift, uint32_t count, uint32_t value) {
    uint8_t* p = texel + shift / 8;
    const uint32_t bytes = (shift % 8 + count + 7) / 8;
    uint64_t v = 0;
    for (uint32_t i = 0; i < bytes; ++i) v |= uint64_t(p[i]) << (8 * i);
    const uint64_t field = (count >= 32 ? 0xffffffffull : ((1ull << count) - 1)) << (shift % 8);
    v = (v & ~field) | ((uint64_t(value) << (shift % 8)) & field);
    for (uint32_t i = 0; i < bytes; ++i) p[i] = uint8_t(v >> (8 * i));
}

inline int32_t sign_extend(uint32_t raw, uint32_t count) {
    return count >= 32 ? int32_t(raw) : int32_t(raw << (32 - count)) >> (32 - count);
}

}  // namespace tilevk::format::bits
