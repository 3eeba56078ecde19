#include "rast/geometry/rect_detect.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace tilevk::rast::geometry {
namespace {

// SAME_POS: the whole window position (x, y, z, 1/w) compares equal.
bool same_pos(const float* a, const float* b) {
    const float* p = win_pos(a);
    const float* q = win_pos(b);
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2] && p[3] == q[3];
}
bool same_x(const float* a, const float* b) {
    return win_pos(a)[0] == win_pos(b)[0];
}
bool same_y(const float* a, const float* b) {
    return win_pos(a)[1] == win_pos(b)[1];
}

int32_t cvtt(float f) {
    // cvttss2si: truncation, INT32_MIN for NaN and out-of-range values
    if (!(f > -2147483904.0f && f < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(f);
}

}  // namespace

Winding float_winding(const float* w0, const float* w1, const float* w2) {
    const float ex = w0[0] - w2[0], ey = w0[1] - w2[1];
    const float fx = w1[0] - w2[0], fy = w1[1] - w2[1];
    const float m0 = ex * fy, m1 = ey * fx;
    const float det = m0 - m1;
    if (det < 0.0f) return Winding::kCcw;
    if (det > 0.0f) return Winding::kCw;
    return Winding::kNone;
}

bool match_rect_ccw(const VertexLayout& layout, const float* const v[6], const float* corner[3]) {
    const float *rv0, *rv1, *rv2, *rv3;
    // The nine ways two ccw triangles (v0 v1 v2) and (v3 v4 v5) share a diagonal, in do_rect_ccw's order.
    if (same_pos(v[0], v[3])) {
        if (same_pos(v[2], v[4])) {
            rv0 = v[5], rv1 = v[0], rv2 = v[1], rv3 = v[2];
        } else if (same_pos(v[1], v[5])) {
            rv0 = v[4], rv1 = v[1], rv2 = v[2], rv3 = v[0];
        } else {
            return false;
        }
    } else if (same_pos(v[0], v[5])) {
        if (same_pos(v[2], v[3])) {
            rv0 = v[4], rv1 = v[0], rv2 = v[1], rv3 = v[2];
        } else if (same_pos(v[1], v[4])) {
            rv0 = v[3], rv1 = v[1], rv2 = v[2], rv3 = v[0];
        } else {
            return false;
        }
    } else if (same_pos(v[0], v[4])) {
        if (same_pos(v[2], v[5])) {
            rv0 = v[3], rv1 = v[0], rv2 = v[1], rv3 = v[2];
        } else if (same_pos(v[1], v[3])) {
            rv0 = v[5], rv1 = v[1], rv2 = v[2], rv3 = v[0];
        } else {
            return false;
        }
    } else if (same_pos(v[2], v[3])) {
        if (!same_pos(v[1], v[4])) return false;
        rv0 = v[5], rv1 = v[2], rv2 = v[0], rv3 = v[1];
    } else if (same_pos(v[2], v[5])) {
        if (!same_pos(v[1], v[3])) return false;
        rv0 = v[4], rv1 = v[2], rv2 = v[0], rv3 = v[1];
    } else if (same_pos(v[2], v[4])) {
        if (!same_pos(v[1], v[5])) return false;
        rv0 = v[3], rv1 = v[2], rv2 = v[0], rv3 = v[1];
    } else {
        return false;
    }
    // rv0..rv3 run counter-clockwise; rotate once when rv0-rv1 is the horizontal side.
    if (same_y(rv0, rv1)) {
        const float* tmp = rv0;
        rv0 = rv1, rv1 = rv2, rv2 = rv3, rv3 = tmp;
    }
    if (!(same_x(rv0, rv1) && same_x(rv2, rv3) && same_y(rv0, rv3) && same_y(rv1, rv2))) return false;
    // Equal 1/w at the corners (the linear interpolator divides by one w).
    const float w = win_pos(rv0)[3];
    if (win_pos(rv1)[3] != w || win_pos(rv2)[3] != w || win_pos(rv3)[3] != w) return false;
    for (uint32_t i = 0; i < layout.num_attribs; ++i) {
        for (int j = 0; j < 4; ++j) {
            const float a0 = attrib(rv0, i)[j], a1 = attrib(rv1, i)[j];
            const float a2 = attrib(rv2, i)[j], a3 = attrib(rv3, i)[j];
            const float dxdx1 = a0 - a3, dxdx2 = a1 - a2;
            const float dxdy1 = a0 - a1, dxdy2 = a3 - a2;
            if (dxdx1 != dxdx2 || dxdy1 != dxdy2) return false;
        }
    }
    // lp_rect_cw(rv0, rv2, rv1): "changing to clockwise here"
    corner[0] = rv0;
    corner[1] = rv2;
    corner[2] = rv1;
    return true;
}

RectDecision decide_rect_pair(const RectPairConfig& cfg, const float* const t0[3], const float* const t1[3]) {
    RectDecision d;
    if (cfg.cull_front && cfg.cull_back) {  // setup_rect_noop
        d.kind = RectDecision::kNothing;
        return d;
    }
    const Winding w0 = float_winding(win_pos(t0[0]), win_pos(t0[1]), win_pos(t0[2]));
    const Winding w1 = float_winding(win_pos(t1[0]), win_pos(t1[1]), win_pos(t1[2]));
    // do_rect_ccw(v0, v1, v2, v3, v4, v5) for two ccw triangles, (v0, v2, v1, v3, v5, v4) for two cw ones.
    auto try_rect = [&](bool cw, bool front) {
        const float* v[6] = {t0[0], t0[1], t0[2], t1[0], t1[1], t1[2]};
        if (cw) std::swap(v[1], v[2]), std::swap(v[4], v[5]);
        if (match_rect_ccw(cfg.layout, v, d.corner)) {
            d.kind = RectDecision::kRect;
            d.front = front;
        } else {
            d.kind = RectDecision::kTriangles;
        }
    };
    if (!cfg.cull_front && !cfg.cull_back) {  // setup_rect_both
        if (w0 != w1)
            d.kind = RectDecision::kTriangles;
        else if (w0 == Winding::kCcw)
            try_rect(false, cfg.front_ccw);
        else if (w0 == Winding::kCw)
            try_rect(true, !cfg.front_ccw);
        else
            d.kind = RectDecision::kNothing;
        return d;
    }
    // Culling one face: setup_rect_ccw keeps ccw triangles, setup_rect_cw keeps cw ones.
    const bool keep_ccw = cfg.cull_back ? cfg.front_ccw : !cfg.front_ccw;
    if (keep_ccw) {
        if (w0 == Winding::kCcw && w1 == Winding::kCcw)
            try_rect(false, cfg.front_ccw);
        else if (w0 == Winding::kCcw)
            d.kind = RectDecision::kFirstTriangle;
        else if (w1 == Winding::kCcw)
            d.kind = RectDecision::kTriangles;  // setup_rect_ccw returns FALSE here
        else
            d.kind = RectDecision::kNothing;
    } else {
        if (w0 == Winding::kCw && w1 == Winding::kCw)
            try_rect(true, !cfg.front_ccw);
        else if (w0 == Winding::kCw)
            d.kind = RectDecision::kFirstTriangle;
        else if (w1 == Winding::kCw)
            d.kind = RectDecision::kSecondTriangle;
        else
            d.kind = RectDecision::kNothing;
    }
    return d;
}

int32_t subpixel_snap_iround(float a) {
    const float f = 256.0f * a;
    return f >= 0.0f ? cvtt(f + 0.5f) : cvtt(f - 0.5f);
}

RectBox rect_box(const float* w0, const float* w1, const float* w2, float pixel_offset, bool bottom_edge_rule) {
    RectBox b;
    const int32_t x0 = subpixel_snap_iround(w0[0] - pixel_offset), y0 = subpixel_snap_iround(w0[1] - pixel_offset);
    const int32_t x1 = subpixel_snap_iround(w1[0] - pixel_offset), y1 = subpixel_snap_iround(w1[1] - pixel_offset);
    const int32_t x2 = subpixel_snap_iround(w2[0] - pixel_offset), y2 = subpixel_snap_iround(w2[1] - pixel_offset);
    if ((x2 < x1) != (y0 < y2)) return b;  // "cull clockwise rects"
    // (v + FIXED_ONE - 1) >> FIXED_ORDER in 32-bit int with an arithmetic shift; the sums cannot overflow for
    // coordinates inside draw's guard band (|x| < 2^24 fixed).
    auto ceil_px = [](int32_t v, int32_t adj) { return static_cast<int32_t>((int64_t{v} + 255 + adj) >> 8); };
    const int32_t adj = bottom_edge_rule ? 1 : 0;
    b.culled = false;
    b.x0 = ceil_px(std::min({x0, x1, x2}), 0);
    b.x1 = ceil_px(std::max({x0, x1, x2}), 0) - 1;
    b.y0 = ceil_px(std::min({y0, y1, y2}), adj);
    b.y1 = ceil_px(std::max({y0, y1, y2}), adj) - 1;
    return b;
}

}  // namespace tilevk::rast::geometry
