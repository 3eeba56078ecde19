#include "rast/geometry/clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace tilevk::rast::geometry {
namespace {

// draw_context.c planes; plane 4 becomes (0,0,1,0) with clip_halfz (draw_pt_post_vs.c).
constexpr float kPlanes[6][4] = {
    {-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1},
};
// draw_pt_post_vs.c with guard_band_xy (llvmpipe's linear mode): x/y planes |x|, |y| <= 2w.
constexpr float kGuardBandPlanes[4][4] = {{-0.5f, 0, 0, 1}, {0.5f, 0, 0, 1}, {0, -0.5f, 0, 1}, {0, 0.5f, 0, 1}};

bool is_inf_or_nan(float f) {
    return !std::isfinite(f);
}

// LINTERP(T, OUT, IN) = OUT + T*(IN - OUT), each operation rounded to float.
void interp4(float* dst, float t, const float* in, const float* out) {
    for (int i = 0; i < 4; ++i) {
        const float d = in[i] - out[i];
        const float m = t * d;
        dst[i] = out[i] + m;
    }
}

bool has_flat(const VertexLayout& l) {
    for (uint32_t i = 0; i < l.num_attribs; ++i)
        if (l.interp[i] == Interp::kFlat) return true;
    return false;
}

void copy_flat(const VertexLayout& l, float* dst, const float* src) {
    for (uint32_t i = 0; i < l.num_attribs; ++i)
        if (l.interp[i] == Interp::kFlat) std::memcpy(dst + kAttribOffset + 4 * i, attrib(src, i), 16);
}

// draw_pipe_clip.c interp(): dst = out + t*(in - out) in clip space, window coords in C, attributes by mode.
void interp(const ClipConfig& cfg, float* dst, float t, const float* out, const float* in) {
    interp4(dst + kClipPosOffset, t, clip_pos(in), clip_pos(out));
    viewport_transform_c(cfg.vp, dst + kClipPosOffset, dst + kWinPosOffset);
    bool any_linear = false;
    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i) {
        float* d = dst + kAttribOffset + 4 * i;
        switch (cfg.layout.interp[i]) {
            case Interp::kPerspective:
                interp4(d, t, attrib(in, i), attrib(out, i));
                break;
            case Interp::kNoPerspective:
                any_linear = true;
                break;
            case Interp::kFlat:
                std::memcpy(d, attrib(out, i), 16);
                break;  // never read unless copied over
        }
    }
    if (!any_linear) return;
    // Screen-space t for noperspective attributes: first of x, y where the endpoints differ in clip space;
    // coordinates divided by w with a real division; otherwise the 3D t.
    float t_nopersp = t;
    const float* ci = clip_pos(in);
    const float* co = clip_pos(out);
    const float* cd = dst + kClipPosOffset;
    for (int k = 0; k < 2; ++k) {
        if (ci[k] != co[k]) {
            const float in_coord = ci[k] / ci[3];
            const float out_coord = co[k] / co[3];
            const float dst_coord = cd[k] / cd[3];
            t_nopersp = (dst_coord - out_coord) / (in_coord - out_coord);
            break;
        }
    }
    for (uint32_t i = 0; i < cfg.layout.num_attribs; ++i)
        if (cfg.layout.interp[i] == Interp::kNoPerspective)
            interp4(dst + kAttribOffset + 4 * i, t_nopersp, attrib(in, i), attrib(out, i));
}

// Whether the float interpolation of a new vertex's position (interp4: out + t*(in - out), three roundings per
// component) may be off by more than 1/1024 px in window x or y: each rounding errs by at most 2^-24 of its result,
// so a component errs by about 2^-24 (|d t| + |t d| + |dst|) <= 2^-23 (|t d| + |dst|), and the window position
// x/w * scale by (e_x + |x/w| e_w) / |w| * scale. Only cancellation between huge inputs gets there: ordinary
// vertices err by 1e-5 px.
bool interp_imprecise(const ClipConfig& cfg, const float* dst, float t, const float* in, const float* out) {
    float e[4];
    for (int i = 0; i < 4; ++i) e[i] = 0x1p-23f * (std::fabs(t * (in[i] - out[i])) + std::fabs(dst[i]));
    const float w = std::fabs(dst[3]);
    for (int i = 0; i < 2; ++i) {
        const float px = (e[i] + std::fabs(dst[i] / dst[3]) * e[3]) / w * std::fabs(cfg.vp.scale[i]);
        if (!(px <= 1.0f / 1024)) return true;  // NaN too
    }
    return false;
}

// A polygon in window coordinates (x, y, z).
using WinPoint = std::array<double, 3>;
using WinPolygon = std::vector<WinPoint>;

// The polygon a fan of clipped triangles came from, in window coordinates (clip_triangle_float's emit order).
WinPolygon fan_polygon(const ClipConfig& cfg, const ClippedTriangle* tri, uint32_t n) {
    WinPolygon p;
    auto add = [&](const float* r) { p.push_back({win_pos(r)[0], win_pos(r)[1], win_pos(r)[2]}); };
    if (cfg.flatshade_first) {
        add(tri[0].v[0]);
        for (uint32_t t = 0; t < n; ++t) add(tri[t].v[1]);
        add(tri[n - 1].v[2]);
    } else {
        add(tri[0].v[2]);
        for (uint32_t t = 0; t < n; ++t) add(tri[t].v[0]);
        add(tri[n - 1].v[1]);
    }
    return p;
}

// The part of a polygon that can draw anything: inside the viewport rectangle, and at the window depths the depth
// test does not reject outright (ClipConfig::hidden_depth). Sutherland-Hodgman in double; depth is affine in window
// coordinates over a triangle, so an edge crosses z = 1 (or 0) where the linear interpolation says.
WinPolygon visible_part(const ClipConfig& cfg, WinPolygon p) {
    const double lo[3] = {double(cfg.vp.translate[0]) - std::fabs(cfg.vp.scale[0]),
                          double(cfg.vp.translate[1]) - std::fabs(cfg.vp.scale[1]),
                          cfg.hidden_depth == HiddenDepth::kUpToZero ? 0.0 : -HUGE_VAL};
    const double hi[3] = {double(cfg.vp.translate[0]) + std::fabs(cfg.vp.scale[0]),
                          double(cfg.vp.translate[1]) + std::fabs(cfg.vp.scale[1]),
                          cfg.hidden_depth == HiddenDepth::kFromOne ? 1.0 : HUGE_VAL};
    const int sides = cfg.hidden_depth == HiddenDepth::kNone ? 4 : 6;
    for (int side = 0; side < sides && !p.empty(); ++side) {
        const int axis = side / 2;
        const double limit = side % 2 ? hi[axis] : lo[axis];
        if (std::isinf(limit)) continue;
        auto inside = [&](const WinPoint& q) { return side % 2 ? !(q[axis] > limit) : !(q[axis] < limit); };
        WinPolygon out;
        for (size_t i = 0; i < p.size(); ++i) {
            const WinPoint &a = p[i], &b = p[(i + 1) % p.size()];
            if (inside(a)) out.push_back(a);
            if (inside(a) != inside(b)) {
                const double t = (limit - a[axis]) / (b[axis] - a[axis]);
                out.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])});
            }
        }
        p = std::move(out);
    }
    return p;
}

// Whether point q lies in polygon p (crossing test) or within `tol` of its boundary.
bool near_polygon(const WinPoint& q, const WinPolygon& p, double tol) {
    bool in = false;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        const WinPoint &a = p[i], &b = p[j];
        if ((a[1] > q[1]) != (b[1] > q[1]) && q[0] < (b[0] - a[0]) * (q[1] - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
        const double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
        const double t = len2 > 0 ? std::clamp(((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len2, 0.0, 1.0) : 0.0;
        const double ex = a[0] + t * dx - q[0], ey = a[1] + t * dy - q[1];
        if (ex * ex + ey * ey <= tol * tol) return true;
    }
    return in;
}

// Whether two clip results cover the same part of the viewport up to half a fixed-point step (1/512 px): every
// corner of either region lies in the other or that close to it (lavapipe's float result then rasterizes as the
// precise one would, e.g. when its imprecise vertex lies far outside the viewport on a shared edge).
bool same_visible_region(const WinPolygon& pa, const WinPolygon& pb) {
    if (pa.empty() || pb.empty()) return pa.empty() == pb.empty();
    for (const auto& q : pa)
        if (!near_polygon(q, pb, 1.0 / 512)) return false;
    for (const auto& q : pb)
        if (!near_polygon(q, pa, 1.0 / 512)) return false;
    return true;
}

// Where a sample point lies against a convex polygon: inside, outside, or within `tol` of its boundary (then the
// fixed-point snap of either result may decide it either way).
enum class PointSide { kInside, kOutside, kNear };

PointSide point_side(const WinPoint& q, const WinPolygon& p, double tol) {
    bool in = false;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        const WinPoint &a = p[i], &b = p[j];
        const double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
        const double t = len2 > 0 ? std::clamp(((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len2, 0.0, 1.0) : 0.0;
        const double ex = a[0] + t * dx - q[0], ey = a[1] + t * dy - q[1];
        if (ex * ex + ey * ey <= tol * tol) return PointSide::kNear;
        if ((a[1] > q[1]) != (b[1] > q[1]) && q[0] < dx * (q[1] - a[1]) / dy + a[0]) in = !in;
    }
    return in ? PointSide::kInside : PointSide::kOutside;
}

// Whether draw's clip result `a` covers the sample points of the viewport that the precise result `b` decides: at
// every pixel centre (1x) or standard 4x sample position (both sets at another count) at least 1/128 px from b's
// boundary (nearer, the exact check does not judge either: cts_subset exact_coverage), a lies on b's side and at
// least 1/256 px from its own boundary (one fixed-point step: the snap may move an edge by half of it). Then draw's
// float result rasterizes the exact coverage although its polygon differs from the precise one by more than
// same_visible_region allows (cancellation moves a vertex far outside the viewport along an edge), and only its
// depth and attribute roundings differ: lavapipe's are kept. Bounded work: false for regions over 2^18 pixels.
bool same_sample_coverage(const ClipConfig& cfg, const WinPolygon& pa, const WinPolygon& pb) {
    if (pa.size() < 3 || pb.size() < 3) return false;
    double lo[2] = {pa[0][0], pa[0][1]}, hi[2] = {pa[0][0], pa[0][1]};
    for (const auto* poly : {&pa, &pb})
        for (const auto& q : *poly)
            for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
    const double x0 = std::floor(lo[0]), y0 = std::floor(lo[1]), x1 = std::ceil(hi[0]), y1 = std::ceil(hi[1]);
    if ((x1 - x0) * (y1 - y0) > double(1 << 18)) return false;
    constexpr double kOffsets[5][2] = {{0.5, 0.5}, {0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
    const size_t first = cfg.samples == 4 ? 1 : 0, end = cfg.samples == 1 ? 1 : 5;
    constexpr double kJudged = 1.0 / 128, kSnap = 1.0 / 256;
    for (double y = y0; y < y1; ++y)
        for (double x = x0; x < x1; ++x)
            for (size_t k = first; k < end; ++k) {
                const WinPoint q = {x + kOffsets[k][0], y + kOffsets[k][1], 0.0};
                const PointSide sb = point_side(q, pb, kJudged);
                if (sb != PointSide::kNear && point_side(q, pa, kSnap) != sb) return false;
            }
    return true;
}

// Whether draw's clip result `a` draws what the precise result `b` draws: the same visible part (visible_part) of
// the viewport, or the same sample points of it.
bool same_drawn_region(const ClipConfig& cfg, const ClippedTriangle* a, uint32_t na, const ClippedTriangle* b,
                       uint32_t nb) {
    const WinPolygon pa = na ? visible_part(cfg, fan_polygon(cfg, a, na)) : WinPolygon();
    const WinPolygon pb = visible_part(cfg, fan_polygon(cfg, b, nb));
    return same_visible_region(pa, pb) || same_sample_coverage(cfg, pa, pb);
}

}  // namespace

float clip_plane_distance(const float c[4], uint32_t plane, bool clip_halfz, bool guard_band_xy) {
    const float* p = (guard_band_xy && plane < 4) ? kGuardBandPlanes[plane] : kPlanes[plane];
    const float p4w = (plane == 4 && clip_halfz) ? 0.0f : p[3];
    // dot4: ((a0*b0 + a1*b1) + a2*b2) + a3*b3, every product and sum rounded
    const float m0 = c[0] * p[0], m1 = c[1] * p[1], m2 = c[2] * p[2], m3 = c[3] * p4w;
    const float s01 = m0 + m1;
    const float s012 = s01 + m2;
    return s012 + m3;
}

namespace {

// draw_pipe_clip.c getclipdist: the frustum planes' dot product on the clip position, or a user plane's
// ClipDistance element as the record holds it (interpolated at new vertices).
float plane_distance(const ClipConfig& cfg, const float* rec, uint32_t plane) {
    if (plane < kClipUserShift) return clip_plane_distance(clip_pos(rec), plane, cfg.clip_halfz, cfg.guard_band_xy);
    return clip_distance_element(cfg, rec, plane - kClipUserShift);
}

// The clip-mask bits the clipper walks: the six frustum planes and the written ClipDistance planes.
uint32_t clip_planes(const ClipConfig& cfg) {
    return 0x3Fu | (((1u << cfg.num_clip_distances) - 1u) << kClipUserShift);
}

// draw's do_clip_tri in float. *imprecise: a plane distance overflowed to Inf/NaN, or an intersection parameter
// underflowed to 0 (FTZ) although the vertex was off the plane: the float result is not the triangle's clip.
uint32_t clip_triangle_float(const ClipConfig& cfg, const float* v0, const float* v1, const float* v2,
                             uint32_t clipmask, float* scratch, ClippedTriangle* out, bool* imprecise) {
    const uint32_t stride = vertex_floats(cfg.layout);
    // Vertex lists with, per position, the vertex's own edge flag (vertex_header.edgeflag: 1 for shaded
    // vertices) and the flag of the edge from this position to the next (the header's DRAW_PIPE_EDGE_FLAG_k).
    const float* a[kMaxClippedVertices];
    const float* b[kMaxClippedVertices];
    bool va[kMaxClippedVertices], vb[kMaxClippedVertices];
    bool ea[kMaxClippedVertices], eb[kMaxClippedVertices];
    const float** inlist = a;
    const float** outlist = b;
    bool *in_vflag = va, *out_vflag = vb;
    bool *in_edge = ea, *out_edge = eb;
    uint32_t tmpnr = 0;
    uint32_t n = 3;
    inlist[0] = v0;
    inlist[1] = v1;
    inlist[2] = v2;
    for (int i = 0; i < 3; ++i) {
        in_vflag[i] = in_edge[i] = true;  // decomposition: DRAW_PIPE_EDGE_FLAG_ALL
    }

    while (clipmask && n >= 3) {
        const uint32_t plane = static_cast<uint32_t>(__builtin_ctz(clipmask));
        clipmask &= ~(1u << plane);
        const float* vert_prev = inlist[0];
        bool vflag_prev = in_vflag[0];
        bool edge_prev = in_edge[0];
        const bool user_plane = plane >= kClipUserShift;
        float dp_prev = plane_distance(cfg, vert_prev, plane);
        if (is_inf_or_nan(dp_prev)) {
            *imprecise = true;
            return 0;
        }
        if (n >= kMaxClippedVertices) return 0;
        inlist[n] = inlist[0];  // close the polygon without rotating it
        in_vflag[n] = in_vflag[0];
        in_edge[n] = in_edge[0];
        uint32_t outcount = 0;
        for (uint32_t i = 1; i <= n; ++i) {
            const float* vert = inlist[i];
            const float dp = plane_distance(cfg, vert, plane);
            if (is_inf_or_nan(dp)) {
                *imprecise = true;
                return 0;
            }
            bool different_sign;
            if (dp_prev >= 0.0f) {
                if (outcount >= kMaxClippedVertices) return 0;
                out_vflag[outcount] = vflag_prev;
                out_edge[outcount] = edge_prev;
                outlist[outcount++] = vert_prev;
                different_sign = dp < 0.0f;
            } else {
                different_sign = !(dp < 0.0f);
            }
            if (different_sign) {
                if (tmpnr >= kClipScratchVertices) return 0;
                float* nv = scratch + static_cast<size_t>(stride) * tmpnr++;
                if (outcount >= kMaxClippedVertices) return 0;
                // The edge from a new vertex keeps the flag of the edge it was cut from. The vertex flag hides
                // the edge along a frustum plane: a vertex going out gets 0, one coming back in copies the
                // flag of the (outside) vertex before it. Along a user plane the edge is shown: a vertex going
                // out sets both flags.
                const bool going_out_user = dp < 0.0f && user_plane;
                out_edge[outcount] = going_out_user ? true : edge_prev;
                out_vflag[outcount] = going_out_user ? true : (dp < 0.0f ? false : vflag_prev);
                outlist[outcount++] = nv;
                const float denom = dp - dp_prev;
                // Interpolate from the vertex nearer the plane so |t| <= 0.5.
                const bool from_vert = dp < 0.0f ? -dp < dp_prev : !(-dp_prev < dp);  // going out / coming back in
                const float num = from_vert ? dp : -dp_prev;
                const float t = num / denom;
                *imprecise |= t == 0.0f && num != 0.0f;  // underflow, or flushed by FTZ as in lavapipe
                if (from_vert)
                    interp(cfg, nv, t, vert, vert_prev);
                else
                    interp(cfg, nv, t, vert_prev, vert);
                if (!*imprecise)
                    *imprecise = interp_imprecise(cfg, clip_pos(nv), t, clip_pos(from_vert ? vert_prev : vert),
                                                  clip_pos(from_vert ? vert : vert_prev));
            }
            vert_prev = vert;
            vflag_prev = in_vflag[i];
            edge_prev = in_edge[i];
            dp_prev = dp;
        }
        std::swap(inlist, outlist);
        std::swap(in_vflag, out_vflag);
        std::swap(in_edge, out_edge);
        n = outcount;
    }
    if (n < 3) return 0;

    const float* provoking = cfg.flatshade_first ? v0 : v2;
    if (has_flat(cfg.layout) && inlist[0] != provoking) {
        if (tmpnr >= kClipScratchVertices) return 0;
        float* dup = scratch + static_cast<size_t>(stride) * tmpnr++;
        std::memcpy(dup, inlist[0], sizeof(float) * stride);
        copy_flat(cfg.layout, dup, provoking);
        inlist[0] = dup;  // dup_vert copies the vertex flag too
    }
    // emit_poly: a fan around inlist[0] in the provoking-vertex order. Header flags: the first triangle carries
    // the edge in[0]->in[1], each the edge in[i-1]->in[i], the last in[n-1]->in[0]; the fan's inner edges none.
    // Triangle edge bit k (the edge from tri.v[k]) is in flag slot 0/1/2 as first/middle/last with
    // flatshade_first, else 2/0/1.
    const uint8_t edge_first = cfg.flatshade_first ? 1 : 4;
    const uint8_t edge_middle = cfg.flatshade_first ? 2 : 1;
    const uint8_t edge_last = cfg.flatshade_first ? 4 : 2;
    uint8_t flags = static_cast<uint8_t>((in_edge[0] ? edge_first : 0) | edge_middle);
    uint32_t count = 0;
    for (uint32_t i = 2; i < n; ++i, flags = edge_middle) {
        uint32_t pos[3];
        if (cfg.flatshade_first) {
            pos[0] = 0, pos[1] = i - 1, pos[2] = i;
        } else {
            pos[0] = i - 1, pos[1] = i, pos[2] = 0;
        }
        if (!in_edge[i - 1]) flags &= static_cast<uint8_t>(~edge_middle);
        if (i == n - 1 && in_edge[i]) flags |= edge_last;
        // draw_pipe_unfilled: edge k (corner k) is drawn iff header flag k and tri.v[k]->edgeflag
        uint8_t edges = 0;
        for (int k = 0; k < 3; ++k)
            if ((flags & (1u << k)) && in_vflag[pos[k]]) edges |= static_cast<uint8_t>(1u << k);
        out[count++] = {{inlist[pos[0]], inlist[pos[1]], inlist[pos[2]]}, edges};
    }
    return count;
}

}  // namespace

uint32_t clip_triangle(const ClipConfig& cfg, const float* v0, const float* v1, const float* v2, uint32_t m0,
                       uint32_t m1, uint32_t m2, float* scratch, ClippedTriangle* out) {
    uint32_t clipmask = m0 | m1 | m2;
    if (clipmask == 0) {
        out[0] = {{v0, v1, v2}, kAllEdges};
        return 1;
    }
    if ((m0 & m1 & m2) != 0) return 0;
    clipmask &= clip_planes(cfg);
    if (!cfg.cut_xy) clipmask &= ~0xFu;  // polygonMode POINT: rejected whole by x/y, never cut (ClipConfig::cut_xy)
    bool imprecise = false;
    const uint32_t n = clip_triangle_float(cfg, v0, v1, v2, clipmask, scratch, out, &imprecise);
    // The precise clipper knows the frustum planes only: with a user plane cut, draw's result stands.
    const bool user_cut = (clipmask >> kClipUserShift) != 0;
    if (!cfg.precise_fallback || cfg.guard_band_xy || user_cut || !clip_inputs_finite(v0, v1, v2)) return n;
    const bool unrepresentable = clip_needs_precision(v0, v1, v2, out, n);
    if (!imprecise && !unrepresentable) return n;
    // The precise clip, into scratch of its own; adopted only when lavapipe's result is materially wrong: not
    // rasterizable faithfully, or another polygon, or a vertex more than half a fixed-point step away.
    const uint32_t stride = vertex_floats(cfg.layout);
    thread_local std::vector<float> precise_scratch;
    precise_scratch.resize(size_t(kClipScratchVertices) * stride);
    ClippedTriangle precise[kMaxClippedTriangles];
    const uint32_t pn = clip_triangle_precise(cfg, v0, v1, v2, clipmask, precise_scratch.data(), precise);
    if (!unrepresentable && (pn == 0 || same_drawn_region(cfg, out, n, precise, pn))) return n;
    std::memcpy(scratch, precise_scratch.data(), sizeof(float) * precise_scratch.size());
    const float* base = precise_scratch.data();
    for (uint32_t t = 0; t < pn; ++t) {
        out[t] = precise[t];
        for (const float*& r : out[t].v)
            if (r >= base && r < base + precise_scratch.size()) r = scratch + (r - base);
    }
    return pn;
}

bool clip_line(const ClipConfig& cfg, const float* v0, const float* v1, uint32_t m0, uint32_t m1, float* scratch,
               const float** out0, const float** out1) {
    const uint32_t mask = m0 | m1;
    *out0 = v0;
    *out1 = v1;
    if (mask == 0) return true;
    if ((m0 & m1) != 0) return false;
    uint32_t clipmask = mask & clip_planes(cfg);
    float t0 = 0.0f, t1 = 0.0f;
    while (clipmask) {
        const uint32_t plane = static_cast<uint32_t>(__builtin_ctz(clipmask));
        const float dp0 = plane_distance(cfg, v0, plane);
        const float dp1 = plane_distance(cfg, v1, plane);
        if (is_inf_or_nan(dp0) || is_inf_or_nan(dp1)) return false;
        if (dp1 < 0.0f) {
            const float t = dp1 / (dp1 - dp0);
            t1 = t1 > t ? t1 : t;  // MAX2
        }
        if (dp0 < 0.0f) {
            const float t = dp0 / (dp0 - dp1);
            t0 = t0 > t ? t0 : t;
        }
        if (t0 + t1 >= 1.0f) return false;
        clipmask &= ~(1u << plane);
    }
    const uint32_t stride = vertex_floats(cfg.layout);
    const float* provoking = cfg.flatshade_first ? v0 : v1;
    if (m0) {
        float* nv = scratch;
        interp(cfg, nv, t0, v0, v1);
        copy_flat(cfg.layout, nv, provoking);
        *out0 = nv;
    }
    if (m1) {
        float* nv = scratch + stride;
        interp(cfg, nv, t1, v1, v0);
        copy_flat(cfg.layout, nv, provoking);
        *out1 = nv;
    }
    return true;
}

bool cull_distance_keep(const ClipConfig& cfg, const float* const* v, uint32_t n) {
    for (uint32_t i = 0; i < cfg.num_cull_distances; ++i) {
        bool all_out = true;
        for (uint32_t k = 0; k < n && all_out; ++k) {
            const float d = clip_distance_element(cfg, v[k], cfg.num_clip_distances + i);
            all_out = d < 0.0f || is_inf_or_nan(d);
        }
        if (all_out) return false;
    }
    return true;
}

bool clip_point_keep(const float c[4], uint32_t mask) {
    if (mask == 0) return true;
    if ((mask & 0xFFFFFFF0u) != 0) return false;
    return !(c[3] <= 0.0f || is_inf_or_nan(c[0]) || is_inf_or_nan(c[1]));
}

bool float_cull_keep(const FloatCull& c, const float* w0, const float* w1, const float* w2) {
    const float ex = w0[0] - w2[0];
    const float ey = w0[1] - w2[1];
    const float fx = w1[0] - w2[0];
    const float fy = w1[1] - w2[1];
    const float p = ex * fy;
    const float q = ey * fx;
    const float det = p - q;
    if (det != 0.0f) {  // NaN included
        const bool ccw = det < 0.0f;
        const bool front = ccw == c.front_ccw;
        return front ? !c.cull_front : !c.cull_back;
    }
    return !c.cull_back;  // zero area counts as back-facing
}

}  // namespace tilevk::rast::geometry
