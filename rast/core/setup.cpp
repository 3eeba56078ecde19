// Triangle / convex / box setup from snapped vertices (lp_setup_tri.c calc_fixed_position, triangle_both/cw/ccw,
// do_triangle_ccw; lp_setup_point.c for boxes).
//
// Range proof for the 64-bit arithmetic here: |X|,|Y| < 2^22, so deltas are < 2^23 and every product DY*x is
// < 2^45; c = DY*x_i - DX*y_i + 1 < 2^46 + 1. Nothing here needs more than 64 bits. Triangles in the wide range
// (a coordinate past 2^22, all below 2^31 as in llvmpipe) must have |DX| + |DY| < 2^23 on every edge, so the same
// delta bound holds and c < 2^23 * 2^31 * 2 = 2^55; the rasterizer's in-tile 32-bit proof depends only on the
// deltas (tile_kernels.h), and its 64-bit tile setup on |c0| < 2^48.
#include "rast/core/setup.h"

#include <algorithm>
#include <cstdlib>

namespace tilevk::rast {

const char* to_string(SetupStatus s) {
    switch (s) {
        case SetupStatus::kAccepted:
            return "accepted";
        case SetupStatus::kCulled:
            return "culled";
        case SetupStatus::kDegenerate:
            return "degenerate";
        case SetupStatus::kClipped:
            return "clipped";
        case SetupStatus::kOutOfRange:
            return "out-of-range";
        case SetupStatus::kInvalid:
            return "invalid";
    }
    return "?";
}

namespace {

ClipRect intersect(const ClipRect& a, const ClipRect& b) {
    return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

uint16_t limit_mask(uint16_t mask, int samples) {
    return mask & static_cast<uint16_t>((1u << samples) - 1u);
}

// Sample X of pixel px satisfies px*256 <= X < px*256 + 256, hence "px >= x0" is "X - x0*256 + 1 > 0" and
// "px <= x1" is "(x1+1)*256 - X > 0".
EdgePlane min_x_plane(int32_t x0) {
    return {-int64_t{x0} * kFixedOne + 1, 1, 0};
}
EdgePlane min_y_plane(int32_t y0) {
    return {-int64_t{y0} * kFixedOne + 1, 0, 1};
}
EdgePlane max_x_plane(int32_t x1) {
    return {(int64_t{x1} + 1) * kFixedOne, -1, 0};
}
EdgePlane max_y_plane(int32_t y1) {
    return {(int64_t{y1} + 1) * kFixedOne, 0, -1};
}

SetupStatus finish_common(const PrimCommon& common, int samples, Prim* out) {
    out->payload = common.payload;
    out->sample_mask = limit_mask(common.sample_mask, samples);
    if (out->sample_mask == 0) return SetupStatus::kDegenerate;
    return SetupStatus::kAccepted;
}

// Clips the fixed-point pixel box [px0,px1]x[py0,py1] (inclusive) against clip ∩ fb and appends box planes
// on every side where the clip cut the box or force_min/force_max ask for one. Triangles need none of their own:
// outside the closed triangle some E <= -1, so E + bias <= 0 (min sides); on the max sides, the only closed-triangle
// points with X == maxX are the rightmost vertex or a vertical right edge, and the top-left rule excludes both (the
// lower/right edge through them has no bias and E == 0 there), so lavapipe's (maxX-1)>>8 cuts nothing the edges keep.
// At 4x every sample of pixel ((maxX-1)>>8)+1 has X >= maxX + 32. The method-equivalence tests (whose reference uses
// the box as loop bounds) check this argument on a million triangles.
SetupStatus finish_box(int32_t px0, int32_t py0, int32_t px1, int32_t py1, const PrimCommon& common, int samples,
                       const ClipRect& fb, bool force_min, bool force_max, Prim* out, PrimEdges* edges) {
    const ClipRect clip = intersect(common.clip, fb);
    const int32_t x0 = std::max(px0, clip.x0), y0 = std::max(py0, clip.y0);
    const int32_t x1 = std::min(px1, clip.x1 - 1), y1 = std::min(py1, clip.y1 - 1);
    if (x0 > x1 || y0 > y1) return SetupStatus::kClipped;
    out->x0 = x0, out->y0 = y0, out->x1 = x1, out->y1 = y1;
    if (const SetupStatus st = finish_common(common, samples, out); st != SetupStatus::kAccepted) return st;
    int n = out->num_shape_planes;
    out->num_scissor_planes = 0;
    if (x0 > px0 || force_min) edges->planes[n++] = min_x_plane(x0);
    if (y0 > py0 || force_min) edges->planes[n++] = min_y_plane(y0);
    if (x1 < px1 || force_max) edges->planes[n++] = max_x_plane(x1);
    if (y1 < py1 || force_max) edges->planes[n++] = max_y_plane(y1);
    out->num_planes = static_cast<uint8_t>(n);
    compute_pixel_planes(samples, *edges, out);
    return SetupStatus::kAccepted;
}

// lavapipe's inclusive pixel bbox of a triangle or line (lp_setup_tri.c / lp_setup_line.c), before the x0/y0 >= 0
// clamp: what it tests against draw_regions (= clip ∩ fb here), decides the scissor planes with and bins from.
struct LavapipeBox {
    int32_t x0, y0, x1, y1;
};

constexpr int32_t kLavapipeTile = 64;  // llvmpipe's TILE_SIZE: binning works on 64-px tiles of absolute position

// 4x triangles and lines as lavapipe 22.3 rasterizes them against draw_regions (framebuffer ∩ scissor ∩ viewport
// rectangle; Vulkan's scissor test discards whole pixels, lavapipe does not — a deliberate match, icd/README.md):
//  - scissor_planes_needed: a side gets a plane only where the bbox (x0, y0 clamped to 0) crosses the region;
//  - lp_setup_add_scissor_planes with adj = 127 at 4x: the left plane passes sample X iff X > (x0-1)*256 + 127,
//    i.e. pixel x0-1's samples 1 and 3 (sx 224, 160) and every sample from x0 on; the top plane likewise (rows:
//    samples 2 and 3, sy 160, 224). The right plane passes X < x1*256 + 254 and the bottom one Y < y1*256 + 254
//    (x1, y1 inclusive): every sample of the last column/row and none past it (max offset 224), i.e. whole pixels;
//  - no other clipping: coverage is the shape ∩ those planes ∩ the 64-px tiles binned from the bbox ∩ region
//    (lp_setup_bin_triangle's trimmed box; the single-tile path bins the bbox's own tile, the same one). So column
//    x0-1 is reached only when x0 % 64 != 0, and a line (whose bbox rounds min up, lp_setup_line.c) keeps its
//    samples in the column left of / row above its bbox wherever that column is in a binned tile — even outside
//    the region when the bbox itself starts at x0 (no plane then).
// At 1x the planes (adj 0) cut whole pixels at the region and no shape sample lies outside the bbox, so finish_box
// gives the same coverage; it stays the 1x path.
SetupStatus finish_box_msaa(int32_t px0, int32_t py0, int32_t px1, int32_t py1, const LavapipeBox& lp,
                            const PrimCommon& common, int samples, const ClipRect& fb, bool force_min, bool force_max,
                            Prim* out, PrimEdges* edges) {
    const ClipRect clip = intersect(common.clip, fb);
    const int32_t rx0 = clip.x0, ry0 = clip.y0, rx1 = clip.x1 - 1, ry1 = clip.y1 - 1;  // inclusive region
    if (rx0 > rx1 || ry0 > ry1) return SetupStatus::kClipped;
    // u_rect_test_intersection also fails when either rectangle is empty. A line's box is empty when no pixel
    // boundary lies in (minX, maxX] or (minY, maxY] (min rounds up, max rounds up minus one): lavapipe then drops
    // the whole line although 4x samples inside it exist (a sub-pixel line between two sample columns or rows).
    if (lp.x1 < lp.x0 || lp.y1 < lp.y0) return SetupStatus::kClipped;
    if (lp.x1 < rx0 || rx1 < lp.x0 || lp.y1 < ry0 || ry1 < lp.y0) return SetupStatus::kClipped;  // test_intersection
    const int32_t bx0 = std::max(lp.x0, 0), by0 = std::max(lp.y0, 0);
    const bool left = bx0<rx0, top = by0<ry0, right = lp.x1> rx1, bottom = lp.y1> ry1;
    // Tiles of the trimmed box (bbox ∩ region), as whole pixels.
    const int32_t tx0 = std::max(bx0, rx0) / kLavapipeTile * kLavapipeTile;
    const int32_t ty0 = std::max(by0, ry0) / kLavapipeTile * kLavapipeTile;
    const int32_t tx1 = (std::min(lp.x1, rx1) / kLavapipeTile + 1) * kLavapipeTile - 1;
    const int32_t ty1 = (std::min(lp.y1, ry1) / kLavapipeTile + 1) * kLavapipeTile - 1;
    int32_t x0 = std::max({px0, tx0, fb.x0}), y0 = std::max({py0, ty0, fb.y0});
    int32_t x1 = std::min({px1, tx1, fb.x1 - 1}), y1 = std::min({py1, ty1, fb.y1 - 1});
    if (left) x0 = std::max(x0, rx0 - 1);
    if (top) y0 = std::max(y0, ry0 - 1);
    if (right) x1 = std::min(x1, rx1);
    if (bottom) y1 = std::min(y1, ry1);
    if (x0 > x1 || y0 > y1) return SetupStatus::kClipped;
    out->x0 = x0, out->y0 = y0, out->x1 = x1, out->y1 = y1;
    if (const SetupStatus st = finish_common(common, samples, out); st != SetupStatus::kAccepted) return st;
    // One plane per side: a sample-exact scissor plane where the box stops at the partial column/row (it also
    // implies the whole-pixel bound there), else a box plane where the box is tighter than the shape.
    const bool left_plane = left && x0 == rx0 - 1, top_plane = top && y0 == ry0 - 1;
    constexpr int64_t kAdj = 127;
    int n = out->num_shape_planes;
    if (left_plane) edges->planes[n++] = {-(int64_t{rx0 - 1} * kFixedOne + kAdj), 1, 0};
    if (top_plane) edges->planes[n++] = {-(int64_t{ry0 - 1} * kFixedOne + kAdj), 0, 1};
    out->num_scissor_planes = static_cast<uint8_t>(n - out->num_shape_planes);
    if (!left_plane && (x0 > px0 || force_min)) edges->planes[n++] = min_x_plane(x0);
    if (!top_plane && (y0 > py0 || force_min)) edges->planes[n++] = min_y_plane(y0);
    if (x1 < px1 || force_max) edges->planes[n++] = max_x_plane(x1);
    if (y1 < py1 || force_max) edges->planes[n++] = max_y_plane(y1);
    out->num_planes = static_cast<uint8_t>(n);
    compute_pixel_planes(samples, *edges, out);
    return SetupStatus::kAccepted;
}

}  // namespace

void compute_pixel_planes(int samples, const PrimEdges& edges, Prim* prim) {
    for (int k = 0; k < prim->num_planes; ++k) {
        const EdgePlane& p = edges.planes[k];
        PixelPlane& q = prim->pix[k];
        q.a = p.a, q.b = p.b;
        // Sample 0 at 1x sits on the lattice (offset 0); at 4x at kSamplePos4x[0].
        int64_t cs[4] = {0, 0, 0, 0};
        for (int s = 0; s < samples; ++s) {
            const int64_t sx = samples == 1 ? 0 : kSamplePos4x[s][0], sy = samples == 1 ? 0 : kSamplePos4x[s][1];
            cs[s] = ceil_shift(p.c + p.a * sx + p.b * sy, kSubpixelBits);  // ceil((c + a*sx + b*sy) / 256)
        }
        q.c0 = cs[0];
        for (int s = 1; s < samples; ++s) prim->d[k][s - 1] = static_cast<int32_t>(cs[s] - cs[0]);
    }
}

namespace {

// Snapped coordinates (lavapipe's range) and the exact area dx01*dy20 - dx20*dy01 (|d| < 2^23, products < 2^46);
// false out of range.
bool snap_triangle(const TriangleInput& in, int samples, int32_t x[3], int32_t y[3], int64_t* area) {
    const float offset = triangle_snap_offset(samples);
    bool wide = false;
    for (int i = 0; i < 3; ++i) {
        if (!snap_triangle_coord_lavapipe(in.x[i], offset, &x[i]) ||
            !snap_triangle_coord_lavapipe(in.y[i], offset, &y[i]))
            return false;
        wide |= x[i] <= -kMaxFixed || x[i] >= kMaxFixed || y[i] <= -kMaxFixed || y[i] >= kMaxFixed;
    }
    if (wide) {
        // llvmpipe computes every edge's dcdx, dcdy (deltas times 256) and their trivial-reject offset eo
        // (|dcdx| + |dcdy| at worst) in 32 bits: exact while |DX| + |DY| < 2^23, which is also what keeps tilevk's
        // 32-bit in-tile evaluation exact. Past it llvmpipe's planes wrap; such a triangle is not set up (it can
        // only come from the clipper's cancellation on enormous inputs, rast/geometry/README.md).
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            if (std::abs(int64_t{x[i]} - x[j]) + std::abs(int64_t{y[i]} - y[j]) >= kMaxLavapipeEdge)
                return false;
        }
    }
    *area = int64_t{x[0] - x[1]} * (y[2] - y[0]) - int64_t{x[2] - x[0]} * (y[0] - y[1]);
    return true;
}

// CW -> CCW keeping the provoking vertex: (v0,v2,v1) with flatshade_first, else (v1,v0,v2).
void ccw_order(bool ccw, bool flatshade_first, int order[3]) {
    order[0] = 0, order[1] = 1, order[2] = 2;
    if (ccw) return;
    if (flatshade_first)
        std::swap(order[1], order[2]);
    else
        std::swap(order[0], order[1]);
}

}  // namespace

void triangle_vertex_order(const TriangleInput& in, int samples, int order[3]) {
    int32_t x[3], y[3];
    int64_t area = 0;
    ccw_order(!snap_triangle(in, samples, x, y, &area) || area >= 0, in.flatshade_first, order);
}

SetupStatus setup_triangle(const TriangleInput& in, int samples, const ClipRect& fb, Prim* out, PrimEdges* edges) {
    int32_t x[3], y[3];
    int64_t area = 0;
    if (!snap_triangle(in, samples, x, y, &area)) return SetupStatus::kOutOfRange;
    if (area == 0) return SetupStatus::kDegenerate;
    const bool ccw = area > 0;
    const bool front = ccw == in.front_ccw;
    if ((front && (static_cast<int>(in.cull) & static_cast<int>(CullMode::kFront))) ||
        (!front && (static_cast<int>(in.cull) & static_cast<int>(CullMode::kBack))))
        return SetupStatus::kCulled;
    int order[3];
    ccw_order(ccw, in.flatshade_first, order);
    int32_t vx[3], vy[3];
    for (int i = 0; i < 3; ++i) {
        vx[i] = x[order[i]], vy[i] = y[order[i]];
        edges->fx[i] = in.x[order[i]], edges->fy[i] = in.y[order[i]];
    }
    out->front_facing = front;
    out->is_triangle = true;
    // Edge i -> j: E = DY*(x_i - X) - DX*(y_i - Y) + bias, i.e. a = -DY, b = DX, c = DY*x_i - DX*y_i + bias,
    // bias = 1 when DY < 0 || (DY == 0 && DX > 0) (top-left rule, y down); DX < 0 with the bottom-left rule.
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const int32_t dy = vy[i] - vy[j], dx = vx[i] - vx[j];
        const bool horizontal_bias = in.bottom_edge_rule ? dx < 0 : dx > 0;
        const int64_t bias = (dy < 0 || (dy == 0 && horizontal_bias)) ? 1 : 0;
        edges->planes[i] = {int64_t{dy} * vx[i] - int64_t{dx} * vy[i] + bias, -dy, dx};
    }
    out->num_shape_planes = 3;
    // Inclusive pixel box: x0 = minX>>8, x1 = (maxX-1)>>8 (arithmetic shifts = floor); y likewise, one unit
    // lower with the bottom-left rule (lp_setup_tri.c's adj).
    const int32_t minx = std::min({vx[0], vx[1], vx[2]}), maxx = std::max({vx[0], vx[1], vx[2]});
    const int32_t miny = std::min({vy[0], vy[1], vy[2]}), maxy = std::max({vy[0], vy[1], vy[2]});
    const int32_t adj = in.bottom_edge_rule ? 1 : 0;
    const int32_t px0 = minx >> kSubpixelBits, py0 = (miny + adj) >> kSubpixelBits;
    const int32_t px1 = (maxx - 1) >> kSubpixelBits, py1 = (maxy - 1 + adj) >> kSubpixelBits;
    if (samples > 1)  // lp_setup_tri.c's bbox is the pixel box itself
        return finish_box_msaa(px0, py0, px1, py1, {px0, py0, px1, py1}, in.common, samples, fb, false, false, out,
                               edges);
    return finish_box(px0, py0, px1, py1, in.common, samples, fb, /*force_min=*/false, /*force_max=*/false, out, edges);
}

SetupStatus setup_convex(const ConvexInput& in, int samples, const ClipRect& fb, Prim* out, PrimEdges* edges) {
    if (in.num_planes < 1 || in.num_planes > 4) return SetupStatus::kInvalid;
    for (int i = 0; i < in.num_planes; ++i) {
        const EdgePlane& p = in.planes[i];
        if (p.a <= -(1 << 23) || p.a >= (1 << 23) || p.b <= -(1 << 23) || p.b >= (1 << 23) ||
            p.c <= -(int64_t{1} << 47) || p.c >= (int64_t{1} << 47))
            return SetupStatus::kInvalid;
        edges->planes[i] = p;
    }
    for (int32_t v : {in.min_x, in.min_y, in.max_x, in.max_y})
        if (v <= -kMaxFixed || v >= kMaxFixed) return SetupStatus::kOutOfRange;
    if (in.min_x >= in.max_x || in.min_y >= in.max_y) return SetupStatus::kDegenerate;
    out->num_shape_planes = static_cast<uint8_t>(in.num_planes);
    out->front_facing = in.front_facing;
    out->is_triangle = false;
    const int32_t px0 = in.min_x >> kSubpixelBits, py0 = in.min_y >> kSubpixelBits;
    const int32_t px1 = (in.max_x - 1) >> kSubpixelBits, py1 = (in.max_y - 1) >> kSubpixelBits;
    if (samples > 1) {
        // lp_setup_line.c's bbox (top-left rule: bottom_edge_rule 0): min rounded up, max rounded up minus one.
        const LavapipeBox lp = {
            (in.min_x + kFixedOne - 1) >> kSubpixelBits, (in.min_y + kFixedOne - 1) >> kSubpixelBits,
            ((in.max_x + kFixedOne - 1) >> kSubpixelBits) - 1, ((in.max_y + kFixedOne - 1) >> kSubpixelBits) - 1};
        return finish_box_msaa(px0, py0, px1, py1, lp, in.common, samples, fb, true, true, out, edges);
    }
    return finish_box(px0, py0, px1, py1, in.common, samples, fb, /*force_min=*/true, /*force_max=*/true, out, edges);
}

SetupStatus setup_box(const BoxInput& in, int samples, const ClipRect& fb, Prim* out, PrimEdges* edges) {
    for (int32_t v : {in.x0, in.y0, in.x1, in.y1})
        if (v <= -kMaxFixed || v >= kMaxFixed) return SetupStatus::kOutOfRange;
    if (in.x0 >= in.x1 || in.y0 >= in.y1) return SetupStatus::kDegenerate;
    // x0 <= X < x1 as planes: X - x0 + 1 > 0 and x1 - X > 0 (lavapipe's point planes with c++ on left/top).
    edges->planes[0] = {-int64_t{in.x0} + 1, 1, 0};
    edges->planes[1] = {-int64_t{in.y0} + 1, 0, 1};
    edges->planes[2] = {int64_t{in.x1}, -1, 0};
    edges->planes[3] = {int64_t{in.y1}, 0, -1};
    out->num_shape_planes = 4;
    out->front_facing = in.front_facing;
    out->is_triangle = false;
    return finish_box(in.x0 >> kSubpixelBits, in.y0 >> kSubpixelBits, (in.x1 - 1) >> kSubpixelBits,
                      (in.y1 - 1) >> kSubpixelBits, in.common, samples, fb, /*force_min=*/false,
                      /*force_max=*/false, out, edges);
}

}  // namespace tilevk::rast
