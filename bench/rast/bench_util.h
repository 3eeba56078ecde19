// Shared by the rast/core benchmarks and the stability sweep: triangles of a given pixel area, consumers.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/core/primitive.h"

namespace tilevk::rast::bench {

// Counts covered samples per worker (so the work cannot be optimized away), padded against false sharing. Kept
// cheap and identical for every method, so that comparisons measure rasterization: one 64-bit popcount per 4x4
// block (the four 16-bit sample masks read as one word; unused samples are zero) and one multiply per full block.
class CountingConsumer : public CoverageConsumer {
  public:
    explicit CountingConsumer(unsigned workers) : counts_(workers * 8, 0) {}
    void begin_tile(unsigned, const TileInfo&) override {}
    void primitive(unsigned w, const TileInfo&, const PrimCoverage& c) override {
        static_assert(sizeof(Block4::mask) == sizeof(uint64_t));
        uint64_t n = 0, full_px = 0;
        for (size_t i = 0; i < c.num_blocks; ++i) {
            uint64_t word;
            std::memcpy(&word, c.blocks[i].mask, sizeof word);
            n += std::popcount(word);
        }
        static_assert(sizeof(Block16::mask) == 4 * sizeof(uint64_t));
        for (size_t i = 0; i < c.num_blocks16; ++i) {  // 1x: sixteen 4x4 masks, four words
            uint64_t words[4];
            std::memcpy(words, c.blocks16[i].mask, sizeof words);
            n += std::popcount(words[0]) + std::popcount(words[1]) + std::popcount(words[2]) + std::popcount(words[3]);
        }
        for (size_t i = 0; i < c.num_full; ++i) full_px += uint64_t(c.full[i].size) * c.full[i].size;
        counts_[w * 8] += n + full_px * std::popcount(unsigned(c.sample_mask));
    }
    void end_tile(unsigned, const TileInfo&) override {}
    uint64_t total() const {
        uint64_t t = 0;
        for (size_t i = 0; i < counts_.size(); i += 8) t += counts_[i];
        return t;
    }

  private:
    std::vector<uint64_t> counts_;
};

// Per-payload hash of the covered (x, y, sample) set: order independent, so methods can be compared per triangle.
class PayloadHashConsumer : public CoverageConsumer {
  public:
    explicit PayloadHashConsumer(size_t n) : hash(n, 0) {}
    static uint64_t mix(uint64_t x) {
        x += 0x9E3779B97F4A7C15ull;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        return x ^ (x >> 31);
    }
    static uint64_t key(int64_t x, int64_t y, int s) { return mix((uint64_t(x) << 34) ^ (uint64_t(y) << 4) ^ s); }
    void begin_tile(unsigned, const TileInfo&) override {}
    void primitive(unsigned, const TileInfo&, const PrimCoverage& c) override {
        uint64_t h = 0;
        for_each_block4(c, [&](int32_t x, int32_t y, const uint16_t* masks) {
            for (int s = 0; s < kMaxSamples; ++s)
                for (int k = 0; k < 16; ++k)
                    if ((masks[s] >> k) & 1) h += key(x + (k & 3), y + (k >> 2), s);
        });
        for (size_t i = 0; i < c.num_full; ++i)
            for (int y = c.full[i].y; y < c.full[i].y + c.full[i].size; ++y)
                for (int x = c.full[i].x; x < c.full[i].x + c.full[i].size; ++x)
                    for (int s = 0; s < kMaxSamples; ++s)
                        if ((c.sample_mask >> s) & 1) h += key(x, y, s);
        hash[c.payload] += h;
    }
    void end_tile(unsigned, const TileInfo&) override {}
    std::vector<uint64_t> hash;  // single-threaded use (payloads shared across tiles)
};

// A random triangle of about `area` pixels (random shape and orientation) centred in [0,w) x [0,h).
inline TriangleInput triangle_of_area(std::mt19937& rng, double area, int w, int h) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const double side = std::sqrt(2.0 * area);  // right isoceles triangle of that area, then rotated/skewed
    const float ang = u(rng) * 6.2831853f;
    const float skew = 0.5f + u(rng);
    const float ax = float(std::cos(ang) * side * skew), ay = float(std::sin(ang) * side * skew);
    const float bx = float(-std::sin(ang) * side / skew), by = float(std::cos(ang) * side / skew);
    const float margin = float(side) + 1;
    const float cx = margin + u(rng) * std::max(1.0f, w - 2 * margin),
                cy = margin + u(rng) * std::max(1.0f, h - 2 * margin);
    TriangleInput t;
    t.x[0] = cx - (ax + bx) / 3, t.y[0] = cy - (ay + by) / 3;
    t.x[1] = t.x[0] + ax, t.y[1] = t.y[0] + ay;
    t.x[2] = t.x[0] + bx, t.y[2] = t.y[0] + by;
    t.common.clip = {0, 0, w, h};
    return t;
}

}  // namespace tilevk::rast::bench
