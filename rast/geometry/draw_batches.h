// lavapipe's draw module never sees a whole draw at once: draw_vbo runs each instance, each primitive-restart
// run (draw_pt.c prim_restart_loop) and, inside a run, each vsplit segment (draw_pt_vsplit.c, draw_split_tmp.h)
// through the vertex shader and the "any vertex clipped?" decision separately. Those segments are the batches
// whose boundaries decide whether a triangle meets draw's clipper and float cull, and whether llvmpipe's
// 9-vertex analysis runs (rast/geometry/README.md, orchestration step 4).
#pragma once

#include <cstdint>
#include <vector>

#include "rast/geometry/primitive_assembly.h"

namespace tilevk::rast::geometry {

// Segment limits for lavapipe (llvmpipe's vbuf: 4096-byte vertex buffers, so draw's middle end reports
// max_vertices = MAX2(4096 / vertex_size, 4096) = 4096; vsplit's segment_size = MIN2(SEGMENT_SIZE 1024, 4096)):
//   non-indexed: max_count_simple = 4096 (every topology while count <= 4096), fans beyond that 1024;
//   indexed:     1024 for every topology — lavapipe passes no index bounds (min 0, max ~0), so vsplit's
//                whole-primitive path (vsplit_primitive_*) always declines and the index cache segments it.
inline constexpr uint32_t kLinearMaxVertices = 4096;
inline constexpr uint32_t kSegmentSize = 1024;

// draw_pt_split_prim: vertices of the first primitive and vertices per further primitive.
void split_prim(Topology t, uint32_t* first, uint32_t* incr);
// draw_pt_trim_count: count < first -> 0, else count - (count - first) % incr.
uint32_t trim_count(uint32_t count, uint32_t first, uint32_t incr);

// Appends, for one restart run of `count` vertices/indices, the number of primitives of each of its segments in
// order (nothing for a run shorter than one primitive). Segments of strips and fans overlap by first - incr
// vertices but never share a primitive, and strip segments hold an even number of triangles (so the parity —
// hence the vertex order — of every triangle is the one of the unsplit strip).
void append_run_batches(Topology t, bool indexed, uint32_t count, std::vector<uint32_t>* prims_per_batch);

// All batches of one instance of a draw, in assembly order (the order assemble_primitives emits primitives):
// restart runs found with fetch_index (indexed draws with restart only), each split by append_run_batches.
void draw_batches(const IndexSource& src, Topology t, std::vector<uint32_t>* prims_per_batch);

}  // namespace tilevk::rast::geometry
