// Scene: setup + binning in API order, then tile-parallel rasterization into the consumer.
#include "rast/core/scene.h"

#include <algorithm>
#include <memory>

#include "rast/core/setup.h"
#include "rast/core/thread_pool.h"
#include "rast/core/tile_raster.h"

namespace tilevk::rast {

Scene::Scene(const SceneConfig& config) : config_(config) {
    config_.width = std::clamp(config_.width, 1, 16384);
    config_.height = std::clamp(config_.height, 1, 16384);
    config_.samples = config_.samples > 1 ? 4 : 1;
    if (config_.tile_size != 16 && config_.tile_size != 32) config_.tile_size = 64;
    tiles_x_ = (config_.width + config_.tile_size - 1) / config_.tile_size;
    tiles_y_ = (config_.height + config_.tile_size - 1) / config_.tile_size;
    bins_.resize(static_cast<size_t>(tiles_x_) * tiles_y_);
}

Scene::~Scene() = default;

void Scene::reset() {
    prims_.clear();
    for (auto& b : bins_) b.clear();
    stats_ = {};
}

SetupStatus Scene::add_triangle(const TriangleInput& tri) {
    Prim p;
    const SetupStatus st = setup_triangle(tri, config_.samples, {0, 0, config_.width, config_.height}, &p);
    return st == SetupStatus::kAccepted ? bin(p) : st;
}

SetupStatus Scene::add_convex(const ConvexInput& in) {
    Prim p;
    const SetupStatus st = setup_convex(in, config_.samples, {0, 0, config_.width, config_.height}, &p);
    return st == SetupStatus::kAccepted ? bin(p) : st;
}

SetupStatus Scene::add_box(const BoxInput& in) {
    Prim p;
    const SetupStatus st = setup_box(in, config_.samples, {0, 0, config_.width, config_.height}, &p);
    return st == SetupStatus::kAccepted ? bin(p) : st;
}

// Small primitives (box within one tile) go to that tile's bin directly; larger ones walk the tiles of their box,
// rejecting tiles outside an edge and turning tiles inside every edge into whole-tile commands (64-bit corner
// tests in tile_setup).
SetupStatus Scene::bin(Prim& prim) {
    const int32_t T = config_.tile_size;
    const int32_t tx0 = prim.x0 / T, tx1 = prim.x1 / T, ty0 = prim.y0 / T, ty1 = prim.y1 / T;
    const auto index = static_cast<uint32_t>(prims_.size());
    bool any = false;
    if (tx0 == tx1 && ty0 == ty1) {
        bins_[static_cast<size_t>(ty0) * tiles_x_ + tx0].push_back({index, kBinPartial});
        any = true;
        ++stats_.bin_cmds;
    } else {
        for (int32_t ty = ty0; ty <= ty1; ++ty) {
            for (int32_t tx = tx0; tx <= tx1; ++tx) {
                int n = 0;
                const TileGeom geom{tx * T, ty * T, T, config_.samples};
                const TileClass cls = tile_setup(prim, geom, nullptr, &n);
                if (cls == TileClass::kReject) continue;
                // A whole tile must also lie inside the framebuffer (box planes guarantee it, see setup.cpp).
                const bool whole = cls == TileClass::kWhole;
                bins_[static_cast<size_t>(ty) * tiles_x_ + tx].push_back({index, whole ? kBinWholeTile : kBinPartial});
                any = true;
                ++stats_.bin_cmds;
                stats_.whole_tiles += whole;
            }
        }
    }
    if (!any) return SetupStatus::kClipped;
    prims_.push_back(prim);
    ++stats_.prims;
    return SetupStatus::kAccepted;
}

void Scene::rasterize(CoverageConsumer& consumer, ThreadPool& pool, bool visit_empty_tiles) {
    std::vector<uint32_t> tiles;
    tiles.reserve(bins_.size());
    for (uint32_t i = 0; i < bins_.size(); ++i)
        if (visit_empty_tiles || !bins_[i].empty()) tiles.push_back(i);
    std::vector<std::unique_ptr<TileScratch>> scratch(pool.num_workers());
    for (auto& p : scratch) p = std::make_unique<TileScratch>();
    const Method method = config_.method;
    const int32_t T = config_.tile_size;
    pool.run(tiles.size(), [&](unsigned worker, size_t task) {
        const uint32_t index = tiles[task];
        const int32_t tx = static_cast<int32_t>(index % tiles_x_), ty = static_cast<int32_t>(index / tiles_x_);
        TileInfo info{index, tx * T, ty * T, std::min(T, config_.width - tx * T), std::min(T, config_.height - ty * T)};
        const TileGeom geom{tx * T, ty * T, T, config_.samples};
        TileScratch& s = *scratch[worker];
        consumer.begin_tile(worker, info);
        const std::vector<BinCmd>& bin = bins_[index];
        for (size_t i = 0; i < bin.size(); ++i) {
            const BinCmd& cmd = bin[i];
            // Primitives are read in API order with gaps: fetch the hot lines of one two commands ahead.
            if (i + 2 < bin.size()) {
                const char* next = reinterpret_cast<const char*>(&prims_[bin[i + 2].prim]);
                __builtin_prefetch(next);
                __builtin_prefetch(next + 64);
                __builtin_prefetch(next + 128);
            }
            const Prim& prim = prims_[cmd.prim];
            raster_prim_in_tile(method, prim, geom, cmd.flags & kBinWholeTile, &s);
            if (s.num_blocks == 0 && s.num_full == 0 && s.num_blocks16 == 0) continue;
            PrimCoverage cov;
            cov.payload = prim.payload;
            cov.sample_mask = prim.sample_mask;
            cov.front_facing = prim.front_facing;
            cov.blocks = s.blocks;
            cov.num_blocks = s.num_blocks;
            cov.full = s.full;
            cov.num_full = s.num_full;
            cov.blocks16 = s.blocks16;
            cov.num_blocks16 = s.num_blocks16;
            consumer.primitive(worker, info, cov);
        }
        consumer.end_tile(worker, info);
    });
}

}  // namespace tilevk::rast
