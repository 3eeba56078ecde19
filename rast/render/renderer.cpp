// The primitive stage of a draw: assembly -> vertex shading -> clipping / float cull -> setup -> binning.
#include "rast/render/renderer.h"

#include <algorithm>

#include "host/cpu.h"
#include "rast/core/fixed_point.h"
#include "rast/fragment/msaa.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/draw_batches.h"
#include "rast/geometry/draw_module.h"
#include "rast/geometry/fp_env.h"
#include "rast/geometry/line_point_setup.h"
#include "rast/geometry/unfilled.h"
#include "rast/geometry/viewport.h"
#include "rast/render/fragment_stage.h"
#include "rast/render/linear_bins.h"
#include "rast/render/linear_mode.h"
#include "rast/render/stage_timer.h"

namespace tilevk::rast::render {
namespace {

// Scenes are flushed (rendered) past this many primitives, so memory stays bounded on huge draws.
constexpr size_t kMaxScenePrims = size_t{1} << 20;
// Between the instances of one draw the bound is tighter: ~45 MB of scene (a set-up rast::Prim is 568 bytes), about
// llvmpipe's LP_SCENE_MAX_SIZE (36 MB, lp_scene.h), so that no growth of the scene's stores copies hundreds of MB in
// one step that a lost device's stop flag could not interrupt.
constexpr size_t kMaxScenePrimsBetweenInstances = size_t{1} << 16;

// Triangle draws from this size set up and bin on the workers (add_triangles_parallel): below it the pool's
// hand-off costs more than it saves.
constexpr uint32_t kParallelTriangles = 2048;

// Stage timing of one draw (stage_timer.h), in the thread's CPU time: the vertex stage is counted apart, the rest
// of the draw is primitive assembly, clipping, setup and binning.
struct DrawTimer {
    uint64_t start = stage_timers_on() ? thread_cpu_ns() : 0;
    uint64_t vertex = 0;
    ~DrawTimer() {
        if (!stage_timers_on()) return;
        const uint64_t total = thread_cpu_ns() - start;
        add_stage_ns(Stage::kVertex, vertex);
        add_stage_ns(Stage::kSetup, total > vertex ? total - vertex : 0);
    }
};

// Record slot per fragment-shader input location, with the interpolation the fragment shader asks for.
void make_varyings(const shader::Program* fs, VaryingMap* out) {
    VaryingMap& map = *out;
    if (!fs) return;
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
}

fragment::ShaderDepthTraits depth_traits(const shader::Program* fs) {
    fragment::ShaderDepthTraits t;
    if (!fs) return t;
    const shader::ProgramInterface& i = fs->interface();
    t.early_fragment_tests = i.early_fragment_tests;
    t.writes_depth = i.writes_frag_depth;
    t.uses_discard = i.uses_discard;
    t.writes_sample_mask = i.builtins_written & shader::bit(shader::BuiltIn::SampleMask);
    t.writes_memory = i.writes_device_addresses;
    for (const shader::DescriptorUse& d : i.descriptors) t.writes_memory |= d.written;
    return t;
}

// The window depths whose fragments this draw's depth test rejects whatever the depth buffer holds
// (geometry::HiddenDepth): the test must see the interpolated depth clamped to [0, 1] against stored values in
// [0, 1] (no bias, depth clamp, shader depth or unrestricted D32F), and a rejected fragment must leave no trace (no
// stencil test, whose depth-fail op writes; no memory writes from the shader, which runs before a late test).
geometry::HiddenDepth hidden_depth(const fragment::DepthStencilState& ds, const PipelineState& pipe,
                                   fragment::DepthFormat format) {
    const fragment::ShaderDepthTraits fs = depth_traits(pipe.fragment);
    if (!ds.depth_test || ds.stencil_test || pipe.depth_bias_enable || ds.depth_clamp || fs.writes_depth ||
        fs.writes_memory || (ds.unrestricted_depth && format == fragment::DepthFormat::D32F))
        return geometry::HiddenDepth::kNone;
    if (ds.depth_compare == fragment::CompareOp::Less) return geometry::HiddenDepth::kFromOne;
    if (ds.depth_compare == fragment::CompareOp::Greater) return geometry::HiddenDepth::kUpToZero;
    return geometry::HiddenDepth::kNone;
}

bool vertex_writes_memory(const shader::Program* vs) {
    if (vs->interface().writes_device_addresses) return true;
    for (const shader::DescriptorUse& d : vs->interface().descriptors)
        if (d.written) return true;
    return false;
}

}  // namespace

bool Renderer::fused() {
    static const bool value = host::has_fma();
    return value;
}

uint64_t Renderer::shader_loop_limit_hits() const {
    uint64_t hits = fragment_->loop_limit_hits();
    for (const auto& w : vertex_workers_) hits += w->scratch.loop_limit_hits();
    return hits;
}

void Renderer::set_stop_flag(const std::atomic<bool>* stop) {
    stop_ = stop;
    for (const auto& w : vertex_workers_) w->scratch.set_stop_flag(stop);
    fragment_->set_stop_flag(stop, &interruption_);
}

std::optional<uint32_t> Renderer::interrupted_draw() const {
    for (const std::atomic<uint32_t>* id : {&interruption_.cut, &interruption_.skipped})
        if (const uint32_t v = id->load(std::memory_order_relaxed); v != Interruption::kNone) return v;
    return std::nullopt;
}

void Renderer::reset_interruption() {
    interruption_.reset();
}

Renderer::Renderer(ThreadPool& pool, Method method) : pool_(pool), method_(method) {
    for (unsigned i = 0; i < pool_.num_workers(); ++i) vertex_workers_.push_back(std::make_unique<VertexWorker>());
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
    cfg.keep_edges = false;  // the method stays method_ (kept anyway when it reads them)
    if (!scene_ || scene_->config().width != cfg.width || scene_->config().height != cfg.height ||
        scene_->config().samples != cfg.samples)
        scene_ = std::make_unique<Scene>(cfg);
    scene_->reset();
    draws_.clear();
    prims_.clear();
    reset_linear_tiles();
}

bool Renderer::end(const TileResolves* resolves) {
    const bool resolved = render_scene(resolves);
    draws_.clear();
    return resolved;
}

// Renders the binned scene (unless the device is lost) and empties it; the draw records stay to the callers.
// With `resolves`, every tile is visited (an empty one still resolves) and true is returned once they ran.
bool Renderer::render_scene(const TileResolves* resolves) {
    bool resolved = false;
    if (!prims_.empty() && stopped()) interruption_.note(false, draws_.back().id);
    if (!prims_.empty() && !stopped()) {
        fragment_->prepare(fb_, draws_, prims_, fused(), pool_.num_workers());
        if (fb_.linear_mode)
            fragment_->set_linear(&tile_linear_, &rect_boxes_);
        else
            fragment_->set_linear(nullptr, nullptr);
        fragment_->set_tile_resolves(resolves);
        scene_->rasterize(*fragment_, pool_, resolves != nullptr);
        fragment_->set_tile_resolves(nullptr);
        resolved = resolves != nullptr;
        for (uint32_t d = 0; d < draws_.size(); ++d) {
            if (uint64_t* sink = draws_[d].samples_passed) *sink += fragment_->samples_passed(d);
            if (RasterStatistics* sink = draws_[d].statistics) sink->fragment_blocks += fragment_->shader_blocks(d);
        }
    }
    scene_->reset();
    prims_.clear();
    reset_linear_tiles();
    return resolved;
}

void Renderer::flush() {
    render_scene();
    draws_.clear();  // draw records stay referenced by nothing once the scene is rendered
}

void Renderer::flush_within_draw(uint32_t* draw_index, const DrawRecord& rec) {
    vbuf_flush(*draw_index, rec);
    render_scene();
    draws_.keep_only_last();  // the running draw's record (its address is unchanged)
    *draw_index = 0;
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

// The draw's record: its pipeline, bindings and push constants (copied: the fragment stage reads them after the
// icd's command has gone), varyings, depth/stencil state against the framebuffer, and llvmpipe's linear-path
// decision for it.
void Renderer::record_draw(DrawRecord& rec, const PipelineState& pipe, const DrawCall& call,
                           const shader::Bindings& bindings) {
    rec.pipe = &pipe;
    rec.id = call.id;
    rec.samples_passed = call.samples_passed;
    rec.statistics = call.statistics;
    rec.bindings = bindings;
    rec.push_constants.assign(bindings.push_constants.begin(), bindings.push_constants.end());
    rec.bindings.push_constants = rec.push_constants;
    make_varyings(pipe.fragment, &rec.varyings);
    if (pipe.polygon_mode == PolygonMode::kPoint && geometry::vertices_per_primitive(pipe.topology) == 3) {
        rec.varyings.carry_point_size = true;
        rec.varyings.slot_interp.push_back(geometry::Interp::kPerspective);
    }
    if (pipe.fragment && (pipe.fragment->interface().builtins_read & shader::bit(shader::BuiltIn::PointCoord))) {
        rec.varyings.point_coord_slot = static_cast<int32_t>(rec.varyings.slot_interp.size());
        rec.varyings.slot_interp.push_back(geometry::Interp::kPerspective);
    }
    const shader::ProgramInterface& vi = pipe.vertex->interface();
    if (const uint32_t distances = vi.clip_distances + vi.cull_distances; distances > 0) {
        rec.varyings.distance_slot = static_cast<int32_t>(rec.varyings.slot_interp.size());
        rec.varyings.num_clip_distances = vi.clip_distances;
        rec.varyings.num_cull_distances = vi.cull_distances;
        for (uint32_t s = 0; s < (distances + 3) / 4; ++s)
            rec.varyings.slot_interp.push_back(geometry::Interp::kPerspective);
    }
    rec.depth_stencil = pipe.depth_stencil;
    {
        const ViewportRect& v = pipe.viewport;
        const geometry::Viewport vp =
            geometry::make_viewport(v.x, v.y, v.width, v.height, v.min_depth, v.max_depth, pipe.clip_halfz);
        geometry::viewport_depth_range(vp, pipe.clip_halfz, &rec.depth_stencil.min_depth, &rec.depth_stencil.max_depth);
    }
    rec.depth_stencil.depth_clamp = pipe.depth_clamp;
    if (!fb_.depth_stencil.depth) rec.depth_stencil.depth_test = rec.depth_stencil.depth_write = false;
    if (!fb_.depth_stencil.stencil) rec.depth_stencil.stencil_test = false;
    rec.depth_mode =
        fragment::choose_depth_mode(rec.depth_stencil, depth_traits(pipe.fragment), pipe.alpha_to_coverage);
    choose_linear_shading(fb_.linear_mode, pipe, rec);
}

// The per-draw configuration that Renderer::draw's batch loop reads, set up once by plan_draw. vcfg.input points at
// input, so a plan is neither copied nor moved.
struct Renderer::DrawPlan {
    const PipelineState* pipe = nullptr;
    bool indexed = false;
    uint32_t num_prims = 0;
    uint32_t verts_per_prim = 0;
    VertexInputState input;
    VertexStageConfig vcfg;
    geometry::ClipConfig ccfg;
    geometry::FloatCull fcull;
    geometry::UnfilledConfig ucfg;
    bool any_cull = false;
    bool unfilled = false;  // polygonMode LINE/POINT on triangles: draw's unfilled stage
    bool discard = false;   // rasterizer discard: the vertex shader runs for its memory writes only
    bool nine_vertex_candidate = false;
    bool reads_front_facing = false;
    bool pair_candidates = false;  // triangle pairs may reach llvmpipe's rectangle test
    bool parallel_triangles = false;
    uint64_t vertex_serial = 0;  // distinguishes vertex headers of different batches and clip calls (vbuf ids)
};

// One draw through lavapipe's draw module and llvmpipe's setup: primitive assembly once for all instances, then
// per instance the vertex stage and draw's batches (emit_batch, or add_triangles_parallel for large triangle draws).
std::string Renderer::draw(const PipelineState& pipe, const DrawCall& call, const shader::Bindings& bindings) {
    // lavapipe runs all of draw (fetch, vertex shader, clip masks, clipper, viewport) and llvmpipe's setup and
    // binning with denormals flushed (draw_pt.c draw_vbo: util_fpstate_set_denorms_to_zero).
    geometry::ScopedFlushDenormals flush_denormals;
    if (!pipe.vertex) return "draw without a vertex shader";
    if (pipe.samples != fb_.samples) return "pipeline sample count differs from the framebuffer's";
    if (call.count == 0 || call.instance_count == 0) return {};
    if (stopped()) {
        interruption_.note(false, call.id);
        return {};
    }
    if (prims_.count() >= kMaxScenePrims) flush();
    DrawTimer timer;  // after the flush: a flush's rendering is timed by the fragment stage

    uint32_t draw_index = static_cast<uint32_t>(draws_.size());
    DrawRecord& rec = draws_.emplace_back();
    record_draw(rec, pipe, call, bindings);

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
    DrawPlan plan;
    if (!plan_draw(plan, pipe, call, rec, src)) return {};

    for (uint32_t n = 0; n < call.instance_count; ++n) {
        const uint32_t inst = call.instance_begin + n;
        if (n > 0 && prims_.count() >= kMaxScenePrimsBetweenInstances) flush_within_draw(&draw_index, rec);
        plan.vcfg.instance = inst;
        uint64_t hits_before = 0;
        for (const auto& w : vertex_workers_) hits_before += w->scratch.loop_limit_hits();
        {
            const uint64_t t0 = stage_timers_on() ? thread_cpu_ns() : 0;
            shade_vertices(plan.vcfg, unique_, pool_, vertex_workers_, &shaded_);
            if (stage_timers_on()) timer.vertex += thread_cpu_ns() - t0;
        }
        if (stopped()) {
            uint64_t hits_after = 0;
            for (const auto& w : vertex_workers_) hits_after += w->scratch.loop_limit_hits();
            interruption_.note(hits_after != hits_before, call.id);
            break;
        }
        if (plan.discard) continue;
        const bool any_clipped =
            std::any_of(shaded_.clipmask.begin(), shaded_.clipmask.end(), [](uint32_t m) { return m != 0; });
        // The parallel path takes the batches up to the last direct one (which flushes draw's vbuf) and, of the
        // batches after it (all through draw's pipeline), the triangles that a full vbuf flushes inside draw_vbo.
        // The rest, from a filling start on, take the batch loop and its vbuf (maybe set up after draw_vbo).
        uint32_t parallel_prims = plan.parallel_triangles ? parallel_prefix(plan, any_clipped) : 0;
        if (plan.parallel_triangles && parallel_prims < plan.num_prims)
            parallel_prims =
                last_filling_start({nullptr, &plan.ccfg, &plan.fcull, plan.any_cull}, plan.num_prims, parallel_prims);
        if (parallel_prims > 0) {
            vbuf_flush(draw_index, rec);
            draw_triangles_parallel(plan, draw_index, rec, any_clipped, parallel_prims);
            if (parallel_prims == plan.num_prims) continue;
        }
        uint32_t first_prim = 0;
        for (const uint32_t batch_prims : batches_) {
            if (stopped()) break;  // the instance loop notes it
            const uint32_t end_prim = std::min(plan.num_prims, first_prim + batch_prims);
            if (end_prim > parallel_prims)
                emit_batch(plan, draw_index, rec, first_prim, end_prim, std::max(first_prim, parallel_prims),
                           any_clipped);
            first_prim = end_prim;
        }
    }
    // llvmpipe_draw_vbo ends with draw_flush, after draw_vbo has restored the thread's float state: the triangles
    // still in draw's vbuf reach setup with denormals kept (lp_draw_arrays.c).
    vbuf_flush(draw_index, rec, /*after_draw=*/true);
    return {};
}

// Assembles the draw's primitives (assembled_, unique_, batches_) and sets up every per-draw configuration; false
// when the draw has nothing to do (rasterizer discard with a vertex shader that writes no memory).
bool Renderer::plan_draw(DrawPlan& plan, const PipelineState& pipe, const DrawCall& call, DrawRecord& rec,
                         const geometry::IndexSource& src) {
    plan.pipe = &pipe;
    plan.indexed = call.indexed;
    assembled_.resize(geometry::assembled_index_capacity(pipe.topology, call.count));
    plan.num_prims =
        geometry::assemble_primitives(src, pipe.topology, pipe.flatshade_first, assembled_.data(), assembled_.size());
    plan.verts_per_prim = geometry::vertices_per_primitive(pipe.topology);
    // The vertices to shade (each used index once, ascending), and assembled_ rewritten from indices to their slots
    // in that list: the primitive loop reads shaded records by slot.
    unique_vertices(size_t(plan.num_prims) * plan.verts_per_prim);

    plan.input.attribs = pipe.attribs;
    plan.input.locations = pipe.attrib_locations;
    plan.input.buffers.resize(pipe.bindings.size());
    for (size_t b = 0; b < pipe.bindings.size(); ++b) {
        geometry::VertexBufferView& vb = plan.input.buffers[b];
        vb.stride = pipe.bindings[b].stride;
        vb.rate = pipe.bindings[b].rate;
        vb.divisor = pipe.bindings[b].divisor;
        if (b < call.vertex_buffers.size()) {
            vb.data = call.vertex_buffers[b].data;
            vb.size = call.vertex_buffers[b].size;
        }
    }

    VertexStageConfig& vcfg = plan.vcfg;
    vcfg.program = pipe.vertex;
    vcfg.bindings = &rec.bindings;
    vcfg.input = &plan.input;
    vcfg.varyings = &rec.varyings;
    const ViewportRect& v = pipe.viewport;
    vcfg.viewport.vp = geometry::make_viewport(v.x, v.y, v.width, v.height, v.min_depth, v.max_depth, pipe.clip_halfz);
    vcfg.viewport.fused = fused();
    vcfg.viewport.bypass = geometry::is_identity_viewport(vcfg.viewport.vp);
    vcfg.clip.clip_z = pipe.depth_clip;
    vcfg.clip.clip_halfz = pipe.clip_halfz;
    vcfg.first_instance = call.first_instance;
    vcfg.base_vertex = call.indexed ? static_cast<uint32_t>(call.vertex_offset) : call.first;
    vcfg.draw_index = call.draw_index;
    vcfg.view_index = fb_.view_index;
    vcfg.stop = stop_;

    const geometry::VertexLayout layout = rec.varyings.layout();
    plan.ccfg.layout = layout;
    plan.ccfg.vp = vcfg.viewport.vp;
    plan.ccfg.clip_halfz = pipe.clip_halfz;
    plan.ccfg.flatshade_first = pipe.flatshade_first;
    plan.ccfg.guard_band_xy = fb_.linear_mode;
    plan.ccfg.cut_xy = pipe.polygon_mode != PolygonMode::kPoint;
    // Filled polygons only: the unfilled stage needs draw's edge flags, which the precise clipper does not keep.
    plan.ccfg.precise_fallback = pipe.polygon_mode == PolygonMode::kFill || plan.verts_per_prim != 3;
    plan.ccfg.samples = fb_.samples;
    plan.ccfg.hidden_depth = hidden_depth(rec.depth_stencil, pipe, fb_.depth_stencil.format);
    plan.ccfg.distance_slot = rec.varyings.distance_slot;
    plan.ccfg.num_clip_distances = rec.varyings.num_clip_distances;
    plan.ccfg.num_cull_distances = rec.varyings.num_cull_distances;
    clip_scratch_.resize(size_t(geometry::kClipScratchVertices) * geometry::vertex_floats(layout));
    attrib_planes_.resize(layout.num_attribs);
    plan.fcull.cull_front = static_cast<int>(pipe.cull) & static_cast<int>(CullMode::kFront);
    plan.fcull.cull_back = static_cast<int>(pipe.cull) & static_cast<int>(CullMode::kBack);
    plan.fcull.front_ccw = pipe.front_ccw;
    plan.any_cull = pipe.cull != CullMode::kNone;
    plan.unfilled = pipe.polygon_mode != PolygonMode::kFill && plan.verts_per_prim == 3;
    // lp_state_derived.c: a sample mask of 0 (all 32 bits, at any sample count) sets rasterizer_discard, so setup
    // drops every primitive; the vertex shader still runs in draw (its memory writes stay visible).
    plan.discard = pipe.sample_mask == 0;
    if (plan.discard && !vertex_writes_memory(pipe.vertex)) return false;

    plan.ucfg.layout = layout;
    plan.ucfg.flatshade_first = pipe.flatshade_first;
    plan.ucfg.bias_enable = pipe.depth_bias_enable;
    plan.ucfg.bias = depth_bias_for_target(pipe);
    unfilled_scratch_.resize(size_t(3) * geometry::vertex_floats(layout));

    // llvmpipe's triangle-list analysis (lp_setup_analysis.c) runs on a non-indexed list batch handed to
    // draw_arrays, i.e. one that skipped draw's pipeline, when the fragment shader has no flat input.
    bool has_flat_input = false;
    for (geometry::Interp i : rec.varyings.slot_interp) has_flat_input |= i == geometry::Interp::kFlat;
    plan.nine_vertex_candidate = !call.indexed && pipe.topology == geometry::Topology::kTriangleList && !has_flat_input;
    plan.reads_front_facing =
        pipe.fragment && (pipe.fragment->interface().builtins_read & shader::bit(shader::BuiltIn::FrontFacing));
    // draw's batches: per instance, per restart run, per vsplit segment (draw_batches.h).
    geometry::draw_batches(src, pipe.topology, &batches_);

    // lp_setup_vbuf.c offers triangle pairs to the rectangle test only without flat inputs (uses_constant_interp)
    // and, except for the 4-vertex fan's triangle order, only in linear mode; unfilled polygons reach setup as
    // lines or points.
    plan.pair_candidates = !has_flat_input && !plan.unfilled && plan.verts_per_prim == 3;
    vbuf_triangles_ = plan.verts_per_prim == 3 && !plan.unfilled;
    geometry::DrawModuleConfig dcfg;
    dcfg.rect.layout = layout;
    dcfg.rect.cull_front = plan.fcull.cull_front;
    dcfg.rect.cull_back = plan.fcull.cull_back;
    dcfg.rect.front_ccw = pipe.front_ccw;
    dcfg.linear_mode = fb_.linear_mode;
    dcfg.pair_candidates = plan.pair_candidates;
    dcfg.flatshade_first = pipe.flatshade_first;
    dcfg.single_sample = fb_.samples == 1;
    // Unfilled triangles reach the vbuf as their edges or corners. Its vertex: position + one vec4 per fragment
    // input (+ face, + point size).
    dcfg.verts_per_prim = !plan.unfilled ? plan.verts_per_prim : pipe.polygon_mode == PolygonMode::kLine ? 2 : 1;
    dcfg.record_floats = geometry::vertex_floats(layout);
    dcfg.vertex_slots = 1 + static_cast<uint32_t>(rec.varyings.slot_location.size());
    if (plan.reads_front_facing) ++dcfg.vertex_slots;
    if (pipe.vertex->interface().builtins_written & shader::bit(shader::BuiltIn::PointSize)) ++dcfg.vertex_slots;
    draw_module_.begin_draw(dcfg);

    // Large triangle draws where the batch loop would call add_triangle for each triangle of a direct batch and
    // for each clipped, float-culled piece of a pipeline batch, in order: no unfilled polygons, no linear mode
    // (rectangle pairs, vbuf), no batch that a lavapipe quirk reads (the 9-vertex list batch, the 4-vertex fan).
    // Those run on the workers (add_triangles_parallel).
    plan.parallel_triangles = plan.verts_per_prim == 3 && !plan.unfilled && !fb_.linear_mode && !plan.discard &&
                              plan.ccfg.num_cull_distances == 0 && plan.num_prims >= kParallelTriangles &&
                              pool_.num_workers() > 1;
    for (const uint32_t batch_prims : batches_) {
        if (!plan.parallel_triangles) break;
        const bool nine = plan.nine_vertex_candidate && size_t(batch_prims) * 3 == 9;
        const bool fan4 = plan.pair_candidates && !call.indexed && pipe.topology == geometry::Topology::kTriangleFan &&
                          batch_prims == 2;
        plan.parallel_triangles = !nine && !fan4;
    }
    return true;
}

// The first `num_prims` triangles of one instance of a parallel triangle draw: which batches go through draw's
// pipeline, then the workers.
void Renderer::draw_triangles_parallel(const DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec,
                                       bool any_clipped, uint32_t num_prims) {
    // draw_pt_fetch_shade_pipeline_llvm.c: one vertex with a clip-mask bit sends the whole batch through draw's
    // pipeline (clipper, float cull), as in emit_batch.
    tri_pipeline_.assign(num_prims, 0);
    // num_prims may end inside a batch: the whole batch decides.
    uint32_t first = 0;
    for (const uint32_t batch_prims : batches_) {
        if (first >= num_prims) break;
        const uint32_t end = std::min(plan.num_prims, first + batch_prims);
        if (batch_takes_pipeline(first, end, any_clipped))
            std::fill(tri_pipeline_.begin() + first, tri_pipeline_.begin() + std::min(num_prims, end), uint8_t(1));
        first = end;
    }
    add_triangles_parallel(draw_index, rec, assembled_.data(), num_prims,
                           {tri_pipeline_.data(), &plan.ccfg, &plan.fcull, plan.any_cull});
}

// Whether triangles [first, end) of a filled triangle draw's batch take draw's pipeline: one of their vertices has
// a clip-mask bit (draw_pt_fetch_shade_pipeline_llvm.c).
bool Renderer::batch_takes_pipeline(uint32_t first, uint32_t end, bool any_clipped) const {
    if (!any_clipped) return false;
    for (size_t k = size_t(first) * 3; k < size_t(end) * 3; ++k)
        if (shaded_.clipmask[assembled_[k]] != 0) return true;
    return false;
}

// How many leading triangles of the instance the parallel path sets up: those up to the end of its last direct
// batch. A batch through draw's pipeline leaves its triangles in draw's vbuf until the next direct batch flushes it
// inside draw_vbo, with denormals flushed, as the parallel path sets everything up; the batches after the last
// direct one are flushed later (maybe after draw_vbo, with denormals kept), so they take the batch loop and its vbuf.
uint32_t Renderer::parallel_prefix(const DrawPlan& plan, bool any_clipped) const {
    uint32_t first = 0, prefix = 0;
    for (const uint32_t batch_prims : batches_) {
        const uint32_t end = std::min(plan.num_prims, first + batch_prims);
        if (!batch_takes_pipeline(first, end, any_clipped)) prefix = end;
        first = end;
    }
    return prefix;
}

// One of draw's batches, primitives [first_prim, end_prim): straight to setup, or through draw's pipeline.
void Renderer::emit_batch(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, uint32_t first_prim,
                          uint32_t end_prim, uint32_t start_prim, bool any_clipped) {
    const uint32_t vpp = plan.verts_per_prim;
    const uint32_t* batch_ids = assembled_.data() + size_t(first_prim) * vpp;
    const size_t batch_verts = size_t(end_prim - first_prim) * vpp;
    // draw_pt_fetch_shade_pipeline_llvm.c: one vertex with a clip-mask bit sends the whole batch through draw's
    // pipeline (clipper, float cull). Unfilled polygons and CullDistance always take it (their stages live there:
    // draw_pipe_validate.c draw_need_pipeline).
    bool pipeline_path = plan.unfilled || plan.ccfg.num_cull_distances > 0;
    for (size_t k = 0; k < batch_verts && any_clipped && !pipeline_path; ++k)
        pipeline_path = shaded_.clipmask[batch_ids[k]] != 0;
    const uint64_t batch_serial = ++plan.vertex_serial;
    // A batch emitted straight to setup flushes draw's pipeline first (draw_pt_emit.c draw_do_flush).
    if (!pipeline_path) vbuf_flush(draw_index, rec);
    if (!pipeline_path && plan.pair_candidates &&
        emit_direct_pairs(draw_index, rec, plan.pipe->topology, plan.indexed, first_prim, end_prim))
        return;
    const uint32_t batch_end = plan.nine_vertex_candidate && !pipeline_path && batch_verts == 9
                                   ? nine_vertex_batch_end(draw_index, rec, first_prim, end_prim)
                                   : end_prim;
    for (uint32_t p = start_prim; p < batch_end; ++p) {
        const uint32_t* ids = assembled_.data() + size_t(p) * vpp;
        if (plan.ccfg.num_cull_distances > 0) {  // draw's user_cull stage, first in the pipeline
            const float* rv[3] = {};
            for (uint32_t k = 0; k < vpp; ++k) rv[k] = shaded_.record(ids[k]);
            if (!geometry::cull_distance_keep(plan.ccfg, rv, vpp)) continue;
        }
        if (vpp == 1) {
            const float* v0 = shaded_.record(ids[0]);
            if (!pipeline_path) {
                add_point(draw_index, rec, v0, shaded_.point_size[ids[0]]);
            } else if (geometry::clip_point_keep(v0, shaded_.clipmask[ids[0]])) {
                const uint64_t id = batch_serial << 32 | ids[0];
                vbuf_primitive(draw_index, rec, &v0, &id, shaded_.point_size[ids[0]]);
            }
        } else if (vpp == 2) {
            emit_line(plan, draw_index, rec, ids, pipeline_path, batch_serial);
        } else if (!pipeline_path) {
            add_triangle(draw_index, rec, shaded_.record(ids[0]), shaded_.record(ids[1]), shaded_.record(ids[2]));
        } else {
            emit_clipped_triangle(plan, draw_index, rec, ids, batch_serial);
        }
    }
}

// A line (shaded slots ids[0..1]): straight to setup, or through draw's clipper into the vbuf stage (a new end is a
// fresh vertex header per clip call).
void Renderer::emit_line(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, const uint32_t* ids,
                         bool pipeline_path, uint64_t batch_serial) {
    const float* v[2] = {shaded_.record(ids[0]), shaded_.record(ids[1])};
    if (!pipeline_path) {
        add_line(draw_index, rec, v[0], v[1]);
        return;
    }
    const float* in[2] = {v[0], v[1]};
    if (!geometry::clip_line(plan.ccfg, in[0], in[1], shaded_.clipmask[ids[0]], shaded_.clipmask[ids[1]],
                             clip_scratch_.data(), &v[0], &v[1]))
        return;
    const uint64_t clip_serial = ++plan.vertex_serial;
    uint64_t vbuf_ids[2];
    for (int k = 0; k < 2; ++k)
        vbuf_ids[k] = v[k] == in[k] ? batch_serial << 32 | ids[k] : clip_serial << 32 | (1u << 31) | uint64_t(k);
    vbuf_primitive(draw_index, rec, v, vbuf_ids);
}

// A triangle of a pipeline batch (shaded slots ids[0..2]): draw's clipper and float cull, then vbuf (linear mode),
// setup, or the unfilled stage.
void Renderer::emit_clipped_triangle(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, const uint32_t* ids,
                                     uint64_t batch_serial) {
    const uint32_t s0 = ids[0], s1 = ids[1], s2 = ids[2];
    const float *v0 = shaded_.record(s0), *v1 = shaded_.record(s1), *v2 = shaded_.record(s2);
    geometry::ClippedTriangle out[geometry::kMaxClippedTriangles];
    const uint32_t n = geometry::clip_triangle(plan.ccfg, v0, v1, v2, shaded_.clipmask[s0], shaded_.clipmask[s1],
                                               shaded_.clipmask[s2], clip_scratch_.data(), out);
    const uint64_t clip_serial = ++plan.vertex_serial;
    for (uint32_t t = 0; t < n; ++t) {
        const float *a = out[t].v[0], *b = out[t].v[1], *c = out[t].v[2];
        if (plan.any_cull &&
            !geometry::float_cull_keep(plan.fcull, geometry::win_pos(a), geometry::win_pos(b), geometry::win_pos(c)))
            continue;
        // vbuf vertex ids (draw's vertex_id caching): an input vertex is one header per batch, a clipper-made one
        // is a fresh header per clip call
        uint64_t vbuf_ids[3];
        for (int k = 0; k < 3; ++k) {
            const float* r = out[t].v[k];
            if (r == v0 || r == v1 || r == v2)
                vbuf_ids[k] = batch_serial << 32 | (r == v0 ? s0 : r == v1 ? s1 : s2);
            else
                vbuf_ids[k] = clip_serial << 32 | (1u << 31) |
                              static_cast<uint64_t>((r - clip_scratch_.data()) / draw_module_.record_floats());
        }
        if (vbuf_triangles_) {
            const float* vv[3] = {a, b, c};
            vbuf_primitive(draw_index, rec, vv, vbuf_ids);
        } else if (!plan.unfilled) {
            add_triangle(draw_index, rec, a, b, c);
        } else {
            emit_unfilled(plan, draw_index, rec, out[t], vbuf_ids);
        }
    }
}

// draw's offset, flatshade and unfilled stages (unfilled.h) on one clipped triangle: edges / corners by edge flag,
// into the vbuf stage. `ids`: its vertex headers as the clipper left them.
void Renderer::emit_unfilled(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec,
                             const geometry::ClippedTriangle& tri, const uint64_t ids[3]) {
    const PipelineState& pipe = *plan.pipe;
    const float* u[3];
    geometry::prepare_unfilled_triangle(plan.ucfg, tri.v, unfilled_scratch_.data(), u);
    // The headers the vbuf sees: the offset stage copies all three (dup_vert), the flatshade stage, always in the
    // pipeline with unfilled polygons, the two that are not provoking, and the face slot's injection resets every
    // header's vertex_id (draw_pipe_offset.c, draw_pipe_flatshade.c, draw_pipe_unfilled.c): each such one is a new
    // vertex per triangle.
    const uint64_t tri_serial = ++plan.vertex_serial;
    const int provoking = pipe.flatshade_first ? 0 : 2;
    uint64_t vid[3];
    for (int k = 0; k < 3; ++k)
        vid[k] = plan.ucfg.bias_enable || plan.reads_front_facing || k != provoking
                     ? tri_serial << 32 | (1u << 30) | uint64_t(k)
                     : ids[k];
    // llvmpipe's line/point setup takes the facing from the face slot draw's unfilled stage injects, which exists
    // only when the fragment shader reads gl_FrontFacing (lp_state_derived.c face_slot); otherwise every
    // edge/corner is front facing, for the two-sided stencil test too.
    const bool front = !plan.reads_front_facing ||
                       geometry::unfilled_front_facing(pipe.front_ccw, geometry::win_pos(tri.v[0]),
                                                       geometry::win_pos(tri.v[1]), geometry::win_pos(tri.v[2]));
    if (pipe.polygon_mode == PolygonMode::kLine) {
        uint8_t lines[3][2];
        const uint32_t nl = geometry::unfilled_lines(tri.edges, lines);
        for (uint32_t l = 0; l < nl; ++l) {
            const float* v[2] = {u[lines[l][0]], u[lines[l][1]]};
            const uint64_t line_ids[2] = {vid[lines[l][0]], vid[lines[l][1]]};
            vbuf_primitive(draw_index, rec, v, line_ids, 1.0f, front);
        }
    } else {
        for (int k = 0; k < 3; ++k)
            if (tri.edges & (1u << k))
                vbuf_primitive(draw_index, rec, &u[k], &vid[k],
                               geometry::attrib(u[k], rec.varyings.point_size_slot())[0], front);
    }
}

// unique_ = the distinct indices of assembled_[0, n) in ascending order; assembled_[i] becomes the position of
// its index in unique_. A table over [min, max] index when the range is not much larger than the draw (every
// non-indexed draw, most indexed ones), else a sort.
void Renderer::unique_vertices(size_t n) {
    unique_.clear();
    if (n == 0) return;
    // Consecutive indices (every non-indexed list draw): each is used once, in order, so slot i is index first + i.
    const uint32_t first = assembled_[0];
    bool consecutive = uint64_t(first) + n - 1 <= 0xFFFFFFFFull;  // no 32-bit wrap
    for (size_t i = 0; i < n && consecutive; i += 1024) {
        const size_t end = std::min(n, i + 1024);
        bool run = true;  // a branch-free inner loop per block, so the check vectorizes
        for (size_t k = i; k < end; ++k) run &= assembled_[k] == first + static_cast<uint32_t>(k);
        consecutive = run;
    }
    if (consecutive) {
        unique_.resize(n);
        for (size_t i = 0; i < n; ++i) {
            unique_[i] = first + static_cast<uint32_t>(i);
            assembled_[i] = static_cast<uint32_t>(i);
        }
        return;
    }
    const auto [lo_it, hi_it] = std::minmax_element(assembled_.begin(), assembled_.begin() + n);
    const uint32_t lo = *lo_it;
    const uint64_t range = uint64_t(*hi_it) - lo + 1;
    if (range <= 4 * uint64_t(n) + 4096) {
        constexpr uint32_t kUnused = ~0u;
        slot_of_.assign(range, kUnused);
        for (size_t i = 0; i < n; ++i) slot_of_[assembled_[i] - lo] = 0;
        for (uint32_t k = 0; k < range; ++k)
            if (slot_of_[k] != kUnused) {
                slot_of_[k] = static_cast<uint32_t>(unique_.size());
                unique_.push_back(lo + k);
            }
        for (size_t i = 0; i < n; ++i) assembled_[i] = slot_of_[assembled_[i] - lo];
        return;
    }
    unique_.assign(assembled_.begin(), assembled_.begin() + n);
    std::sort(unique_.begin(), unique_.end());
    unique_.erase(std::unique(unique_.begin(), unique_.end()), unique_.end());
    for (size_t i = 0; i < n; ++i)
        assembled_[i] =
            static_cast<uint32_t>(std::lower_bound(unique_.begin(), unique_.end(), assembled_[i]) - unique_.begin());
}

}  // namespace tilevk::rast::render
