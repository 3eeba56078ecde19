// Renderer's primitives on their way to setup and the bins (renderer.cpp runs the draw up to them): points,
// lines and triangles (one by one or set up on the workers) and llvmpipe's rectangles, as the draw module
// emulation (rast/geometry/draw_module.h: vbuf stage, rectangle pairing, 9-vertex analysis) hands them over.
#include <algorithm>
#include <atomic>
#include <cstring>
#include <optional>

#include "rast/core/fixed_point.h"
#include "rast/fragment/msaa.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/draw_module.h"
#include "rast/geometry/fp_env.h"
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

// The draw module's way into this renderer's setup, for one draw.
class Renderer::Setup final : public geometry::SetupSink {
  public:
    Setup(Renderer& r, uint32_t draw, const DrawRecord& rec) : r_(r), draw_(draw), rec_(rec) {}
    void triangle(const float* v0, const float* v1, const float* v2) override {
        r_.add_triangle(draw_, rec_, v0, v1, v2);
    }
    void rect(const float* c0, const float* c1, const float* c2, bool front) override {
        r_.add_rect(draw_, rec_, c0, c1, c2, front);
    }
    void line(const float* v0, const float* v1, bool front) override { r_.add_line(draw_, rec_, v0, v1, front); }
    void point(const float* v, float size, bool front) override { r_.add_point(draw_, rec_, v, size, front); }

  private:
    Renderer& r_;
    uint32_t draw_;
    const DrawRecord& rec_;
};

// Triangles [first_prim, end_prim) of the assembled list, as the draw module reads a batch.
geometry::TriangleBatch Renderer::triangle_batch(uint32_t first_prim, uint32_t end_prim) const {
    return {assembled_.data() + size_t(first_prim) * 3, end_prim - first_prim, shaded_.records.data(),
            shaded_.floats_per_vertex};
}

bool Renderer::emit_direct_pairs(uint32_t draw_index, const DrawRecord& rec, geometry::Topology topology, bool indexed,
                                 uint32_t first_prim, uint32_t end_prim) {
    Setup setup(*this, draw_index, rec);
    return draw_module_.direct_pairs(setup, topology, indexed, triangle_batch(first_prim, end_prim));
}

uint32_t Renderer::nine_vertex_batch_end(uint32_t draw_index, const DrawRecord& rec, uint32_t first_prim,
                                         uint32_t end_prim) {
    Setup setup(*this, draw_index, rec);
    return first_prim + draw_module_.nine_vertex_batch(setup, triangle_batch(first_prim, end_prim));
}

void Renderer::vbuf_primitive(uint32_t draw, const DrawRecord& rec, const float* const* v, const uint64_t* ids,
                              float point_size, bool front) {
    Setup setup(*this, draw, rec);
    draw_module_.vbuf_primitive(setup, v, ids, point_size, front);
}

// vbuf_primitive's count replayed without copying: per batch of the tail, each triangle's pieces as
// emit_clipped_triangle makes them (clipped only when a vertex has a clip-mask bit, then the float cull), each
// vertex counted once per buffer: an input vertex by its shaded slot within the batch (vbuf_stamp_ holds the
// generation, bumped per batch and per buffer, in which the slot was last counted), a clipper-made one by its
// record within the clip call. A filling that starts at a triangle's first piece is a place where the batch loop
// can take over with an empty vbuf; one that starts at a later piece is not.
uint32_t Renderer::last_filling_start(const TrianglePipeline& cfg, uint32_t num_prims, uint32_t tail_first) {
    const uint32_t max_vertices = draw_module_.vbuf_max_vertices();
    uint32_t vertices = draw_module_.vbuf_vertices();
    uint32_t indices = draw_module_.vbuf_indices();
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
                if (vertices + 3 > max_vertices || indices + 3 > geometry::DrawModule::kMaxVbufIndices) {
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
    Setup setup(*this, draw, rec);
    draw_module_.vbuf_flush(setup, after_draw);
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
