// Per 4x4 block: interpolate -> (early depth/stencil) -> fragment shader -> alpha to coverage -> (late
// depth/stencil) -> blend and write, per sample plane. Orders and formulas are lavapipe's (lavapipe-rules §3–§5).
#include "rast/render/fragment_stage.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "host/cpu.h"
#include "rast/fragment/blend.h"
#include "rast/fragment/block.h"
#include "rast/fragment/interp.h"
#include "rast/fragment/msaa.h"
#include "rast/geometry/fp_env.h"
#include "rast/render/fragment_plan.h"
#include "rast/render/stage_timer.h"
#include "shader/program.h"

namespace tilevk::rast::render {

namespace {
// Adds the ticks from construction to destruction to `sink` when stage timing is on.
struct TickScope {
    uint64_t& sink;
    uint64_t start;
    explicit TickScope(uint64_t& s) : sink(s), start(stage_timers_on() ? stage_ticks() : 0) {}
    ~TickScope() {
        if (stage_timers_on()) sink += stage_ticks() - start;
    }
};
}  // namespace

namespace {
std::atomic<int> g_fast_paths{-1};  // -1: not read from the environment yet
}  // namespace

uint64_t FragmentStage::samples_passed(uint32_t draw) const {
    uint64_t n = 0;
    for (const auto& w : workers_)
        if (draw < w->samples_passed.size()) n += w->samples_passed[draw];
    return n;
}

uint64_t FragmentStage::shader_blocks(uint32_t draw) const {
    uint64_t n = 0;
    for (const auto& w : workers_)
        if (draw < w->shader_blocks.size()) n += w->shader_blocks[draw];
    return n;
}

namespace {
// FRAGMENT_SHADER_INVOCATIONS / 16 of one primitive in one tile. llvmpipe's generated 4x4-block fragment function
// adds 1 to its thread's counter on every call, before any test and whatever its mask (lp_state_fs.c; lavapipe's
// NIR shaders, its dummy one included, always pass the `num_instructions > 1` guard: nir_tgsi_scan_shader sets 2),
// and lp_query.c multiplies the sum by 16. Its rasterizer calls the function once per 4x4 block with coverage:
// partial blocks with a non-zero mask (lp_rast_tri_tmp.h, lp_rast_rect.c) and every block of a fully covered 16x16
// block or 64x64 tile (lp_rast_shade_tile, up to the framebuffer's edge, which full squares never cross). Once per
// block also under sample shading (the sample loop is inside the function) and at any sample count. Linear bins
// (lp_rast_linear.c) call it only where the linear shader declines (lp_rast_linear_fallback.c: every block of the
// box), which is where primitive() goes on to the general path.
uint64_t shader_calls(const PrimCoverage& cov) {
    uint64_t n = cov.num_blocks;
    for (size_t i = 0; i < cov.num_blocks16; ++i)
        for (const uint16_t m : cov.blocks16[i].mask) n += m != 0;
    for (size_t i = 0; i < cov.num_full; ++i) n += uint64_t(cov.full[i].size / 4) * uint64_t(cov.full[i].size / 4);
    return n;
}
}  // namespace

uint64_t FragmentStage::loop_limit_hits() const {
    uint64_t hits = 0;
    for (const auto& w : workers_) hits += w->scratch.loop_limit_hits();
    return hits;
}

void set_fragment_fast_paths(bool on) {
    g_fast_paths.store(on ? 1 : 0);
}

bool fragment_fast_paths() {
    int v = g_fast_paths.load();
    if (v < 0) {
        const char* e = std::getenv("TILEVK_FRAG");
        v = (e && std::string_view(e) == "reference") ? 0 : 1;
        g_fast_paths.store(v);
    }
    return v != 0;
}

namespace {

using fragment::kBlockLanes;

// Raster-order coverage (bit y*4+x) of the pixels of a block that exist in the framebuffer.
uint16_t inside_mask(int32_t x, int32_t y, int32_t width, int32_t height) {
    uint16_t m = 0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            if (x + i < width && y + j < height) m |= uint16_t(1u << (j * 4 + i));
    return m;
}

// The planes of the copied location's four components (plan.copy_location) when all four are interpolated alike and
// not flat (flat ones take the uniform run): their slot plane offsets, and whether they divide by w.
bool copied_planes(const DrawPlan& plan, uint32_t plane[4], bool& perspective) {
    if (plan.copy_location < 0 || plan.uniform_shader) return false;
    uint32_t found = 0;
    geometry::Interp interp = geometry::Interp::kFlat;
    for (const InputPlan& in : plan.inputs) {
        if (in.loc != uint32_t(plan.copy_location) || in.comp >= 4) continue;
        if (found != 0 && in.interp != interp) return false;
        interp = in.interp;
        plane[in.comp] = in.plane;
        found |= 1u << in.comp;
    }
    if (found != 0xf || interp == geometry::Interp::kFlat) return false;
    perspective = interp == geometry::Interp::kPerspective;
    return true;
}

// SquarePlan (fragment_plan.h) from a finished plan: whether the fused square kernel reproduces the block pipeline.
void make_square_plan(const DrawRecord& draw, const Framebuffer& fb, DrawPlan& plan) {
    SquarePlan& sq = plan.square;
    const PipelineState& pipe = *draw.pipe;
    if (!pipe.fragment || plan.copy_location < 0 || plan.uniform_shader || fb.samples != 1 || draw.depth_mode != 0 ||
        pipe.alpha_to_coverage || pipe.alpha_to_one || fb.num_color < 1 || !fb.color[0].data)
        return;
    for (uint32_t c = 1; c < fb.num_color && c < kMaxColorTargets; ++c)
        if (fb.color[c].data && plan.color[c] != ColorPath::kNone) return;
    const ColorPath path = plan.color[0];
    if (path == ColorPath::kRgba8) {
        if (!plan.rgba8[0].ok || !plan.rgba8[0].over) return;
        sq.over = true;
        sq.bgra = plan.rgba8[0].bgra;
        sq.wmask_mem = plan.rgba8[0].wmask_mem;
    } else if (path == ColorPath::kOpaqueRgba8 || path == ColorPath::kOpaqueBgra8) {
        sq.bgra = path == ColorPath::kOpaqueBgra8;
    } else {
        return;
    }
    sq.ok = copied_planes(plan, sq.plane, sq.perspective);
}

// The one colour target the plan writes, or -1 when it writes none or more than one.
int sole_written_target(const Framebuffer& fb, const DrawPlan& plan) {
    int target = -1;
    for (uint32_t c = 0; c < fb.num_color && c < shader::kMaxColorOutputs; ++c) {
        if (!fb.color[c].data || plan.color[c] == ColorPath::kNone) continue;
        if (target >= 0) return -1;  // a second written target
        target = int(c);
    }
    return target;
}

// Block1xPlan from a finished plan. The conditions are those under which shade_block_n<1>'s steps leave the final
// mask equal to the early test's survivors (no discard, sample mask output, alpha to coverage, late test or query)
// and its colour is write_color_in_place's opaque store of the uniform run's or the copied input's colour.
void make_block1x_plan(const DrawRecord& draw, const Framebuffer& fb, DrawPlan& plan) {
    Block1xPlan& bp = plan.block1x;
    const PipelineState& pipe = *draw.pipe;
    if (fb.samples != 1 || !pipe.fragment || draw.samples_passed || pipe.alpha_to_coverage || pipe.alpha_to_one) return;
    const uint8_t depth_flags = draw.depth_mode & uint8_t(~fragment::kEarlyDepthTestInferred);
    if (depth_flags != 0) {
        if (!plan.depth_fast || (depth_flags & ~fragment::kEarlyDepthWrite) != fragment::kEarlyDepthTest) return;
        bp.depth = true;
        bp.depth_write = depth_flags & fragment::kEarlyDepthWrite;
    }
    const int target = sole_written_target(fb, plan);
    if (target < 0) return;
    const ColorPath path = plan.color[target];
    if (path != ColorPath::kOpaqueRgba8 && path != ColorPath::kOpaqueBgra8) return;
    bp.bgra = path == ColorPath::kOpaqueBgra8;
    bp.target = uint32_t(target);
    bp.copy = !plan.uniform_shader;
    if (bp.copy && (target != 0 || !copied_planes(plan, bp.plane, bp.perspective))) return;
    bp.ok = true;
}

// DrawPlan::uniform_store_4x from a finished plan. The conditions are those under which shade_block_n<4> keeps
// each sample's coverage as its final mask: no depth or query, a uniform shader (no discard, no written sample
// mask), no alpha to coverage; and those of write_color_in_place's opaque store: no alpha to one, an opaque RGBA8 or
// BGRA8 path.
void make_uniform_store_plan(const DrawRecord& draw, const Framebuffer& fb, DrawPlan& plan) {
    const PipelineState& pipe = *draw.pipe;
    if (fb.samples != 4 || !pipe.fragment || !plan.uniform_shader || draw.depth_mode != 0 || draw.samples_passed ||
        pipe.alpha_to_coverage || pipe.alpha_to_one)
        return;
    const int target = sole_written_target(fb, plan);
    if (target < 0) return;
    const ColorPath path = plan.color[target];
    if (path == ColorPath::kOpaqueRgba8 || path == ColorPath::kOpaqueBgra8) plan.uniform_store_4x = target;
}

// What the fast path needs to know about a draw, derived once per scene.
// Fills `plan` in place (its input list keeps its storage from the last scene: no allocation in a steady frame).
// DrawPlan::direct, after the inputs and colour paths are planned. Each plan gets a key of its own: a draw record's
// bindings may change between scenes at the same address.
void make_direct_plan(const DrawRecord& draw, const Framebuffer& fb, DrawPlan& plan) {
    static std::atomic<uint64_t> next_key{1};
    const shader::Program* fs = draw.pipe->fragment;
    if (!fs || plan.uniform_shader || plan.copy_location >= 0 || draw.pipe->alpha_to_coverage) return;
    const shader::Program::FragmentDirect& d = fs->fragment_direct();
    if (!d.ok) return;
    uint32_t provided[shader::kMaxLocations] = {};  // components the plan interpolates, per location
    for (const InputPlan& in : plan.inputs) {
        if (in.loc >= uint32_t(shader::kMaxLocations)) return;  // gl_PointCoord: a FragmentBlock input
        provided[in.loc] |= 1u << in.comp;
    }
    for (uint32_t i = 0; i < std::size(d.input_word); ++i)
        if (d.input_word[i] != ~0u && !((provided[i / 4] >> (i % 4)) & 1)) return;  // would keep a stale word
    for (uint32_t c = 0; c < fb.num_color && c < uint32_t(kMaxColorTargets); ++c) {
        if (plan.color[c] == ColorPath::kNone) continue;
        if (c >= uint32_t(shader::kMaxColorOutputs) || d.output_word[c] == ~0u) return;
        plan.output_word[c] = d.output_word[c];
    }
    for (InputPlan& in : plan.inputs) in.word = d.input_word[in.loc * 4 + in.comp];
    plan.direct = true;
    plan.bindings_key = next_key.fetch_add(1, std::memory_order_relaxed);
}

void make_plan(const DrawRecord& draw, const Framebuffer& fb, DrawPlan& plan) {
    std::vector<InputPlan> inputs = std::move(plan.inputs);
    inputs.clear();
    plan = DrawPlan{};
    plan.inputs = std::move(inputs);
    if (!draw.pipe) return;
    const PipelineState& pipe = *draw.pipe;
    // Sample shading, and centroid inputs at 4x, take the reference pipeline (shade_block, shade_samples), which
    // interpolates each input at its own site.
    if (fb.samples > 1 && pipe.fragment) {
        if (pipe.per_sample) return;
        for (const shader::IoVariable& v : pipe.fragment->interface().inputs)
            if (v.centroid || v.sample) return;
    }
    // InterpolateAt* re-evaluates planes the reference pipeline hands the program (set_fragment_inputs).
    if (pipe.fragment && pipe.fragment->interface().interpolates_at) return;
    // Dual-source blending takes the reference pipeline, the only one that reads the second colour output.
    plan.fast = !fragment::uses_second_source(pipe.blend[0]);

    const shader::Program* fs = pipe.fragment;
    bool all_flat = true;
    if (fs) {
        const shader::ProgramInterface& iface = fs->interface();
        const size_t num_slots = draw.varyings.slot_location.size();
        for (size_t slot = 0; slot < num_slots; ++slot) {
            const uint32_t loc = draw.varyings.slot_location[slot];
            // Components the shader declares at this location (the interpreter copies only those in).
            uint32_t comps = 0;
            for (const shader::IoVariable& v : iface.inputs)
                if (v.location == loc) comps |= ((1u << v.components) - 1u) << v.component;
            const geometry::Interp interp = draw.varyings.slot_interp[slot];
            all_flat &= interp == geometry::Interp::kFlat;
            plan.perspective |= interp == geometry::Interp::kPerspective && (comps & 0xfu);
            for (uint32_t c = 0; c < 4; ++c)
                if (comps & (1u << c)) plan.inputs.push_back({loc, c, uint32_t(slot * kPlaneFloats), interp});
        }
        if (draw.varyings.point_coord_slot >= 0) {
            all_flat = false;
            plan.perspective = true;
            for (uint32_t c = 0; c < 2; ++c)
                plan.inputs.push_back({kPointCoordLoc, c, uint32_t(draw.varyings.point_coord_slot * kPlaneFloats),
                                       geometry::Interp::kPerspective});
        }
        // The outputs cannot vary across a primitive when every input is flat, no per-fragment built-in is read
        // (front facing is per primitive), nothing is discarded or written besides colour, and there are no
        // derivatives (helper lanes): one run per primitive then gives every fragment's result.
        bool writes_memory = iface.writes_device_addresses;
        for (const shader::DescriptorUse& d : iface.descriptors) writes_memory |= d.written;
        const uint32_t per_prim_builtins = shader::bit(shader::BuiltIn::FrontFacing);
        plan.uniform_shader = all_flat && !(iface.builtins_read & ~per_prim_builtins) && !iface.uses_discard &&
                              !iface.writes_frag_depth && !iface.uses_derivatives && iface.builtins_written == 0 &&
                              !writes_memory;
        // A plain copy (colour = one float vec4 input, unchanged; nothing else: no discard, no built-ins, no memory;
        // shader::Program::linear_shader) is its interpolated input: the run is a move of the same bits.
        plan.copy_location = fs->linear_copy_input();
    }

    const DepthStencilTarget& ds = fb.depth_stencil;
    plan.depth_fast = draw.depth_mode != 0 && ds.depth && fragment::depth_fast_supported(draw.depth_stencil, ds.format);
    if (plan.depth_fast) plan.depth = fragment::make_depth_fast(draw.depth_stencil, ds.format);

    for (uint32_t c = 0; c < fb.num_color && c < kMaxColorTargets; ++c) {
        const fragment::BlendAttachment& a = pipe.blend[c];
        const fragment::ColorFormat f = fb.color[c].format;
        plan.color_bytes[c] = fragment::format_info(f).bytes;
        const bool rgba8 = f == fragment::ColorFormat::R8G8B8A8_UNORM || f == fragment::ColorFormat::B8G8R8A8_UNORM;
        if ((a.write_mask & 0xf) == 0) {
            plan.color[c] = ColorPath::kNone;
        } else if (rgba8 && !a.blend_enable && !a.logic_op_enable && (a.write_mask & 0xf) == 0xf) {
            plan.color[c] =
                f == fragment::ColorFormat::B8G8R8A8_UNORM ? ColorPath::kOpaqueBgra8 : ColorPath::kOpaqueRgba8;
        } else if (rgba8) {
            plan.rgba8[c] = fragment::prepare_rgba8_blend(a, f, pipe.blend_constants);
            if (plan.rgba8[c].ok) plan.color[c] = ColorPath::kRgba8;
        }
    }
    make_square_plan(draw, fb, plan);
    make_direct_plan(draw, fb, plan);
    make_uniform_store_plan(draw, fb, plan);
    make_block1x_plan(draw, fb, plan);
}

}  // namespace

FragmentStage::FragmentStage() = default;
FragmentStage::~FragmentStage() = default;

void FragmentStage::prepare(const Framebuffer& fb, const DrawRecords& draws, const PrimStore& prims, bool fused,
                            unsigned workers) {
    fb_ = fb;
    draws_ = &draws;
    prims_ = &prims;
    fused_ = fused;
    fast_ = fragment_fast_paths();
    block_fn_ = fast_block_function();
    square_fn_ = fast_square_function();
    uniform_4x_fn_ = fast_uniform_4x_function();
    while (workers_.size() < workers) workers_.push_back(std::make_unique<FragmentWorker>());
    for (auto& w : workers_) {
        w->scratch.set_stop_flag(stop_);
        w->hits_seen = w->scratch.loop_limit_hits();
        w->uniform_prim = nullptr;  // prim records are rebuilt for every scene
        w->samples_passed.assign(draws.size(), 0);
        w->shader_blocks.assign(draws.size(), 0);
    }
    // Which worker runs which fragment program depends on timing: every worker's scratch is grown for all of them
    // now, so that rendering allocates nothing.
    for (size_t d = 0; d < draws.size(); ++d)
        if (draws[d].pipe && draws[d].pipe->fragment)
            for (auto& w : workers_) draws[d].pipe->fragment->reserve(w->scratch);
    if (fast_) {
        plans_.resize(draws.size());
        for (size_t d = 0; d < draws.size(); ++d) make_plan(draws[d], fb, plans_[d]);
    }
    may_hide_ = scene_may_hide(fb, draws);
    hides_.assign(may_hide_ ? draws.size() : 0, 0);
    for (size_t d = 0; d < hides_.size(); ++d) hides_[d] = draw_hides_earlier(draws[d], fb) ? 1 : 0;
}

// Triangles only: a whole-tile line or point command is possible in principle, but lines and points are
// rasterized by their own rules, which the whole-tile bit of their planes need not describe.
bool FragmentStage::hides_earlier(uint32_t payload) const {
    const PrimRecord prim = prims_->header(payload);
    return prim.kind == PrimKind::kTriangle && prim.draw < hides_.size() && hides_[prim.draw] != 0;
}

void FragmentStage::set_linear(const std::vector<uint8_t>* tile_linear,
                               const std::vector<fragment::LinearRegion>* rect_boxes) {
    tile_linear_ = tile_linear;
    rect_boxes_ = rect_boxes;
}

void FragmentStage::set_stop_flag(const std::atomic<bool>* stop, Interruption* interruption) {
    stop_ = stop;
    interruption_ = interruption;
    for (auto& w : workers_) w->scratch.set_stop_flag(stop);
}

// llvmpipe's rasterizer threads run with denormals flushed (lp_rast.c thread_function:
// util_fpstate_set_denorms_to_zero): every tile is shaded that way, whichever pool thread renders it.
void FragmentStage::begin_tile(unsigned worker, const TileInfo&) {
    FragmentWorker& w = *workers_[worker];
    w.saved_fp_state = geometry::flush_denormals_begin();
    if (!stage_timers_on()) return;
    w.tile_cpu_start = thread_cpu_ns();
    w.tile_consumer = w.tile_shade = 0;
}

void FragmentStage::prefetch(uint32_t payload, int step) const {
    // The record's header (draw, position plane, depth offset) and its first attribute planes: the header and at
    // least two attributes lie in the three lines from its start. Step 1 has nothing left to fetch: the record
    // holds the draw index itself, so no second dependent fetch is needed.
    if (step != 0 || !prims_->contains(payload)) return;
    const char* head = reinterpret_cast<const char*>(prims_->record(payload));
    for (size_t off = 0; off < 192; off += 64) __builtin_prefetch(head + off);
}

// The tile's part of each TileResolve, after the tile's FP state is restored: the whole-image resolve it replaces
// runs in the workers' own state.
void FragmentStage::resolve_tile(const TileInfo& tile) const {
    const StageScope timed(Stage::kResolve);
    for (uint32_t i = 0; i < resolves_->count; ++i) {
        const TileResolve& r = resolves_->items[i];
        const ColorTarget& t = fb_.color[r.target];
        const int32_t x0 = std::max(r.x0, tile.x0), x1 = std::min(r.x1, tile.x0 + tile.width);
        const int32_t y0 = std::max(r.y0, tile.y0), y1 = std::min(r.y1, tile.y0 + tile.height);
        if (x0 >= x1 || y0 >= y1 || t.data == nullptr) continue;
        const size_t bytes = fragment::format_info(t.format).bytes;
        fragment::resolve_rect(t.format, t.data + size_t(y0) * t.row_pitch + size_t(x0) * bytes, t.sample_stride,
                               t.row_pitch, r.dst + size_t(y0) * r.dst_pitch + size_t(x0) * bytes, r.dst_pitch, x1 - x0,
                               y1 - y0, host::has_fma(), bytes);
    }
}

void FragmentStage::end_tile(unsigned worker, const TileInfo& tile) {
    const FragmentWorker& w = *workers_[worker];
    geometry::flush_denormals_end(w.saved_fp_state);
    if (stage_timers_on()) {
        // The tile's CPU time; the fragment stage's part of it from the time stamps of its (short) calls, the rest
        // is the core's descent and bin walk. Only short intervals are measured with the time-stamp counter: one
        // that spans a move to another CPU could be off by the CPUs' counter offset.
        const double cpu = double(thread_cpu_ns() - w.tile_cpu_start);
        const double consumer = std::min(ticks_to_ns(w.tile_consumer), cpu);
        const double shade = std::min(ticks_to_ns(w.tile_shade), consumer);  // sampled: may exceed on one tile
        add_stage_ns(Stage::kCoverage, uint64_t(cpu - consumer));
        add_stage_ns(Stage::kShade, uint64_t(shade));
        add_stage_ns(Stage::kOutput, uint64_t(consumer - shade));
    }
    if (resolves_ != nullptr) resolve_tile(tile);  // timed as kResolve on its own
}

bool FragmentStage::stop_tile(unsigned, uint32_t next_payload) {
    if (!stopped()) return false;
    interruption_->note(false, (*draws_)[prims_->header(next_payload).draw].id);
    return true;
}

void FragmentStage::primitive(unsigned worker, const TileInfo& tile, const PrimCoverage& cov) {
    const TickScope timed(workers_[worker]->tile_consumer);
    const PrimRecord prim = prims_->header(cov.payload);
    const DrawRecord& draw = (*draws_)[prim.draw];
    if (stopped()) {
        interruption_->note(false, draw.id);
        return;
    }
    if (tile_linear_ && draw.linear && (*tile_linear_)[tile.index] &&
        (prim.kind == PrimKind::kRect || prim.kind == PrimKind::kTriangle)) {
        // llvmpipe's linear bin (lp_rast_linear.c): a rectangle's box within the tile (lp_rast_linear_rect) or the
        // whole tile of a whole-tile command (lp_rast_linear_tile; in a linear bin every triangle with coverage
        // has one), shaded from the region's own origin. When lp_fs_linear_run declines, llvmpipe runs its
        // general shader on the same pixels: the code below.
        fragment::LinearRegion r = {tile.x0, tile.y0, tile.width, tile.height};
        if (prim.kind == PrimKind::kRect) {
            const fragment::LinearRegion& b = (*rect_boxes_)[prim.rect];
            r.x = std::max(b.x, tile.x0);
            r.y = std::max(b.y, tile.y0);
            r.width = std::min(b.x + b.width, tile.x0 + tile.width) - r.x;
            r.height = std::min(b.y + b.height, tile.y0 + tile.height) - r.y;
        }
        const float* pl = prim.planes;
        const float* input = draw.linear_slot >= 0
                                 ? pl + kPrimHeaderFloats + size_t(kPlaneFloats) * uint32_t(draw.linear_slot)
                                 : nullptr;
        if (r.width > 0 && r.height > 0 &&
            fragment::linear_shade(r, pl, input, draw.linear_perspective, draw.linear_channels, fb_.color[0].data,
                                   fb_.color[0].row_pitch, &draw.pipe->blend[0], draw.pipe->blend_constants)) {
            // Every pixel of the region was written: linear mode is 1x with no depth/stencil and the linear shader
            // class cannot discard. lavapipe's linear rasterizer forgets to count them (a named difference,
            // icd/README.md "Queries"); a precise occlusion query must.
            if (draw.samples_passed) workers_[worker]->samples_passed[prim.draw] += uint64_t(r.width) * r.height;
            return;
        }
    }
    FragmentWorker& w = *workers_[worker];
    if (draw.statistics) w.shader_blocks[prim.draw] += shader_calls(cov);  // only inside a statistics query
    const DrawPlan* plan = fast_ && plans_[prim.draw].fast ? &plans_[prim.draw] : nullptr;
    const BlockFn fast = block_fn_;  // the fast pipeline for this CPU (fragment_plan.h)
    const BlockArgs args{&fb_, &draw, plan, &prim, prim.planes, cov.front_facing, fused_};
    auto one_block = [&](int32_t x, int32_t y, const uint16_t masks[4]) {
        if (stopped()) return;  // checked between shader batches: the rest of the tile is skipped
        if (plan)
            fast(w, args, x, y, masks);
        else
            shade_block(w, draw, prim, cov.front_facing, x, y, masks);
    };
    if (plan && uniform_4x_fn_ && plan->uniform_store_4x >= 0) {
        // 4x: no Block16 entries; the stop flag is read once for the primitive's blocks instead of per block.
        if (!stopped()) uniform_4x_fn_(w, args, cov.blocks, cov.num_blocks);
    } else {
        for_each_block4(cov, one_block);
    }
    const bool squares = plan && square_fn_ && plan->square.ok && (cov.sample_mask & 1u);
    for (size_t i = 0; i < cov.num_full; ++i) {
        const FullBlock& f = cov.full[i];
        if (squares && !stopped() && square_fn_(args, f.x, f.y, f.size)) {
            if (draw.samples_passed) w.samples_passed[prim.draw] += uint64_t(f.size) * uint64_t(f.size);
            continue;
        }
        for (int32_t by = f.y; by < f.y + f.size; by += 4)
            for (int32_t bx = f.x; bx < f.x + f.size; bx += 4) {
                // Full squares lie inside the framebuffer (coverage.h); the check costs two compares.
                const uint16_t inside = bx + 4 <= fb_.width && by + 4 <= fb_.height
                                            ? uint16_t(0xffff)
                                            : inside_mask(bx, by, fb_.width, fb_.height);
                uint16_t masks[4];
                for (int s = 0; s < 4; ++s) masks[s] = (cov.sample_mask >> s) & 1 ? inside : 0;
                one_block(bx, by, masks);
            }
    }
    if (const uint64_t hits = w.scratch.loop_limit_hits(); hits != w.hits_seen) {
        w.hits_seen = hits;
        if (stop_ != nullptr) interruption_->note(true, draw.id);
    }
}

// Sample shading (llvmpipe's sample loop when min_samples > 1, lp_state_fs.c generate_fs_loop): the shader runs
// once per sample s over the lanes in mask_store[s] (the coverage after early depth/stencil), interpolated at that
// sample (RunSite). After run s, alpha to coverage with that run's alpha ANDs every sample's mask_store entry, then
// mask_store[s] becomes the run's own mask (its lanes minus discards), so a run's alpha also trims the samples
// shaded after it and those before it. A written SampleMask keeps sample s where run s set bit s. Each run's FragDepth
// replaces z[s] (when `z` is set); its colours go to w.sample_outputs[s].
void FragmentStage::shade_samples(FragmentWorker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing,
                                  int32_t x, int32_t y, const uint16_t cover[4], const uint16_t pass[4],
                                  float (*z)[kBlockLanes], uint16_t final_mask[4]) {
    const PipelineState& pipe = *draw.pipe;
    const shader::Program* fs = pipe.fragment;
    const shader::ProgramInterface& iface = fs->interface();
    const bool writes_mask = iface.builtins_written & shader::bit(shader::BuiltIn::SampleMask);
    const int samples = fb_.samples;
    uint16_t store[fragment::kMaxSamples] = {pass[0], pass[1], pass[2], pass[3]};
    uint16_t written[fragment::kMaxSamples] = {};  // lanes whose run s wrote bit s of SampleMask
    shader::FragmentBlock& b = w.block;
    for (int s = 0; s < samples; ++s) {
        const uint16_t run_mask = store[s];
        b.cover_mask = run_mask;
        b.front_facing = front_facing ? 1u : 0u;
        b.view_index = fb_.view_index;
        set_fragment_inputs(b, draw, prim.planes, x, y, RunSite{samples, s, store, cover, &w.input_planes}, fused_);
        fs->run_fragment(draw.bindings, b, w.scratch);
        if (pipe.alpha_to_coverage) {
            float alpha[kBlockLanes];
            std::memcpy(alpha, b.outputs[0][3], sizeof alpha);
            fragment::alpha_to_coverage_4x(alpha, store);
        }
        store[s] = static_cast<uint16_t>(b.live_mask & run_mask);
        if (writes_mask)
            for (int l = 0; l < kBlockLanes; ++l)
                if ((b.sample_mask[l] >> s) & 1u) written[s] |= uint16_t(1u << l);
        if (z && iface.writes_frag_depth) std::memcpy(z[s], b.frag_depth, sizeof(float) * kBlockLanes);
        std::memcpy(w.sample_outputs[s], b.outputs, sizeof w.sample_outputs[s]);
    }
    for (int s = 0; s < samples; ++s) final_mask[s] = writes_mask ? uint16_t(store[s] & written[s]) : store[s];
}

// The reference fragment pipeline of one block: coverage, depth, inputs (set_fragment_inputs), the shader (once, or
// per sample in shade_samples), the sample masks, late depth and blend in lavapipe's order on lane arrays they all
// share; shade_block_fast (fragment_block.cpp) is its step-by-step twin for the states its plan covers.
void FragmentStage::shade_block(FragmentWorker& w, const DrawRecord& draw, const PrimRecord& prim, bool front_facing,
                                int32_t x, int32_t y, const uint16_t raster_masks[4]) {
    w.uniform_prim = nullptr;  // block.outputs is about to change
    const PipelineState& pipe = *draw.pipe;
    const int samples = fb_.samples;
    const float* planes = prim.planes;
    const float depth_offset = planes[kPlaneFloats];

    // Coverage per sample in shader lane order.
    uint16_t cover[4] = {0, 0, 0, 0};
    for (int s = 0; s < samples; ++s) cover[s] = fragment::raster_to_lanes(raster_masks[s]);
    uint16_t any = 0;
    for (int s = 0; s < samples; ++s) any |= cover[s];
    if (!any) return;

    // Depth per sample: 1x at the pixel centre (plane origin), 4x at each sample position.
    float z[4][kBlockLanes];
    const fragment::Plane zplane = plane_of(planes, 2);
    const bool depth_active = draw.depth_mode != 0;
    if (depth_active)
        for (int s = 0; s < samples; ++s)
            fragment::eval_depth(zplane, depth_offset, x, y, fragment::plane_offset(samples, samples > 1 ? s : -1),
                                 fused_, z[s]);

    const DepthStencilTarget& dst = fb_.depth_stencil;
    fragment::DepthStencilBlock zs[4];
    const bool early = draw.depth_mode & fragment::kEarlyDepthTest;
    const bool early_write = draw.depth_mode & fragment::kEarlyDepthWrite;
    uint16_t pass[4] = {cover[0], cover[1], cover[2], cover[3]};
    if (depth_active) {
        for (int s = 0; s < samples; ++s) {
            load_depth_stencil(dst, s, x, y, cover[s], zs[s]);
            if (early) {
                pass[s] = fragment::depth_stencil_test(draw.depth_stencil, dst.format, front_facing, z[s], cover[s],
                                                       zs[s], early_write);
                if (early_write) store_depth_stencil(dst, s, x, y, cover[s], zs[s]);
            }
        }
    }
    uint16_t shade_lanes = 0;
    for (int s = 0; s < samples; ++s) shade_lanes |= pass[s];
    if (!shade_lanes) return;
    const uint64_t shade_start = w.shade_sample_start();

    // Fragment shader runs: once per pixel, or once per sample under sample shading.
    shader::FragmentBlock& b = w.block;
    const shader::Program* fs = pipe.fragment;
    const bool per_sample = fs && pipe.per_sample && samples > 1;
    uint16_t final_mask[4] = {};
    if (per_sample) {
        shade_samples(w, draw, prim, front_facing, x, y, cover, pass, depth_active ? z : nullptr, final_mask);
    } else {
        uint16_t live = shade_lanes;
        if (fs) {
            b.cover_mask = shade_lanes;
            b.front_facing = front_facing ? 1u : 0u;
            b.view_index = fb_.view_index;
            set_fragment_inputs(b, draw, planes, x, y, RunSite{samples, -1, pass, cover, &w.input_planes}, fused_);
            fs->run_fragment(draw.bindings, b, w.scratch);
            live = static_cast<uint16_t>(b.live_mask & shade_lanes);
            if (fs->interface().writes_frag_depth && depth_active)
                for (int s = 0; s < samples; ++s)
                    for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&z[s][l], &b.frag_depth[l], 4);
        }
        // Per-sample survivors of the shader, alpha to coverage and the shader's sample mask.
        for (int s = 0; s < samples; ++s) final_mask[s] = pass[s] & live;
        shader_coverage(fs, pipe.alpha_to_coverage, b, samples, final_mask);
    }
    w.shade_sample_end(shade_start);

    // Late depth/stencil: lanes that failed the early test re-run it so their stencil fail ops apply.
    if (depth_active && !(early && early_write)) {
        for (int s = 0; s < samples; ++s) {
            const uint16_t test_lanes =
                early ? static_cast<uint16_t>((cover[s] & ~pass[s]) | final_mask[s]) : final_mask[s];
            if (!test_lanes) continue;
            const uint16_t late_pass = fragment::depth_stencil_test(draw.depth_stencil, dst.format, front_facing, z[s],
                                                                    test_lanes, zs[s], true);
            store_depth_stencil(dst, s, x, y, test_lanes, zs[s]);
            final_mask[s] &= late_pass;
        }
    }
    if (draw.samples_passed) count_passed(w, prim.draw, final_mask, samples);  // only inside a query
    if (!fs) return;

    // Blend and write each colour target, per sample plane.
    fragment::BlendOptions opt;
    opt.fused = fused_;
    float src[4][kBlockLanes], src1[4][kBlockLanes];
    for (uint32_t c = 0; c < fb_.num_color && c < shader::kMaxColorOutputs; ++c) {
        const ColorTarget& t = fb_.color[c];
        if (!t.data) continue;
        // Dual-source blending (attachment 0 only): the second output, under alpha to one as the first
        // (lp_state_fs.c applies it to both colour outputs).
        const bool dual = c == 0 && fragment::uses_second_source(pipe.blend[0]);
        const size_t bytes = fragment::format_info(t.format).bytes;
        for (int s = 0; s < samples; ++s) {
            if (!final_mask[s]) continue;
            const shader::Lanes* out = per_sample ? w.sample_outputs[s][c] : b.outputs[c];
            for (int ch = 0; ch < 4; ++ch) std::memcpy(src[ch], out[ch], sizeof(float) * kBlockLanes);
            if (pipe.alpha_to_one) std::fill(src[3], src[3] + kBlockLanes, 1.0f);
            if (dual) {
                const shader::Lanes* out1 = per_sample ? w.sample_outputs[s][shader::kSecondColorOutput]
                                                       : b.outputs[shader::kSecondColorOutput];
                for (int ch = 0; ch < 4; ++ch) std::memcpy(src1[ch], out1[ch], sizeof(float) * kBlockLanes);
                if (pipe.alpha_to_one) std::fill(src1[3], src1[3] + kBlockLanes, 1.0f);
            }
            uint8_t* origin = t.data + size_t(s) * t.sample_stride + size_t(y) * t.row_pitch + size_t(x) * bytes;
            fragment::blend_block(pipe.blend[c], t.format, pipe.blend_constants, src, final_mask[s], origin,
                                  t.row_pitch, opt, dual ? src1 : nullptr);
        }
    }
}

}  // namespace tilevk::rast::render
