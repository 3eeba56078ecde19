// Bad input never crashes: NaN/Inf/huge coordinates, garbage planes and boxes, empty clips and sample masks get a
// status; primitives at the +-16K extremes are rasterized identically by every exact method.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>

#include "grid_consumer.h"

namespace tilevk::rast::test {
namespace {

TriangleInput tri(float x0, float y0, float x1, float y1, float x2, float y2) {
    TriangleInput t;
    t.x[0] = x0, t.y[0] = y0, t.x[1] = x1, t.y[1] = y1, t.x[2] = x2, t.y[2] = y2;
    t.common.clip = {0, 0, 100, 100};
    return t;
}

// Rejected: non-finite or past llvmpipe's 2^31 fixed-point range (8M px), or an edge spanning 32768 px or more
// (|DX| + |DY| >= 2^23, where llvmpipe's 32-bit plane values wrap).
TEST(Robustness, NonFiniteAndHugeTrianglesAreRejected) {
    Scene scene({.width = 100, .height = 100, .samples = 1});
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float bad : {nan, inf, -inf, 1e30f, -1e30f, 8388608.0f, -8388609.0f, 32800.0f, -32800.0f,
                      std::numeric_limits<float>::max()}) {
        for (int v = 0; v < 3; ++v) {
            for (int axis = 0; axis < 2; ++axis) {
                TriangleInput t = tri(1, 1, 50, 2, 3, 60);
                (axis ? t.y : t.x)[v] = bad;
                EXPECT_EQ(scene.add_triangle(t), SetupStatus::kOutOfRange) << bad;
            }
        }
    }
    EXPECT_EQ(scene.stats().prims, 0u);
    ThreadPool pool(1);
    GridConsumer g = render(scene, Method::kHier, pool);
    for (uint32_t c : g.count) ASSERT_EQ(c, 0u);
}

// The wide range: a vertex past 16384 px is set up (as llvmpipe does, up to 2^31 fixed) while every edge stays
// below 32768 px, and rasterized by every exact method identically, also when all three vertices are outside.
TEST(Robustness, WideRangeTrianglesAreRasterizedExactly) {
    for (int samples : {1, 4}) {
        Scene scene({.width = 300, .height = 200, .samples = samples});
        std::mt19937 rng(11 + samples);
        std::uniform_real_distribution<float> far(16384.5f, 24000.0f), near(-500.0f, 800.0f);
        uint32_t accepted = 0;
        for (uint32_t i = 0; i < 300; ++i) {
            const float s = i % 2 ? -1.0f : 1.0f;
            TriangleInput t = i % 4 == 0 ? tri(near(rng), s * far(rng), near(rng), near(rng), near(rng), near(rng))
                                         : tri(s * far(rng), near(rng), near(rng), near(rng), near(rng), near(rng));
            t.common.clip = {0, 0, 300, 200};
            t.common.payload = i;
            accepted += scene.add_triangle(t) == SetupStatus::kAccepted;
        }
        TriangleInput around = tri(-14000.0f, -100.0f, 150.0f, 12000.0f, 9000.0f, -9000.0f);  // all outside
        around.common.clip = {0, 0, 300, 200};
        around.common.payload = 1000;
        EXPECT_EQ(scene.add_triangle(around), SetupStatus::kAccepted);
        EXPECT_GT(accepted, 100u);  // the others miss the framebuffer
        ThreadPool pool(1);
        const GridConsumer ref = render(scene, Method::kReference, pool);
        EXPECT_EQ(render(scene, Method::kHier, pool).diff(ref), "");
        EXPECT_EQ(render(scene, Method::kBBox, pool).diff(ref), "");
        EXPECT_GT(scene.stats().whole_tiles, 0u);
    }
}

TEST(Robustness, EmptyClipAndSampleMask) {
    Scene scene({.width = 100, .height = 100, .samples = 4});
    TriangleInput t = tri(1, 1, 50, 2, 3, 60);
    t.common.clip = {50, 50, 50, 80};
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kClipped);
    t.common.clip = {-1000, -1000, -900, -900};
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kClipped);
    t.common.clip = {0, 0, 100, 100};
    t.common.sample_mask = 0;
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kDegenerate);
    t.common.sample_mask = 0xF0;  // only bits beyond 4 samples
    EXPECT_EQ(scene.add_triangle(t), SetupStatus::kDegenerate);
}

TEST(Robustness, GarbageConvexAndBoxes) {
    Scene scene({.width = 100, .height = 100, .samples = 1});
    ConvexInput cv;
    cv.num_planes = 0;
    EXPECT_EQ(scene.add_convex(cv), SetupStatus::kInvalid);
    cv.num_planes = 5;
    EXPECT_EQ(scene.add_convex(cv), SetupStatus::kInvalid);
    cv.num_planes = 1;
    cv.planes[0] = {0, 1 << 23, 0};
    EXPECT_EQ(scene.add_convex(cv), SetupStatus::kInvalid);
    cv.planes[0] = {int64_t{1} << 50, 1, 0};
    EXPECT_EQ(scene.add_convex(cv), SetupStatus::kInvalid);
    cv.planes[0] = {1, 1, 0};
    cv.min_x = -(1 << 22), cv.max_x = 10;
    EXPECT_EQ(scene.add_convex(cv), SetupStatus::kOutOfRange);
    cv.min_x = 10, cv.max_x = 10;
    EXPECT_EQ(scene.add_convex(cv), SetupStatus::kDegenerate);
    BoxInput b;
    b.x0 = 5, b.x1 = 5, b.y0 = 0, b.y1 = 100;
    EXPECT_EQ(scene.add_box(b), SetupStatus::kDegenerate);
    b.x1 = INT32_MAX;
    EXPECT_EQ(scene.add_box(b), SetupStatus::kOutOfRange);
    b.x0 = INT32_MIN;
    EXPECT_EQ(scene.add_box(b), SetupStatus::kOutOfRange);
}

TEST(Robustness, BadSceneConfigIsClamped) {
    Scene scene({.width = -5, .height = 1 << 30, .samples = 3, .tile_size = 7});
    EXPECT_EQ(scene.config().width, 1);
    EXPECT_EQ(scene.config().height, 16384);
    EXPECT_EQ(scene.config().samples, 4);
    EXPECT_EQ(scene.config().tile_size, 64);
}

// Triangles with vertices at the representable extremes (|x| just below 16384 px) covering a framebuffer at the
// far corner of the range: all exact methods agree, nothing overflows.
TEST(Robustness, ExtremeCoordinatesAgree) {
    for (int samples : {1, 4}) {
        Scene scene({.width = 300, .height = 200, .samples = samples});
        std::mt19937 rng(5 + samples);
        std::uniform_real_distribution<float> u(-16383.9f, 16383.9f);
        for (uint32_t i = 0; i < 300; ++i) {
            TriangleInput t = tri(u(rng), u(rng), u(rng), u(rng), i % 2 ? -16383.9f : 16383.9f, u(rng));
            t.common.clip = {0, 0, 300, 200};
            t.common.payload = i;
            scene.add_triangle(t);
        }
        TriangleInput big = tri(-16383.0f, -16383.0f, 16383.0f, -16383.0f, 0.0f, 16383.0f);
        big.common.clip = {0, 0, 300, 200};
        big.common.payload = 1000;
        EXPECT_EQ(scene.add_triangle(big), SetupStatus::kAccepted);
        ThreadPool pool(1);
        const GridConsumer ref = render(scene, Method::kReference, pool);
        EXPECT_EQ(render(scene, Method::kHier, pool).diff(ref), "");
        EXPECT_EQ(render(scene, Method::kBBox, pool).diff(ref), "");
        EXPECT_GT(scene.stats().whole_tiles, 0u);
    }
}

TEST(Robustness, MethodNames) {
    EXPECT_EQ(parse_method("hier"), Method::kHier);
    EXPECT_EQ(parse_method("reference"), Method::kReference);
    EXPECT_EQ(parse_method("bbox"), Method::kBBox);
    EXPECT_EQ(parse_method("float"), Method::kFloat);
    EXPECT_FALSE(parse_method("Hier").has_value());
    EXPECT_FALSE(parse_method("").has_value());
}

// A consumer that asks to stop (a lost device) ends a tile's walk at the next check: the rest of a huge bin is never
// rasterized, and every begun tile is still ended.
TEST(Robustness, StopTileEndsTheWalkOfEveryTile) {
    struct Stopping : CoverageConsumer {
        std::atomic<uint32_t> prims{0}, begun{0}, ended{0}, asked{0};
        void begin_tile(unsigned, const TileInfo&) override { ++begun; }
        void primitive(unsigned, const TileInfo&, const PrimCoverage&) override { ++prims; }
        void end_tile(unsigned, const TileInfo&) override { ++ended; }
        bool stop_tile(unsigned, uint32_t) override {
            ++asked;
            return true;
        }
    };
    Scene scene({.width = 128, .height = 128, .samples = 1});  // 2x2 tiles
    for (uint32_t i = 0; i < 10000; ++i) {
        TriangleInput t = tri(-10, -10, 400, -10, -10, 400);
        t.common.clip = {0, 0, 128, 128};
        t.common.payload = i;
        ASSERT_EQ(scene.add_triangle(t), SetupStatus::kAccepted);
    }
    for (unsigned threads : {1u, 2u}) {
        ThreadPool pool(threads);
        Stopping c;
        scene.rasterize(c, pool);
        EXPECT_EQ(c.begun.load(), 4u);
        EXPECT_EQ(c.ended.load(), 4u);
        EXPECT_EQ(c.asked.load(), 4u);
        EXPECT_EQ(c.prims.load(), 4u * (CoverageConsumer::kStopCheckInterval - 1));
    }
}

}  // namespace
}  // namespace tilevk::rast::test
