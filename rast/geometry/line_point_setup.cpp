#include "rast/geometry/line_point_setup.h"

#include <climits>
#include <cmath>

namespace tilevk::rast::geometry {
namespace {

constexpr int32_t kFixedOne = 256;

// cvttss2si: truncation, NaN/out of range -> INT32_MIN
int32_t cvtt(float f, bool* ok) {
    if (!(f > -2147483904.0f && f < 2147483648.0f)) {  // NaN fails both
        if (ok) *ok = false;
        return INT32_MIN;
    }
    return static_cast<int32_t>(f);
}

// Edge plane from corner i to j with the top-left bias (lp_setup_line.c, also lavapipe-rules §2).
FixedPlane edge(int32_t xi, int32_t yi, int32_t xj, int32_t yj) {
    const int64_t dy = static_cast<int64_t>(yi) - yj;  // dcdx before the << 8
    const int64_t dx = static_cast<int64_t>(xi) - xj;  // dcdy
    FixedPlane p;
    p.c = dy * xi - dx * yi;
    if (dy < 0 || (dy == 0 && dx > 0)) p.c += 1;
    p.a = static_cast<int32_t>(-dy);
    p.b = static_cast<int32_t>(dx);
    return p;
}

float fracf(float f) {
    return f - std::floor(f);
}
bool sign(float x) {
    return x >= 0;
}

// a0/dadx/dady of one channel for lines: dadx = (da21*dx)*ooa, a0 = a1 - (dadx*(x1-0.5) + dady*(y1-0.5))
void line_coef(float a1, float a2, float dx, float dy, float ooa, float x1c, float y1c, float* a0, float* dadx,
               float* dady) {
    const float da21 = a1 - a2;
    const float gx = (da21 * dx) * ooa;
    const float gy = (da21 * dy) * ooa;
    const float px = gx * x1c;
    const float py = gy * y1c;
    const float s = px + py;
    *dadx = gx;
    *dady = gy;
    *a0 = a1 - s;
}

}  // namespace

int32_t util_iround(float f, bool* ok) {
    if (f >= 0.0f) {
        const float g = f + 0.5f;
        return cvtt(g, ok);
    }
    const float g = f - 0.5f;
    return cvtt(g, ok);
}

int32_t subpixel_snap(float a, bool* ok) {
    return util_iround(256.0f * a, ok);
}

namespace {

// The Bresenham line's diamond-exit inputs (lp_setup_line.c): the ends' offsets from their pixel centres.
struct DiamondLine {
    const float* w1;
    const float* w2;
    float dx, dy;
    float x1diff, y1diff, x2diff, y2diff;
    int32_t fixed_width;  // util_iround(width) pixels, in fixed point
    float po;             // the snap's pixel offset
};

// x-major Bresenham line: ends moved along x by the diamond-exit rule, util_iround(width) tall. Sets info_dx/dy
// (lp_line_info's gradient inputs) and the corners; false when a snap is out of range.
bool bresenham_x_major(DiamondLine l, float* info_dx, float* info_dy, int32_t x[4], int32_t y[4]) {
    float x_off = 0, y_off = 0, x_off_end = 0, y_off_end = 0;
    bool draw_start, draw_end;
    bool ok = true;
    const float* p1 = l.w1;
    const float* p2 = l.w2;
    const float dydx = l.dy / l.dx;
    if (l.y2diff == -0.5f && l.dy < 0) l.y2diff = 0.5f;
    if (std::fabs(l.x1diff) + std::fabs(l.y1diff) < 0.5f) {
        draw_start = true;
    } else if (sign(l.x1diff) == sign(-l.dx)) {
        draw_start = false;
    } else if (sign(-l.y1diff) != sign(l.dy)) {
        draw_start = true;
    } else {
        const float yi = fracf(l.w1[1]) + l.x1diff * dydx;
        draw_start = yi < 1.0f && yi > 0.0f;
    }
    if (std::fabs(l.x2diff) + std::fabs(l.y2diff) < 0.5f) {
        draw_end = false;
    } else if (sign(l.x2diff) != sign(-l.dx)) {
        draw_end = false;
    } else if (sign(-l.y2diff) == sign(l.dy)) {
        draw_end = true;
    } else {
        const float yi = fracf(l.w2[1]) + l.x2diff * dydx;
        draw_end = yi < 1.0f && yi > 0.0f;
    }
    const bool will_start = sign(-l.x1diff) != sign(l.dx);
    const bool will_end = (sign(l.x2diff) == sign(-l.dx)) || l.x2diff == 0;
    *info_dx = *info_dx * (1 + dydx * dydx);
    *info_dy = 0;
    // the offsets are C doubles (0.5 literal) stored to float
    if (l.dx < 0) {
        p1 = l.w2, p2 = l.w1;  // lavapipe also negates dx and dy here; nothing reads them afterwards
        if (will_start != draw_start) {
            x_off_end = static_cast<float>(static_cast<double>(-l.x1diff) - 0.5);
            y_off_end = x_off_end * dydx;
        }
        if (will_end != draw_end) {
            x_off = static_cast<float>(static_cast<double>(-l.x2diff) - 0.5);
            y_off = x_off * dydx;
        }
    } else {
        if (will_start != draw_start) {
            x_off = static_cast<float>(static_cast<double>(-l.x1diff) + 0.5);
            y_off = x_off * dydx;
        }
        if (will_end != draw_end) {
            x_off_end = static_cast<float>(static_cast<double>(-l.x2diff) + 0.5);
            y_off_end = x_off_end * dydx;
        }
    }
    const int32_t ax = subpixel_snap((p1[0] + x_off) - l.po, &ok);
    const int32_t bx = subpixel_snap((p2[0] + x_off_end) - l.po, &ok);
    const int32_t ay = subpixel_snap((p1[1] + y_off) - l.po, &ok);
    const int32_t by = subpixel_snap((p2[1] + y_off_end) - l.po, &ok);
    if (!ok) return false;
    x[0] = ax, x[1] = bx, x[2] = bx, x[3] = ax;
    y[0] = ay - l.fixed_width / 2, y[1] = by - l.fixed_width / 2;
    y[2] = by + l.fixed_width / 2, y[3] = ay + l.fixed_width / 2;
    return true;
}

// y-major Bresenham line: the same rule with the axes exchanged. A deliberate twin of bresenham_x_major, line for
// line as lp_setup_line.c writes its two branches, so that each can be checked against its Mesa branch.
bool bresenham_y_major(DiamondLine l, float* info_dx, float* info_dy, int32_t x[4], int32_t y[4]) {
    float x_off = 0, y_off = 0, x_off_end = 0, y_off_end = 0;
    bool draw_start, draw_end;
    bool ok = true;
    const float* p1 = l.w1;
    const float* p2 = l.w2;
    const float dxdy = l.dx / l.dy;
    if (l.x2diff == -0.5f && l.dx < 0) l.x2diff = 0.5f;
    if (std::fabs(l.x1diff) + std::fabs(l.y1diff) < 0.5f) {
        draw_start = true;
    } else if (sign(-l.y1diff) == sign(l.dy)) {
        draw_start = false;
    } else if (sign(l.x1diff) != sign(-l.dx)) {
        draw_start = true;
    } else {
        const float xi = fracf(l.w1[0]) + l.y1diff * dxdy;
        draw_start = xi < 1.0f && xi > 0.0f;
    }
    if (std::fabs(l.x2diff) + std::fabs(l.y2diff) < 0.5f) {
        draw_end = false;
    } else if (sign(-l.y2diff) != sign(l.dy)) {
        draw_end = false;
    } else if (sign(l.x2diff) == sign(-l.dx)) {
        draw_end = true;
    } else {
        const float xi = fracf(l.w2[0]) + l.y2diff * dxdy;
        draw_end = xi < 1.0f && xi >= 0.0f;
    }
    const bool will_start = sign(l.y1diff) == sign(l.dy);
    const bool will_end = (sign(-l.y2diff) == sign(l.dy)) || l.y2diff == 0;
    *info_dx = 0;
    *info_dy = *info_dy * (1 + dxdy * dxdy);
    if (l.dy > 0) {
        p1 = l.w2, p2 = l.w1;  // lavapipe also negates dx and dy here; nothing reads them afterwards
        if (will_start != draw_start) {
            y_off_end = static_cast<float>(static_cast<double>(-l.y1diff) + 0.5);
            x_off_end = y_off_end * dxdy;
        }
        if (will_end != draw_end) {
            y_off = static_cast<float>(static_cast<double>(-l.y2diff) + 0.5);
            x_off = y_off * dxdy;
        }
    } else {
        if (will_start != draw_start) {
            y_off = static_cast<float>(static_cast<double>(-l.y1diff) - 0.5);
            x_off = y_off * dxdy;
        }
        if (will_end != draw_end) {
            y_off_end = static_cast<float>(static_cast<double>(-l.y2diff) - 0.5);
            x_off_end = y_off_end * dxdy;
        }
    }
    const int32_t ax = subpixel_snap((p1[0] + x_off) - l.po, &ok);
    const int32_t bx = subpixel_snap((p2[0] + x_off_end) - l.po, &ok);
    const int32_t ay = subpixel_snap((p1[1] + y_off) - l.po, &ok);
    const int32_t by = subpixel_snap((p2[1] + y_off_end) - l.po, &ok);
    if (!ok) return false;
    x[0] = ax - l.fixed_width / 2, x[1] = bx - l.fixed_width / 2;
    x[2] = bx + l.fixed_width / 2, x[3] = ax + l.fixed_width / 2;
    y[0] = ay, y[1] = by, y[2] = by, y[3] = ay;
    return true;
}

// Rectangular line (Vulkan's default mode): scale = (width*0.5)/sqrt(area); corners = snap(end) -/+
// (snap(-dy*scale), snap(dx*scale)). False when a corner is out of range.
bool rectangular_corners(float width, const float* w1, const float* w2, float dx, float dy, float area, float po,
                         int32_t x[4], int32_t y[4]) {
    bool ok = true;
    const float scale = (width * 0.5f) / std::sqrt(area);
    const int32_t tx = subpixel_snap(-dy * scale, &ok);
    const int32_t ty = subpixel_snap(dx * scale, &ok);
    const int32_t sx1 = subpixel_snap(w1[0] - po, &ok), sx2 = subpixel_snap(w2[0] - po, &ok);
    const int32_t sy1 = subpixel_snap(w1[1] - po, &ok), sy2 = subpixel_snap(w2[1] - po, &ok);
    if (!ok) return false;
    const int64_t xs[4] = {int64_t{sx1} - tx, int64_t{sx2} - tx, int64_t{sx2} + tx, int64_t{sx1} + tx};
    const int64_t ys[4] = {int64_t{sy1} - ty, int64_t{sy2} - ty, int64_t{sy2} + ty, int64_t{sy1} + ty};
    for (int i = 0; i < 4; ++i) {
        if (xs[i] < INT32_MIN || xs[i] > INT32_MAX || ys[i] < INT32_MIN || ys[i] > INT32_MAX) return false;
        x[i] = static_cast<int32_t>(xs[i]);
        y[i] = static_cast<int32_t>(ys[i]);
    }
    return true;
}

// Bresenham (VK_EXT_line_rasterization): a parallelogram along the major axis whose ends are moved by the
// diamond-exit rule, util_iround(width) pixels thick.
bool bresenham_corners(float width, const float* w1, const float* w2, float dx, float dy, float po, float* info_dx,
                       float* info_dy, int32_t x[4], int32_t y[4]) {
    bool ok = true;
    width = width < 1.0f ? 1.0f : width;  // MAX2(1.0, width)
    DiamondLine l{w1, w2, dx, dy, fracf(w1[0]) - 0.5f, fracf(w1[1]) - 0.5f, fracf(w2[0]) - 0.5f,
                  fracf(w2[1]) - 0.5f, util_iround(width, &ok) * kFixedOne, po};
    if (std::fabs(dx) >= std::fabs(dy)) return bresenham_x_major(l, info_dx, info_dy, x, y) && ok;
    return bresenham_y_major(l, info_dx, info_dy, x, y) && ok;
}

// The four edges (corner i to i + 1) and the fixed-point box of the corners.
void line_planes(const int32_t x[4], const int32_t y[4], LineSetup* out) {
    out->min_x = out->max_x = x[0];
    out->min_y = out->max_y = y[0];
    for (int i = 0; i < 4; ++i) {
        out->corner_x[i] = x[i];
        out->corner_y[i] = y[i];
        out->planes[i] = edge(x[i], y[i], x[(i + 1) & 3], y[(i + 1) & 3]);
        out->min_x = std::min(out->min_x, x[i]);
        out->max_x = std::max(out->max_x, x[i]);
        out->min_y = std::min(out->min_y, y[i]);
        out->max_y = std::max(out->max_y, y[i]);
    }
}

// Attribute planes relative to the first vertex c1, with setup->pixel_offset (0.5, also in MSAA), from
// lp_line_info's gradient inputs (info_dx, info_dy) and ooa = 1 / |d|^2; flat attributes from the provoking vertex.
void line_attrib_planes(const LineSetupConfig& cfg, const float* c1, const float* c2, const float* pv, float info_dx,
                        float info_dy, float ooa, LineSetup* out, AttribPlane* attribs) {
    const float* q1 = win_pos(c1);
    const float* q2 = win_pos(c2);
    const float x1c = q1[0] - 0.5f;
    const float y1c = q1[1] - 0.5f;
    out->pos = AttribPlane{{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}};
    for (int ch = 2; ch < 4; ++ch)
        line_coef(q1[ch], q2[ch], info_dx, info_dy, ooa, x1c, y1c, &out->pos.a0[ch], &out->pos.dadx[ch],
                  &out->pos.dady[ch]);
    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) {
        AttribPlane& o = attribs[i];
        const float* a1 = attrib(c1, i);
        const float* a2 = attrib(c2, i);
        switch (cfg.layout.interp[i]) {
            case Interp::kFlat:
                for (int ch = 0; ch < 4; ++ch) {
                    o.a0[ch] = attrib(pv, i)[ch];
                    o.dadx[ch] = o.dady[ch] = 0.0f;
                }
                break;
            case Interp::kNoPerspective:
                for (int ch = 0; ch < 4; ++ch)
                    line_coef(a1[ch], a2[ch], info_dx, info_dy, ooa, x1c, y1c, &o.a0[ch], &o.dadx[ch], &o.dady[ch]);
                break;
            case Interp::kPerspective:
                for (int ch = 0; ch < 4; ++ch) {
                    const float b1 = a1[ch] * q1[3];
                    const float b2 = a2[ch] * q2[3];
                    line_coef(b1, b2, info_dx, info_dy, ooa, x1c, y1c, &o.a0[ch], &o.dadx[ch], &o.dady[ch]);
                }
                break;
        }
    }
}

}  // namespace

PrimSetupStatus setup_line(const LineSetupConfig& cfg, const float* v0, const float* v1, LineSetup* out,
                           AttribPlane* attribs) {
    const float* w1 = win_pos(v0);  // lavapipe's v1 = first vertex
    const float* w2 = win_pos(v1);
    const float dx = w1[0] - w2[0];
    const float dy = w1[1] - w2[1];
    const float area = dx * dx + dy * dy;
    if (area == 0.0f) return PrimSetupStatus::kEmpty;
    const float ooa = 1.0f / area;
    float info_dx = dx, info_dy = dy;
    // line and point snapping ignore the 0.5 offset in MSAA; coefficients below always use 0.5
    const float po = cfg.multisample ? 0.0f : 0.5f;
    int32_t x[4], y[4];
    const bool ok = cfg.mode == LineMode::kRectangular
                        ? rectangular_corners(cfg.width, w1, w2, dx, dy, area, po, x, y)
                        : bresenham_corners(cfg.width, w1, w2, dx, dy, po, &info_dx, &info_dy, x, y);
    if (!ok) return PrimSetupStatus::kOutOfRange;
    line_planes(x, y, out);
    // The attribute planes always use the draw-order vertices and the pre-swap dx/dy: lavapipe's lp_line_info
    // keeps v1/v2 from before the Bresenham swap.
    line_attrib_planes(cfg, v0, v1, cfg.flatshade_first ? v0 : v1, info_dx, info_dy, ooa, out, attribs);
    return PrimSetupStatus::kOk;
}

PrimSetupStatus setup_point(const PointSetupConfig& cfg, const float* v, float size, PointSetup* out,
                            AttribPlane* attribs) {
    const float* p = win_pos(v);
    if (size > 255.0f) size = 255.0f;  // LP_MAX_POINT_WIDTH
    bool ok = true;
    bool size_ok = true;
    // fixed_width = MAX2(FIXED_ONE, subpixel_snap(size)); a NaN size snaps to INT32_MIN -> 256
    const int32_t snapped = subpixel_snap(size, &size_ok);
    const int32_t fw = snapped > kFixedOne ? snapped : kFixedOne;
    const float po = cfg.multisample ? 0.0f : 0.5f;
    const int32_t sx = subpixel_snap(p[0] - po, &ok);
    const int32_t sy = subpixel_snap(p[1] - po, &ok);
    if (!ok) return PrimSetupStatus::kOutOfRange;
    const int64_t x0 = int64_t{sx} - fw / 2, y0 = int64_t{sy} - fw / 2;
    if (x0 < INT32_MIN || x0 + fw > INT32_MAX || y0 < INT32_MIN || y0 + fw > INT32_MAX)
        return PrimSetupStatus::kOutOfRange;
    out->x0 = static_cast<int32_t>(x0);
    out->x1 = static_cast<int32_t>(x0 + fw);
    out->y0 = static_cast<int32_t>(y0);
    out->y1 = static_cast<int32_t>(y0 + fw);
    out->pos = AttribPlane{{0, 0, p[2], p[3]}, {1, 0, 0, 0}, {0, 1, 0, 0}};

    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) {
        AttribPlane& o = attribs[i];
        const float* a = attrib(v, i);
        const bool persp = cfg.layout.interp[i] == Interp::kPerspective;
        if (static_cast<int32_t>(i) == cfg.point_coord_attrib) {
            // texcoord_coef: s = 0.5 - (dadx*(x-0.5)), dadx = 256/fixed_width; 0.5 is a C double
            const float w0 = p[3];
            const bool pp = cfg.point_coord_perspective;
            const float d = 256.0f / static_cast<float>(fw);
            const float xc = p[0] - 0.5f;  // setup->pixel_offset, also in MSAA
            const float yc = p[1] - 0.5f;
            const float sx_sum = d * xc + 0.0f * yc;
            const float sy_sum = 0.0f * xc + d * yc;
            o.dadx[0] = d, o.dady[0] = 0.0f;
            o.a0[0] = static_cast<float>(0.5 - static_cast<double>(sx_sum));
            o.dadx[1] = 0.0f, o.dady[1] = d;
            o.a0[1] = static_cast<float>(0.5 - static_cast<double>(sy_sum));
            if (pp) {
                for (int ch = 0; ch < 2; ++ch) {
                    o.dadx[ch] *= w0;
                    o.dady[ch] *= w0;
                    o.a0[ch] *= w0;
                }
            }
            o.a0[2] = o.dadx[2] = o.dady[2] = 0.0f;
            o.a0[3] = pp ? w0 : 1.0f;
            o.dadx[3] = o.dady[3] = 0.0f;
            continue;
        }
        for (int ch = 0; ch < 4; ++ch) {
            o.a0[ch] = persp ? a[ch] * p[3] : a[ch];
            o.dadx[ch] = o.dady[ch] = 0.0f;
        }
    }
    return PrimSetupStatus::kOk;
}

}  // namespace tilevk::rast::geometry
