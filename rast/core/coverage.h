// The coverage consumer interface: how the core hands per-tile, API-ordered coverage to the fragment stage.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rast/core/fixed_point.h"

namespace tilevk::rast {

// A screen tile (pixels [x0, x0+width) x [y0, y0+height), clipped to the framebuffer).
struct TileInfo {
    uint32_t index = 0;  // row-major tile index
    int32_t x0 = 0, y0 = 0;
    int32_t width = 0, height = 0;
};

// A partially covered 4x4 pixel block. x, y: absolute pixel origin (multiple of 4).
// mask[s] bit (y*4 + x) = sample s of pixel (x0+x, y0+y) covered, already ANDed with the primitive's sample_mask.
// At 1x only mask[0] is meaningful. Never all-zero.
struct Block4 {
    int32_t x = 0, y = 0;
    uint16_t mask[kMaxSamples] = {};
};

// A fully covered square: every pixel in [x, x+size)^2 (size 4, 16 or the tile size; the square is always inside
// the framebuffer and the clip rect) has, for every sample s, coverage bit s == bit s of the primitive's
// sample_mask. The fast path for consumers: no per-pixel mask to look at.
struct FullBlock {
    int32_t x = 0, y = 0;
    int32_t size = 0;
};

// At 1x only: a 4-aligned 16x16-pixel square as its sixteen 4x4 masks, the hier method's unit at 1x (one kernel
// call yields all sixteen, so they are handed over together instead of as sixteen Block4 entries). mask[j] covers
// pixels (x + 4*(j&3) + i%4, y + 4*(j>>2) + i/4) for bit i, like Block4::mask[0], already ANDed with the primitive's
// sample_mask; 0 = nothing covered there, 0xFFFF = all 16 pixels. Parts of the square outside the tile, the
// framebuffer or the clip rect always have mask 0 (the square itself may reach past them). Never all-zero.
struct Block16 {
    int32_t x = 0, y = 0;
    uint16_t mask[16] = {};
};

// Coverage of one primitive within one tile. The three lists never overlap; the order within each list is
// deterministic (the same for any thread count) but otherwise unspecified.
struct PrimCoverage {
    uint32_t payload = 0;      // PrimCommon::payload
    uint16_t sample_mask = 0;  // PrimCommon::sample_mask & ((1 << samples) - 1)
    bool front_facing = true;
    const Block4* blocks = nullptr;
    size_t num_blocks = 0;
    const FullBlock* full = nullptr;
    size_t num_full = 0;
    const Block16* blocks16 = nullptr;  // 1x only
    size_t num_blocks16 = 0;
};

// Calls fn(x, y, masks) for every partially or fully covered 4x4 block given as masks (Block4 entries, then the
// non-zero 4x4 parts of Block16 entries, whose masks[1..3] read 0): for consumers that want one 4x4 unit. FullBlock
// squares are not included.
template <typename Fn>
void for_each_block4(const PrimCoverage& c, Fn&& fn) {
    for (size_t i = 0; i < c.num_blocks; ++i) fn(c.blocks[i].x, c.blocks[i].y, c.blocks[i].mask);
    for (size_t i = 0; i < c.num_blocks16; ++i) {
        const Block16& b = c.blocks16[i];
        for (int j = 0; j < 16; ++j) {
            if (!b.mask[j]) continue;
            static_assert(kMaxSamples == 4);
            const uint16_t masks[kMaxSamples] = {b.mask[j], 0, 0, 0};
            fn(b.x + 4 * (j & 3), b.y + 4 * (j >> 2), masks);
        }
    }
}

// Implemented by the fragment stage. Called from worker threads: begin_tile, then primitive() for each primitive
// binned to the tile in API order (only those with some coverage), then end_tile. One tile has one worker at a
// time; `worker` (< Scene::rasterize's worker count) indexes per-thread scratch. The sequence of calls per tile
// is identical for any thread count and any method that matches the reference.
class CoverageConsumer {
  public:
    virtual ~CoverageConsumer() = default;
    virtual void begin_tile(unsigned worker, const TileInfo& tile) = 0;
    virtual void primitive(unsigned worker, const TileInfo& tile, const PrimCoverage& coverage) = 0;
    virtual void end_tile(unsigned worker, const TileInfo& tile) = 0;
    // Asked every kStopCheckInterval commands of a tile's walk, with the payload of the next primitive: true ends
    // the walk there (end_tile still follows). A consumer that can be stopped from outside (a lost device) answers
    // from its stop flag, so a huge bin is abandoned in microseconds instead of being walked to its end.
    virtual bool stop_tile(unsigned /*worker*/, uint32_t /*next_payload*/) { return false; }
    static constexpr size_t kStopCheckInterval = 64;
    // A hint from the tile loop, a few commands before primitive() may be called with this payload in the same
    // tile: step 0 first, step 1 some commands later (by then what step 0 fetched has arrived), so a consumer that
    // reaches its per-primitive data through a per-primitive record can prefetch the record at step 0 and the data
    // at step 1. Called on the tile's worker; it must not change anything primitive() depends on. Default: nothing.
    virtual void prefetch(uint32_t payload, int step) const {
        (void)payload;
        (void)step;
    }
    // Occlusion, as llvmpipe's binner does it (lp_setup_whole_tile resets the bin under an opaque whole-tile
    // command): hides_earlier(payload) true promises that a primitive with this payload covering a whole tile
    // writes every byte that the tile's earlier primitives wrote, whatever they wrote, and that nothing else of
    // theirs can be observed (no memory writes, no query counts, no depth or stencil). The tile loop then starts at
    // the tile's last whole-tile command that hides the earlier ones. Asked only for whole-tile commands, and only
    // when may_hide() (once per rasterize) is true, so a consumer that never hides costs the loop nothing.
    virtual bool may_hide() const { return false; }
    virtual bool hides_earlier(uint32_t payload) const {
        (void)payload;
        return false;
    }
};

}  // namespace tilevk::rast
