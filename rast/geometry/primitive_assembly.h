// Primitive assembly: topology decomposition into the exact vertex order lavapipe feeds setup
// (llvmpipe lp_setup_vbuf.c lp_setup_draw_elements; draw_decompose_tmp.h gives the same orders on the pipeline
// path), primitive restart (draw_pt.c prim_restart_loop) and index fetch (draw_private.h DRAW_GET_IDX).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tilevk::rast::geometry {

enum class Topology : uint8_t { kPointList, kLineList, kLineStrip, kTriangleList, kTriangleStrip, kTriangleFan };

uint32_t vertices_per_primitive(Topology t);  // 1, 2 or 3

// Where the vertex indices of a draw come from.
//  Non-indexed (indices == nullptr): vertex i of the draw has index first + i (32-bit wrap).
//  Indexed: element first + i of the index buffer, + vertex_offset (32-bit wrap). Elements at positions
//  >= index_count_total read as 0 (lavapipe's DRAW_GET_IDX rule; never read out of bounds).
struct IndexSource {
    const uint8_t* indices = nullptr;  // index buffer bytes, starting at the bound offset
    uint32_t index_size = 4;           // 1, 2 or 4 bytes
    uint32_t index_count_total = 0;    // number of whole indices available in the buffer from `indices`
    uint32_t first = 0;                // firstIndex / firstVertex
    uint32_t count = 0;                // indexCount / vertexCount
    int32_t vertex_offset = 0;         // vertexOffset (indexed only)
    bool primitive_restart = false;    // indexed only; restart value is all ones of index_size
};

// Upper bound on the number of vertex indices assemble_primitives() writes (3 per triangle etc.).
size_t assembled_index_capacity(Topology t, uint32_t count);

// Decomposes the draw into primitives, writing vertices_per_primitive(t) vertex indices per primitive into
// `out` (capacity `out_capacity` indices; use assembled_index_capacity). Returns the number of primitives.
// Orders, for primitive k with run-local positions (each restart starts a new run; incomplete primitives dropped):
//   points: (k)        lines: (2k, 2k+1)        line strip: (k, k+1)
//   triangle list: (3k, 3k+1, 3k+2)
//   triangle strip, flatshade_first: even k (k, k+1, k+2), odd k (k, k+2, k+1)
//                   last-vertex:     even k (k, k+1, k+2), odd k (k+1, k, k+2)
//   triangle fan,   flatshade_first: (k+1, k+2, 0)      last-vertex: (0, k+1, k+2)
// Restart applies to every topology (as in draw; Vulkan only allows it for strips and fans).
uint32_t assemble_primitives(const IndexSource& src, Topology t, bool flatshade_first, uint32_t* out,
                             size_t out_capacity);

// Index of draw position i (0-based) before restart handling; `is_restart` set when it equals the restart value.
uint32_t fetch_index(const IndexSource& src, uint32_t i, bool* is_restart);

}  // namespace tilevk::rast::geometry
