// The conformance subset's random source: xorshift32 seeded through one splitmix64 step, so a seed gives the same
// sequence on every platform and compiler (the random and extreme groups name scenes by seed).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tilevk::cts {

struct Rng {
    uint32_t s;
    explicit Rng(uint32_t seed) {
        uint64_t z = seed + 0x9E3779B97F4A7C15ull;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        s = uint32_t(z ^ (z >> 31)) | 1u;
    }
    uint32_t next() {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        return s;
    }
    uint32_t below(uint32_t n) { return next() % n; }
    float unit() { return float(next() >> 8) * (1.0f / 16777216.0f); }
    bool chance(float p) { return unit() < p; }
    float range(float a, float b) { return a + (b - a) * unit(); }
    float sign() { return next() & 1 ? -1.0f : 1.0f; }
    template <typename T, size_t N>
    T pick(const T (&a)[N]) {
        return a[below(N)];
    }
};

}  // namespace tilevk::cts
