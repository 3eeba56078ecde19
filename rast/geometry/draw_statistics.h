// The vertex-side pipeline statistics lavapipe counts for one instance of a draw (VK_QUERY_TYPE_PIPELINE_STATISTICS:
// input-assembly vertices and primitives, vertex shader invocations, clipping invocations). draw's llvm middle end
// adds them per vsplit segment (draw_pt_fetch_shade_pipeline_llvm.c llvm_pipeline_generic, draw_context.c
// draw_stats_clipper_primitives): the segment's vertex count (after draw_pt_trim_count dropped the incomplete last
// primitive), its primitives, and the vertices it fetched. Segments are the batches of draw_batches.h; an indexed
// segment fetches each index once per hit in vsplit's 256-entry direct-mapped cache (draw_pt_vsplit.c
// vsplit_add_cache), so a repeated index is shaded again when another index with the same low 8 bits came between.
#pragma once

#include <cstdint>

#include "rast/geometry/primitive_assembly.h"

namespace tilevk::rast::geometry {

struct VertexStatistics {
    uint64_t ia_vertices = 0;
    uint64_t ia_primitives = 0;  // also the clipping invocations without a geometry stage
    uint64_t vs_invocations = 0;
};

// Adds one instance of the draw `src` (restart runs included) with topology `t` to `*out`.
void add_vertex_statistics(const IndexSource& src, Topology t, VertexStatistics* out);

}  // namespace tilevk::rast::geometry
