// query.pipeline_statistics.*: pipeline-statistics queries around the draws (Scene::statistics, render.cpp): the
// results (64-bit values in bit order + availability) are copied with vkCmdCopyQueryPoolResults and read back as
// the plane "queries", judged byte for byte against lavapipe. Where the spec fixes a count (input-assembly
// vertices and primitives of whole primitives, vertex shader invocations of non-indexed draws, clipping
// invocations = primitives reaching the clipper, 0 for stages that do not exist) a check demands it on both
// devices too. Counts lavapipe derives from its draw module's internals (vsplit's index cache and segments, its
// clipping-invocation reset at discarding draws) are stated as lavapipe's rules (docs/lavapipe-rules.md
// "Pipeline statistics") and checked the same way, so a driver agreeing with a wrong reference still fails.
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "case.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kW = 32, kH = 32;

// The counters both drivers count (tilevk refuses CLIPPING_PRIMITIVES and FRAGMENT_SHADER_INVOCATIONS).
constexpr VkQueryPipelineStatisticFlags kAll = 0x7FF & ~(VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
                                                         VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT);

// Expected counts of one query, by counter (index = bit position).
struct Counts {
    uint64_t ia_vertices = 0, ia_primitives = 0, vs_invocations = 0, clip_invocations = 0, cs_invocations = 0;
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
            case 10:
                return cs_invocations;
            default:
                return 0;  // geometry and tessellation: no such stages
        }
    }
};

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
                    if (v != expected[q].at(bit))
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
    const Counts two_triangles{6, 2, 6, 2, 0};
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
                   stats_are(sparse, {{7, 5, 7, 5, 0}})});
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
         stats_are(
             kAll,
             {{5, 5, 5, 5, 0}, {8, 4, 8, 4, 0}, {6, 5, 6, 5, 0}, {9, 3, 9, 3, 0}, {8, 6, 8, 6, 0}, {7, 5, 7, 5, 0}})});
    // An incomplete last primitive (a list of 8: 2 triangles + 2 vertices): lavapipe's draw trims it before
    // counting (draw_pt_trim_count), so 6 vertices; the spec leaves the count of such vertices open.
    out.push_back({"query.pipeline_statistics.incomplete_primitive",
                   [] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(8)),
                                           draw_of(VK_PRIMITIVE_TOPOLOGY_LINE_LIST, ring(5))});
                   },
                   stats_are(kAll, {{6, 2, 6, 2, 0}, {4, 2, 4, 2, 0}})});
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
                   stats_are(kAll, {{9, 5, 9, 5, 0}, {9, 5, 9, 5, 0}, {9, 7, 9, 7, 0}, {10, 8, 9, 8, 0}})});
    // Runs shorter than a primitive count nothing.
    out.push_back({"query.pipeline_statistics.restart_short_runs",
                   [=] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(9),
                                                   {0, 1, kR, kR, 2, 3, 4, kR, 5}, true)});
                   },
                   stats_are(kAll, {{3, 1, 3, 1, 0}})});
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
                   stats_are(kAll, {{9, 3, 4, 3, 0}})});
    // Indices 0 and 256 share a cache entry: 0,1,2 (3), 256 (4, evicts 0), 1,2 hit, 0 (5, evicts 256), 1,2 hit.
    out.push_back({"query.pipeline_statistics.index_cache_collision",
                   [] {
                       return stats_scene(
                           kAll, QueryMode::kPerDraw,
                           {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(260), {0, 1, 2, 256, 1, 2, 0, 1, 2})});
                   },
                   stats_are(kAll, {{9, 3, 5, 3, 0}})});
    // Instancing multiplies everything: 3 instances of 2 triangles, indexed and not.
    out.push_back({"query.pipeline_statistics.instances",
                   [] {
                       Draw a = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6));
                       a.instances = 3;
                       Draw b = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(5), {0, 1, 2, 1, 3, 4});
                       b.instances = 4;
                       return stats_scene(kAll, QueryMode::kPerDraw, {a, b});
                   },
                   stats_are(kAll, {{18, 6, 18, 6, 0}, {24, 16, 20, 16, 0}})});
    // Big draws, split into draw's segments (non-indexed: up to 4096 vertices; indexed: 1024 indices, trimmed to
    // whole primitives; strips and fans repeat the vertices their segments share): judged against lavapipe and
    // by lavapipe's segment rule (rast/geometry/draw_batches.h).
    // A strip of 5000: segments of 4096 and 906 vertices (2 shared): 5002 vertices, 4094 + 904 triangles.
    out.push_back({"query.pipeline_statistics.split_strip",
                   [] {
                       return stats_scene(kAll, QueryMode::kPerDraw,
                                          {draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, ring(5000))});
                   },
                   stats_are(kAll, {{5002, 4998, 5002, 4998, 0}})});
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
                   stats_are(kAll, {{6, 2, 6, 2, 0}, {6, 2, 6, 2, 0}, {3, 1, 3, 1, 0}})});
    out.push_back({"query.pipeline_statistics.fragment_side",
                   [] {
                       Scene s = stats_scene(kAll, QueryMode::kAcrossPass, {});
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       Draw front = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6, 0.2f));
                       front.depth_test = front.depth_write = true;
                       Draw failing = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, ring(6, 0.7f));
                       failing.depth_test = true;
                       Draw discarding = failing;
                       discarding.frag = Frag::kDiscard;
                       s.draws = {front, failing, discarding};
                       return s;
                   },
                   stats_are(kAll, {{18, 6, 18, 6, 0}})});
    for (const bool shading : {false, true}) {
        out.push_back({std::string("query.pipeline_statistics.msaa4x") + (shading ? "_sample_shading" : ""),
                       [=] {
                           Draw d = draw_of(VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, ring(8));
                           if (shading) d.min_sample_shading = 1.0f;
                           return stats_scene(kAll, QueryMode::kPerDraw, {d}, VK_SAMPLE_COUNT_4_BIT);
                       },
                       stats_are(kAll, {{8, 6, 8, 6, 0}})});
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
                   stats_are(kAll, {{20, 8, 20, 3, 0}})});
}

}  // namespace

void add_statistics_cases(CaseList& out) {
    add_counter_cases(out);
    add_topology_cases(out);
    add_index_cases(out);
    add_raster_cases(out);
}

}  // namespace tilevk::cts
