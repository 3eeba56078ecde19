// Pipeline-statistics queries at vkQueueSubmit: the counters lavapipe 22.3 reports, counted where it counts them.
// Vertex side (draw module, per instance, restart run and vsplit segment): rast/geometry/draw_statistics.h.
// Clipping invocations: draw counts every primitive it hands on (draw_stats_clipper_primitives), but llvmpipe's
// lp_setup_pipeline_statistics, which adds a draw's counts to the context, sets the context's running total to 0
// instead at a draw whose rasterization is discarded (setup->rasterizer_discard: rasterizerDiscardEnable, a sample
// mask of 0, or no fragment shader with depth and stencil testing off; lp_state_derived.c). Compute: llvmpipe adds
// workgroups x local size per dispatch (lp_state_cs.c). Geometry and tessellation counters stay 0: tilevk has no
// such stages, and lavapipe's are 0 without them.
#include "execute.h"
#include "rast/geometry/draw_statistics.h"
#include "rast/render/draw_state.h"

namespace tilevk::icd {
namespace {

constexpr uint32_t stat_index(VkQueryPipelineStatisticFlagBits bit) {
    return uint32_t(__builtin_ctz(uint32_t(bit)));
}

// llvmpipe's setup->rasterizer_discard for this draw.
bool setup_discards(const rast::render::PipelineState& s, bool rasterizer_discard) {
    const bool null_fs = s.fragment == nullptr;
    return rasterizer_discard || s.sample_mask == 0 ||
           (null_fs && !s.depth_stencil.depth_test && !s.depth_stencil.stencil_test);
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

void count_dispatch_statistics(ExecState& st, uint64_t workgroups, const std::array<uint32_t, 3>& local_size) {
    st.statistics_totals[stat_index(VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT)] +=
        workgroups * local_size[0] * local_size[1] * local_size[2];
}

}  // namespace tilevk::icd
