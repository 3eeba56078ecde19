#include "rast/geometry/draw_module.h"

#include <algorithm>
#include <optional>

#include "rast/geometry/fp_env.h"

namespace tilevk::rast::geometry {

NineVertexQuirk nine_vertex_quirk(const TriangleListBatch& b, const float (*v)[2]) {
    const uint32_t trimmed = b.vertex_count - b.vertex_count % 3;  // draw drops an incomplete last triangle
    if (b.indexed || b.any_vertex_clipped || b.fs_has_flat_input || trimmed != 9 || v == nullptr)
        return NineVertexQuirk::kNone;
    // is_zero_area: the y of vertices 8, 7, 6 all equal (float ==, so NaN never matches)
    if (!(v[8][1] == v[7][1] && v[8][1] == v[6][1])) return NineVertexQuirk::kNone;
    const bool aero = v[0][0] == v[1][0] && v[0][0] == v[5][0] && v[2][0] == v[3][0] && v[2][0] == v[4][0] &&
                      v[0][1] == v[3][1] && v[0][1] == v[5][1] && v[1][1] == v[2][1] && v[1][1] == v[4][1];
    return aero ? NineVertexQuirk::kAeroRect : NineVertexQuirk::kSwallowed;
}

void DrawModule::begin_draw(const DrawModuleConfig& cfg) {
    cfg_ = cfg;
    rect_pairs_ = cfg.linear_mode && cfg.pair_candidates;
    // vbuf vertex size: 16 bytes per slot (lp_state_derived.c compute_vertex_info); max_vertices =
    // LP_MAX_VBUF_SIZE 4096 / size
    max_vertices_ = 4096 / (16 * cfg.vertex_slots);
    vbuf_clear();
}

bool DrawModule::direct_pairs(SetupSink& setup, Topology topology, bool indexed, const TriangleBatch& batch) {
    const float* t0[3];
    const float* t1[3];
    const bool list6 = topology == Topology::kTriangleList && (size_t(batch.count) * 3) % 6 == 0;
    if (rect_pairs_ && list6) {
        // draw_arrays / draw_elements, PIPE_PRIM_TRIANGLES with nr % 6 == 0: rect() per pair
        for (uint32_t p = 0; p + 1 < batch.count; p += 2) {
            batch.triangle(p, t0);
            batch.triangle(p + 1, t1);
            rect_or_triangles(setup, t0, t1);
        }
        return true;
    }
    if (rect_pairs_ && !indexed && topology == Topology::kTriangleStrip && cfg_.flatshade_first) {
        // draw_arrays, strip with flatshade_first: setup->rect on each pair of consecutive triangles;
        // when it declines, the first is drawn and the pairing moves on by one (last-vertex strips: triangles)
        uint32_t p = 0;
        while (p + 1 < batch.count) {
            batch.triangle(p, t0);
            batch.triangle(p + 1, t1);
            if (apply_rect_decision(setup, t0, t1)) {
                p += 2;
            } else {
                setup.triangle(t0[0], t0[1], t0[2]);
                p += 1;
            }
        }
        if (p < batch.count) {
            batch.triangle(p, t0);
            setup.triangle(t0[0], t0[1], t0[2]);
        }
        return true;
    }
    if (!indexed && topology == Topology::kTriangleFan && batch.count == 2) {
        // draw_arrays, 4-vertex fan (any mode, either provoking vertex): rect(v0, v1, v2, v0, v2, v3), i.e.
        // outside linear mode the triangles (v0, v1, v2), (v0, v2, v3) instead of the fan's (v1, v2, v0),
        // (v2, v3, v0) — with the last vertex provoking the fan's own order
        const float* a[3];
        const float* b[3];
        batch.triangle(0, a);
        batch.triangle(1, b);
        const bool first = cfg_.flatshade_first;  // assembled (v1, v2, v0), (v2, v3, v0) else (v0, v1, v2), ...
        const float* q[4] = {first ? a[2] : a[0], first ? a[0] : a[1], first ? a[1] : a[2], first ? b[1] : b[2]};
        const float* u0[3] = {q[0], q[1], q[2]};
        const float* u1[3] = {q[0], q[2], q[3]};
        rect_or_triangles(setup, u0, u1);
        return true;
    }
    return false;
}

uint32_t DrawModule::nine_vertex_batch(SetupSink& setup, const TriangleBatch& batch) {
    float xy[9][2];
    for (int k = 0; k < 9; ++k) {
        const float* w = win_pos(batch.record(batch.ids[k]));
        xy[k][0] = w[0];
        xy[k][1] = w[1];
    }
    TriangleListBatch qb;
    qb.vertex_count = 9;
    const NineVertexQuirk q = nine_vertex_quirk(qb, xy);
    // Swallowed: nothing. Aero: llvmpipe bins one rectangle, lp_rect_cw(v0, v1, v2, front = TRUE), in
    // any mode; at 4x it is still drawn as its two triangles (rectangles in MSAA are not modelled).
    if (q == NineVertexQuirk::kSwallowed) return 0;
    if (q == NineVertexQuirk::kAeroRect) {
        if (!cfg_.single_sample) return 2;
        const float* t0[3];
        batch.triangle(0, t0);
        setup.rect(t0[0], t0[1], t0[2], true);
        return 0;
    }
    return batch.count;
}

bool DrawModule::apply_rect_decision(SetupSink& setup, const float* const t0[3], const float* const t1[3]) {
    const RectDecision d = decide_rect_pair(cfg_.rect, t0, t1);
    switch (d.kind) {
        case RectDecision::kTriangles:
            return false;
        case RectDecision::kRect:
            setup.rect(d.corner[0], d.corner[1], d.corner[2], d.front);
            break;
        case RectDecision::kFirstTriangle:
            setup.triangle(t0[0], t0[1], t0[2]);
            break;
        case RectDecision::kSecondTriangle:
            setup.triangle(t1[0], t1[1], t1[2]);
            break;
        case RectDecision::kNothing:
            break;
    }
    return true;
}

void DrawModule::rect_or_triangles(SetupSink& setup, const float* const t0[3], const float* const t1[3]) {
    if (cfg_.linear_mode && apply_rect_decision(setup, t0, t1)) return;
    setup.triangle(t0[0], t0[1], t0[2]);
    setup.triangle(t1[0], t1[1], t1[2]);
}

void DrawModule::vbuf_primitive(SetupSink& setup, const float* const* v, const uint64_t* ids, float point_size,
                                bool front) {
    // draw_pipe_vbuf.c vbuf_tri / vbuf_line / vbuf_point: check_space(n) against both buffers, then each vertex
    // emitted once per buffer.
    const uint32_t n = cfg_.verts_per_prim;
    const size_t indices = records_.size() / cfg_.record_floats;
    if (vertices_ + n > max_vertices_ || indices + n > kMaxVbufIndices) vbuf_flush(setup);
    for (uint32_t k = 0; k < n; ++k) {
        if (std::find(emitted_id_.begin(), emitted_id_.end(), ids[k]) == emitted_id_.end()) {
            emitted_id_.push_back(ids[k]);
            ++vertices_;
        }
        records_.insert(records_.end(), v[k], v[k] + cfg_.record_floats);
    }
    point_size_.push_back(point_size);
    front_.push_back(front ? 1 : 0);
}

void DrawModule::vbuf_flush(SetupSink& setup, bool after_draw) {
    if (records_.empty()) return;
    std::optional<ScopedKeepDenormals> keep_denormals;
    if (after_draw) keep_denormals.emplace();
    // lp_setup_vbuf.c draw_elements: PIPE_PRIM_TRIANGLES rect() per pair when nr % 6 == 0, else triangles;
    // PIPE_PRIM_LINES / POINTS setup->line / setup->point each.
    const size_t stride = cfg_.record_floats;
    const size_t nr = records_.size() / stride;
    auto vert = [&](size_t i) { return records_.data() + i * stride; };
    if (cfg_.verts_per_prim == 1) {
        for (size_t i = 0; i < nr; ++i) setup.point(vert(i), point_size_[i], front_[i] != 0);
    } else if (cfg_.verts_per_prim == 2) {
        for (size_t i = 0; i + 1 < nr; i += 2) setup.line(vert(i), vert(i + 1), front_[i / 2] != 0);
    } else if (rect_pairs_ && nr % 6 == 0) {
        for (size_t i = 0; i + 5 < nr; i += 6) {
            const float* t0[3] = {vert(i), vert(i + 1), vert(i + 2)};
            const float* t1[3] = {vert(i + 3), vert(i + 4), vert(i + 5)};
            rect_or_triangles(setup, t0, t1);
        }
    } else {
        for (size_t i = 0; i + 2 < nr; i += 3) setup.triangle(vert(i), vert(i + 1), vert(i + 2));
    }
    vbuf_clear();
}

void DrawModule::vbuf_clear() {
    records_.clear();
    point_size_.clear();
    front_.clear();
    vertices_ = 0;
    emitted_id_.clear();
}

}  // namespace tilevk::rast::geometry
