// Pipeline-statistics queries at vkQueueSubmit: the counters lavapipe 22.3 reports, counted where it counts them.
// Vertex side (draw module, per instance, restart run and vsplit segment): rast/geometry/draw_statistics.h.
// Clipping invocations: draw counts every primitive it hands on (draw_stats_clipper_primitives), but llvmpipe's
// lp_setup_pipeline_statistics, which adds a draw's counts to the context, sets the context's running total to 0
// instead at a draw whose rasterization is discarded (setup->rasterizer_discard: rasterizerDiscardEnable or a sample
// mask of 0; lp_state_derived.c's third case, a null fragment shader with depth and stencil testing off, never
// applies to lavapipe, whose pipelines without one get a dummy NIR shader that nir_tgsi_scan_shader reports as 2
// instructions, so llvmpipe rasterizes them and counts their fragment blocks too). Compute: llvmpipe adds
// workgroups x local size per dispatch (lp_state_cs.c). Geometry and tessellation counters stay 0: tilevk has no
// such stages, and lavapipe's are 0 without them. Clipping primitives and fragment shader invocations are counted
// by the renderer for each draw (rast/render RasterStatistics: primitives reaching llvmpipe's setup, calls of its
// 4x4-block fragment function); lavapipe bins its query begin/end commands between draws, so a query gets the
// counts of exactly the draws recorded while it was active (ExecState::raster_epochs).
#include "execute.h"
#include "query_pool.h"
#include "rast/geometry/draw_statistics.h"
#include "rast/render/draw_state.h"

namespace tilevk::icd {
namespace {

constexpr uint32_t stat_index(VkQueryPipelineStatisticFlagBits bit) {
    return uint32_t(__builtin_ctz(uint32_t(bit)));
}

// llvmpipe's setup->rasterizer_discard for this draw (see above: never for a missing fragment shader).
bool setup_discards(const rast::render::PipelineState& s, bool rasterizer_discard) {
    return rasterizer_discard || s.sample_mask == 0;
}

}  // namespace

void count_draw_statistics(ExecState& st, const rast::render::DrawCall& call, const rast::render::PipelineState& s,
                           bool rasterizer_discard) {
    // llvmpipe_draw_vbo returns before counting anything for an empty draw.
    if (st.statistics_queries.empty() || call.count == 0 || call.instance_count == 0) return;
    rast::geometry::IndexSource src;
    src.first = call.first;
    src.count = call.count;
    if (call.indexed) {
        src.indices = call.index_data;
        src.index_size = call.index_size;
        src.index_count_total = call.index_bytes / call.index_size;
        src.vertex_offset = call.vertex_offset;
        src.primitive_restart = s.primitive_restart;
    }
    rast::geometry::VertexStatistics one;
    rast::geometry::add_vertex_statistics(src, s.topology, &one);
    StatisticCounters& t = st.statistics_totals;
    const uint64_t n = call.instance_count;
    t[stat_index(VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT)] += n * one.ia_vertices;
    t[stat_index(VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT)] += n * one.ia_primitives;
    t[stat_index(VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT)] += n * one.vs_invocations;
    uint64_t& clip = t[stat_index(VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT)];
    clip = setup_discards(s, rasterizer_discard) ? 0 : clip + n * one.ia_primitives;
}

rast::render::RasterStatistics* active_raster_statistics(ExecState& st) {
    return st.statistics_queries.empty() ? nullptr : st.raster_epochs.back().get();
}

namespace {
// The set of active queries changed: later draws count into a new epoch.
void next_epoch(ExecState& st) {
    if (!st.statistics_queries.empty()) st.raster_epochs.push_back(std::make_unique<rast::render::RasterStatistics>());
}
}  // namespace

// llvmpipe_begin_query: the running totals restart from 0 when no statistics query is active.
void begin_statistics(ExecState& st, QueryPool& pool, uint32_t query) {
    if (st.statistics_queries.empty()) st.statistics_totals = {};
    pool.begin_statistics(query, st.statistics_totals);
    st.statistics_queries.push_back({&pool, query, st.raster_epochs.size()});
    next_epoch(st);
}

bool end_statistics(ExecState& st, QueryPool& pool, uint32_t query) {
    auto& active = st.statistics_queries;
    for (auto it = active.begin(); it != active.end(); ++it) {
        if (it->pool != &pool || it->query != query) continue;
        // The vertex-side counters and the compute ones are final now (counted as draws are recorded for the
        // renderer); the renderer's counts are once the draws are rendered.
        st.statistics_ended.push_back({&pool, query, it->first_epoch, st.raster_epochs.size(), st.statistics_totals});
        active.erase(it);
        next_epoch(st);
        if (st.render_pass == nullptr) publish_statistics(st);  // no draw of it is still binned
        return true;
    }
    return false;
}

void publish_statistics(ExecState& st) {
    for (const ExecState::EndedStatistics& e : st.statistics_ended) {
        StatisticCounters raster{};
        for (size_t k = e.first_epoch; k < e.end_epoch; ++k) {
            const rast::render::RasterStatistics& r = *st.raster_epochs[k];
            raster[stat_index(VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT)] += r.clipping_primitives;
            // lp_query.c: the 4x4-block function's calls times LP_RASTER_BLOCK_SIZE squared.
            raster[stat_index(VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT)] += 16 * r.fragment_blocks;
        }
        e.pool->end_statistics(e.query, e.totals, raster);
    }
    st.statistics_ended.clear();
    if (st.statistics_queries.empty()) st.raster_epochs.clear();  // no draw points at them any more
}

void count_dispatch_statistics(ExecState& st, uint64_t workgroups, const std::array<uint32_t, 3>& local_size) {
    st.statistics_totals[stat_index(VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT)] +=
        workgroups * local_size[0] * local_size[1] * local_size[2];
}

}  // namespace tilevk::icd
