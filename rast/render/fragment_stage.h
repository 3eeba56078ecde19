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
#include "rast/render/fragment_plan.h"
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
    void prepare(const Framebuffer& fb, const DrawRecords& draws, const PrimStore& prims, bool fused, unsigned workers);

    // Linear mode: per 64x64 tile (row-major) whether its bin can be llvmpipe's linear bin (only rectangles
    // touch it), and each rectangle's pixel box. Null pointers: not in linear mode.
    void set_linear(const std::vector<uint8_t>* tile_linear, const std::vector<fragment::LinearRegion>* rect_boxes);

    // The resolves each tile runs after its last primitive (targets.h TileResolve); null: none. Must outlive
    // rasterize().
    void set_tile_resolves(const TileResolves* resolves) { resolves_ = resolves; }

    void begin_tile(unsigned worker, const TileInfo& tile) override;
    void primitive(unsigned worker, const TileInfo& tile, const PrimCoverage& coverage) override;
    bool stop_tile(unsigned worker, uint32_t next_payload) override;
    void end_tile(unsigned worker, const TileInfo& tile) override;
    // Step 0: the primitive record; step 1: the head of its plane record (the first read of every block).
    void prefetch(uint32_t payload, int step) const override;
    // Occlusion (fragment_plan.h scene_may_hide / draw_hides_earlier): a triangle of a draw that hides.
    bool may_hide() const override { return may_hide_; }
    bool hides_earlier(uint32_t payload) const override;

    // Samples of draw record `draw` that passed every per-sample test in the scene last rasterized: the sum of
    // popcount(final mask) per sample plane over all blocks. Counted per (draw, worker), so no two threads share a
    // counter and the sum does not depend on the thread count or on which worker rendered which tile.
    uint64_t samples_passed(uint32_t draw) const;
    // Pipeline statistics (only for draws with DrawRecord::statistics): the calls llvmpipe makes to its 4x4-block
    // fragment function for draw record `draw` in the scene last rasterized, counted as samples_passed is.
    uint64_t shader_blocks(uint32_t draw) const;

    // Fragment-shader runs the loop watchdog cut short so far (shader::Scratch::loop_limit_hits of every worker).
    uint64_t loop_limit_hits() const;
    // The driver's stop flag (Renderer::set_stop_flag): once set, the remaining primitives and blocks of the scene
    // are skipped and shader runs end at their next loop back edge; what was interrupted goes to `interruption`.
    void set_stop_flag(const std::atomic<bool>* stop, Interruption* interruption);

  private:
    // The reference pipeline: every step in full, for every state (TILEVK_FRAG=reference, and what the fast path
    // falls back to).
    void shade_block(FragmentWorker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing, int32_t x,
                     int32_t y, const uint16_t raster_masks[4]);

    // Its fragment-shader runs under sample shading, one per sample (fragment_stage.cpp).
    void shade_samples(FragmentWorker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing, int32_t x,
                       int32_t y, const uint16_t cover[4], const uint16_t pass[4], float (*z)[fragment::kBlockLanes],
                       uint16_t final_mask[4]);

    void resolve_tile(const TileInfo& tile) const;

    Framebuffer fb_;
    const DrawRecords* draws_ = nullptr;
    const PrimStore* prims_ = nullptr;
    bool fused_ = true;
    bool fast_ = true;
    std::vector<DrawPlan> plans_;  // per draw record (fast path)
    std::vector<uint8_t> hides_;   // per draw record: draw_hides_earlier, when may_hide_
    bool may_hide_ = false;
    BlockFn block_fn_ = nullptr;   // the fast path's block function (fragment_plan.h)
    SquareFn square_fn_ = nullptr;  // its fused full-square kernel, or null (fragment_plan.h)
    Uniform4xFn uniform_4x_fn_ = nullptr;  // its per-primitive 4x uniform store, or null (fragment_plan.h)
    const std::vector<uint8_t>* tile_linear_ = nullptr;
    const std::vector<fragment::LinearRegion>* rect_boxes_ = nullptr;
    std::vector<std::unique_ptr<FragmentWorker>> workers_;
    const TileResolves* resolves_ = nullptr;
    const std::atomic<bool>* stop_ = nullptr;
    Interruption* interruption_ = nullptr;
    bool stopped() const { return stop_ != nullptr && stop_->load(std::memory_order_relaxed); }
};

}  // namespace tilevk::rast::render
