// query.pipeline_statistics.*: pipeline-statistics queries around the draws (Scene::statistics, render.cpp): the
// results (64-bit values in bit order + availability) are copied with vkCmdCopyQueryPoolResults and read back as
// the plane "queries", judged byte for byte against lavapipe. Where the spec fixes a count (input-assembly
// vertices and primitives of whole primitives, vertex shader invocations of non-indexed draws, clipping
// invocations = primitives reaching the clipper, 0 for stages that do not exist) a check demands it on both
// devices too. Counts lavapipe derives from its draw module's internals (vsplit's index cache and segments, its
// clipping-invocation reset at discarding draws) are stated as lavapipe's rules (docs/lavapipe-rules.md
// "Pipeline statistics") and checked the same way, so a driver agreeing with a wrong reference still fails.
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kW = 32, kH = 32;

constexpr VkQueryPipelineStatisticFlags kAll = 0x7FF;  // every counter
constexpr uint64_t kAny = ~uint64_t(0);                // a count judged against lavapipe only

// Expected counts of one query, by counter (index = bit position). Clipping primitives: the primitives reaching
// llvmpipe's setup (after draw's clipper and float cull, before its own culling; rectangles not counted);
// fragment shader invocations: 16 per call of llvmpipe's 4x4-block fragment function, i.e. per 4x4 block with
// coverage of each primitive (docs/lavapipe-rules.md §13).
struct Counts {
    uint64_t ia_vertices = 0, ia_primitives = 0, vs_invocations = 0, clip_invocations = 0, cs_invocations = 0;
    uint64_t clip_primitives = kAny, fs_invocations = kAny;
    uint64_t at(uint32_t bit) const {
        switch (bit) {
            case 0:
                return ia_vertices;
            case 1:
                return ia_primitives;
            case 2:
                return vs_invocations;
            case 5:
                return clip_invocations;
            case 6:
                return clip_primitives;
            case 7:
                return fs_invocations;
            case 10:
                return cs_invocations;
            default:
                return 0;  // geometry and tessellation: no such stages
        }
    }
};

// `c` with the two raster-side counts set.
Counts with(Counts c, uint64_t clip_primitives, uint64_t fs_invocations) {
    c.clip_primitives = clip_primitives;
    c.fs_invocations = fs_invocations;
    return c;
}

// Every query available with exactly these counts, for the counters of `mask` in bit order.
Check stats_are(VkQueryPipelineStatisticFlags mask, const std::vector<Counts>& expected) {
    return [mask, expected](const std::vector<Plane>& planes) -> std::string {
        const size_t values = size_t(__builtin_popcount(mask));
        for (const Plane& p : planes) {
            if (p.name != "queries") continue;
            if (p.width != expected.size() || p.texel_bytes != 8 * (values + 1))
                return "queries: " + std::to_string(p.width) + " results of " + std::to_string(p.texel_bytes) +
                       " bytes";
            for (size_t q = 0; q < expected.size(); ++q) {
                const uint8_t* r = &p.data[q * p.texel_bytes];
                uint64_t v;
                std::memcpy(&v, r + 8 * values, 8);
                if (v != 1) return "query " + std::to_string(q) + " not available";
                size_t k = 0;
                for (uint32_t bit = 0; bit < 11; ++bit) {
                    if (!(mask & (1u << bit))) continue;
                    std::memcpy(&v, r + 8 * k++, 8);
                    if (expected[q].at(bit) != kAny && v != expected[q].at(bit))
                        return "query " + std::to_string(q) + " statistic bit " + std::to_string(bit) + " counted " +
                               std::to_string(v) + ", expected " + std::to_string(expected[q].at(bit));
                }
            }
            return {};
        }
        return "no 'queries' plane";
    };
}

// Every query available (counts judged against the reference only).
Check all_available(size_t n) {
    return [n](const std::vector<Plane>& planes) -> std::string {
        for (const Plane& p : planes) {
            if (p.name != "queries") continue;
            if (p.width != n) return "queries: " + std::to_string(p.width) + " results";
            for (size_t q = 0; q < n; ++q) {
                uint64_t avail;
                std::memcpy(&avail, &p.data[(q + 1) * p.texel_bytes - 8], 8);
                if (avail != 1) return "query " + std::to_string(q) + " not available";
            }
            return {};
        }
        return "no 'queries' plane";
    };
}

Scene stats_scene(VkQueryPipelineStatisticFlags mask, QueryMode mode, std::vector<Draw> draws,
                  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT) {
    Scene s;
    s.target.width = kW;
    s.target.height = kH;
    s.target.samples = samples;
    s.queries = mode;
    s.statistics = mask;
    s.draws = std::move(draws);
    return s;
}

// n vertices on a circle of radius 0.8 (any topology gets non-degenerate primitives from them).
std::vector<Vertex> ring(uint32_t n, float z = 0.5f) {
    std::vector<Vertex> v;
    for (uint32_t i = 0; i < n; ++i) {
        const float a = 6.2831853f * float(i) / float(n) + 0.3f * float(i % 2);
        v.push_back(vtx(0.8f * std::cos(a), 0.8f * std::sin(a), z, 1, {float(i % 3) / 2, float(i % 5) / 4, 0.5f, 1}));
    }
    return v;
}

// The corner triangle: pixel corners (4, 4), (28, 4), (4, 28) of the 32x32 target. Its pixels are those with
// centres x + y < 32 (x, y >= 4), so llvmpipe calls its fragment function on the 21 blocks (bx, by >= 1,
// bx + by <= 7) whose first pixel centre (or sample at 4x) lies inside: 21 x 16 invocations, against 276 covered
// pixels (a count per pixel or per sample would differ). Back-facing with VK_FRONT_FACE_COUNTER_CLOCKWISE.
constexpr uint64_t kCornerInvocations = 21 * 16;
Draw corner_triangle(float z = 0.5f, bool reversed = false) {
    Draw d;
    d.vertices = {vtx(-0.75f, -0.75f, z), vtx(0.75f, -0.75f, z), vtx(-0.75f, 0.75f, z)};
    if (reversed) std::swap(d.vertices[1], d.vertices[2]);
    return d;
}

Draw draw_of(VkPrimitiveTopology t, std::vector<Vertex> v, std::vector<uint32_t> indices = {}, bool restart = false) {
    Draw d;
    d.topology = t;
    d.vertices = std::move(v);
    d.indices = std::move(indices);
    d.primitive_restart = restart;
    return d;
}

constexpr uint32_t kR = 0xFFFFFFFFu;  // restart value of 32-bit indices

void add_counter_cases(CaseList& out) {
    // Each counter alone, then all together: two triangles (6 vertices, 2 primitives, 6 invocations).
    const Counts two_triangles = with({6, 2, 6, 2, 0}, 2, kAny);
    for (uint32_t bit = 0; bit < 11; ++bit) {
        const VkQueryPipelineStatisticFlags mask = 1u << bit;
        if (!(kAll & mask)) continue;
        out.push_back({"query.pipeline_statistics.alone_bit" + std::to_string(bit),
                       [=] {
                           return stats_scene(mask, QueryMode::kPerDraw,
                                              {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6))});
                       },
                       stats_are(mask, {two_triangles})});
    }
    out.push_back(
        {"query.pipeline_statistics.all",
         [] { return stats_scene(kAll, QueryMode::kPerDraw, {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6))}); },
         stats_are(kAll, {two_triangles})});
    // Two counters far apart in bit order (the layout packs the ones asked for).
    const VkQueryPipelineStatisticFlags sparse = VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
                                                 VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT;
    out.push_back({"query.pipeline_statistics.two_counters",
                   [=] {
                       return stats_scene(sparse, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(7))});
                   },
                   stats_are(sparse, {with({7, 5, 7, 5, 0}, 5, kAny)})});
}

void add_topology_cases(CaseList& out) {
    // Lists, strips and fans, non-indexed: vertices n, primitives by the topology's rule, one invocation per vertex.
    out.push_back(
        {"query.pipeline_statistics.topologies",
         [] {
             return stats_scene(
                 kAll, QueryMode::kPerDraw,
                 {draw_of(VK_PRIMITIVE_TOPOLOGY_POINT_LIST, ring(5)), draw_of(VK_PRIMITIVE_TOPOLOGY_LINE_LIST, ring(8)),
                  draw_of(VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, ring(6)),
                  draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(9)),
                  draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(8)),
                  draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, ring(7))});
         },
         stats_are(kAll,
                   // Every primitive reaches setup; the five 1-pixel points lie in five 4x4 blocks: 5 x 16 invocations.
                   {with({5, 5, 5, 5, 0}, 5, 5 * 16), with({8, 4, 8, 4, 0}, 4, kAny), with({6, 5, 6, 5, 0}, 5, kAny),
                    with({9, 3, 9, 3, 0}, 3, kAny), with({8, 6, 8, 6, 0}, 6, kAny), with({7, 5, 7, 5, 0}, 5, kAny)})});
    // An incomplete last primitive (a list of 8: 2 triangles + 2 vertices): lavapipe's draw trims it before
    // counting (draw_pt_trim_count), so 6 vertices; the spec leaves the count of such vertices open.
    out.push_back({"query.pipeline_statistics.incomplete_primitive",
                   [] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(8)),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_LINE_LIST, ring(5))});
                   },
                   stats_are(kAll, {with({6, 2, 6, 2, 0}, 2, kAny), with({4, 2, 4, 2, 0}, 2, kAny)})});
    // Restart: each run is drawn on its own; the restart indices are not vertices. Runs of 4 and 5 (strip: 2 + 3
    // triangles; fan: 2 + 3; line strip: 3 + 4 lines), each index once per run.
    const std::vector<uint32_t> runs = {0, 1, 2, 3, kR, 4, 5, 6, 7, 8};
    out.push_back({"query.pipeline_statistics.restart",
                   [=] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(9), runs, true),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, ring(9), runs, true),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, ring(9), runs, true),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(9),
                                                   {0, 1, 2, 3, 8, 4, 5, 6, 7, 8}, true)});
                   },
                   // The last draw has no restart index: one run of 10 (index 8 twice, the second a cache hit).
                   stats_are(kAll, {with({9, 5, 9, 5, 0}, 5, kAny), with({9, 5, 9, 5, 0}, 5, kAny),
                                    with({9, 7, 9, 7, 0}, 7, kAny), with({10, 8, 9, 8, 0}, 8, kAny)})});
    // Runs shorter than a primitive count nothing.
    out.push_back({"query.pipeline_statistics.restart_short_runs",
                   [=] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(9),
                                                   {0, 1, kR, kR, 2, 3, 4, kR, 5}, true)});
                   },
                   stats_are(kAll, {with({3, 1, 3, 1, 0}, 1, kAny)})});
}

void add_index_cases(CaseList& out) {
    // Repeated indices: draw's index cache shades each distinct index of a segment once while no other index
    // with the same low 8 bits came between (vsplit_add_cache): 4 invocations for 9 indices.
    out.push_back({"query.pipeline_statistics.repeated_indices",
                   [] {
                       return stats_scene(
                           kAll, QueryMode::kPerDraw,
                           {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(4), {0, 1, 2, 2, 1, 3, 0, 2, 3})});
                   },
                   stats_are(kAll, {with({9, 3, 4, 3, 0}, 3, kAny)})});
    // Indices 0 and 256 share a cache entry: 0,1,2 (3), 256 (4, evicts 0), 1,2 hit, 0 (5, evicts 256), 1,2 hit.
    out.push_back({"query.pipeline_statistics.index_cache_collision",
                   [] {
                       return stats_scene(
                           kAll, QueryMode::kPerDraw,
                           {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(260), {0, 1, 2, 256, 1, 2, 0, 1, 2})});
                   },
                   stats_are(kAll, {with({9, 3, 5, 3, 0}, 3, kAny)})});
    // Instancing multiplies everything: 3 instances of 2 triangles, indexed and not.
    out.push_back({"query.pipeline_statistics.instances",
                   [] {
                       Draw a = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6));
                       a.instances = 3;
                       Draw b = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(5), {0, 1, 2, 1, 3, 4});
                       b.instances = 4;
                       return stats_scene(kAll, QueryMode::kPerDraw, {a, b});
                   },
                   stats_are(kAll, {with({18, 6, 18, 6, 0}, 6, kAny), with({24, 16, 20, 16, 0}, 16, kAny)})});
    // Big draws, split into draw's segments (non-indexed: up to 4096 vertices; indexed: 1024 indices, trimmed to
    // whole primitives; strips and fans repeat the vertices their segments share): judged against lavapipe and
    // by lavapipe's segment rule (rast/geometry/draw_batches.h).
    // A strip of 5000: segments of 4096 and 906 vertices (2 shared): 5002 vertices, 4094 + 904 triangles.
    out.push_back({"query.pipeline_statistics.split_strip",
                   [] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(5000))});
                   },
                   stats_are(kAll, {with({5002, 4998, 5002, 4998, 0}, 4998, kAny)})});
    // Indexed, 2500 indices (7i mod 600): list 2499 (trimmed) in 1023 + 1023 + 453; fan 2500 in 1024 + 1024 +
    // 456 (each later segment starts again at the fan's first vertex); strip 2500 the same (2 shared, even
    // triangle counts). Invocations follow the cache per segment: judged against lavapipe only.
    out.push_back({"query.pipeline_statistics.split_indexed",
                   [] {
                       std::vector<uint32_t> idx(2500);
                       for (uint32_t i = 0; i < idx.size(); ++i) idx[i] = (i * 7) % 600;
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(600), idx),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, ring(600), idx),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(600), idx)});
                   },
                   all_available(3)});
}

void add_raster_cases(CaseList& out) {
    // What happens after the clipper's input does not change these counters: primitives outside the frustum,
    // clipped, back-facing and culled, zero-area; discard, early fragment tests, depth-failed fragments, 4x MSAA
    // with and without sample shading.
    out.push_back({"query.pipeline_statistics.clip_cull",
                   [] {
                       Draw outside = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                                              {vtx(2, 2), vtx(3, 2), vtx(2, 3), vtx(-1.5f, -0.5f), vtx(1.5f, -0.5f),
                                               vtx(0, 1.8f, 0.5f)});  // one outside, one clipped by three planes
                       Draw culled = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                                             {vtx(-0.5f, -0.5f), vtx(0, 0.5f), vtx(0.5f, -0.5f), vtx(0, 0), vtx(0, 0),
                                              vtx(0.3f, 0.3f)});  // clockwise, zero-area
                       culled.cull = VK_CULL_MODE_BACK_BIT;
                       Draw behind = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
                                             {vtx(-1, -1, 1.5f), vtx(1, -1, 1.5f), vtx(0, 1, 1.5f)});  // past far
                       return stats_scene(kAll, QueryMode::kPerDraw, {outside, culled, behind});
                   },
                   // Setup gets the clipped triangle's four fan pieces (a hexagon), both triangles of `culled`
                   // (front-facing in Vulkan's y-down framebuffer: pixels (8, 8), (16, 24), (24, 8), whose centres
                   // fall in 4 + 4 + 2 + 2 blocks of block rows 2-5; the zero-area one still counts there and
                   // shades nothing), nothing of `behind`.
                   stats_are(kAll, {with({6, 2, 6, 2, 0}, 4, kAny), with({6, 2, 6, 2, 0}, 2, 12 * 16),
                                    with({3, 1, 3, 1, 0}, 0, 0)})});
    // Early depth failures and discards still call the fragment function: three draws of the corner triangle.
    out.push_back({"query.pipeline_statistics.fragment_side",
                   [] {
                       Scene s = stats_scene(kAll, QueryMode::kAcrossPass, {});
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       Draw front = corner_triangle(0.2f);
                       front.depth_test = front.depth_write = true;
                       Draw failing = corner_triangle(0.7f);
                       failing.depth_test = true;
                       Draw discarding = failing;
                       discarding.frag = Frag::kDiscard;
                       s.draws = {front, failing, discarding};
                       return s;
                   },
                   stats_are(kAll, {with({9, 3, 9, 3, 0}, 3, 3 * kCornerInvocations)})});
    // 4x: one call per block whatever its samples, also under sample shading (the sample loop is inside it).
    for (const bool shading : {false, true}) {
        out.push_back(
            {std::string("query.pipeline_statistics.msaa4x") + (shading ? "_sample_shading" : ""),
             [=] {
                 Draw d = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, ring(8));
                 Draw c = corner_triangle();
                 if (shading) d.min_sample_shading = c.min_sample_shading = 1.0f;
                 return stats_scene(kAll, QueryMode::kPerDraw, {d, c}, VK_SAMPLE_COUNT_4_BIT);
             },
             stats_are(kAll, {with({8, 6, 8, 6, 0}, 6, kAny), with({3, 1, 3, 1, 0}, 1, kCornerInvocations)})});
    }
    // A draw whose rasterization is discarded (here by a sample mask of 0) sets lavapipe's running total of
    // clipping invocations to 0 instead of adding to it (lp_setup_vbuf.c lp_setup_pipeline_statistics): a query
    // spanning it counts only the clipping invocations of the draws after it. Its other counters count.
    out.push_back({"query.pipeline_statistics.discarding_draw_resets_clipping",
                   [] {
                       Draw a = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6));
                       Draw masked = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(5));
                       masked.sample_mask = 0;
                       Draw c = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(9));
                       return stats_scene(kAll, QueryMode::kAcrossPass, {a, masked, c});
                   },
                   // The masked draw's primitives never reach setup (triangle_noop): 2 + 3 clipping primitives.
                   stats_are(kAll, {with({20, 8, 20, 3, 0}, 5, kAny)})});
}

void add_fragment_cases(CaseList& out) {
    // Blocks, 16x16 blocks and a whole 64x64 tile on a 128x128 target: the corner triangle, now pixels (16, 16),
    // (112, 16), (16, 112), is the 300 blocks with bx, by >= 4 and bx + by <= 31; the triangle (0, 0), (128, 0),
    // (0, 128) covers the pixel centres x + y < 127, i.e. the 528 blocks with bx + by <= 31 (tile (0, 0) whole).
    out.push_back({"query.pipeline_statistics.fragment_blocks",
                   [] {
                       Draw big;
                       big.vertices = {vtx(-1, -1), vtx(1, -1), vtx(-1, 1)};
                       Scene s = stats_scene(kAll, QueryMode::kPerDraw, {corner_triangle(), big});
                       s.target.width = s.target.height = 128;
                       return s;
                   },
                   stats_are(kAll, {with({3, 1, 3, 1, 0}, 1, 300 * 16), with({3, 1, 3, 1, 0}, 1, 528 * 16)})});
    // Culling: FRONT_AND_BACK installs llvmpipe's triangle_noop (nothing counted); a culled winding reaches setup
    // (counted) and shades nothing; the other winding shades its 21 blocks.
    out.push_back({"query.pipeline_statistics.culled",
                   [] {
                       Draw both = corner_triangle();
                       both.cull = VK_CULL_MODE_FRONT_AND_BACK;
                       Draw back = corner_triangle();
                       back.cull = VK_CULL_MODE_BACK_BIT;
                       Draw front = corner_triangle(0.5f, true);
                       front.cull = VK_CULL_MODE_BACK_BIT;
                       return stats_scene(kAll, QueryMode::kPerDraw, {both, back, front});
                   },
                   stats_are(kAll, {with({3, 1, 3, 1, 0}, 0, 0), with({3, 1, 3, 1, 0}, 1, 0),
                                    with({3, 1, 3, 1, 0}, 1, kCornerInvocations)})});
    // Lines and polygonMode LINE: a horizontal line through pixel row 8 from x = 5 to 27 lies in blocks 1-6 of
    // block row 2 (6 x 16, whichever end pixel the line rule keeps); the corner triangle drawn as lines hands its
    // three edges to setup.
    out.push_back(
        {"query.pipeline_statistics.lines",
         [] {
             Draw line = draw_of(VK_PRIMITIVE_TOPOLOGY_LINE_LIST, {vtx(-0.6875f, -0.46875f), vtx(0.6875f, -0.46875f)});
             Draw edges = corner_triangle();
             edges.polygon_mode = VK_POLYGON_MODE_LINE;
             return stats_scene(kAll, QueryMode::kPerDraw, {line, edges});
         },
         stats_are(kAll, {with({2, 1, 2, 1, 0}, 1, 6 * 16), with({3, 1, 3, 1, 0}, 3, kAny)})});
    // llvmpipe's rectangles (a constant-colour pair on B8G8R8A8, as query.linear_path.*; pixels [30, 98) of
    // 128x128) are not counted by setup. Inside the pass the query's commands keep every bin general: 18 x 18
    // blocks are shaded. Begun before the pass, the bins are linear and nothing calls the fragment function.
    for (const auto& variant :
         {std::pair{"per_draw", QueryMode::kPerDraw}, std::pair{"across_pass", QueryMode::kAcrossPass}}) {
        const QueryMode mode = variant.second;
        out.push_back({std::string("query.pipeline_statistics.linear_path_") + variant.first,
                       [mode] {
                           const std::array<float, 4> half = {0.5f, 0.5f, 0.5f, 1.0f};
                           const float e = 0.53125f;
                           Draw d;
                           d.vertices = {vtxc(-e, -e, half), vtxc(e, -e, half), vtxc(e, e, half),
                                         vtxc(-e, -e, half), vtxc(e, e, half),  vtxc(-e, e, half)};
                           Scene s = stats_scene(kAll, mode, {d});
                           s.target.width = s.target.height = 128;
                           s.target.color = VK_FORMAT_B8G8R8A8_UNORM;
                           return s;
                       },
                       stats_are(kAll, {with({6, 2, 6, 2, 0}, 0, mode == QueryMode::kPerDraw ? 18 * 18 * 16 : 0)}),
                       "bgra-linear-path"});
    }
}

}  // namespace

void add_statistics_cases(CaseList& out) {
    add_counter_cases(out);
    add_topology_cases(out);
    add_index_cases(out);
    add_raster_cases(out);
    add_fragment_cases(out);
}

}  // namespace tilevk::cts
