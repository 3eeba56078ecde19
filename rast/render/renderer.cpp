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
#include "rast/render/linear_bins.h"

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

uint64_t Renderer::shader_loop_limit_hits() const {
    uint64_t hits = fragment_->loop_limit_hits();
    for (const auto& s : scratch_) hits += s->loop_limit_hits();
    return hits;
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
    reset_linear_tiles();
}

void Renderer::end() {
    flush();
}

void Renderer::flush() {
    if (!prims_.empty()) {
        fragment_->prepare(fb_, draws_, prims_, planes_, fused(), pool_.num_workers());
        if (fb_.linear_mode)
            fragment_->set_linear(&tile_linear_, &rect_boxes_);
        else
            fragment_->set_linear(nullptr, nullptr);
        scene_->rasterize(*fragment_, pool_);
        for (uint32_t d = 0; d < draws_.size(); ++d)
            if (uint64_t* sink = draws_[d].samples_passed) *sink += fragment_->samples_passed(d);
    }
    scene_->reset();
    // Draw records stay referenced by nothing once the scene is rendered.
    draws_.clear();
    prims_.clear();
    planes_.clear();
    reset_linear_tiles();
}

// Linear-mode bins are llvmpipe's 64x64 tiles; the scene's tiles are the same (SceneConfig's default tile size,
// which the renderer never changes), so TileInfo::index addresses tile_linear_ directly.
void Renderer::reset_linear_tiles() {
    rect_boxes_.clear();
    if (!fb_.linear_mode) return;
    const int32_t tx = (fb_.width + 63) / 64, ty = (fb_.height + 63) / 64;
    tile_linear_.assign(size_t(tx) * size_t(ty), 1);
}

void Renderer::mark_scene_not_linear() {
    std::fill(tile_linear_.begin(), tile_linear_.end(), uint8_t(0));
}

void Renderer::mark_not_linear(int32_t px0, int32_t py0, int32_t px1, int32_t py1, const ClipRect& clip) {
    px0 = std::max(px0, clip.x0);
    py0 = std::max(py0, clip.y0);
    px1 = std::min(px1, clip.x1 - 1);
    py1 = std::min(py1, clip.y1 - 1);
    if (px0 > px1 || py0 > py1) return;
    const int32_t tx = (fb_.width + 63) / 64;
    for (int32_t y = py0 / 64; y <= py1 / 64; ++y)
        for (int32_t x = px0 / 64; x <= px1 / 64; ++x) tile_linear_[size_t(y) * size_t(tx) + size_t(x)] = 0;
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
    rec.samples_passed = call.samples_passed;
    rec.bindings = bindings;
    rec.push_constants.assign(bindings.push_constants.begin(), bindings.push_constants.end());
    rec.bindings.push_constants = rec.push_constants;
    rec.varyings = make_varyings(pipe.fragment);
    if (pipe.polygon_mode == PolygonMode::kPoint && geometry::vertices_per_primitive(pipe.topology) == 3) {
        rec.varyings.carry_point_size = true;
        rec.varyings.slot_interp.push_back(geometry::Interp::kPerspective);
    }
    if (pipe.fragment && (pipe.fragment->interface().builtins_read & shader::bit(shader::BuiltIn::PointCoord))) {
        rec.varyings.point_coord_slot = static_cast<int32_t>(rec.varyings.slot_interp.size());
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
    rec.linear_slot = -1;
    // lp_fs_linear_run: every float of constant buffer 0 (the fragment push constants) must lie in [0, 1].
    bool constants_in_range = true;
    for (uint32_t off = 0; off + 4 <= pipe.fragment_push_constant_bytes; off += 4) {
        float v = 0.0f;
        if (off + 4 <= rec.push_constants.size()) std::memcpy(&v, rec.push_constants.data() + off, 4);
        constants_in_range = constants_in_range && !(v < 0.0f || v > 1.0f);
    }
    rec.linear = false;
    if (fb_.linear_mode && pipe.fragment && constants_in_range) {
        // llvmpipe's linear variant (lp_state_fs.c, lp_linear.c) for the class shader/ recognises.
        const shader::Program::LinearShader ls = pipe.fragment->linear_shader();
        int slot = -1;
        bool perspective = true, found = ls.location < 0;
        for (size_t k = 0; ls.ok && ls.location >= 0 && k < rec.varyings.slot_location.size(); ++k)
            if (int(rec.varyings.slot_location[k]) == ls.location &&
                rec.varyings.slot_interp[k] != geometry::Interp::kFlat) {
                slot = static_cast<int>(k);
                perspective = rec.varyings.slot_interp[k] == geometry::Interp::kPerspective;
                found = true;
            }
        if (ls.ok && found) {
            rec.linear = true;
            rec.linear_slot = slot;
            rec.linear_perspective = perspective;
            for (int c = 0; c < 4; ++c) {
                rec.linear_channels.source[c] = ls.source[c];
                rec.linear_channels.constant[c] = ls.constant[c];
            }
            rec.linear_channels.usage = ls.usage;
        }
    }

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

    const bool reads_front_facing =
        pipe.fragment && (pipe.fragment->interface().builtins_read & shader::bit(shader::BuiltIn::FrontFacing));
    // draw's batches: per instance, per restart run, per vsplit segment (draw_batches.h).
    geometry::draw_batches(src, pipe.topology, &batches_);

    // lp_setup_vbuf.c offers triangle pairs to the rectangle test only without flat inputs (uses_constant_interp)
    // and, except for the 4-vertex fan's triangle order, only in linear mode; unfilled polygons reach setup as
    // lines or points.
    rect_cfg_.layout = layout;
    rect_cfg_.cull_front = fcull.cull_front;
    rect_cfg_.cull_back = fcull.cull_back;
    rect_cfg_.front_ccw = pipe.front_ccw;
    const bool pair_candidates = !has_flat_input && !unfilled && verts_per_prim == 3;
    rect_pairs_ = fb_.linear_mode && pair_candidates;
    if (rect_pairs_) {
        // vbuf vertex size: position + one vec4 per fragment input (+ face, + point size), 16 bytes each
        // (lp_state_derived.c compute_vertex_info); max_vertices = LP_MAX_VBUF_SIZE 4096 / size.
        uint32_t slots = 1 + static_cast<uint32_t>(rec.varyings.slot_location.size());
        if (pipe.fragment && (pipe.fragment->interface().builtins_read & shader::bit(shader::BuiltIn::FrontFacing)))
            ++slots;
        if (pipe.vertex->interface().builtins_written & shader::bit(shader::BuiltIn::PointSize)) ++slots;
        vbuf_.stride = geometry::vertex_floats(layout);
        vbuf_.max_vertices = 4096 / (16 * slots);
        vbuf_.records.clear();
        vbuf_.vertices = 0;
        vbuf_.emitted_id.clear();
    }
    uint64_t vertex_serial = 0;  // distinguishes vertex headers of different batches and clip calls (vbuf ids)

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
            const uint64_t batch_serial = ++vertex_serial;
            // A batch emitted straight to setup flushes draw's pipeline first (draw_pt_emit.c draw_do_flush).
            if (rect_pairs_ && !pipeline_path) vbuf_flush(draw_index, rec);
            auto tri_of = [&](uint32_t p, const float* v[3]) {
                const uint32_t* ids = assembled_.data() + size_t(p) * 3;
                for (int k = 0; k < 3; ++k) v[k] = shaded_.record(slot(ids[k]));
            };
            if (!pipeline_path && pair_candidates) {
                const float* t0[3];
                const float* t1[3];
                const bool list6 = pipe.topology == geometry::Topology::kTriangleList && batch_verts % 6 == 0;
                if (rect_pairs_ && list6) {
                    // draw_arrays / draw_elements, PIPE_PRIM_TRIANGLES with nr % 6 == 0: rect() per pair
                    for (uint32_t p = first_prim; p + 1 < end_prim; p += 2) {
                        tri_of(p, t0);
                        tri_of(p + 1, t1);
                        rect_or_triangles(draw_index, rec, t0, t1);
                    }
                    first_prim = end_prim;
                    continue;
                }
                if (rect_pairs_ && !call.indexed && pipe.topology == geometry::Topology::kTriangleStrip) {
                    // draw_arrays, strip with flatshade_first: setup->rect on each pair of consecutive triangles;
                    // when it declines, the first is drawn and the pairing moves on by one
                    uint32_t p = first_prim;
                    for (; p + 1 < end_prim;) {
                        tri_of(p, t0);
                        tri_of(p + 1, t1);
                        if (apply_rect_decision(draw_index, rec, t0, t1)) {
                            p += 2;
                        } else {
                            add_triangle(draw_index, rec, t0[0], t0[1], t0[2]);
                            p += 1;
                        }
                    }
                    if (p < end_prim) {
                        tri_of(p, t0);
                        add_triangle(draw_index, rec, t0[0], t0[1], t0[2]);
                    }
                    first_prim = end_prim;
                    continue;
                }
                if (!call.indexed && pipe.topology == geometry::Topology::kTriangleFan && end_prim - first_prim == 2) {
                    // draw_arrays, 4-vertex fan (any mode): rect(v0, v1, v2, v0, v2, v3), i.e. outside linear mode
                    // the triangles (v0, v1, v2), (v0, v2, v3) instead of the fan's (v1, v2, v0), (v2, v3, v0)
                    const float* a[3];
                    const float* b[3];
                    tri_of(first_prim, a);
                    tri_of(first_prim + 1, b);
                    const float* q[4] = {a[2], a[0], a[1], b[1]};
                    const float* u0[3] = {q[0], q[1], q[2]};
                    const float* u1[3] = {q[0], q[2], q[3]};
                    rect_or_triangles(draw_index, rec, u0, u1);
                    first_prim = end_prim;
                    continue;
                }
            }
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
                // Swallowed: nothing. Aero: llvmpipe bins one rectangle, lp_rect_cw(v0, v1, v2, front = TRUE), in
                // any mode; at 4x it is still drawn as its two triangles (rectangles in MSAA are not modelled).
                if (q == geometry::NineVertexQuirk::kSwallowed) batch_end = first_prim;
                if (q == geometry::NineVertexQuirk::kAeroRect) {
                    if (fb_.samples == 1) {
                        const float* t0[3];
                        tri_of(first_prim, t0);
                        add_rect(draw_index, rec, t0[0], t0[1], t0[2], true);
                        batch_end = first_prim;
                    } else {
                        batch_end = first_prim + 2;
                    }
                }
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
                const uint64_t clip_serial = ++vertex_serial;
                for (uint32_t t = 0; t < n; ++t) {
                    const float *a = out[t].v[0], *b = out[t].v[1], *c = out[t].v[2];
                    if (any_cull && !geometry::float_cull_keep(fcull, geometry::win_pos(a), geometry::win_pos(b),
                                                               geometry::win_pos(c)))
                        continue;
                    if (rect_pairs_) {
                        // vbuf vertex ids (draw's vertex_id caching): an input vertex is one header per batch,
                        // a clipper-made one is a fresh header per clip call
                        uint64_t ids[3];
                        for (int k = 0; k < 3; ++k) {
                            const float* r = out[t].v[k];
                            if (r == v0 || r == v1 || r == v2)
                                ids[k] = batch_serial << 32 | (r == v0 ? s0 : r == v1 ? s1 : s2);
                            else
                                ids[k] = clip_serial << 32 | (1u << 31) |
                                         static_cast<uint64_t>((r - clip_scratch_.data()) / vbuf_.stride);
                        }
                        const float* vv[3] = {a, b, c};
                        vbuf_triangle(draw_index, rec, vv, ids);
                        continue;
                    }
                    if (!unfilled) {
                        add_triangle(draw_index, rec, a, b, c);
                        continue;
                    }
                    // draw's offset, flatshade and unfilled stages (unfilled.h): edges / corners by edge flag.
                    const float* u[3];
                    geometry::prepare_unfilled_triangle(ucfg, out[t].v, unfilled_scratch_.data(), u);
                    // llvmpipe's line/point setup takes the facing from the face slot draw's unfilled stage injects,
                    // which exists only when the fragment shader reads gl_FrontFacing (lp_state_derived.c
                    // face_slot); otherwise every edge/corner is front facing, for the two-sided stencil test too.
                    const bool front = !reads_front_facing ||
                                       geometry::unfilled_front_facing(pipe.front_ccw, geometry::win_pos(a),
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
    if (rect_pairs_) vbuf_flush(draw_index, rec);  // llvmpipe_draw_vbo ends with draw_flush
    return {};
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

void Renderer::vbuf_triangle(uint32_t draw, const DrawRecord& rec, const float* const v[3], const uint64_t ids[3]) {
    // draw_pipe_vbuf.c vbuf_tri: check_space(3) against both buffers, then each vertex emitted once per buffer.
    constexpr uint32_t kMaxIndices = 1020;  // lp_setup_vbuf.c LP_MAX_VBUF_INDEXES
    const size_t indices = vbuf_.records.size() / vbuf_.stride;
    if (vbuf_.vertices + 3 > vbuf_.max_vertices || indices + 3 > kMaxIndices) vbuf_flush(draw, rec);
    for (int k = 0; k < 3; ++k) {
        if (std::find(vbuf_.emitted_id.begin(), vbuf_.emitted_id.end(), ids[k]) == vbuf_.emitted_id.end()) {
            vbuf_.emitted_id.push_back(ids[k]);
            ++vbuf_.vertices;
        }
        vbuf_.records.insert(vbuf_.records.end(), v[k], v[k] + vbuf_.stride);
    }
}

void Renderer::vbuf_flush(uint32_t draw, const DrawRecord& rec) {
    // lp_setup_vbuf.c draw_elements, PIPE_PRIM_TRIANGLES: rect() per pair when nr % 6 == 0, else triangles.
    const size_t nr = vbuf_.records.size() / vbuf_.stride;
    auto vert = [&](size_t i) { return vbuf_.records.data() + i * vbuf_.stride; };
    if (nr % 6 == 0) {
        for (size_t i = 0; i + 5 < nr; i += 6) {
            const float* t0[3] = {vert(i), vert(i + 1), vert(i + 2)};
            const float* t1[3] = {vert(i + 3), vert(i + 4), vert(i + 5)};
            rect_or_triangles(draw, rec, t0, t1);
        }
    } else {
        for (size_t i = 0; i + 2 < nr; i += 3) add_triangle(draw, rec, vert(i), vert(i + 1), vert(i + 2));
    }
    vbuf_.records.clear();
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
    in.common.sample_mask = fb_.samples > 1 ? static_cast<uint16_t>(pipe.sample_mask & 0xF) : 1;
    in.common.payload = static_cast<uint32_t>(prims_.size());
    in.front_facing = front;
    if (scene_->add_box(in) != SetupStatus::kAccepted) return;
    // The setup JIT on (c0, c1, c2) as given: no cw reorder for rectangles.
    geometry::PlaneSetupConfig pcfg;
    pcfg.layout = rec.varyings.layout();
    pcfg.multisample = fb_.samples > 1;
    pcfg.flatshade_first = true;
    pcfg.bias = pipe.depth_bias_enable ? depth_bias_for_target(pipe) : geometry::DepthBias{};
    geometry::TrianglePlanes tp;
    geometry::setup_triangle_planes(pcfg, c0, c1, c2, &tp, attrib_planes_.data());
    push_prim(draw, PrimKind::kRect, tp.pos, tp.depth_offset, pcfg.layout.num_attribs);
    if (fb_.linear_mode) {
        prims_.back().rect = static_cast<uint32_t>(rect_boxes_.size());
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
    // No attributes: attrib_planes_ may be empty with a null data(), and memcpy from null is UB even for 0 bytes.
    if (num_attribs != 0)
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
    // one pixel of margin around the line's fixed-point box (llvmpipe's own line box is not modelled)
    if (fb_.linear_mode)
        mark_not_linear((ls.min_x >> 8) - 1, (ls.min_y >> 8) - 1, (ls.max_x >> 8) + 1, (ls.max_y >> 8) + 1,
                        in.common.clip);
    push_prim(draw, PrimKind::kLine, ls.pos, 0.0f, cfg.layout.num_attribs);
}

void Renderer::add_point(uint32_t draw, const DrawRecord& rec, const float* v, float size, bool front_facing) {
    const PipelineState& pipe = *rec.pipe;
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
    in.common.sample_mask = fb_.samples > 1 ? static_cast<uint16_t>(pipe.sample_mask & 0xF) : 1;
    in.common.payload = static_cast<uint32_t>(prims_.size());
    in.front_facing = front_facing;
    if (scene_->add_box(in) != SetupStatus::kAccepted) return;
    if (fb_.linear_mode)
        mark_not_linear((in.x0 >> 8) - 1, (in.y0 >> 8) - 1, (in.x1 >> 8) + 1, (in.y1 >> 8) + 1, in.common.clip);
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
    const bool ccw = snapped_ccw(w[0], w[1], w[2], fb_.samples);
    if (fb_.linear_mode) {
        // llvmpipe's binning of this triangle: tiles where it leaves a partial command are not linear bins
        const float off = triangle_snap_offset(fb_.samples);
        int32_t x[3], y[3];
        bool ok = true;
        const int order[3] = {0, ccw ? 1 : 2, ccw ? 2 : 1};
        for (int i = 0; i < 3; ++i)
            ok = ok && snap_triangle_coord(w[order[i]][0], off, &x[i]) &&
                 snap_triangle_coord(w[order[i]][1], off, &y[i]);
        if (ok)
            mark_partial_triangle_bins(x, y, tri.common.clip, (fb_.width + 63) / 64, &tile_linear_);
        else
            mark_not_linear(0, 0, fb_.width, fb_.height, tri.common.clip);
    }

    // Planes from the vertices in the order rast/core rasterizes them: cw triangles become (v0, v2, v1).
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
    if (pcfg.layout.num_attribs != 0)  // as in push_prim: never memcpy from a null data()
        std::memcpy(dst + kPrimHeaderFloats, attrib_planes_.data(),
                    sizeof(float) * kPlaneFloats * pcfg.layout.num_attribs);
}

}  // namespace tilevk::rast::render
