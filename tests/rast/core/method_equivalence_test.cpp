// hier and bbox must equal the 64-bit brute-force reference sample for sample (and API order per tile) on
// >= 1,000,000 seeded random triangles per run, split across the kinds below at 1x and 4x.
#include <gtest/gtest.h>

#include "grid_consumer.h"
#include "random_tris.h"

namespace tilevk::rast::test {
namespace {

struct Case {
    TriKind kind;
    const char* name;
    int count;  // triangles per sample count
    int w, h;
};

const Case kCases[] = {
    {TriKind::kTiny, "tiny", 230000, 250, 190},    {TriKind::kSliver, "sliver", 100000, 250, 190},
    {TriKind::kExact, "exact", 100000, 250, 190},  {TriKind::kTileBorder, "tile_border", 20000, 250, 190},
    {TriKind::kMedium, "medium", 30000, 250, 190}, {TriKind::kDegenerate, "degenerate", 20000, 250, 190},
    {TriKind::kHuge, "huge", 5000, 130, 100},      {TriKind::kExtreme, "extreme", 5000, 130, 100},
};

class MethodEquivalence : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(MethodEquivalence, HierAndBBoxEqualReference) {
    const Case& c = kCases[std::get<0>(GetParam())];
    const int samples = std::get<1>(GetParam());
    TriGen gen(0x7113 + 977 * std::get<0>(GetParam()) + samples, c.w, c.h);
    ThreadPool pool(1);
    constexpr int kBatch = 2000;
    uint64_t accepted = 0;
    for (int first = 0; first < c.count; first += kBatch) {
        Scene scene({.width = c.w, .height = c.h, .samples = samples});
        for (int i = first; i < std::min(c.count, first + kBatch); ++i)
            accepted += scene.add_triangle(gen.make(c.kind, uint32_t(i))) == SetupStatus::kAccepted;
        const GridConsumer ref = render(scene, Method::kReference, pool);
        const GridConsumer hier = render(scene, Method::kHier, pool);
        const GridConsumer bbox = render(scene, Method::kBBox, pool);
        ASSERT_TRUE(ref.all_ok());
        ASSERT_TRUE(hier.all_ok()) << "order/bounds, batch at " << first;
        ASSERT_TRUE(bbox.all_ok()) << "order/bounds, batch at " << first;
        ASSERT_EQ(hier.diff(ref), "") << c.name << " batch at " << first;
        ASSERT_EQ(bbox.diff(ref), "") << c.name << " batch at " << first;
    }
    // The generator must actually exercise coverage (guards against a test that silently bins nothing).
    if (c.kind != TriKind::kExtreme && c.kind != TriKind::kDegenerate) {
        EXPECT_GT(accepted, uint64_t(c.count) / 4);
    }
    EXPECT_GT(accepted, 0u);
}

INSTANTIATE_TEST_SUITE_P(All, MethodEquivalence,
                         ::testing::Combine(::testing::Range(0, int(std::size(kCases))), ::testing::Values(1, 4)),
                         [](const auto& info) {
                             return std::string(kCases[std::get<0>(info.param)].name) + "_" +
                                    std::to_string(std::get<1>(info.param)) + "x";
                         });

// Smaller tiles use the same descent with fewer 16-px lanes; they must agree too.
TEST(MethodEquivalence, TileSizes16And32) {
    for (int tile : {16, 32}) {
        for (int samples : {1, 4}) {
            TriGen gen(99 + tile + samples, 200, 150);
            ThreadPool pool(1);
            Scene scene({.width = 200, .height = 150, .samples = samples, .tile_size = tile});
            for (int i = 0; i < 4000; ++i) scene.add_triangle(gen.make(static_cast<TriKind>(i % 8), uint32_t(i)));
            const GridConsumer ref = render(scene, Method::kReference, pool);
            EXPECT_EQ(render(scene, Method::kHier, pool).diff(ref), "") << tile << " " << samples;
            EXPECT_EQ(render(scene, Method::kBBox, pool).diff(ref), "") << tile << " " << samples;
        }
    }
}

}  // namespace
}  // namespace tilevk::rast::test
