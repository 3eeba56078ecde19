// Output is identical for 1, 2 and 7 threads: the per-tile call digests (payload order, blocks, masks) match.
// TSan: meson setup build-tsan -Db_sanitize=thread && ninja -C build-tsan tests/rast/core/rast_core_threads_test
//       && build-tsan/tests/rast/core/rast_core_threads_test   (see bench/rast/README.md for the recorded run)
#include <gtest/gtest.h>

#include <atomic>
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
