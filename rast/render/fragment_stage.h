// The fragment stage: the coverage consumer that turns each covered 4x4 block into pixels — interpolation,
// fragment shader, depth/stencil, alpha to coverage, blending and writes — for one tile at a time.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/render/scene_records.h"
#include "rast/render/targets.h"

namespace tilevk::rast::render {

class FragmentStage final : public CoverageConsumer {
  public:
    FragmentStage();
    ~FragmentStage() override;

    // Points the stage at the scene about to be rasterized (the references must outlive rasterize()).
    void prepare(const Framebuffer& fb, const std::deque<DrawRecord>& draws, const std::vector<PrimRecord>& prims,
                 const std::vector<float>& planes, bool fused, unsigned workers);

    void begin_tile(unsigned worker, const TileInfo& tile) override;
    void primitive(unsigned worker, const TileInfo& tile, const PrimCoverage& coverage) override;
    void end_tile(unsigned worker, const TileInfo& tile) override;

  private:
    struct Worker;
    void shade_block(Worker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing, int32_t x, int32_t y,
                     const uint16_t raster_masks[4]);
    void clear_block(const ClearRecord& clear, int32_t x, int32_t y, const uint16_t raster_masks[4]);

    Framebuffer fb_;
    const std::deque<DrawRecord>* draws_ = nullptr;
    const std::vector<PrimRecord>* prims_ = nullptr;
    const std::vector<float>* planes_ = nullptr;
    bool fused_ = true;
    std::vector<std::unique_ptr<Worker>> workers_;
};

}  // namespace tilevk::rast::render
