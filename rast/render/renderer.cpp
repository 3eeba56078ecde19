// The primitive stage of a draw: assembly -> vertex shading -> clipping / float cull -> setup -> binning.
#include "rast/render/renderer.h"

#include <algorithm>
#include <cstring>

#include "rast/core/fixed_point.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/draw_batches.h"
#include "rast/geometry/lavapipe_quirks.h"
#include "rast/geometry/line_point_setup.h"
#include "rast/geometry/unfilled.h"
#include "rast/geometry/viewport.h"
#include "rast/render/fragment_stage.h"

namespace tilevk::rast::render {
namespace {

// Scenes are flushed (rendered) past this many primitives, so memory stays bounded on huge draws.
constexpr size_t kMaxScenePrims = size_t{1} << 20;

// Record slot per fragment-shader input location, with the interpolation the fragment shader asks for.
VaryingMap make_varyings(const shader::Program* fs) {
    VaryingMap map;
    if (!fs) return map;
    for (const shader::IoVariable& v : fs->interface().inputs) {
        if (std::find(map.slot_location.begin(), map.slot_location.end(), v.location) != map.slot_location.end())
            continue;
        map.slot_location.push_back(v.location);
        geometry::Interp interp = geometry::Interp::kPerspective;
        if (v.interpolation == shader::Interpolation::Flat || v.type != shader::ScalarType::Float)
            interp = geometry::Interp::kFlat;
        else if (v.interpolation == shader::Interpolation::NoPerspective)
            interp = geometry::Interp::kNoPerspective;
        map.slot_interp.push_back(interp);
    }
    return map;
}

fragment::ShaderDepthTraits depth_traits(const shader::Program* fs) {
    fragment::ShaderDepthTraits t;
    if (!fs) return t;
    const shader::ProgramInterface& i = fs->interface();
    t.early_fragment_tests = i.early_fragment_tests;
    t.writes_depth = i.writes_frag_depth;
    t.uses_discard = i.uses_discard;
    t.writes_sample_mask = i.builtins_written & shader::bit(shader::BuiltIn::SampleMask);
    for (const shader::DescriptorUse& d : i.descriptors) t.writes_memory |= d.written;
    return t;
}

bool vertex_writes_memory(const shader::Program* vs) {
    for (const shader::DescriptorUse& d : vs->interface().descriptors)
        if (d.written) return true;
    return false;
}

// lavapipe's orientation decision, from the same snapped coordinates rast/core uses: area > 0 is "ccw".
// Needed before plane setup because a cw triangle's planes are computed from (v0, v2, v1).
bool snapped_ccw(const float* w0, const float* w1, const float* w2, int samples) {
    const float off = triangle_snap_offset(samples);
    int32_t x[3], y[3];
    const float* w[3] = {w0, w1, w2};
    for (int i = 0; i < 3; ++i)
        if (!snap_triangle_coord(w[i][0], off, &x[i]) || !snap_triangle_coord(w[i][1], off, &y[i])) return true;
    const int64_t area = int64_t{x[0] - x[1]} * (y[2] - y[0]) - int64_t{x[2] - x[0]} * (y[0] - y[1]);
    return area > 0;
}

}  // namespace

bool Renderer::fused() {
    static const bool value = geometry::host_has_fma();
    return value;
}

Renderer::Renderer(ThreadPool& pool, Method method) : pool_(pool), method_(method) {
    for (unsigned i = 0; i < pool_.num_workers(); ++i) scratch_.push_back(std::make_unique<shader::Scratch>());
    fragment_ = std::make_unique<FragmentStage>();
}

Renderer::~Renderer() = default;

void Renderer::begin(const Framebuffer& fb) {
    fb_ = fb;
    SceneConfig cfg;
    cfg.width = fb.width;
    cfg.height = fb.height;
    cfg.samples = fb.samples;
    cfg.method = method_;
    if (!scene_ || scene_->config().width != cfg.width || scene_->config().height != cfg.height ||
        scene_->config().samples != cfg.samples)
        scene_ = std::make_unique<Scene>(cfg);
    scene_->reset();
    draws_.clear();
    prims_.clear();
    planes_.clear();
}

void Renderer::end() {
    flush();
}

void Renderer::flush() {
    if (!prims_.empty()) {
        fragment_->prepare(fb_, draws_, prims_, planes_, fused(), pool_.num_workers());
        scene_->rasterize(*fragment_, pool_);
    }
    scene_->reset();
    // Draw records stay referenced by nothing once the scene is rendered.
    draws_.clear();
    prims_.clear();
    planes_.clear();
}

void Renderer::clear(const ClipRect& rect, const ClearRecord& clear) {
    DrawRecord& rec = draws_.emplace_back();
    rec.is_clear = true;
    rec.clear = clear;
    BoxInput box;
    box.x0 = rect.x0 * kFixedOne;
    box.y0 = rect.y0 * kFixedOne;
    box.x1 = rect.x1 * kFixedOne;
    box.y1 = rect.y1 * kFixedOne;
    box.common.clip = rect;
    box.common.sample_mask = 0xF;
    box.common.payload = static_cast<uint32_t>(prims_.size());
    if (scene_->add_box(box) == SetupStatus::kAccepted)
        prims_.push_back({static_cast<uint32_t>(draws_.size() - 1), 0, PrimKind::kClear});
}

std::string Renderer::draw(const PipelineState& pipe, const DrawCall& call, const shader::Bindings& bindings) {
    if (!pipe.vertex) return "draw without a vertex shader";
    if (pipe.samples != fb_.samples) return "pipeline sample count differs from the framebuffer's";
    if (call.count == 0 || call.instance_count == 0) return {};
    if (prims_.size() >= kMaxScenePrims) flush();

    const uint32_t draw_index = static_cast<uint32_t>(draws_.size());
    DrawRecord& rec = draws_.emplace_back();
    rec.pipe = &pipe;
    rec.bindings = bindings;
    rec.push_constants.assign(bindings.push_constants.begin(), bindings.push_constants.end());
    rec.bindings.push_constants = rec.push_constants;
    rec.varyings = make_varyings(pipe.fragment);
    if (pipe.polygon_mode == PolygonMode::kPoint && geometry::vertices_per_primitive(pipe.topology) == 3) {
        rec.varyings.carry_point_size = true;
        rec.varyings.slot_interp.push_back(geometry::Interp::kPerspective);
    }
    rec.depth_stencil = pipe.depth_stencil;
    rec.depth_stencil.min_depth = std::min(pipe.viewport.min_depth, pipe.viewport.max_depth);
    rec.depth_stencil.max_depth = std::max(pipe.viewport.min_depth, pipe.viewport.max_depth);
    rec.depth_stencil.depth_clamp = pipe.depth_clamp;
    if (!fb_.depth_stencil.depth) rec.depth_stencil.depth_test = rec.depth_stencil.depth_write = false;
    if (!fb_.depth_stencil.stencil) rec.depth_stencil.stencil_test = false;
    rec.depth_mode =
        fragment::choose_depth_mode(rec.depth_stencil, depth_traits(pipe.fragment), pipe.alpha_to_coverage);

    // Primitive assembly once for all instances.
    geometry::IndexSource src;
    if (call.indexed) {
        src.indices = call.index_data;
        src.index_size = call.index_size;
        src.index_count_total = call.index_size ? call.index_bytes / call.index_size : 0;
        src.vertex_offset = call.vertex_offset;
        src.primitive_restart = pipe.primitive_restart;
    }
    src.first = call.first;
    src.count = call.count;
    assembled_.resize(geometry::assembled_index_capacity(pipe.topology, call.count));
    const uint32_t num_prims =
        geometry::assemble_primitives(src, pipe.topology, true, assembled_.data(), assembled_.size());
    const uint32_t verts_per_prim = geometry::vertices_per_primitive(pipe.topology);
    unique_.assign(assembled_.begin(), assembled_.begin() + size_t(num_prims) * verts_per_prim);
    std::sort(unique_.begin(), unique_.end());
    unique_.erase(std::unique(unique_.begin(), unique_.end()), unique_.end());

    VertexInputState input;
    input.attribs = pipe.attribs;
    input.locations = pipe.attrib_locations;
    input.buffers.resize(pipe.bindings.size());
    for (size_t b = 0; b < pipe.bindings.size(); ++b) {
        geometry::VertexBufferView& vb = input.buffers[b];
        vb.stride = pipe.bindings[b].stride;
        vb.rate = pipe.bindings[b].rate;
        if (b < call.vertex_buffers.size()) {
            vb.data = call.vertex_buffers[b].data;
            vb.size = call.vertex_buffers[b].size;
        }
    }

    VertexStageConfig vcfg;
    vcfg.program = pipe.vertex;
    vcfg.bindings = &rec.bindings;
    vcfg.input = &input;
    vcfg.varyings = &rec.varyings;
    const ViewportRect& v = pipe.viewport;
    vcfg.viewport.vp = geometry::make_viewport(v.x, v.y, v.width, v.height, v.min_depth, v.max_depth);
    vcfg.viewport.fused = fused();
    vcfg.viewport.bypass = geometry::is_identity_viewport(vcfg.viewport.vp);
    vcfg.clip.clip_z = !pipe.depth_clamp;
    vcfg.first_instance = call.first_instance;
    vcfg.base_vertex = call.indexed ? static_cast<uint32_t>(call.vertex_offset) : call.first;

    const geometry::VertexLayout layout = rec.varyings.layout();
    geometry::ClipConfig ccfg;
    ccfg.layout = layout;
    ccfg.vp = vcfg.viewport.vp;
    ccfg.guard_band_xy = fb_.linear_mode;
    clip_scratch_.resize(size_t(geometry::kClipScratchVertices) * geometry::vertex_floats(layout));
    attrib_planes_.resize(layout.num_attribs);
    geometry::FloatCull fcull;
    fcull.cull_front = static_cast<int>(pipe.cull) & static_cast<int>(CullMode::kFront);
    fcull.cull_back = static_cast<int>(pipe.cull) & static_cast<int>(CullMode::kBack);
    fcull.front_ccw = pipe.front_ccw;
    const bool any_cull = pipe.cull != CullMode::kNone;
    const bool unfilled = pipe.polygon_mode != PolygonMode::kFill && verts_per_prim == 3;
    // lp_state_derived.c: a sample mask of 0 (all 32 bits, at any sample count) sets rasterizer_discard, so setup
    // drops every primitive; the vertex shader still runs in draw (its memory writes stay visible).
    const bool discard = pipe.sample_mask == 0;
    if (discard && !vertex_writes_memory(pipe.vertex)) return {};

    geometry::UnfilledConfig ucfg;
    ucfg.layout = layout;
    ucfg.bias_enable = pipe.depth_bias_enable;
    ucfg.bias = depth_bias_for_target(pipe);
    unfilled_scratch_.resize(size_t(3) * geometry::vertex_floats(layout));

    // llvmpipe's triangle-list analysis (lp_setup_analysis.c) runs on a non-indexed list batch handed to
    // draw_arrays, i.e. one that skipped draw's pipeline, when the fragment shader has no flat input.
    bool has_flat_input = false;
    for (geometry::Interp i : rec.varyings.slot_interp) has_flat_input |= i == geometry::Interp::kFlat;
    const bool nine_vertex_candidate =
        !call.indexed && pipe.topology == geometry::Topology::kTriangleList && !has_flat_input;

    // draw's batches: per instance, per restart run, per vsplit segment (draw_batches.h).
    geometry::draw_batches(src, pipe.topology, &batches_);

    for (uint32_t inst = 0; inst < call.instance_count; ++inst) {
        vcfg.instance = inst;
        shade_vertices(vcfg, unique_, *scratch_[0], &shaded_);
        if (discard) continue;
        const bool any_clipped =
            std::any_of(shaded_.clipmask.begin(), shaded_.clipmask.end(), [](uint32_t m) { return m != 0; });
        auto slot = [&](uint32_t index) {
            return static_cast<uint32_t>(std::lower_bound(unique_.begin(), unique_.end(), index) - unique_.begin());
        };
        uint32_t first_prim = 0;
        for (const uint32_t batch_prims : batches_) {
            const uint32_t end_prim = std::min(num_prims, first_prim + batch_prims);
            const uint32_t* batch_ids = assembled_.data() + size_t(first_prim) * verts_per_prim;
            const size_t batch_verts = size_t(end_prim - first_prim) * verts_per_prim;
            // draw_pt_fetch_shade_pipeline_llvm.c: one vertex with a clip-mask bit sends the whole batch through
            // draw's pipeline (clipper, float cull). Unfilled polygons always take it (their stage lives there).
            bool pipeline_path = unfilled;
            for (size_t k = 0; k < batch_verts && any_clipped && !pipeline_path; ++k)
                pipeline_path = shaded_.clipmask[slot(batch_ids[k])] != 0;
            uint32_t batch_end = end_prim;
            if (nine_vertex_candidate && !pipeline_path && batch_verts == 9) {
                float xy[9][2];
                for (int k = 0; k < 9; ++k) {
                    const float* w = geometry::win_pos(shaded_.record(slot(batch_ids[k])));
                    xy[k][0] = w[0];
                    xy[k][1] = w[1];
                }
                geometry::TriangleListBatch qb;
                qb.vertex_count = 9;
                const geometry::NineVertexQuirk q = geometry::nine_vertex_quirk(qb, xy);
                // Swallowed: nothing. Aero: llvmpipe bins one rectangle (lp_rect_cw) covering the first two
                // triangles; drawn here as those two triangles (the rect path is not modelled).
                if (q == geometry::NineVertexQuirk::kSwallowed) batch_end = first_prim;
                if (q == geometry::NineVertexQuirk::kAeroRect) batch_end = first_prim + 2;
            }
            for (uint32_t p = first_prim; p < batch_end; ++p) {
                const uint32_t* ids = assembled_.data() + size_t(p) * verts_per_prim;
                if (verts_per_prim == 1) {
                    const uint32_t s0 = slot(ids[0]);
                    const float* v0 = shaded_.record(s0);
                    if (pipeline_path && !geometry::clip_point_keep(v0, shaded_.clipmask[s0])) continue;
                    add_point(draw_index, rec, v0, shaded_.point_size[s0]);
                    continue;
                }
                if (verts_per_prim == 2) {
                    const uint32_t s0 = slot(ids[0]), s1 = slot(ids[1]);
                    const float *v0 = shaded_.record(s0), *v1 = shaded_.record(s1);
                    if (pipeline_path && !geometry::clip_line(ccfg, v0, v1, shaded_.clipmask[s0], shaded_.clipmask[s1],
                                                              clip_scratch_.data(), &v0, &v1))
                        continue;
                    add_line(draw_index, rec, v0, v1);
                    continue;
                }
                const uint32_t s0 = slot(ids[0]), s1 = slot(ids[1]), s2 = slot(ids[2]);
                const float *v0 = shaded_.record(s0), *v1 = shaded_.record(s1), *v2 = shaded_.record(s2);
                const uint32_t m0 = shaded_.clipmask[s0], m1 = shaded_.clipmask[s1], m2 = shaded_.clipmask[s2];
                if (!pipeline_path) {
                    add_triangle(draw_index, rec, v0, v1, v2);
                    continue;
                }
                geometry::ClippedTriangle out[geometry::kMaxClippedTriangles];
                const uint32_t n = geometry::clip_triangle(ccfg, v0, v1, v2, m0, m1, m2, clip_scratch_.data(), out);
                for (uint32_t t = 0; t < n; ++t) {
                    const float *a = out[t].v[0], *b = out[t].v[1], *c = out[t].v[2];
                    if (any_cull && !geometry::float_cull_keep(fcull, geometry::win_pos(a), geometry::win_pos(b),
                                                               geometry::win_pos(c)))
                        continue;
                    if (!unfilled) {
                        add_triangle(draw_index, rec, a, b, c);
                        continue;
                    }
                    // draw's offset, flatshade and unfilled stages (unfilled.h): edges / corners by edge flag.
                    const float* u[3];
                    geometry::prepare_unfilled_triangle(ucfg, out[t].v, unfilled_scratch_.data(), u);
                    const bool front = geometry::unfilled_front_facing(pipe.front_ccw, geometry::win_pos(a),
                                                                       geometry::win_pos(b), geometry::win_pos(c));
                    if (pipe.polygon_mode == PolygonMode::kLine) {
                        uint8_t lines[3][2];
                        const uint32_t nl = geometry::unfilled_lines(out[t].edges, lines);
                        for (uint32_t l = 0; l < nl; ++l)
                            add_line(draw_index, rec, u[lines[l][0]], u[lines[l][1]], front);
                    } else {
                        for (int k = 0; k < 3; ++k)
                            if (out[t].corners & (1u << k))
                                add_point(draw_index, rec, u[k],
                                          geometry::attrib(u[k], rec.varyings.point_size_slot())[0], front);
                    }
                }
            }
            first_prim = end_prim;
        }
    }
    return {};
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
// draw_regions[0], notes §2).
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

void Renderer::push_prim(uint32_t draw, PrimKind kind, const geometry::AttribPlane& pos, float depth_offset,
                         uint32_t num_attribs) {
    PrimRecord pr;
    pr.draw = draw;
    pr.plane_base = static_cast<uint32_t>(planes_.size());
    pr.kind = kind;
    prims_.push_back(pr);
    const size_t base = planes_.size();
    planes_.resize(base + kPrimHeaderFloats + size_t(kPlaneFloats) * num_attribs);
    float* dst = planes_.data() + base;
    std::memcpy(dst, &pos, sizeof(float) * kPlaneFloats);
    dst[kPlaneFloats] = depth_offset;
    std::memcpy(dst + kPrimHeaderFloats, attrib_planes_.data(), sizeof(float) * kPlaneFloats * num_attribs);
}

void Renderer::add_line(uint32_t draw, const DrawRecord& rec, const float* v0, const float* v1, bool front_facing) {
    const PipelineState& pipe = *rec.pipe;
    geometry::LineSetupConfig cfg;
    cfg.layout = rec.varyings.layout();
    cfg.mode = geometry::LineMode::kRectangular;  // Vulkan's default mode: lavapipe's rectangular lines (notes §6)
    cfg.width = pipe.line_width;
    cfg.multisample = fb_.samples > 1;
    cfg.flatshade_first = true;
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
    in.common.sample_mask = fb_.samples > 1 ? static_cast<uint16_t>(pipe.sample_mask & 0xF) : 1;
    in.common.payload = static_cast<uint32_t>(prims_.size());
    in.front_facing = front_facing;
    if (scene_->add_convex(in) != SetupStatus::kAccepted) return;
    push_prim(draw, PrimKind::kLine, ls.pos, 0.0f, cfg.layout.num_attribs);
}

void Renderer::add_point(uint32_t draw, const DrawRecord& rec, const float* v, float size, bool front_facing) {
    const PipelineState& pipe = *rec.pipe;
    geometry::PointSetupConfig cfg;
    cfg.layout = rec.varyings.layout();
    cfg.multisample = fb_.samples > 1;
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
    in.common.sample_mask = fb_.samples > 1 ? static_cast<uint16_t>(pipe.sample_mask & 0xF) : 1;
    in.common.payload = static_cast<uint32_t>(prims_.size());
    in.front_facing = front_facing;
    if (scene_->add_box(in) != SetupStatus::kAccepted) return;
    push_prim(draw, PrimKind::kPoint, ps.pos, 0.0f, cfg.layout.num_attribs);
}

void Renderer::add_triangle(uint32_t draw, const DrawRecord& rec, const float* v0, const float* v1, const float* v2) {
    const PipelineState& pipe = *rec.pipe;
    TriangleInput tri;
    const float* w[3] = {geometry::win_pos(v0), geometry::win_pos(v1), geometry::win_pos(v2)};
    for (int i = 0; i < 3; ++i) {
        tri.x[i] = w[i][0];
        tri.y[i] = w[i][1];
    }
    tri.cull = pipe.cull;
    tri.front_ccw = pipe.front_ccw;
    tri.flatshade_first = true;
    tri.common.clip = prim_clip(pipe);
    tri.common.sample_mask = fb_.samples > 1 ? static_cast<uint16_t>(pipe.sample_mask & 0xF) : 1;
    tri.common.payload = static_cast<uint32_t>(prims_.size());
    if (scene_->add_triangle(tri) != SetupStatus::kAccepted) return;

    // Planes from the vertices in the order rast/core rasterizes them: cw triangles become (v0, v2, v1).
    const bool ccw = snapped_ccw(w[0], w[1], w[2], fb_.samples);
    const float* o1 = ccw ? v1 : v2;
    const float* o2 = ccw ? v2 : v1;
    geometry::PlaneSetupConfig pcfg;
    pcfg.layout = rec.varyings.layout();
    pcfg.multisample = fb_.samples > 1;
    pcfg.flatshade_first = true;
    pcfg.bias = pipe.depth_bias_enable ? depth_bias_for_target(pipe) : geometry::DepthBias{};
    geometry::TrianglePlanes tp;
    geometry::setup_triangle_planes(pcfg, v0, o1, o2, &tp, attrib_planes_.data());

    PrimRecord pr;
    pr.draw = draw;
    pr.plane_base = static_cast<uint32_t>(planes_.size());
    pr.kind = PrimKind::kTriangle;
    prims_.push_back(pr);
    const size_t base = planes_.size();
    planes_.resize(base + kPrimHeaderFloats + size_t(kPlaneFloats) * pcfg.layout.num_attribs);
    float* dst = planes_.data() + base;
    std::memcpy(dst, &tp.pos, sizeof(float) * kPlaneFloats);
    dst[kPlaneFloats] = tp.depth_offset;
    std::memcpy(dst + kPrimHeaderFloats, attrib_planes_.data(), sizeof(float) * kPlaneFloats * pcfg.layout.num_attribs);
}

}  // namespace tilevk::rast::render
