// Output is identical for 1, 2 and 7 threads: the per-tile call digests (payload order, blocks, masks) match.
// TSan: meson setup build-tsan -Db_sanitize=thread && ninja -C build-tsan tests/rast/core/rast_core_threads_test
//       && build-tsan/tests/rast/core/rast_core_threads_test   (see bench/rast/README.md for the recorded run)
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdlib>

#include "grid_consumer.h"
#include "random_tris.h"

namespace tilevk::rast::test {
namespace {

TEST(Threads, IdenticalOutputFor1_2_7Threads) {
    for (int samples : {1, 4}) {
        for (Method m : {Method::kHier, Method::kBBox}) {
            TriGen gen(31 + samples, 400, 300);
            Scene scene({.width = 400, .height = 300, .samples = samples, .method = m});
            for (uint32_t i = 0; i < 3000; ++i) scene.add_triangle(gen.make(static_cast<TriKind>(i % 8), i));
            std::vector<uint64_t> digest1;
            for (unsigned threads : {1u, 2u, 7u}) {
                ThreadPool pool(threads);
                EXPECT_EQ(pool.num_workers(), threads);
                GridConsumer g = render(scene, m, pool);
                EXPECT_TRUE(g.all_ok());
                if (threads == 1)
                    digest1 = g.digest;
                else
                    EXPECT_EQ(g.digest, digest1) << threads << " threads";
            }
        }
    }
}

// The tile loop's prefetch hints (CoverageConsumer::prefetch) name the tile's own primitives by payload, in API
// order, ahead of their primitive() calls: step 0 before every call, step 1 before all but a tile's first few
// (kDataAhead in scene.cpp). The payloads differ from the scene's primitive indices, so hinting an index fails.
TEST(Threads, PrefetchHintsNameEachTilesPrimitivesAhead) {
    struct Hints final : CoverageConsumer {
        struct Tile {
            std::vector<uint32_t> step[2];
            size_t calls = 0, late = 0;  // primitive() calls; those without a step-1 hint before them
            bool ok = true;
        };
        std::vector<Tile> tiles;
        Tile* current = nullptr;  // one worker: hints come from the tile begun last
        explicit Hints(size_t n) : tiles(n) {}
        static bool has(const std::vector<uint32_t>& v, uint32_t p) {
            return std::find(v.begin(), v.end(), p) != v.end();
        }
        void begin_tile(unsigned, const TileInfo& t) override { current = &tiles[t.index]; }
        void end_tile(unsigned, const TileInfo&) override { current = nullptr; }
        void primitive(unsigned, const TileInfo& t, const PrimCoverage& c) override {
            Tile& tile = tiles[t.index];
            tile.ok = tile.ok && &tile == current && has(tile.step[0], c.payload);
            ++tile.calls;
            tile.late += !has(tile.step[1], c.payload);
        }
        void prefetch(uint32_t payload, int step) const override {
            ASSERT_TRUE(current != nullptr && (step == 0 || step == 1));
            std::vector<uint32_t>& v = current->step[step];
            // API order within each step; a step-1 hint follows the same payload's step-0 hint.
            current->ok =
                current->ok && (v.empty() || v.back() < payload) && (step == 0 || has(current->step[0], payload));
            v.push_back(payload);
        }
    };
    TriGen gen(77, 300, 200);
    Scene scene({.width = 300, .height = 200, .samples = 1});
    for (uint32_t i = 0; i < 4000; ++i)
        scene.add_triangle(gen.make(i % 2 ? TriKind::kTiny : TriKind::kMedium, 10 + 3 * i));
    ThreadPool pool(1);
    Hints h(size_t(scene.tiles_x()) * scene.tiles_y());
    scene.rasterize(h, pool);
    size_t calls = 0, late = 0;
    for (const Hints::Tile& t : h.tiles) {
        EXPECT_TRUE(t.ok);
        EXPECT_LE(t.late, 3u);
        calls += t.calls;
        late += t.late;
    }
    EXPECT_GT(calls, 2000u);
    EXPECT_LT(late, calls / 10);
}

// Occlusion (CoverageConsumer::hides_earlier): a tile's walk starts at its last whole-tile command whose payload
// hides, and is otherwise the full walk. The expectation comes from a walk without hiding (which commands covered
// the whole tile), the walk with hiding must be exactly its suffix, at any thread count; the float method, whose
// coverage is not the planes', never hides.
TEST(Threads, TileWalkStartsAtTheLastHidingWholeTileCommand) {
    struct Walks final : CoverageConsumer {
        struct Call {
            uint32_t payload;
            bool whole;
            bool operator==(const Call&) const = default;
        };
        std::vector<std::vector<Call>> tiles;
        bool hide = false;
        int tile_size = 64;
        explicit Walks(size_t n) : tiles(n) {}
        static bool hider(uint32_t payload) { return payload % 3 == 0; }
        void begin_tile(unsigned, const TileInfo& t) override { tiles[t.index].clear(); }
        void end_tile(unsigned, const TileInfo&) override {}
        void primitive(unsigned, const TileInfo& t, const PrimCoverage& c) override {
            // every pixel of the tile covered, however the method reports it
            int pixels = 0;
            for (size_t i = 0; i < c.num_full; ++i) pixels += c.full[i].size * c.full[i].size;
            for (size_t i = 0; i < c.num_blocks; ++i) pixels += std::popcount(c.blocks[i].mask[0]);
            for (size_t i = 0; i < c.num_blocks16; ++i)
                for (const uint16_t m : c.blocks16[i].mask) pixels += std::popcount(m);
            tiles[t.index].push_back({c.payload, pixels == tile_size * tile_size});
        }
        bool may_hide() const override { return hide; }
        bool hides_earlier(uint32_t payload) const override { return hider(payload); }
    };
    TriGen gen(5, 300, 200);
    Scene scene({.width = 300, .height = 200, .samples = 1});
    for (uint32_t i = 0; i < 600; ++i) {
        const TriKind kind = i % 7 == 0 ? TriKind::kHuge : (i % 2 ? TriKind::kTiny : TriKind::kMedium);
        scene.add_triangle(gen.make(kind, 1000 + i));
    }
    const size_t n = size_t(scene.tiles_x()) * scene.tiles_y();
    for (const Method m : {Method::kHier, Method::kBBox, Method::kReference, Method::kFloat}) {
        scene.set_method(m);
        ThreadPool one(1);
        Walks full(n);
        scene.rasterize(full, one);
        size_t hidden = 0;
        for (unsigned threads : {1u, 2u}) {
            ThreadPool pool(threads);
            Walks cut(n);
            cut.hide = true;
            scene.rasterize(cut, pool);
            for (size_t t = 0; t < n; ++t) {
                const std::vector<Walks::Call>& all = full.tiles[t];
                size_t start = 0;
                for (size_t k = all.size(); m != Method::kFloat && k-- > 1;)
                    if (all[k].whole && Walks::hider(all[k].payload)) {
                        start = k;
                        break;
                    }
                hidden += start;
                EXPECT_EQ(cut.tiles[t], std::vector<Walks::Call>(all.begin() + long(start), all.end()))
                    << "tile " << t << ", method " << int(m) << ", " << threads << " threads";
            }
        }
        if (m != Method::kFloat) {
            EXPECT_GT(hidden, 50u) << int(m);  // the scene does exercise hiding
        }
    }
}

TEST(Threads, PoolRunsEveryTaskOnceAndIsReusable) {
    ThreadPool pool(4);
    for (int round = 0; round < 50; ++round) {
        std::vector<std::atomic<int>> hits(97 + round);
        pool.run(hits.size(), [&](unsigned worker, size_t task) {
            ASSERT_LT(worker, pool.num_workers());
            hits[task].fetch_add(1);
        });
        for (auto& h : hits) ASSERT_EQ(h.load(), 1);
    }
    ThreadPool single(0);
    EXPECT_EQ(single.num_workers(), 1u);
    int count = 0;
    single.run(10, [&](unsigned w, size_t) { count += w == 0; });
    EXPECT_EQ(count, 10);
}

TEST(Threads, EnvParsing) {
    setenv("TILEVK_THREADS", "3", 1);
    EXPECT_EQ(ThreadPool::threads_from_env(), 3u);
    setenv("TILEVK_THREADS", "0", 1);
    EXPECT_EQ(ThreadPool::threads_from_env(), 0u);
    setenv("TILEVK_THREADS", "junk", 1);
    EXPECT_GE(ThreadPool::threads_from_env(), 1u);
    unsetenv("TILEVK_THREADS");
    setenv("TILEVK_RAST", "bbox", 1);
    EXPECT_EQ(method_from_env(), Method::kBBox);
    setenv("TILEVK_RAST", "nonsense", 1);
    EXPECT_EQ(method_from_env(), Method::kHier);
    unsetenv("TILEVK_RAST");
    EXPECT_EQ(method_from_env(), Method::kHier);
}

}  // namespace
}  // namespace tilevk::rast::test
