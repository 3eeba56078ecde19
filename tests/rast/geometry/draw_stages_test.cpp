// draw's batch segmentation (draw_batches.h). Expectations are worked out by hand from the Mesa rules quoted in the
// comments, independently of the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

#include "rast/geometry/draw_batches.h"

using namespace tilevk::rast::geometry;

namespace {

std::vector<uint32_t> batches(Topology t, bool indexed, uint32_t count) {
    std::vector<uint32_t> out;
    append_run_batches(t, indexed, count, &out);
    return out;
}

TEST(DrawBatches, SmallDrawsAreOneBatch) {
    EXPECT_EQ(batches(Topology::kTriangleList, false, 9), (std::vector<uint32_t>{3}));
    EXPECT_EQ(batches(Topology::kTriangleList, false, 11), (std::vector<uint32_t>{3}));  // trimmed to 9
    EXPECT_EQ(batches(Topology::kTriangleList, false, 2), (std::vector<uint32_t>{}));
    // 4096 vertices: still "no splitting required", fans included
    EXPECT_EQ(batches(Topology::kTriangleFan, false, 4096), (std::vector<uint32_t>{4094}));
    EXPECT_EQ(batches(Topology::kTriangleStrip, false, 4096), (std::vector<uint32_t>{4094}));
    EXPECT_EQ(batches(Topology::kPointList, false, 4096), (std::vector<uint32_t>{4096}));
}

TEST(DrawBatches, NonIndexedListsSplitAt4095Vertices) {
    // seg_max = trim(4096, 3, 3) = 4095 vertices = 1365 triangles; 4104 vertices -> 1365 + 3
    EXPECT_EQ(batches(Topology::kTriangleList, false, 4104), (std::vector<uint32_t>{1365, 3}));
    // lines: trim(4096, 2, 2) = 4096 -> 2048 lines; 5000 vertices = 2500 lines -> 2048 + 452
    EXPECT_EQ(batches(Topology::kLineList, false, 5000), (std::vector<uint32_t>{2048, 452}));
}

TEST(DrawBatches, StripsKeepAnEvenTriangleCountAndOverlapTwoVertices) {
    // seg_max 4096 -> (4096-3) odd, kept: 4094 triangles; next segment starts at vertex 4094: 5000-4094 = 906
    // vertices = 904 triangles
    EXPECT_EQ(batches(Topology::kTriangleStrip, false, 5000), (std::vector<uint32_t>{4094, 904}));
    // indexed: segment 1024 -> 1022 triangles, step 1022
    EXPECT_EQ(batches(Topology::kTriangleStrip, true, 2048), (std::vector<uint32_t>{1022, 1022, 2}));
    // line strip: rollback 1, 4095 lines per 4096-vertex segment
    EXPECT_EQ(batches(Topology::kLineStrip, false, 4100), (std::vector<uint32_t>{4095, 4}));
}

TEST(DrawBatches, LongFansSplitAt1024) {
    // 5000 > 4096: fan segments of 1024 vertices (1022 triangles), 4 of them, then 5000-4088 = 912 -> 910
    EXPECT_EQ(batches(Topology::kTriangleFan, false, 5000), (std::vector<uint32_t>{1022, 1022, 1022, 1022, 910}));
}

TEST(DrawBatches, IndexedListsSplitAt1023Indices) {
    EXPECT_EQ(batches(Topology::kTriangleList, true, 2000), (std::vector<uint32_t>{341, 325}));
    EXPECT_EQ(batches(Topology::kPointList, true, 2049), (std::vector<uint32_t>{1024, 1024, 1}));
}

TEST(DrawBatches, EveryPrimitiveInExactlyOneBatch) {
    for (Topology t : {Topology::kPointList, Topology::kLineList, Topology::kLineStrip, Topology::kTriangleList,
                       Topology::kTriangleStrip, Topology::kTriangleFan})
        for (bool indexed : {false, true})
            for (uint32_t count : {0u, 1u, 3u, 1023u, 1024u, 1025u, 4095u, 4096u, 4097u, 9000u, 20001u}) {
                const auto b = batches(t, indexed, count);
                uint32_t first, incr;
                split_prim(t, &first, &incr);
                const uint32_t prims = count < first ? 0 : (count - first) / incr + 1;
                EXPECT_EQ(std::accumulate(b.begin(), b.end(), 0u), prims)
                    << "topology " << int(t) << " indexed " << indexed << " count " << count;
            }
}

TEST(DrawBatches, RestartRunsAreSeparateDraws) {
    const uint16_t idx[] = {0, 1, 2, 3, 0xFFFF, 4, 5, 6, 0xFFFF, 7, 8};
    IndexSource src;
    src.indices = reinterpret_cast<const uint8_t*>(idx);
    src.index_size = 2;
    src.index_count_total = 11;
    src.count = 11;
    src.primitive_restart = true;
    std::vector<uint32_t> b;
    draw_batches(src, Topology::kTriangleStrip, &b);
    EXPECT_EQ(b, (std::vector<uint32_t>{2, 1}));  // runs of 4, 3, 2 vertices
}

}  // namespace
