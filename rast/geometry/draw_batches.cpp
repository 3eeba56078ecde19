#include "rast/geometry/draw_batches.h"

#include <algorithm>

namespace tilevk::rast::geometry {

void split_prim(Topology t, uint32_t* first, uint32_t* incr) {
    switch (t) {
        case Topology::kPointList:
            *first = 1, *incr = 1;
            return;
        case Topology::kLineList:
            *first = 2, *incr = 2;
            return;
        case Topology::kLineStrip:
            *first = 2, *incr = 1;
            return;
        case Topology::kTriangleList:
            *first = 3, *incr = 3;
            return;
        case Topology::kTriangleStrip:
        case Topology::kTriangleFan:
            *first = 3, *incr = 1;
            return;
    }
    *first = 1, *incr = 1;
}

uint32_t trim_count(uint32_t count, uint32_t first, uint32_t incr) {
    if (count < first) return 0;
    return count - (count - first) % incr;
}

void append_run_batches(Topology t, bool indexed, uint32_t count, std::vector<uint32_t>* out) {
    uint32_t first, incr;
    split_prim(t, &first, &incr);
    count = trim_count(count, first, incr);
    if (count < first) return;
    // primitives in a segment of n vertices (n >= first, n already trimmed)
    auto prims = [&](uint32_t n) { return (n - first) / incr + 1; };
    const uint32_t max_simple = indexed ? kSegmentSize : kLinearMaxVertices;
    if (count <= max_simple) {  // "no splitting required", fans included
        out->push_back(prims(count));
        return;
    }
    const uint32_t max_count = t == Topology::kTriangleFan ? kSegmentSize : max_simple;
    const uint32_t rollback = first - incr;
    uint32_t seg_max = trim_count(std::min(max_count, count), first, incr);
    // strips: flush an even number of triangles at a time
    if (t == Topology::kTriangleStrip && seg_max < count && !(((seg_max - first) / incr) & 1)) seg_max -= incr;
    uint32_t seg_start = 0;
    do {
        const uint32_t remaining = count - seg_start;
        if (remaining > seg_max) {
            out->push_back(prims(seg_max));
            seg_start += seg_max - rollback;
        } else {
            out->push_back(prims(remaining));
            seg_start += remaining;
        }
    } while (seg_start < count);
}

void draw_batches(const IndexSource& src, Topology t, std::vector<uint32_t>* out) {
    out->clear();
    const bool indexed = src.indices != nullptr;
    if (!indexed || !src.primitive_restart) {
        append_run_batches(t, indexed, src.count, out);
        return;
    }
    // draw_pt.c prim_restart_loop: every run between restart indices is a draw of its own.
    uint32_t run = 0;
    for (uint32_t i = 0; i < src.count; ++i) {
        bool restart = false;
        fetch_index(src, i, &restart);
        if (restart) {
            append_run_batches(t, indexed, run, out);
            run = 0;
        } else {
            ++run;
        }
    }
    append_run_batches(t, indexed, run, out);
}

}  // namespace tilevk::rast::geometry
