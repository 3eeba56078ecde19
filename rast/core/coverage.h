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

// Coverage of one primitive within one tile. The two lists never overlap; the order within each list is
// deterministic (the same for any thread count) but otherwise unspecified.
struct PrimCoverage {
    uint32_t payload = 0;      // PrimCommon::payload
    uint16_t sample_mask = 0;  // PrimCommon::sample_mask & ((1 << samples) - 1)
    bool front_facing = true;
    const Block4* blocks = nullptr;
    size_t num_blocks = 0;
    const FullBlock* full = nullptr;
    size_t num_full = 0;
};

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
};

}  // namespace tilevk::rast
