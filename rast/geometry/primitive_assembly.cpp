#include "rast/geometry/primitive_assembly.h"

#include <algorithm>
#include <cstring>

namespace tilevk::rast::geometry {

uint32_t vertices_per_primitive(Topology t) {
    switch (t) {
        case Topology::kPointList:
            return 1;
        case Topology::kLineList:
        case Topology::kLineStrip:
            return 2;
        default:
            return 3;
    }
}

size_t assembled_index_capacity(Topology t, uint32_t count) {
    // every topology makes at most `count` primitives
    return static_cast<size_t>(count) * vertices_per_primitive(t);
}

uint32_t fetch_index(const IndexSource& src, uint32_t i, bool* is_restart) {
    *is_restart = false;
    const uint32_t pos = src.first + i;  // 32-bit wrap, like draw_overflow_uadd's clamp is never reached in practice
    if (src.indices == nullptr) return pos;
    uint32_t elt = 0;
    // DRAW_GET_IDX: positions past the end of the index buffer read as 0 and are never a restart
    if (pos < src.index_count_total && static_cast<uint64_t>(src.first) + i < src.index_count_total) {
        switch (src.index_size) {
            case 1:
                elt = src.indices[pos];
                break;
            case 2: {
                uint16_t v;
                std::memcpy(&v, src.indices + static_cast<size_t>(pos) * 2, 2);
                elt = v;
                break;
            }
            default:
                std::memcpy(&elt, src.indices + static_cast<size_t>(pos) * 4, 4);
                break;
        }
        const uint32_t restart_value = src.index_size == 1 ? 0xFFu : src.index_size == 2 ? 0xFFFFu : 0xFFFFFFFFu;
        *is_restart = src.primitive_restart && elt == restart_value;
    }
    return elt + static_cast<uint32_t>(src.vertex_offset);
}

namespace {

// Emits the primitives of one restart-free run of vertex indices v[0..n).
// Appends whole primitives while they fit; never writes past `cap`.
struct Emitter {
    Topology t;
    uint32_t* out;
    size_t cap;
    size_t used = 0;
    uint32_t prims = 0;

    void emit(const uint32_t* idx) {
        const uint32_t per = vertices_per_primitive(t);
        if (used + per > cap) return;
        for (uint32_t j = 0; j < per; ++j) out[used++] = idx[j];
        ++prims;
    }
};

}  // namespace

uint32_t assemble_primitives(const IndexSource& src, Topology t, bool flatshade_first, uint32_t* out,
                             size_t out_capacity) {
    // A non-indexed list: primitive k is vertices first + per*k .. first + per*k + per - 1 (fetch_index without an
    // index buffer, no restart), written in one pass instead of vertex by vertex through the topology switch.
    const uint32_t per = vertices_per_primitive(t);
    const bool list = t == Topology::kPointList || t == Topology::kLineList || t == Topology::kTriangleList;
    if (src.indices == nullptr && list) {
        const uint32_t prims = static_cast<uint32_t>(std::min<size_t>(src.count / per, out_capacity / per));
        for (size_t i = 0; i < size_t(prims) * per; ++i) out[i] = src.first + static_cast<uint32_t>(i);
        return prims;
    }
    Emitter e{t, out, out_capacity};
    // State of the current run: run position n, first vertex (fans), last two vertices (strips/lists).
    uint32_t n = 0;
    uint32_t v0 = 0, prev2 = 0, prev1 = 0;
    for (uint32_t i = 0; i < src.count; ++i) {
        bool restart = false;
        const uint32_t v = fetch_index(src, i, &restart);
        if (restart) {
            n = 0;
            continue;
        }
        uint32_t p[3];
        switch (t) {
            case Topology::kPointList:
                p[0] = v;
                e.emit(p);
                break;
            case Topology::kLineList:
                if (n & 1) {
                    p[0] = prev1;
                    p[1] = v;
                    e.emit(p);
                }
                break;
            case Topology::kLineStrip:
                if (n >= 1) {
                    p[0] = prev1;
                    p[1] = v;
                    e.emit(p);
                }
                break;
            case Topology::kTriangleList:
                if (n % 3 == 2) {
                    p[0] = prev2;
                    p[1] = prev1;
                    p[2] = v;
                    e.emit(p);
                }
                break;
            case Topology::kTriangleStrip:
                if (n >= 2) {
                    const bool odd = (n & 1) != 0;  // triangle k = n-2 is odd iff n is odd
                    if (flatshade_first) {
                        // lp_setup_vbuf: (i-2, i+(i&1)-1, i-(i&1))
                        p[0] = prev2;
                        p[1] = odd ? v : prev1;
                        p[2] = odd ? prev1 : v;
                    } else {
                        // (i+(i&1)-2, i-(i&1)-1, i)
                        p[0] = odd ? prev1 : prev2;
                        p[1] = odd ? prev2 : prev1;
                        p[2] = v;
                    }
                    e.emit(p);
                }
                break;
            case Topology::kTriangleFan:
                if (n >= 2) {
                    if (flatshade_first) {
                        p[0] = prev1;
                        p[1] = v;
                        p[2] = v0;
                    } else {
                        p[0] = v0;
                        p[1] = prev1;
                        p[2] = v;
                    }
                    e.emit(p);
                }
                break;
        }
        if (n == 0) v0 = v;
        prev2 = prev1;
        prev1 = v;
        ++n;
    }
    return e.prims;
}

}  // namespace tilevk::rast::geometry
