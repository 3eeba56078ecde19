// Test helper: a consumer that accumulates coverage into a per-sample grid (count and payload hash), checks
// API order and tile bounds, and a per-tile call digest for thread-count comparisons.
#pragma once

#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"

namespace tilevk::rast::test {

inline uint64_t mix(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

class GridConsumer : public CoverageConsumer {
  public:
    GridConsumer(int w, int h, int samples, size_t num_tiles)
        : count(size_t(w) * h * samples),
          hash(count.size()),
          digest(num_tiles),
          order_ok(num_tiles, 1),
          bounds_ok(num_tiles, 1),
          w_(w),
          h_(h),
          samples_(samples),
          last_payload_(num_tiles) {}

    void begin_tile(unsigned, const TileInfo& t) override {
        last_payload_[t.index] = -1;
        digest[t.index] = mix(t.index);
    }
    void primitive(unsigned, const TileInfo& t, const PrimCoverage& c) override {
        if (int64_t(c.payload) <= last_payload_[t.index]) order_ok[t.index] = 0;
        last_payload_[t.index] = c.payload;
        const uint64_t ph = mix(c.payload);
        uint64_t& d = digest[t.index];
        d = mix(d ^ ph);
        for (size_t i = 0; i < c.num_blocks; ++i) {
            const Block4& b = c.blocks[i];
            d = mix(d ^ (uint64_t(uint32_t(b.x)) << 32 | uint32_t(b.y)));
            for (int s = 0; s < samples_; ++s) {
                d = mix(d ^ b.mask[s]);
                for (int k = 0; k < 16; ++k)
                    if ((b.mask[s] >> k) & 1) add(t, b.x + (k & 3), b.y + (k >> 2), s, ph);
            }
        }
        for (size_t i = 0; i < c.num_blocks16; ++i) {
            const Block16& b = c.blocks16[i];
            d = mix(d ^ (uint64_t(uint32_t(b.x)) << 32 | uint32_t(b.y)) ^ 0x16ull << 56);
            bool any = false;
            for (int j = 0; j < 16; ++j) {
                d = mix(d ^ b.mask[j]);
                any |= b.mask[j] != 0;
                for (int k = 0; k < 16; ++k)
                    if ((b.mask[j] >> k) & 1) add(t, b.x + 4 * (j & 3) + (k & 3), b.y + 4 * (j >> 2) + (k >> 2), 0, ph);
            }
            if (!any || samples_ != 1) bounds_ok[t.index] = 0;  // coverage.h: never all-zero, 1x only
        }
        for (size_t i = 0; i < c.num_full; ++i) {
            const FullBlock& f = c.full[i];
            d = mix(d ^ (uint64_t(uint32_t(f.x)) << 32 | uint32_t(f.y)) ^ uint64_t(f.size) << 56);
            for (int y = f.y; y < f.y + f.size; ++y)
                for (int x = f.x; x < f.x + f.size; ++x)
                    for (int s = 0; s < samples_; ++s)
                        if ((c.sample_mask >> s) & 1) add(t, x, y, s, ph);
        }
    }
    void end_tile(unsigned, const TileInfo& t) override { digest[t.index] = mix(digest[t.index] ^ 0xE4D); }

    size_t idx(int x, int y, int s) const { return (size_t(y) * w_ + x) * samples_ + s; }

    // First differing sample as "x,y,s" or "" if equal.
    std::string diff(const GridConsumer& o) const {
        for (int y = 0; y < h_; ++y)
            for (int x = 0; x < w_; ++x)
                for (int s = 0; s < samples_; ++s)
                    if (count[idx(x, y, s)] != o.count[idx(x, y, s)] || hash[idx(x, y, s)] != o.hash[idx(x, y, s)])
                        return std::to_string(x) + "," + std::to_string(y) + " s" + std::to_string(s) + " count " +
                               std::to_string(count[idx(x, y, s)]) + " vs " + std::to_string(o.count[idx(x, y, s)]);
        return "";
    }
    bool all_ok() const {
        for (size_t i = 0; i < order_ok.size(); ++i)
            if (!order_ok[i] || !bounds_ok[i]) return false;
        return true;
    }

    std::vector<uint32_t> count;
    std::vector<uint64_t> hash;
    std::vector<uint64_t> digest;
    std::vector<uint8_t> order_ok, bounds_ok;

  private:
    void add(const TileInfo& t, int x, int y, int s, uint64_t ph) {
        if (x < t.x0 || y < t.y0 || x >= t.x0 + t.width || y >= t.y0 + t.height || x >= w_ || y >= h_) {
            bounds_ok[t.index] = 0;
            return;
        }
        ++count[idx(x, y, s)];
        hash[idx(x, y, s)] += ph;
    }
    int w_, h_, samples_;
    std::vector<int64_t> last_payload_;
};

// Renders `scene` with `method` into a fresh grid.
inline GridConsumer render(Scene& scene, Method method, ThreadPool& pool) {
    const SceneConfig& c = scene.config();
    GridConsumer g(c.width, c.height, c.samples, size_t(scene.tiles_x()) * scene.tiles_y());
    scene.set_method(method);
    scene.rasterize(g, pool);
    return g;
}

// The samples a render covers, as (x, y, sample).
using SampleSet = std::set<std::tuple<int, int, int>>;

// The samples `scene` covers with `method` on one thread (each counted at least once).
inline SampleSet covered(Scene& scene, Method method) {
    ThreadPool pool(1);
    GridConsumer g = render(scene, method, pool);
    SampleSet out;
    const SceneConfig& c = scene.config();
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x)
            for (int s = 0; s < c.samples; ++s)
                if (g.count[g.idx(x, y, s)]) out.insert({x, y, s});
    return out;
}

}  // namespace tilevk::rast::test
