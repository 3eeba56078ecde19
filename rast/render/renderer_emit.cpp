// Renderer's primitives on their way to setup and the bins (renderer.cpp runs the draw up to them): points,
// lines and triangles (one by one or set up on the workers), llvmpipe's rectangles and the draw module's triangle
// pairing and vbuf stage that feed them (lp_setup_vbuf.c, lp_setup_rect.c, lp_setup_analysis.c).
#include <algorithm>
#include <atomic>
#include <cstring>
#include <optional>

#include "rast/core/fixed_point.h"
#include "rast/fragment/msaa.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/fp_env.h"
#include "rast/geometry/lavapipe_quirks.h"
#include "rast/geometry/line_point_setup.h"
#include "rast/geometry/viewport.h"
#include "rast/render/linear_bins.h"
#include "rast/render/renderer.h"

namespace tilevk::rast::render {

namespace {
// CLIPPING_PRIMITIVES (pipeline statistics) of n triangles reaching llvmpipe's setup: lp_setup_tri.c triangle_cw,
// triangle_ccw and triangle_both count on entry, whatever the triangle's winding, area or position; cull
// FRONT_AND_BACK installs triangle_noop, which counts nothing. Rectangles (lp_setup_rect.c) are not counted.
void count_setup_triangles(const DrawRecord& rec, uint64_t n) {
    if (rec.pipe->cull != CullMode::kBoth) rec.statistics->clipping_primitives += n;
}
}  // namespace

// The plane setup of every triangle and rectangle of the draw: lavapipe's flatshade_first, the target's bias.
geometry::PlaneSetupConfig Renderer::plane_setup_config(const DrawRecord& rec) const {
    const PipelineState& pipe = *rec.pipe;
    geometry::PlaneSetupConfig pcfg;
    pcfg.layout = rec.varyings.layout();
    pcfg.multisample = fb_.samples > 1;
    pcfg.flatshade_first = pipe.flatshade_first;
    pcfg.bias = pipe.depth_bias_enable ? depth_bias_for_target(pipe) : geometry::DepthBias{};
    return pcfg;
}

// The shaded records of triangle p of the assembled list.
void Renderer::triangle_records(uint32_t p, const float* v[3]) const {
    const uint32_t* ids = assembled_.data() + size_t(p) * 3;
    for (int k = 0; k < 3; ++k) v[k] = shaded_.record(ids[k]);
}

// A batch that skipped draw's pipeline, as lp_setup_vbuf.c hands its triangle pairs to setup->rect: 6N-vertex
// lists and strips in linear mode, the non-indexed 4-vertex fan in any mode. False (nothing drawn) for any other
// batch, which the caller draws triangle by triangle.
bool Renderer::emit_direct_pairs(uint32_t draw_index, const DrawRecord& rec, geometry::Topology topology, bool indexed,
                                 uint32_t first_prim, uint32_t end_prim, size_t batch_verts) {
    const float* t0[3];
    const float* t1[3];
    const bool list6 = topology == geometry::Topology::kTriangleList && batch_verts % 6 == 0;
    if (rect_pairs_ && list6) {
        // draw_arrays / draw_elements, PIPE_PRIM_TRIANGLES with nr % 6 == 0: rect() per pair
        for (uint32_t p = first_prim; p + 1 < end_prim; p += 2) {
            triangle_records(p, t0);
            triangle_records(p + 1, t1);
            rect_or_triangles(draw_index, rec, t0, t1);
        }
        return true;
    }
    if (rect_pairs_ && !indexed && topology == geometry::Topology::kTriangleStrip && rec.pipe->flatshade_first) {
        // draw_arrays, strip with flatshade_first: setup->rect on each pair of consecutive triangles;
        // when it declines, the first is drawn and the pairing moves on by one (last-vertex strips: triangles)
        uint32_t p = first_prim;
        for (; p + 1 < end_prim;) {
            triangle_records(p, t0);
            triangle_records(p + 1, t1);
            if (apply_rect_decision(draw_index, rec, t0, t1)) {
                p += 2;
            } else {
                add_triangle(draw_index, rec, t0[0], t0[1], t0[2]);
                p += 1;
            }
        }
        if (p < end_prim) {
            triangle_records(p, t0);
            add_triangle(draw_index, rec, t0[0], t0[1], t0[2]);
        }
        return true;
    }
    if (!indexed && topology == geometry::Topology::kTriangleFan && end_prim - first_prim == 2) {
        // draw_arrays, 4-vertex fan (any mode, either provoking vertex): rect(v0, v1, v2, v0, v2, v3), i.e.
        // outside linear mode the triangles (v0, v1, v2), (v0, v2, v3) instead of the fan's (v1, v2, v0),
        // (v2, v3, v0) — with the last vertex provoking the fan's own order
        const float* a[3];
        const float* b[3];
        triangle_records(first_prim, a);
        triangle_records(first_prim + 1, b);
        const bool first = rec.pipe->flatshade_first;  // assembled (v1, v2, v0), (v2, v3, v0) else (v0, v1, v2), ...
        const float* q[4] = {first ? a[2] : a[0], first ? a[0] : a[1], first ? a[1] : a[2], first ? b[1] : b[2]};
        const float* u0[3] = {q[0], q[1], q[2]};
        const float* u1[3] = {q[0], q[2], q[3]};
        rect_or_triangles(draw_index, rec, u0, u1);
        return true;
    }
    return false;
}

// A 9-vertex non-indexed triangle-list batch that skipped draw's pipeline, through llvmpipe's list analysis
// (lp_setup_analysis.c, geometry/lavapipe_quirks.h): returns where the caller's triangle loop ends, having drawn
// the rectangle llvmpipe bins instead.
uint32_t Renderer::nine_vertex_batch_end(uint32_t draw_index, const DrawRecord& rec, uint32_t first_prim,
                                         uint32_t end_prim, const uint32_t* batch_ids) {
    float xy[9][2];
    for (int k = 0; k < 9; ++k) {
        const float* w = geometry::win_pos(shaded_.record(batch_ids[k]));
        xy[k][0] = w[0];
        xy[k][1] = w[1];
    }
    geometry::TriangleListBatch qb;
    qb.vertex_count = 9;
    const geometry::NineVertexQuirk q = geometry::nine_vertex_quirk(qb, xy);
    // Swallowed: nothing. Aero: llvmpipe bins one rectangle, lp_rect_cw(v0, v1, v2, front = TRUE), in
    // any mode; at 4x it is still drawn as its two triangles (rectangles in MSAA are not modelled).
    if (q == geometry::NineVertexQuirk::kSwallowed) return first_prim;
    if (q == geometry::NineVertexQuirk::kAeroRect) {
        if (fb_.samples != 1) return first_prim + 2;
        const float* t0[3];
        triangle_records(first_prim, t0);
        add_rect(draw_index, rec, t0[0], t0[1], t0[2], true);
        return first_prim;
    }
    return end_prim;
}

bool Renderer::apply_rect_decision(uint32_t draw, const DrawRecord& rec, const float* const t0[3],
                                   const float* const t1[3]) {
    const geometry::RectDecision d = geometry::decide_rect_pair(rect_cfg_, t0, t1);
    switch (d.kind) {
        case geometry::RectDecision::kTriangles:
            return false;
        case geometry::RectDecision::kRect:
            add_rect(draw, rec, d.corner[0], d.corner[1], d.corner[2], d.front);
            break;
        case geometry::RectDecision::kFirstTriangle:
            add_triangle(draw, rec, t0[0], t0[1], t0[2]);
            break;
        case geometry::RectDecision::kSecondTriangle:
            add_triangle(draw, rec, t1[0], t1[1], t1[2]);
            break;
        case geometry::RectDecision::kNothing:
            break;
    }
    return true;
}

void Renderer::rect_or_triangles(uint32_t draw, const DrawRecord& rec, const float* const t0[3],
                                 const float* const t1[3]) {
    if (fb_.linear_mode && apply_rect_decision(draw, rec, t0, t1)) return;
    add_triangle(draw, rec, t0[0], t0[1], t0[2]);
    add_triangle(draw, rec, t1[0], t1[1], t1[2]);
}

void Renderer::vbuf_primitive(uint32_t draw, const DrawRecord& rec, const float* const* v, const uint64_t* ids,
                              float point_size, bool front) {
    // draw_pipe_vbuf.c vbuf_tri / vbuf_line / vbuf_point: check_space(n) against both buffers, then each vertex
    // emitted once per buffer.
    const uint32_t n = vbuf_.verts_per_prim;
    const size_t indices = vbuf_.records.size() / vbuf_.stride;
    if (vbuf_.vertices + n > vbuf_.max_vertices || indices + n > VbufGroup::kMaxIndices) vbuf_flush(draw, rec);
    for (uint32_t k = 0; k < n; ++k) {
        if (std::find(vbuf_.emitted_id.begin(), vbuf_.emitted_id.end(), ids[k]) == vbuf_.emitted_id.end()) {
            vbuf_.emitted_id.push_back(ids[k]);
            ++vbuf_.vertices;
        }
        vbuf_.records.insert(vbuf_.records.end(), v[k], v[k] + vbuf_.stride);
    }
    vbuf_.point_size.push_back(point_size);
    vbuf_.front.push_back(front ? 1 : 0);
}

// vbuf_primitive's count replayed without copying: per batch of the tail, each triangle's pieces as
// emit_clipped_triangle makes them (clipped only when a vertex has a clip-mask bit, then the float cull), each
// vertex counted once per buffer: an input vertex by its shaded slot within the batch (vbuf_stamp_ holds the
// generation, bumped per batch and per buffer, in which the slot was last counted), a clipper-made one by its
// record within the clip call. A filling that starts at a triangle's first piece is a place where the batch loop
// can take over with an empty vbuf; one that starts at a later piece is not.
uint32_t Renderer::last_filling_start(const TrianglePipeline& cfg, uint32_t num_prims, uint32_t tail_first) {
    const uint32_t max_vertices = vbuf_.max_vertices;
    uint32_t vertices = vbuf_.vertices;
    uint32_t indices = static_cast<uint32_t>(vbuf_.records.size() / vbuf_.stride);
    if (tail_first > 0) vertices = indices = 0;  // the prefix's last (direct) batch flushed the vbuf
    vbuf_stamp_.assign(shaded_.clipmask.size(), 0);
    uint32_t generation = 0, start = tail_first, first = 0;
    const float* made[3 * geometry::kMaxClippedTriangles];  // clipper-made vertices counted in this buffer
    for (const uint32_t batch_prims : batches_) {
        const uint32_t end = std::min(num_prims, first + batch_prims);
        const uint32_t from = std::max(first, tail_first);
        first = end;
        if (from >= end) continue;
        ++generation;  // a new batch: its vertices are new vertex headers
        for (uint32_t i = from; i < end; ++i) {
            const uint32_t* s = assembled_.data() + size_t(i) * 3;
            const float* v[3] = {shaded_.record(s[0]), shaded_.record(s[1]), shaded_.record(s[2])};
            geometry::ClippedTriangle out[geometry::kMaxClippedTriangles];
            const uint32_t pieces =
                geometry::clip_triangle(*cfg.clip, v[0], v[1], v[2], shaded_.clipmask[s[0]], shaded_.clipmask[s[1]],
                                        shaded_.clipmask[s[2]], clip_scratch_.data(), out);
            uint32_t num_made = 0;
            bool first_piece = true;
            for (uint32_t t = 0; t < pieces; ++t) {
                const float* const* p = out[t].v;
                if (cfg.any_cull && !geometry::float_cull_keep(*cfg.float_cull, geometry::win_pos(p[0]),
                                                               geometry::win_pos(p[1]), geometry::win_pos(p[2])))
                    continue;
                if (vertices + 3 > max_vertices || indices + 3 > VbufGroup::kMaxIndices) {
                    vertices = indices = num_made = 0;
                    ++generation;
                    if (first_piece) start = i;
                }
                first_piece = false;
                indices += 3;
                for (int k = 0; k < 3; ++k) {
                    const int input = p[k] == v[0] ? 0 : p[k] == v[1] ? 1 : p[k] == v[2] ? 2 : -1;
                    if (input >= 0) {
                        if (vbuf_stamp_[s[input]] != generation) ++vertices;
                        vbuf_stamp_[s[input]] = generation;
                    } else if (std::find(made, made + num_made, p[k]) == made + num_made) {
                        made[num_made++] = p[k];
                        ++vertices;
                    }
                }
            }
        }
    }
    return start;
}

void Renderer::vbuf_flush(uint32_t draw, const DrawRecord& rec, bool after_draw) {
    if (vbuf_.records.empty()) return;
    std::optional<geometry::ScopedKeepDenormals> keep_denormals;
    if (after_draw) keep_denormals.emplace();
    // lp_setup_vbuf.c draw_elements: PIPE_PRIM_TRIANGLES rect() per pair when nr % 6 == 0, else triangles;
    // PIPE_PRIM_LINES / POINTS setup->line / setup->point each.
    const size_t nr = vbuf_.records.size() / vbuf_.stride;
    auto vert = [&](size_t i) { return vbuf_.records.data() + i * vbuf_.stride; };
    if (vbuf_.verts_per_prim == 1) {
        for (size_t i = 0; i < nr; ++i) add_point(draw, rec, vert(i), vbuf_.point_size[i], vbuf_.front[i] != 0);
    } else if (vbuf_.verts_per_prim == 2) {
        for (size_t i = 0; i + 1 < nr; i += 2) add_line(draw, rec, vert(i), vert(i + 1), vbuf_.front[i / 2] != 0);
    } else if (rect_pairs_ && nr % 6 == 0) {
        for (size_t i = 0; i + 5 < nr; i += 6) {
            const float* t0[3] = {vert(i), vert(i + 1), vert(i + 2)};
            const float* t1[3] = {vert(i + 3), vert(i + 4), vert(i + 5)};
            rect_or_triangles(draw, rec, t0, t1);
        }
    } else {
        for (size_t i = 0; i + 2 < nr; i += 3) add_triangle(draw, rec, vert(i), vert(i + 1), vert(i + 2));
    }
    vbuf_.records.clear();
    vbuf_.point_size.clear();
    vbuf_.front.clear();
    vbuf_.vertices = 0;
    vbuf_.emitted_id.clear();
}

void Renderer::add_rect(uint32_t draw, const DrawRecord& rec, const float* c0, const float* c1, const float* c2,
                        bool front) {
    const PipelineState& pipe = *rec.pipe;
    const float* w[3] = {geometry::win_pos(c0), geometry::win_pos(c1), geometry::win_pos(c2)};
    const geometry::RectBox box = geometry::rect_box(w[0], w[1], w[2], triangle_snap_offset(fb_.samples));
    // An empty box (a rectangle narrower than one 1/256 step after snapping) is dropped here; llvmpipe bins it
    // with x1 < x0 (rast/geometry/README.md, "Linear mode").
    if (box.culled || box.x0 > box.x1 || box.y0 > box.y1) return;
    // u_rect_find_intersection with draw_regions[0] (scissor, framebuffer, viewport rectangle)
    const ClipRect clip = prim_clip(pipe);
    BoxInput in;
    in.x0 = std::max(box.x0, clip.x0) * kFixedOne;
    in.y0 = std::max(box.y0, clip.y0) * kFixedOne;
    in.x1 = std::min(box.x1 + 1, clip.x1) * kFixedOne;
    in.y1 = std::min(box.y1 + 1, clip.y1) * kFixedOne;
    if (in.x0 >= in.x1 || in.y0 >= in.y1) return;
    in.common.clip = clip;
    in.common.sample_mask = fragment::coverage_sample_mask(pipe.sample_mask, fb_.samples);
    in.common.payload = prims_.next_payload();
    in.front_facing = front;
    if (scene_->add_box(in) != SetupStatus::kAccepted) return;
    // The setup JIT on (c0, c1, c2) as given: no cw reorder for rectangles.
    const geometry::PlaneSetupConfig pcfg = plane_setup_config(rec);
    geometry::TrianglePlanes tp;
    geometry::setup_triangle_planes(pcfg, c0, c1, c2, &tp, attrib_planes_.data());
    const uint32_t payload = push_prim(draw, PrimKind::kRect, tp.pos, tp.depth_offset, pcfg.layout.num_attribs);
    if (fb_.linear_mode) {
        prims_.set_rect(payload, static_cast<uint32_t>(rect_boxes_.size()));
        rect_boxes_.push_back(
            {in.x0 / kFixedOne, in.y0 / kFixedOne, (in.x1 - in.x0) / kFixedOne, (in.y1 - in.y0) / kFixedOne});
    } else {
        // rectangles outside linear mode (the Aero quirk) are binned as llvmpipe's RECTANGLE commands, which
        // only the linear rasterizer shades differently
    }
}

// The pipeline's depth-bias factors with the depth format's rule (util_get_depth_format_mrd: D16 16 bits, D32F
// the float rule, anything else — D24 or no depth attachment — 24 bits).
geometry::DepthBias Renderer::depth_bias_for_target(const PipelineState& pipe) const {
    geometry::DepthBias b = pipe.depth_bias;
    const fragment::DepthFormat df = fb_.depth_stencil.depth ? fb_.depth_stencil.format : fragment::DepthFormat::None;
    b.float_depth = df == fragment::DepthFormat::D32F;
    b.unorm_bits = df == fragment::DepthFormat::D16 ? 16 : 24;
    return b;
}

// Scissor ∩ viewport rectangle: the viewport rectangle also bounds coverage (lp_setup_set_viewports
// draw_regions[0], lavapipe-rules §2).
ClipRect Renderer::prim_clip(const PipelineState& pipe) const {
    ClipRect r = {std::max(pipe.scissor.x0, 0), std::max(pipe.scissor.y0, 0), pipe.scissor.x1, pipe.scissor.y1};
    const ViewportRect& v = pipe.viewport;
    const float sx = 0.5f * v.width, tx = sx + v.x;
    const float sy = std::fabs(0.5f * v.height), ty = 0.5f * v.height + v.y;
    const ClipRect vp_rect = {static_cast<int32_t>(tx - sx + 0.499f), static_cast<int32_t>(ty - sy + 0.499f),
                              static_cast<int32_t>(2 * sx + (tx - sx) - 0.501f) + 1,
                              static_cast<int32_t>(2 * sy + (ty - sy) - 0.501f) + 1};
    r = {std::max(r.x0, vp_rect.x0), std::max(r.y0, vp_rect.y0), std::min(r.x1, vp_rect.x1),
         std::min(r.y1, vp_rect.y1)};
    r.x1 = std::min(r.x1, fb_.width);
    r.y1 = std::min(r.y1, fb_.height);
    return r;
}

uint32_t Renderer::push_prim(uint32_t draw, PrimKind kind, const geometry::AttribPlane& pos, float depth_offset,
                             uint32_t num_attribs) {
    const uint32_t payload = prims_.append(1, record_floats(num_attribs));
    prims_.set_header(payload, pos, depth_offset, draw, kind, 0);
    // No attributes: attrib_planes_ may be empty with a null data(), and memcpy from null is UB even for 0 bytes.
    if (num_attribs != 0)
        std::memcpy(prims_.record(payload) + kPrimHeaderFloats, attrib_planes_.data(),
                    sizeof(float) * kPlaneFloats * num_attribs);
    return payload;
}

void Renderer::add_line(uint32_t draw, const DrawRecord& rec, const float* v0, const float* v1, bool front_facing) {
    const PipelineState& pipe = *rec.pipe;
    if (rec.statistics) ++rec.statistics->clipping_primitives;  // try_setup_line counts on entry
    geometry::LineSetupConfig cfg;
    cfg.layout = rec.varyings.layout();
    cfg.mode = pipe.line_mode;
    cfg.width = pipe.line_width;
    cfg.multisample = fb_.samples > 1;
    cfg.flatshade_first = pipe.flatshade_first;
    geometry::LineSetup ls;
    if (geometry::setup_line(cfg, v0, v1, &ls, attrib_planes_.data()) != geometry::PrimSetupStatus::kOk) return;
    ConvexInput in;
    for (int i = 0; i < 4; ++i) in.planes[i] = {ls.planes[i].c, ls.planes[i].a, ls.planes[i].b};
    in.num_planes = 4;
    in.min_x = ls.min_x;
    in.min_y = ls.min_y;
    in.max_x = ls.max_x;
    in.max_y = ls.max_y;
    in.common.clip = prim_clip(pipe);
    in.common.sample_mask = fragment::coverage_sample_mask(pipe.sample_mask, fb_.samples);
    in.common.payload = prims_.next_payload();
    in.front_facing = front_facing;
    if (scene_->add_convex(in) != SetupStatus::kAccepted) return;
    // one pixel of margin around the line's fixed-point box (llvmpipe's own line box is not modelled)
    if (fb_.linear_mode)
        mark_not_linear((ls.min_x >> 8) - 1, (ls.min_y >> 8) - 1, (ls.max_x >> 8) + 1, (ls.max_y >> 8) + 1,
                        in.common.clip);
    push_prim(draw, PrimKind::kLine, ls.pos, 0.0f, cfg.layout.num_attribs);
}

void Renderer::add_point(uint32_t draw, const DrawRecord& rec, const float* v, float size, bool front_facing) {
    const PipelineState& pipe = *rec.pipe;
    // try_setup_point counts once it has the point's box, before any test on it
    if (rec.statistics) ++rec.statistics->clipping_primitives;
    geometry::PointSetupConfig cfg;
    cfg.layout = rec.varyings.layout();
    cfg.multisample = fb_.samples > 1;
    cfg.point_coord_attrib = rec.varyings.point_coord_slot;
    cfg.point_coord_perspective = true;  // PNTC has no interpolation qualifier: perspective in lavapipe
    geometry::PointSetup ps;
    if (geometry::setup_point(cfg, v, size, &ps, attrib_planes_.data()) != geometry::PrimSetupStatus::kOk) return;
    BoxInput in;
    // Intersect with the clip rect first: far-off boxes can exceed the core's range (rast/geometry/README.md).
    const ClipRect clip = prim_clip(pipe);
    in.x0 = std::max<int64_t>(ps.x0, int64_t(clip.x0) * kFixedOne);
    in.y0 = std::max<int64_t>(ps.y0, int64_t(clip.y0) * kFixedOne);
    in.x1 = std::min<int64_t>(ps.x1, int64_t(clip.x1) * kFixedOne);
    in.y1 = std::min<int64_t>(ps.y1, int64_t(clip.y1) * kFixedOne);
    in.common.clip = clip;
    in.common.sample_mask = fragment::coverage_sample_mask(pipe.sample_mask, fb_.samples);
    in.common.payload = prims_.next_payload();
    in.front_facing = front_facing;
    if (scene_->add_box(in) != SetupStatus::kAccepted) return;
    if (fb_.linear_mode)
        mark_not_linear((in.x0 >> 8) - 1, (in.y0 >> 8) - 1, (in.x1 >> 8) + 1, (in.y1 >> 8) + 1, in.common.clip);
    push_prim(draw, PrimKind::kPoint, ps.pos, 0.0f, cfg.layout.num_attribs);
}

void Renderer::add_triangles_parallel(uint32_t draw, const DrawRecord& rec, const uint32_t* prim_slots, uint32_t n,
                                      const TrianglePipeline& tp_cfg) {
    const PipelineState& pipe = *rec.pipe;
    // What add_triangle derives per triangle, once.
    TriangleInput proto;
    proto.cull = pipe.cull;
    proto.front_ccw = pipe.front_ccw;
    proto.flatshade_first = pipe.flatshade_first;
    proto.common.clip = prim_clip(pipe);
    proto.common.sample_mask = fb_.samples > 1 ? static_cast<uint16_t>(pipe.sample_mask & 0xF) : 1;
    const geometry::PlaneSetupConfig pcfg = plane_setup_config(rec);
    const uint32_t prim_floats = record_floats(pcfg.layout.num_attribs);
    const uint32_t rec_floats = geometry::vertex_floats(pcfg.layout);
    while (clip_workers_.size() < pool_.num_workers()) clip_workers_.emplace_back();
    for (auto& c : clip_workers_) c.resize(size_t(geometry::kClipScratchVertices) * rec_floats);

    // A triangle of a batch that went through draw's pipeline with a clipped vertex becomes the clipper's pieces
    // (then the float cull); every other triangle stays one. Pass 1 counts the pieces, pass 2 sets them up into
    // their slots: slot k of the scene, of prims_ and of planes_ holds the k-th piece in API order (a piece that
    // is culled or rejected leaves its slots unused).
    auto triangle = [&](uint32_t i, const float* v[3], uint32_t m[3]) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t slot = prim_slots[3 * size_t(i) + k];
            v[k] = shaded_.record(slot);
            m[k] = shaded_.clipmask[slot];
        }
        return tp_cfg.pipeline[i] && (m[0] | m[1] | m[2]) != 0;
    };
    constexpr uint32_t kChunk = 1024;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    piece_first_.resize(size_t(n) + 1);
    pool_.run(chunks, [&](unsigned w, size_t chunk) {
        geometry::ScopedFlushDenormals flush_denormals;  // on every worker, as on the drawing thread (draw())
        const uint32_t end = std::min<uint32_t>(n, uint32_t(chunk) * kChunk + kChunk);
        for (uint32_t i = uint32_t(chunk) * kChunk; i < end; ++i) {
            const float* v[3];
            uint32_t m[3];
            uint32_t pieces = 1;
            if (triangle(i, v, m)) {
                geometry::ClippedTriangle out[geometry::kMaxClippedTriangles];
                pieces = geometry::clip_triangle(*tp_cfg.clip, v[0], v[1], v[2], m[0], m[1], m[2],
                                                 clip_workers_[w].data(), out);
            }
            piece_first_[i + 1] = pieces;
        }
    });
    piece_first_[0] = 0;
    for (uint32_t i = 0; i < n; ++i) piece_first_[i + 1] += piece_first_[i];
    const uint32_t total = piece_first_[n];

    const uint32_t scene_first = scene_->reserve(total);
    const uint32_t rec_first = prims_.append(total, prim_floats);  // record k's payload: rec_first + k * rec_step
    const uint32_t rec_step = prim_floats / kRecordAlign;
    auto set_up = [&](uint32_t k, const float* a, const float* b, const float* c, geometry::AttribPlane* attribs) {
        TriangleInput tri = proto;
        const float* v[3] = {a, b, c};
        for (int j = 0; j < 3; ++j) {
            tri.x[j] = geometry::win_pos(v[j])[0];
            tri.y[j] = geometry::win_pos(v[j])[1];
        }
        const uint32_t payload = rec_first + k * rec_step;
        tri.common.payload = payload;
        bool ccw = true;
        if (scene_->setup_triangle_at(scene_first + k, tri, &ccw) != SetupStatus::kAccepted) return;
        // Planes from the vertices in the order rast/core rasterizes them: cw triangles become (v0, v2, v1) with
        // the first vertex provoking, (v1, v0, v2) with the last (the provoking vertex keeps its place).
        geometry::TrianglePlanes tp;
        if (ccw)
            geometry::setup_triangle_planes(pcfg, a, b, c, &tp, attribs);
        else if (pcfg.flatshade_first)
            geometry::setup_triangle_planes(pcfg, a, c, b, &tp, attribs);
        else
            geometry::setup_triangle_planes(pcfg, b, a, c, &tp, attribs);
        prims_.set_header(payload, tp.pos, tp.depth_offset, draw, PrimKind::kTriangle, 0);
        if (pcfg.layout.num_attribs != 0)
            std::memcpy(prims_.record(payload) + kPrimHeaderFloats, attribs,
                        sizeof(float) * kPlaneFloats * pcfg.layout.num_attribs);
    };
    std::atomic<uint64_t> reached_setup{0};  // triangles handed to llvmpipe's setup (pipeline statistics only)
    pool_.run(chunks, [&](unsigned w, size_t chunk) {
        geometry::ScopedFlushDenormals flush_denormals;  // setup and planes as on the drawing thread
        geometry::AttribPlane attribs[shader::kMaxLocations + 2];
        const uint32_t end = std::min<uint32_t>(n, uint32_t(chunk) * kChunk + kChunk);
        uint64_t reached = 0;
        for (uint32_t i = uint32_t(chunk) * kChunk; i < end; ++i) {
            const float* v[3];
            uint32_t m[3];
            const bool clipped = triangle(i, v, m);
            if (!tp_cfg.pipeline[i]) {
                set_up(piece_first_[i], v[0], v[1], v[2], attribs);
                ++reached;
                continue;
            }
            geometry::ClippedTriangle out[geometry::kMaxClippedTriangles];
            uint32_t pieces = 1;
            out[0].v[0] = v[0], out[0].v[1] = v[1], out[0].v[2] = v[2];
            if (clipped)
                pieces = geometry::clip_triangle(*tp_cfg.clip, v[0], v[1], v[2], m[0], m[1], m[2],
                                                 clip_workers_[w].data(), out);
            for (uint32_t t = 0; t < pieces; ++t) {
                const float *a = out[t].v[0], *b = out[t].v[1], *c = out[t].v[2];
                if (tp_cfg.any_cull && !geometry::float_cull_keep(*tp_cfg.float_cull, geometry::win_pos(a),
                                                                  geometry::win_pos(b), geometry::win_pos(c)))
                    continue;
                set_up(piece_first_[i] + t, a, b, c, attribs);
                ++reached;
            }
        }
        if (rec.statistics) reached_setup.fetch_add(reached, std::memory_order_relaxed);
    });
    if (rec.statistics) count_setup_triangles(rec, reached_setup.load(std::memory_order_relaxed));
    scene_->bin_reserved(scene_first, total, pool_);
}

void Renderer::add_triangle(uint32_t draw, const DrawRecord& rec, const float* v0, const float* v1, const float* v2) {
    const PipelineState& pipe = *rec.pipe;
    if (rec.statistics) count_setup_triangles(rec, 1);
    TriangleInput tri;
    const float* w[3] = {geometry::win_pos(v0), geometry::win_pos(v1), geometry::win_pos(v2)};
    for (int i = 0; i < 3; ++i) {
        tri.x[i] = w[i][0];
        tri.y[i] = w[i][1];
    }
    tri.cull = pipe.cull;
    tri.front_ccw = pipe.front_ccw;
    tri.flatshade_first = pipe.flatshade_first;
    tri.common.clip = prim_clip(pipe);
    tri.common.sample_mask = fragment::coverage_sample_mask(pipe.sample_mask, fb_.samples);
    tri.common.payload = prims_.next_payload();
    if (scene_->add_triangle(tri) != SetupStatus::kAccepted) return;
    // cw triangles become (v0, v2, v1) with the first vertex provoking, (v1, v0, v2) with the last
    int core_order[3];
    triangle_vertex_order(tri, fb_.samples, core_order);
    if (fb_.linear_mode) {
        // llvmpipe's binning of this triangle: tiles where it leaves a partial command are not linear bins
        const float off = triangle_snap_offset(fb_.samples);
        int32_t x[3], y[3];
        bool ok = true;
        for (int i = 0; i < 3; ++i)
            ok = ok && snap_triangle_coord(w[core_order[i]][0], off, &x[i]) &&
                 snap_triangle_coord(w[core_order[i]][1], off, &y[i]);
        if (ok)
            mark_partial_triangle_bins(x, y, tri.common.clip, (fb_.width + 63) / 64, &tile_linear_);
        else
            mark_not_linear(0, 0, fb_.width, fb_.height, tri.common.clip);
    }

    // Planes from the vertices in the order rast/core rasterizes them.
    const float* v[3] = {v0, v1, v2};
    const geometry::PlaneSetupConfig pcfg = plane_setup_config(rec);
    geometry::TrianglePlanes tp;
    geometry::setup_triangle_planes(pcfg, v[core_order[0]], v[core_order[1]], v[core_order[2]], &tp,
                                    attrib_planes_.data());

    push_prim(draw, PrimKind::kTriangle, tp.pos, tp.depth_offset, pcfg.layout.num_attribs);
}

}  // namespace tilevk::rast::render
