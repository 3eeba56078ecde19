#include "rast/geometry/draw_statistics.h"

#include <algorithm>
#include <array>

#include "rast/geometry/draw_batches.h"

namespace tilevk::rast::geometry {
namespace {

// vsplit's index cache, cleared at every segment: fetches[elt % 256] holds the last index that hashed there.
struct IndexCache {
    std::array<uint32_t, 256> fetches;
    bool has_max_fetch = false;
    uint32_t misses = 0;
    IndexCache() { fetches.fill(0xFFFFFFFFu); }
    void add(uint32_t elt) {
        // The cache starts at all ones, so index 0xFFFFFFFF would hit an empty entry: vsplit forces its first
        // occurrence to miss.
        if (elt == 0xFFFFFFFFu && !has_max_fetch) {
            fetches[elt % 256] = 0;
            has_max_fetch = true;
        }
        if (fetches[elt % 256] != elt) {
            fetches[elt % 256] = elt;
            ++misses;
        }
    }
};

// One segment: `count` positions from run-relative `start` of the run beginning at draw position `run_first`;
// a fan segment after the first replaces its first vertex by the run's first one (vsplit's "spoken" vertex).
void add_segment(const IndexSource& src, Topology t, uint32_t run_first, uint32_t start, uint32_t count, bool spoken,
                 VertexStatistics* out) {
    uint32_t first, incr;
    split_prim(t, &first, &incr);
    out->ia_vertices += count;
    out->ia_primitives += (count - first) / incr + 1;
    if (src.indices == nullptr) {
        out->vs_invocations += count;
        return;
    }
    IndexCache cache;
    bool restart;
    if (spoken) cache.add(fetch_index(src, run_first, &restart));
    for (uint32_t i = spoken ? 1 : 0; i < count; ++i) cache.add(fetch_index(src, run_first + start + i, &restart));
    out->vs_invocations += cache.misses;
}

// draw_split_tmp.h for one restart run of `count` positions from draw position `run_first` (the segment sizes of
// append_run_batches, with their starts).
void add_run(const IndexSource& src, Topology t, uint32_t run_first, uint32_t count, VertexStatistics* out) {
    uint32_t first, incr;
    split_prim(t, &first, &incr);
    count = trim_count(count, first, incr);
    if (count < first) return;
    const bool indexed = src.indices != nullptr;
    const uint32_t max_simple = indexed ? kSegmentSize : kLinearMaxVertices;
    if (count <= max_simple) {
        add_segment(src, t, run_first, 0, count, false, out);
        return;
    }
    const bool fan = t == Topology::kTriangleFan;
    const uint32_t rollback = first - incr;
    uint32_t seg_max = trim_count(std::min(fan ? kSegmentSize : max_simple, count), first, incr);
    if (t == Topology::kTriangleStrip && seg_max < count && !(((seg_max - first) / incr) & 1)) seg_max -= incr;
    uint32_t seg_start = 0;
    do {
        const uint32_t remaining = count - seg_start;
        const bool last = remaining <= seg_max;
        add_segment(src, t, run_first, seg_start, last ? remaining : seg_max, fan && seg_start != 0, out);
        seg_start += last ? remaining : seg_max - rollback;
    } while (seg_start < count);
}

}  // namespace

void add_vertex_statistics(const IndexSource& src, Topology t, VertexStatistics* out) {
    if (src.indices == nullptr || !src.primitive_restart) {
        add_run(src, t, 0, src.count, out);
        return;
    }
    // draw_pt.c prim_restart_loop: each run between restart indices is drawn on its own.
    uint32_t run_first = 0;
    for (uint32_t i = 0; i < src.count; ++i) {
        bool restart = false;
        fetch_index(src, i, &restart);
        if (restart) {
            add_run(src, t, run_first, i - run_first, out);
            run_first = i + 1;
        }
    }
    add_run(src, t, run_first, src.count - run_first, out);
}

}  // namespace tilevk::rast::geometry
