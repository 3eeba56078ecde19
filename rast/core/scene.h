// The scene: primitives set up and binned into tiles in API order, then rasterized tile-parallel into a consumer.
//
//   Scene scene({.width = w, .height = h, .samples = 4});
//   scene.add_triangle(tri);           // snap, cull, setup, bin (returns a SetupStatus)
//   scene.rasterize(consumer, pool);   // per tile, in API order, coverage -> consumer
//   scene.reset();                     // reuse the memory for the next scene
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/core/huge_page_allocator.h"
#include "rast/core/method.h"
#include "rast/core/primitive.h"

namespace tilevk::rast {

class ThreadPool;
struct Prim;         // set-up primitive (setup.h)
struct PrimEdges;    // its 64-bit planes (setup.h)
struct BinCmd;       // tile command (setup.h)
struct TileScratch;  // coverage lists of one worker (tile_raster.h)

struct SceneConfig {
    int32_t width = 0, height = 0;  // framebuffer size in pixels, 1..16384
    int samples = 1;                // 1 or 4
    int tile_size = 64;             // 16, 32 or 64 (the 32-bit in-tile bound is proved for <= 64)
    Method method = Method::kHier;
    // Keep each primitive's PrimEdges (64-bit planes, float coordinates: setup.h) so that set_method may switch to
    // the reference or float method, which read them. A user whose method stays hier or bbox (the renderer) turns it
    // off: setup then writes about half the memory per primitive. Always on when `method` reads them.
    bool keep_edges = true;
};

struct SceneStats {
    uint64_t prims = 0, bin_cmds = 0, whole_tiles = 0;
};

class Scene {
  public:
    explicit Scene(const SceneConfig& config);  // invalid sizes are clamped to [1,16384], samples to {1,4}
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    SetupStatus add_triangle(const TriangleInput& tri);
    SetupStatus add_convex(const ConvexInput& prim);
    SetupStatus add_box(const BoxInput& box);

    // Many triangles at once, set up on several threads and binned by several threads, with the same bins (the
    // same API order) as add_triangle one after the other:
    //   first = reserve(n);                          // slots first .. first+n-1, in API order
    //   setup_triangle_at(first + i, tri_i, &ccw);   // any thread, each slot once (or never: dropped)
    //   bin_reserved(first, n, pool);                // bins the accepted slots; tile bands run on the pool
    // A primitive that add_triangle would reject after setup because every tile of its box rejects it (a thin
    // triangle across tile corners) is kept here and rasterizes to nothing. No add_* call may come between
    // reserve and bin_reserved.
    uint32_t reserve(uint32_t n);
    // Sets up slot `slot` (thread-safe for distinct slots). `ccw`: the snapped orientation (area > 0) when accepted.
    SetupStatus setup_triangle_at(uint32_t slot, const TriangleInput& tri, bool* ccw);
    void bin_reserved(uint32_t first, uint32_t n, ThreadPool& pool);

    // Renders every tile that has commands (tiles without commands are still begun/ended only if
    // visit_empty_tiles): consumer calls as documented in coverage.h. Deterministic for any pool size.
    void rasterize(CoverageConsumer& consumer, ThreadPool& pool, bool visit_empty_tiles = false);
    void reset();  // drops all primitives, keeps capacity

    const SceneConfig& config() const { return config_; }
    int32_t tiles_x() const { return tiles_x_; }
    int32_t tiles_y() const { return tiles_y_; }
    const SceneStats& stats() const { return stats_; }
    // The reference and float methods evaluate the 64-bit planes, hier and bbox only the pixel planes.
    static bool reads_edges(Method m) { return m == Method::kReference || m == Method::kFloat; }
    // A scene made with keep_edges off stays with a method that does not read them (an invalid switch is ignored).
    void set_method(Method m) {
        if (config_.keep_edges || !reads_edges(m)) config_.method = m;
    }

  private:
    SetupStatus bin(const Prim& prim, const PrimEdges& edges);
    bool keep_edges() const { return config_.keep_edges; }
    // The tiles of a primitive's pixel box (inclusive) and its payload: all that binning a primitive within one
    // tile needs, so bin_reserved's bands, which walk every slot, read 12 bytes per slot instead of the primitive
    // (a cache miss each).
    struct TileBox {
        uint16_t tx0, ty0, tx1, ty1;
        uint32_t payload;
    };
    TileBox tile_box(const Prim& prim) const;
    static size_t first_visible(const std::vector<BinCmd>& bin, const CoverageConsumer& consumer, bool hide);
    // Appends the bin commands of prim `index` (tiles `box`) whose tiles lie in rows [ty_begin, ty_end); counts them.
    bool bin_rows(uint32_t index, const TileBox& box, int32_t ty_begin, int32_t ty_end, SceneStats* stats);

    SceneConfig config_;
    int32_t tiles_x_ = 0, tiles_y_ = 0;
    // prims_[0, num_prims_) are the scene's primitives; the vector never shrinks, so a steady frame reuses it.
    std::vector<Prim, HugePageAllocator<Prim>> prims_;
    std::vector<PrimEdges> edges_;  // per primitive (as prims_) when keep_edges(), else empty
    uint32_t num_prims_ = 0;
    std::vector<TileBox> reserved_boxes_;  // per reserved slot: its tiles once set up and accepted
    std::vector<std::vector<BinCmd>> bins_;
    SceneStats stats_;
    // Reused from scene to scene (a steady frame allocates nothing): per tile band of bin_reserved and its slots
    // per chunk, the tiles to render, per-worker coverage scratch.
    std::vector<SceneStats> band_stats_;
    std::vector<std::vector<uint32_t>> band_slots_;  // [chunk * bands + band]: the chunk's slots in the band's rows
    std::vector<uint32_t> chunk_accepted_;           // per chunk of bin_reserved: its accepted slots
    std::vector<uint32_t> tiles_to_render_;
    std::vector<std::unique_ptr<TileScratch>> scratch_;
};

}  // namespace tilevk::rast
