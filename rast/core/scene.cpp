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
    config_.keep_edges = config_.keep_edges || reads_edges(config_.method);
    tiles_x_ = (config_.width + config_.tile_size - 1) / config_.tile_size;
    tiles_y_ = (config_.height + config_.tile_size - 1) / config_.tile_size;
    bins_.resize(static_cast<size_t>(tiles_x_) * tiles_y_);
}

Scene::~Scene() = default;

void Scene::reset() {
    num_prims_ = 0;
    for (auto& b : bins_) b.clear();
    stats_ = {};
}

SetupStatus Scene::add_triangle(const TriangleInput& tri) {
    Prim p;
    PrimEdges e;
    const SetupStatus st = setup_triangle(tri, config_.samples, {0, 0, config_.width, config_.height}, &p, &e);
    return st == SetupStatus::kAccepted ? bin(p, e) : st;
}

SetupStatus Scene::add_convex(const ConvexInput& in) {
    Prim p;
    PrimEdges e;
    const SetupStatus st = setup_convex(in, config_.samples, {0, 0, config_.width, config_.height}, &p, &e);
    return st == SetupStatus::kAccepted ? bin(p, e) : st;
}

SetupStatus Scene::add_box(const BoxInput& in) {
    Prim p;
    PrimEdges e;
    const SetupStatus st = setup_box(in, config_.samples, {0, 0, config_.width, config_.height}, &p, &e);
    return st == SetupStatus::kAccepted ? bin(p, e) : st;
}

Scene::TileBox Scene::tile_box(const Prim& prim) const {
    const int32_t T = config_.tile_size;  // the box lies in the framebuffer: tile indices below 1024
    return {uint16_t(prim.x0 / T), uint16_t(prim.y0 / T), uint16_t(prim.x1 / T), uint16_t(prim.y1 / T), prim.payload};
}

// Small primitives (box within one tile) go to that tile's bin directly, from the box alone; larger ones walk the
// tiles of their box, rejecting tiles outside an edge and turning tiles inside every edge into whole-tile commands
// (64-bit corner tests in tile_setup).
bool Scene::bin_rows(uint32_t index, const TileBox& box, int32_t ty_begin, int32_t ty_end, SceneStats* stats) {
    const int32_t T = config_.tile_size;
    const int32_t tx0 = box.tx0, tx1 = box.tx1;
    const int32_t ty0 = std::max<int32_t>(box.ty0, ty_begin), ty1 = std::min<int32_t>(box.ty1, ty_end - 1);
    bool any = false;
    if (tx0 == tx1 && box.ty0 == box.ty1) {
        if (ty0 > ty1) return false;
        bins_[static_cast<size_t>(ty0) * tiles_x_ + tx0].push_back({index, 0, box.payload});
        ++stats->bin_cmds;
        return true;
    }
    const Prim& prim = prims_[index];
    for (int32_t ty = ty0; ty <= ty1; ++ty) {
        for (int32_t tx = tx0; tx <= tx1; ++tx) {
            int n = 0;
            const TileGeom geom{tx * T, ty * T, T, config_.samples};
            const TileClass cls = tile_setup(prim, geom, nullptr, &n);
            if (cls == TileClass::kReject) continue;
            // A whole tile must also lie inside the framebuffer (box planes guarantee it, see setup.cpp).
            const bool whole = cls == TileClass::kWhole;
            bins_[static_cast<size_t>(ty) * tiles_x_ + tx].push_back({index, whole ? 1u : 0u, box.payload});
            any = true;
            ++stats->bin_cmds;
            stats->whole_tiles += whole;
        }
    }
    return any;
}

SetupStatus Scene::bin(const Prim& prim, const PrimEdges& edges) {
    if (num_prims_ == prims_.size()) prims_.emplace_back();
    prims_[num_prims_] = prim;
    if (keep_edges()) {
        if (num_prims_ >= edges_.size()) edges_.resize(size_t(num_prims_) + 1);
        edges_[num_prims_] = edges;
    }
    if (!bin_rows(num_prims_, tile_box(prim), 0, tiles_y_, &stats_)) return SetupStatus::kClipped;
    ++num_prims_;
    ++stats_.prims;
    return SetupStatus::kAccepted;
}

uint32_t Scene::reserve(uint32_t n) {
    const uint32_t first = num_prims_;
    if (prims_.size() < size_t(first) + n) prims_.resize(size_t(first) + n);
    if (keep_edges() && edges_.size() < size_t(first) + n) edges_.resize(size_t(first) + n);
    reserved_boxes_.assign(n, {0, 1, 0, 0, 0});  // rows 1..0: not accepted
    num_prims_ += n;
    return first;
}

SetupStatus Scene::setup_triangle_at(uint32_t slot, const TriangleInput& tri, bool* ccw) {
    // Not cleared first: setup writes every field a binned primitive's readers use (the header, and the pixel planes
    // up to num_planes, d only at 4x; add_triangle's Prim leaves pix[] beyond them undefined too). A 1x triangle
    // then writes 2 of the Prim's 4 cache lines: the store is a large part of a small triangle's memory traffic.
    // The edges go to a local unless the method reads them.
    Prim& p = prims_[slot];
    PrimEdges local;
    PrimEdges* e = keep_edges() ? &edges_[slot] : &local;
    const SetupStatus st = setup_triangle(tri, config_.samples, {0, 0, config_.width, config_.height}, &p, e);
    if (st != SetupStatus::kAccepted) return st;
    reserved_boxes_[slot - (num_prims_ - reserved_boxes_.size())] = tile_box(p);
    *ccw = p.front_facing == tri.front_ccw;  // setup's front = (ccw == front_ccw)
    return st;
}

void Scene::bin_reserved(uint32_t first, uint32_t n, ThreadPool& pool) {
    // Bands of tile rows, each binned by one task into its rows only, so every bin gets its commands in API order
    // whatever the number of tasks or threads. First the slots are sorted into bands, chunk by chunk (a slot in
    // the rows of several bands goes to each), so a band task visits its own slots only: walking every slot in
    // every band cost O(bands x slots).
    const int32_t rows_per_band =
        pool.num_workers() == 1 ? tiles_y_ : std::max<int32_t>(1, tiles_y_ / int32_t(4 * pool.num_workers()));
    const size_t bands = size_t((tiles_y_ + rows_per_band - 1) / rows_per_band);
    constexpr uint32_t kChunk = 4096;
    const size_t chunks = (size_t(n) + kChunk - 1) / kChunk;
    if (band_slots_.size() < chunks * bands) band_slots_.resize(chunks * bands);  // never shrinks: reused
    chunk_accepted_.assign(chunks, 0);
    pool.run(chunks, [&](unsigned, size_t chunk) {
        std::vector<uint32_t>* lists = band_slots_.data() + chunk * bands;
        for (size_t b = 0; b < bands; ++b) lists[b].clear();
        const uint32_t end = std::min<uint32_t>(n, uint32_t(chunk) * kChunk + kChunk);
        uint32_t accepted = 0;
        for (uint32_t i = uint32_t(chunk) * kChunk; i < end; ++i) {
            const TileBox& b = reserved_boxes_[i];  // an empty row range for a slot not accepted
            if (b.ty0 > b.ty1) continue;
            ++accepted;
            for (int32_t band = b.ty0 / rows_per_band; band <= b.ty1 / rows_per_band; ++band) lists[band].push_back(i);
        }
        chunk_accepted_[chunk] = accepted;
    });
    band_stats_.assign(bands, SceneStats{});
    pool.run(bands, [&](unsigned, size_t band) {
        const int32_t ty_begin = int32_t(band) * rows_per_band, ty_end = std::min(tiles_y_, ty_begin + rows_per_band);
        // Counted on the stack and stored once: the bands' totals are neighbours in band_stats_, and a counter
        // bumped per command there would bounce its cache line between the threads.
        SceneStats local;
        for (size_t chunk = 0; chunk < chunks; ++chunk)  // chunks in order: API order within the band
            for (const uint32_t i : band_slots_[chunk * bands + band])
                bin_rows(first + i, reserved_boxes_[i], ty_begin, ty_end, &local);
        band_stats_[band] = local;
    });
    for (const SceneStats& b : band_stats_) {
        stats_.bin_cmds += b.bin_cmds;
        stats_.whole_tiles += b.whole_tiles;
    }
    for (const uint32_t a : chunk_accepted_) stats_.prims += a;
}

// Where a tile's walk starts: at its last whole-tile command whose primitive hides everything before it
// (CoverageConsumer::hides_earlier), else at 0. Only the commands' whole-tile bits are read until one is found.
size_t Scene::first_visible(const std::vector<BinCmd>& bin, const CoverageConsumer& consumer, bool hide) {
    if (!hide) return 0;
    for (size_t k = bin.size(); k-- > 1;)
        if (bin[k].whole_tile && consumer.hides_earlier(bin[k].payload)) return k;
    return 0;
}

void Scene::rasterize(CoverageConsumer& consumer, ThreadPool& pool, bool visit_empty_tiles) {
    std::vector<uint32_t>& tiles = tiles_to_render_;
    tiles.clear();
    for (uint32_t i = 0; i < bins_.size(); ++i)
        if (visit_empty_tiles || !bins_[i].empty()) tiles.push_back(i);
    while (scratch_.size() < pool.num_workers()) scratch_.push_back(std::make_unique<TileScratch>());
    const std::vector<std::unique_ptr<TileScratch>>& scratch = scratch_;
    const Method method = config_.method;
    const int32_t T = config_.tile_size;
    // The float method's coverage is not the planes' (it is the naive baseline): a whole-tile command need not
    // cover its tile there, so nothing is hidden.
    const bool hide = method != Method::kFloat && consumer.may_hide();
    pool.run(tiles.size(), [&](unsigned worker, size_t task) {
        const uint32_t index = tiles[task];
        const int32_t tx = static_cast<int32_t>(index % tiles_x_), ty = static_cast<int32_t>(index / tiles_x_);
        TileInfo info{index, tx * T, ty * T, std::min(T, config_.width - tx * T), std::min(T, config_.height - ty * T)};
        const TileGeom geom{tx * T, ty * T, T, config_.samples};
        TileScratch& s = *scratch[worker];
        consumer.begin_tile(worker, info);
        const std::vector<BinCmd>& bin = bins_[index];
        const size_t start = first_visible(bin, consumer, hide);
        // Primitives are read in API order with gaps, each a cache miss of its own, and so are the consumer's
        // records they lead to: the hot lines of a primitive and the consumer's record are fetched kAhead
        // commands ahead, what that record points to kDataAhead commands ahead (the record has arrived by then).
        // The hot lines: the header and the first pixel planes (a 1x triangle's all), at 4x also the offsets.
        constexpr size_t kAhead = 6, kDataAhead = 3;
        const int hot_lines = config_.samples == 1 ? 2 : 4;
        auto fetch = [&](size_t k) {
            const char* p = reinterpret_cast<const char*>(&prims_[bin[k].prim]);
            for (int l = 0; l < hot_lines; ++l) __builtin_prefetch(p + 64 * l);
            consumer.prefetch(bin[k].payload, 0);
        };
        for (size_t k = start; k < std::min(start + kAhead, bin.size()); ++k) fetch(k);
        for (size_t i = start; i < bin.size(); ++i) {
            const BinCmd& cmd = bin[i];
            if ((i - start) % CoverageConsumer::kStopCheckInterval == CoverageConsumer::kStopCheckInterval - 1 &&
                consumer.stop_tile(worker, cmd.payload))
                break;
            if (i + kAhead < bin.size()) fetch(i + kAhead);
            if (i + kDataAhead < bin.size()) consumer.prefetch(bin[i + kDataAhead].payload, 1);
            const Prim& prim = prims_[cmd.prim];
            raster_prim_in_tile(method, prim, keep_edges() ? &edges_[cmd.prim] : nullptr, geom, cmd.whole_tile, &s);
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
