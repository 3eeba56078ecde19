// llvmpipe's rectangle path (lp_setup_rect.c): two triangles handed to setup together are tested for an
// axis-aligned rectangle; a rectangle is set up once from three corners and covers the box of its snapped corners
// (no edge functions). Which triangle pairs are offered is the caller's business (lp_setup_vbuf.c: 6N-vertex
// lists, strip pairs, 4-vertex fans; rast/geometry/README.md "Linear mode").
#pragma once

#include <cstdint>

#include "rast/geometry/vertex.h"

namespace tilevk::rast::geometry {

// lp_setup_rect.c winding(): det = fl(fl(ex*fy) - fl(ey*fx)), e = v0 - v2, f = v1 - v2 (window x, y).
// det < 0 is ccw, det > 0 cw, 0 (or NaN) none.
enum class Winding : uint8_t { kNone, kCcw, kCw };
Winding float_winding(const float* win0, const float* win1, const float* win2);

struct RectPairConfig {
    VertexLayout layout;  // attributes tested for coplanarity (all four components of every slot)
    bool cull_front = false, cull_back = false;
    bool front_ccw = true;  // VK_FRONT_FACE_COUNTER_CLOCKWISE (lavapipe's ccw_is_frontface)
};

// What setup->rect (setup_rect_both / _ccw / _cw / _noop, chosen by the cull mode) does with the triangles
// (t0[0], t0[1], t0[2]) and (t1[0], t1[1], t1[2]) as lp_setup_vbuf.c rect() hands them over.
struct RectDecision {
    enum Kind : uint8_t {
        kTriangles,       // returned false: both triangles through the normal triangle setup, in order
        kRect,            // a rectangle: lp_rect_cw(corner[0], corner[1], corner[2], front)
        kFirstTriangle,   // only t0 through the triangle setup (its fixed-point cull still applies)
        kSecondTriangle,  // only t1
        kNothing,         // both dropped (zero float windings, culled windings, or cull FRONT_AND_BACK)
    };
    Kind kind = kTriangles;
    const float* corner[3] = {nullptr, nullptr, nullptr};
    bool front = true;
};
RectDecision decide_rect_pair(const RectPairConfig& cfg, const float* const t0[3], const float* const t1[3]);

// do_rect_ccw on two ccw triangles: the nine ways they can share a diagonal, axis alignment (exact float
// compares of window x and y), equal 1/w at the four corners, and coplanar attributes (for each component:
// fl(rv0 - rv3) == fl(rv1 - rv2) and fl(rv0 - rv1) == fl(rv3 - rv2)). On success sets corner = (rv0, rv2, rv1).
bool match_rect_ccw(const VertexLayout& layout, const float* const v[6], const float* corner[3]);

// try_rect_cw's coverage: corners snapped with util_iround(256 * fl(x - pixel_offset)) (half away from zero,
// after a float add), culled when (x2 < x1) ^ (y0 < y2), else the inclusive pixel box
// x0 = (min + 255) >> 8, x1 = ((max + 255) >> 8) - 1 (same for y with the top-left rule; with lavapipe's
// bottom_edge_rule, u_blitter's, y adds one more unit: (min + 256) >> 8, ((max + 256) >> 8) - 1).
struct RectBox {
    bool culled = true;
    int32_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive; may be empty (x0 > x1) for sub-pixel rectangles
};
RectBox rect_box(const float* win0, const float* win1, const float* win2, float pixel_offset,
                 bool bottom_edge_rule = false);

// util_iround(256 * a) on x86-64 (u_math.h): (int)(f + 0.5f) for f >= 0, else (int)(f - 0.5f). Out-of-int and
// NaN values give INT32_MIN (cvttss2si), like the C cast on x86-64.
int32_t subpixel_snap_iround(float a);

}  // namespace tilevk::rast::geometry
