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
#include "rast/core/method.h"
#include "rast/core/primitive.h"

namespace tilevk::rast {

class ThreadPool;
struct Prim;    // set-up primitive (setup.h)
struct BinCmd;  // tile command (setup.h)

struct SceneConfig {
    int32_t width = 0, height = 0;  // framebuffer size in pixels, 1..16384
    int samples = 1;                // 1 or 4
    int tile_size = 64;             // 16, 32 or 64 (the 32-bit in-tile bound is proved for <= 64)
    Method method = Method::kHier;
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

    // Renders every tile that has commands (tiles without commands are still begun/ended only if
    // visit_empty_tiles): consumer calls as documented in coverage.h. Deterministic for any pool size.
    void rasterize(CoverageConsumer& consumer, ThreadPool& pool, bool visit_empty_tiles = false);
    void reset();  // drops all primitives, keeps capacity

    const SceneConfig& config() const { return config_; }
    int32_t tiles_x() const { return tiles_x_; }
    int32_t tiles_y() const { return tiles_y_; }
    const SceneStats& stats() const { return stats_; }
    void set_method(Method m) { config_.method = m; }

  private:
    SetupStatus bin(Prim& prim);

    SceneConfig config_;
    int32_t tiles_x_ = 0, tiles_y_ = 0;
    std::vector<Prim> prims_;
    std::vector<std::vector<BinCmd>> bins_;
    SceneStats stats_;
};

}  // namespace tilevk::rast
