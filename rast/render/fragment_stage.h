// The fragment stage: the coverage consumer that turns each covered 4x4 block into pixels — interpolation,
// fragment shader, depth/stencil, alpha to coverage, blending and writes — for one tile at a time.
//
// Two paths give the same bytes. The reference path runs the general per-block pipeline for every block. The
// fast path (default) looks at each draw once (DrawPlan) and models no more than it needs: only the input
// components the shader declares are interpolated (SIMD, one reciprocal of w per block), D16/D32F depth without
// stencil runs a 16-lane kernel, opaque RGBA8/BGRA8 writes a fused convert-and-store, and a shader whose result
// cannot vary across a primitive (flat inputs only, no per-pixel built-ins, no discard, no side effects) runs once
// per primitive and tile instead of once per block. tests/rast/fragment/stage_test.cpp renders random scenes both
// ways and compares every byte.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/fragment/linear.h"
#include "rast/render/scene_records.h"
#include "rast/render/targets.h"

namespace tilevk::rast::render {

// Process-wide switch for the fast paths: on unless TILEVK_FRAG=reference; tests flip it to compare both paths.
// Read when a scene is prepared.
void set_fragment_fast_paths(bool on);
bool fragment_fast_paths();

class FragmentStage final : public CoverageConsumer {
  public:
    FragmentStage();
    ~FragmentStage() override;

    // Points the stage at the scene about to be rasterized (the references must outlive rasterize()).
    void prepare(const Framebuffer& fb, const std::deque<DrawRecord>& draws, const std::vector<PrimRecord>& prims,
                 const std::vector<float>& planes, bool fused, unsigned workers);

    // Linear mode: per 64x64 tile (row-major) whether its bin can be llvmpipe's linear bin (only rectangles and
    // clears touch it), and each rectangle's pixel box. Null pointers: not in linear mode.
    void set_linear(const std::vector<uint8_t>* tile_linear, const std::vector<fragment::LinearRegion>* rect_boxes);

    void begin_tile(unsigned worker, const TileInfo& tile) override;
    void primitive(unsigned worker, const TileInfo& tile, const PrimCoverage& coverage) override;
    void end_tile(unsigned worker, const TileInfo& tile) override;

    // Samples of draw record `draw` that passed every per-sample test in the scene last rasterized: the sum of
    // popcount(final mask) per sample plane over all blocks. Counted per (draw, worker), so no two threads share a
    // counter and the sum does not depend on the thread count or on which worker rendered which tile.
    uint64_t samples_passed(uint32_t draw) const;

    // Fragment-shader runs the loop watchdog cut short so far (shader::Scratch::loop_limit_hits of every worker).
    uint64_t loop_limit_hits() const;

    struct DrawPlan;  // what the fast path derived from one draw's state (fragment_stage.cpp)

  private:
    struct Worker;
    void shade_block(Worker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing, int32_t x, int32_t y,
                     const uint16_t raster_masks[4]);
    void shade_block_fast(Worker& w, const DrawPlan& plan, const DrawRecord& draw, const PrimRecord& prim,
                          bool front_facing, int32_t x, int32_t y, const uint16_t raster_masks[4]);
    void clear_block(const ClearRecord& clear, int32_t x, int32_t y, const uint16_t raster_masks[4]);

    Framebuffer fb_;
    const std::deque<DrawRecord>* draws_ = nullptr;
    const std::vector<PrimRecord>* prims_ = nullptr;
    const std::vector<float>* planes_ = nullptr;
    bool fused_ = true;
    bool fast_ = true;
    std::vector<DrawPlan> plans_;  // per draw record (fast path)
    const std::vector<uint8_t>* tile_linear_ = nullptr;
    const std::vector<fragment::LinearRegion>* rect_boxes_ = nullptr;
    std::vector<std::unique_ptr<Worker>> workers_;
};

}  // namespace tilevk::rast::render
