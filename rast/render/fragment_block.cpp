// The fast block pipeline (fragment_plan.h): the reference pipeline of FragmentStage::shade_block with each step
// replaced by what the draw's plan allows. Built once per instruction set (rast/meson.build: this file is
// compiled as TILEVK_ISA = isa_base and, where the compiler can, isa_avx2 with -mavx2 -mfma); the kernels it
// inlines (block_kernels.h, blend_rgba8.h) follow TILEVK_SIMD_AVX2 of that build.
//
// Per block, in lavapipe's order: coverage -> depth values -> early depth/stencil -> interpolation and shader (or
// the per-primitive run of a uniform shader, or the copy of a copied input) -> alpha to coverage and the shader's
// sample mask -> late depth/stencil -> occlusion count -> blend and store.
#include <algorithm>
#include <cstring>

#include "rast/fragment/blend_rgba8.h"
#include "rast/fragment/block.h"
#include "rast/render/fragment_plan.h"

namespace tilevk::rast::render::TILEVK_ISA {
namespace {

using fragment::kBlockLanes;
// SamplePosition of a per-pixel run, 0.5 in float bits: shaders that read it at 4x shade per sample, which the
// reference pipeline runs (make_plan), so the fast paths only ever run them at 1x, where lavapipe's is (0.5, 0.5).
constexpr uint32_t kHalfBits = 0x3f000000u;

// memcpy for lane arrays, in 32-byte units in the AVX2 build. GCC inlines a 256-byte memcpy as 16-byte moves; the
// AVX2 kernels then read the copy with 32-byte loads, and a load spanning two stores cannot be forwarded from the
// store buffer (a stall per load; perf showed it on the first load of every blend16 block).
template <size_t kBytes>
void copy_lanes(void* dst, const void* src) {
    static_assert(kBytes % 32 == 0);
#if TILEVK_SIMD_AVX2
    auto* d = static_cast<uint8_t*>(dst);
    const auto* s = static_cast<const uint8_t*>(src);
    for (size_t i = 0; i < kBytes; i += 32)
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + i),
                            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + i)));
#else
    std::memcpy(dst, src, kBytes);
#endif
}

// What one block carries from step to step, for a framebuffer of kSamples samples (1 or 4): with the count a
// constant every per-sample loop of the steps below is unrolled (at 1x: straight-line code), which took a fifth of
// the block's instructions when it was read from the framebuffer.
template <int kSamples>
struct Block {
    static constexpr int samples = kSamples;
    int32_t x = 0, y = 0;
    bool inside = true;      // the whole block lies in the framebuffer
    uint16_t cover[4] = {};  // per sample, lane order
    uint16_t pass[4] = {};   // survivors of the early test (cover without one)
    uint16_t final_mask[4] = {};
    // Lane coordinates at the pixel centres (1x: also the depth sample positions), formed on first use (centre()):
    // a uniform shader at 4x never reads them.
    bool centre_ready = false;
    fragment::LaneCoords centre_coords;
    const fragment::LaneCoords& centre() {
        if (!centre_ready) {
            fragment::make_lane_coords(x, y, fragment::plane_offset(samples, -1), centre_coords);
            centre_ready = true;
        }
        return centre_coords;
    }
    alignas(32) float z[4][kBlockLanes];
    fragment::DepthStencilBlock zs[4];
    const uint32_t* local = nullptr;  // a direct run's local memory (DrawPlan::direct): the colours are there
};

// Returns the lanes any sample covers (0: nothing to do). pass starts as cover, sample by sample: the mask arrays
// are written and read in 16-bit units only (a copy of all four at once becomes one 64-bit load of four fresh
// 16-bit stores, which the CPU cannot forward: a stall on every block).
template <class B>
uint16_t coverage(const BlockArgs& a, const uint16_t raster_masks[4], B& k) {
    uint16_t any = 0;
    for (int s = 0; s < k.samples; ++s) {
        const uint16_t lanes = fragment::raster_to_lanes(raster_masks[s]);
        k.cover[s] = k.pass[s] = lanes;
        any |= lanes;
    }
    if (!any) return 0;
    k.inside = k.x + 4 <= a.fb->width && k.y + 4 <= a.fb->height;
    return any;
}

// z per sample: 1x at the pixel centre, 4x at each sample position, plus the depth offset (eval_depth's plain add).
template <class B>
void depth_values(const BlockArgs& a, B& k) {
    const fragment::Plane zplane = plane_of(a.planes, 2);
    const float depth_offset = a.planes[kPlaneFloats];
    for (int s = 0; s < k.samples; ++s) {
        if (k.samples > 1) {
            fragment::LaneCoords at;
            fragment::make_lane_coords(k.x, k.y, fragment::plane_offset(k.samples, s), at);
            fragment::eval_plane_fast(zplane, at, a.fused, k.z[s]);
        } else {
            fragment::eval_plane_fast(zplane, k.centre(), a.fused, k.z[s]);
        }
        for (int l = 0; l < kBlockLanes; ++l) k.z[s][l] = k.z[s][l] + depth_offset;
    }
}

template <class B>
uint8_t* depth_origin(const BlockArgs& a, const B& k, int s) {
    const DepthStencilTarget& dst = a.fb->depth_stencil;
    return dst.depth + size_t(s) * dst.depth_sample_stride + size_t(k.y) * dst.depth_row_pitch +
           size_t(k.x) * depth_bytes(dst.format);
}

// The early test when the depth mode has one (its write too when allowed); otherwise the depth/stencil values
// the late test will need. Returns the lanes that go on to the shader.
template <class B>
uint16_t early_depth(const BlockArgs& a, B& k) {
    const DrawRecord& draw = *a.draw;
    const DrawPlan& plan = *a.plan;
    const DepthStencilTarget& dst = a.fb->depth_stencil;
    const bool early = draw.depth_mode & fragment::kEarlyDepthTest;
    const bool early_write = draw.depth_mode & fragment::kEarlyDepthWrite;
    if (early) {
        for (int s = 0; s < k.samples; ++s) {
            if (plan.depth_fast) {
                if (k.cover[s])
                    k.pass[s] = fragment::depth_block_fast(plan.depth, k.z[s], k.cover[s], depth_origin(a, k, s),
                                                           dst.depth_row_pitch, early_write, k.inside);
                continue;
            }
            load_depth_stencil(dst, s, k.x, k.y, k.cover[s], k.zs[s]);
            k.pass[s] = fragment::depth_stencil_test(draw.depth_stencil, dst.format, a.front_facing, k.z[s], k.cover[s],
                                                     k.zs[s], early_write);
            if (early_write) store_depth_stencil(dst, s, k.x, k.y, k.cover[s], k.zs[s]);
        }
    } else if (!plan.depth_fast) {
        for (int s = 0; s < k.samples; ++s) load_depth_stencil(dst, s, k.x, k.y, k.cover[s], k.zs[s]);
    }
    uint16_t lanes = 0;
    for (int s = 0; s < k.samples; ++s) lanes |= k.pass[s];
    return lanes;
}

// A uniform shader (plan.uniform_shader): one run per primitive and worker (for a copy of a flat input, the copy);
// block.outputs stays valid for every block of the primitive, since every lane sees the same flat inputs.
void run_uniform(FragmentWorker& w, const BlockArgs& a) {
    if (w.uniform_prim == a.planes && w.uniform_front == a.front_facing) return;
    w.uniform_rows_valid = 0;
    shader::FragmentBlock& b = w.block;
    b.cover_mask = shader::kAllLanes;
    b.front_facing = a.front_facing ? 1u : 0u;
    b.sample_id = 0;
    b.sample_position[0] = b.sample_position[1] = kHalfBits;
    b.view_index = a.fb->view_index;
    const float* attribs = a.planes + kPrimHeaderFloats;
    for (const InputPlan& in : a.plan->inputs) {
        uint32_t* lanes = input_lanes(b, in);
        const uint32_t v = bits_of(attribs[in.plane + in.comp]);
        for (int l = 0; l < kBlockLanes; ++l) lanes[l] = v;
    }
    if (a.plan->copy_location >= 0)
        copy_lanes<sizeof b.outputs[0]>(b.outputs[0], b.inputs[a.plan->copy_location]);  // what the run would do
    else
        a.draw->pipe->fragment->run_fragment(a.draw->bindings, b, w.scratch);
    w.uniform_prim = a.planes;
    w.uniform_front = a.front_facing;
}

// A direct run (DrawPlan::direct): run_shader's interpolation, written into the program's local words of the inputs
// it reads, and the run on them. Returns the live lanes; k.local holds the colour outputs after it.
template <class B>
uint16_t run_direct(FragmentWorker& w, const BlockArgs& a, B& k, uint16_t lanes) {
    const DrawPlan& plan = *a.plan;
    const shader::Program* fs = a.draw->pipe->fragment;
    shader::FragmentBlock& b = w.block;  // its scalars only
    uint32_t* local = fs->bind_fragment(a.draw->bindings, plan.bindings_key, w.scratch);
    const fragment::LaneCoords& centre = k.centre();
    alignas(32) float wlanes[kBlockLanes], oow[kBlockLanes] = {};
    if (plan.perspective) {
        fragment::eval_plane_fast(plane_of(a.planes, 3), centre, a.fused, wlanes);
        fragment::reciprocal_fast(wlanes, oow);
    }
    const float* attribs = a.planes + kPrimHeaderFloats;
    for (const InputPlan& in : plan.inputs) {
        if (in.word == ~0u) continue;
        const float* p = attribs + in.plane;
        uint32_t* dst = local + size_t(in.word) * kBlockLanes;
        if (in.interp == geometry::Interp::kFlat) {
            for (int l = 0; l < kBlockLanes; ++l) dst[l] = bits_of(p[in.comp]);
            continue;
        }
        fragment::interpolate_input(plane_of(p, int(in.comp)), centre, a.fused,
                                    in.interp == geometry::Interp::kPerspective ? oow : nullptr, dst);
    }
    b.cover_mask = lanes;
    b.front_facing = a.front_facing ? 1u : 0u;
    b.sample_id = 0;
    b.sample_position[0] = b.sample_position[1] = kHalfBits;
    b.view_index = a.fb->view_index;
    k.local = local;
    return static_cast<uint16_t>(fs->run_bound_fragment(b, w.scratch) & lanes);
}

// The shader's inputs for `lanes` (built-ins it reads, then the planned components: a * fl(1/w) for perspective
// ones, the reciprocal once per block), then its run (or the copy of a copied input). Returns the live lanes.
template <class B>
uint16_t run_shader(FragmentWorker& w, const BlockArgs& a, B& k, uint16_t lanes) {
    const DrawPlan& plan = *a.plan;
    const shader::Program* fs = a.draw->pipe->fragment;
    shader::FragmentBlock& b = w.block;
    w.uniform_prim = nullptr;  // block.inputs/outputs are about to change
    if (plan.direct) return run_direct(w, a, k, lanes);
    b.cover_mask = lanes;
    b.front_facing = a.front_facing ? 1u : 0u;
    b.sample_id = 0;
    b.sample_position[0] = b.sample_position[1] = kHalfBits;
    b.view_index = a.fb->view_index;
    const shader::ProgramInterface& iface = fs->interface();
    const bool frag_coord = iface.builtins_read & shader::bit(shader::BuiltIn::FragCoord);
    const fragment::LaneCoords& centre = k.centre();
    alignas(32) float wlanes[kBlockLanes], oow[kBlockLanes] = {};
    if (plan.perspective || frag_coord) fragment::eval_plane_fast(plane_of(a.planes, 3), centre, a.fused, wlanes);
    if (frag_coord) {
        const fragment::EvalOffset off = fragment::plane_offset(k.samples, -1);
        float fx[kBlockLanes], fy[kBlockLanes], fz[kBlockLanes];
        fragment::frag_coord_xy(k.x, k.y, fragment::frag_coord_offset(k.samples, -1), fx, fy);
        fragment::eval_depth(plane_of(a.planes, 2), a.planes[kPlaneFloats], k.x, k.y, off, a.fused, fz);
        for (int l = 0; l < kBlockLanes; ++l) {
            b.frag_coord[0][l] = bits_of(fx[l]);
            b.frag_coord[1][l] = bits_of(fy[l]);
            b.frag_coord[2][l] = bits_of(fz[l]);
            b.frag_coord[3][l] = bits_of(wlanes[l]);
        }
    }
    if (iface.builtins_read & shader::bit(shader::BuiltIn::SampleMask))
        for (int l = 0; l < kBlockLanes; ++l) {
            uint32_t m = 0;
            for (int s = 0; s < k.samples; ++s) m |= ((k.cover[s] >> l) & 1u) << s;
            b.sample_mask_in[l] = m;
        }
    if (plan.perspective) fragment::reciprocal_fast(wlanes, oow);
    const float* attribs = a.planes + kPrimHeaderFloats;
    for (const InputPlan& in : plan.inputs) {
        const float* p = attribs + in.plane;
        if (in.interp == geometry::Interp::kFlat) {
            uint32_t* dst = input_lanes(b, in);
            for (int l = 0; l < kBlockLanes; ++l) dst[l] = bits_of(p[in.comp]);
            continue;
        }
        fragment::interpolate_input(plane_of(p, int(in.comp)), centre, a.fused,
                                    in.interp == geometry::Interp::kPerspective ? oow : nullptr, input_lanes(b, in));
    }
    uint16_t live = lanes;
    if (plan.copy_location >= 0) {
        copy_lanes<sizeof b.outputs[0]>(b.outputs[0], b.inputs[plan.copy_location]);  // what the run would do
    } else {
        fs->run_fragment(a.draw->bindings, b, w.scratch);
        live = static_cast<uint16_t>(b.live_mask & lanes);
    }
    if (iface.writes_frag_depth && a.draw->depth_mode != 0)
        for (int s = 0; s < k.samples; ++s)
            for (int l = 0; l < kBlockLanes; ++l) std::memcpy(&k.z[s][l], &b.frag_depth[l], 4);
    return live;
}

// The late test (lanes that failed the early test re-run it so their stencil fail ops apply).
template <class B>
void late_depth(const BlockArgs& a, B& k) {
    const DrawRecord& draw = *a.draw;
    const DepthStencilTarget& dst = a.fb->depth_stencil;
    const bool early = draw.depth_mode & fragment::kEarlyDepthTest;
    if (early && (draw.depth_mode & fragment::kEarlyDepthWrite)) return;
    for (int s = 0; s < k.samples; ++s) {
        const uint16_t test_lanes =
            early ? static_cast<uint16_t>((k.cover[s] & ~k.pass[s]) | k.final_mask[s]) : k.final_mask[s];
        if (!test_lanes) continue;
        if (a.plan->depth_fast) {
            k.final_mask[s] &= fragment::depth_block_fast(a.plan->depth, k.z[s], test_lanes, depth_origin(a, k, s),
                                                          dst.depth_row_pitch, true, k.inside);
            continue;
        }
        const uint16_t late_pass = fragment::depth_stencil_test(draw.depth_stencil, dst.format, a.front_facing, k.z[s],
                                                                test_lanes, k.zs[s], true);
        store_depth_stencil(dst, s, k.x, k.y, test_lanes, k.zs[s]);
        k.final_mask[s] &= late_pass;
    }
}

#if TILEVK_SIMD_AVX2
// The opaque store's rows of target c: packed from src, or for a uniform shader from the worker's rows of the
// primitive's run (packed by its first block; the same conversion of the same outputs).
void opaque_rows(FragmentWorker& w, const BlockArgs& a, uint32_t c, bool bgra, const float src[4][kBlockLanes],
                 __m128i rows[4]) {
    auto* cached = reinterpret_cast<__m128i*>(w.uniform_rows[c]);
    if (!a.plan->uniform_shader) {
        fragment::detail::pack_rgba8_rows(bgra, src, rows);
    } else if (w.uniform_rows_valid & (1u << c)) {
        for (int r = 0; r < 4; ++r) rows[r] = _mm_load_si128(cached + r);
    } else {
        fragment::detail::pack_rgba8_rows(bgra, src, rows);
        for (int r = 0; r < 4; ++r) _mm_store_si128(cached + r, rows[r]);
        w.uniform_rows_valid |= 1u << c;
    }
}

// The primitive's uniform run packed for the opaque store of target c. After the primitive's first block its run and
// packed rows are the worker's already: what run_uniform and opaque_rows would find, tested once.
void uniform_rows(FragmentWorker& w, const BlockArgs& a, uint32_t c, bool bgra, __m128i rows[4]) {
    if (w.uniform_prim == a.planes && w.uniform_front == a.front_facing && (w.uniform_rows_valid >> c & 1)) {
        for (int r = 0; r < 4; ++r) rows[r] = _mm_load_si128(reinterpret_cast<const __m128i*>(w.uniform_rows[c][r]));
        return;
    }
    const uint64_t shade_start = w.shade_sample_start();
    run_uniform(w, a);
    w.shade_sample_end(shade_start);
    opaque_rows(w, a, c, bgra, reinterpret_cast<const float(*)[kBlockLanes]>(w.block.outputs[c][0]), rows);
}

// A block inside the framebuffer: shade_block_n<4>'s steps as they fall out in that state (each sample's final mask
// is its coverage, the colour is the primitive's uniform run), with the masks kept in the rasterizer's order: the
// lane order only served the steps that have nothing to do here.
[[gnu::always_inline]] inline void store_uniform_4x_block(const ColorTarget& t, const __m128i rows[4], int32_t x,
                                                          int32_t y, const uint16_t raster_masks[4]) {
    uint8_t* origin = t.data + size_t(y) * t.row_pitch + size_t(x) * 4;
    for (int s = 0; s < 4; ++s, origin += t.sample_stride)
        if (raster_masks[s]) fragment::store_rgba8_raster_block_avx2(rows, raster_masks[s], origin, t.row_pitch);
}

void store_uniform_4x(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]) {
    if (!(raster_masks[0] | raster_masks[1] | raster_masks[2] | raster_masks[3])) return;
    const auto c = uint32_t(a.plan->uniform_store_4x);
    __m128i rows[4];
    uniform_rows(w, a, c, a.plan->color[c] == ColorPath::kOpaqueBgra8, rows);
    store_uniform_4x_block(a.fb->color[c], rows, x, y, raster_masks);
}

// Block1xPlan: a 1x block inside the framebuffer from coverage to memory in raster order (lane 4 * row + column;
// half h of a vector = rows 2h and 2h + 1), every value per pixel computed by the block pipeline's operations in its
// order (lane order only permutes them): z = eval_plane + depth offset, the early depth kernel, the colour either
// the uniform run's packed rows (opaque_rows) or the copied input fmuladd(dady, py, fmuladd(dadx, px, a0)) * fl(1/w)
// (interpolate_input, mul_oow) packed by pack_row8, then the opaque row store under the survivors' raster mask.
void shade_block_1x(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, uint16_t raster) {
    const DrawPlan& plan = *a.plan;
    const Block1xPlan& bp = plan.block1x;
    // make_lane_coords: fl(fl(lane) + fl(block origin)) + offset
    const fragment::EvalOffset off = fragment::plane_offset(1, -1);
    const __m256 px = _mm256_add_ps(_mm256_add_ps(_mm256_setr_ps(0, 1, 2, 3, 0, 1, 2, 3), _mm256_set1_ps(float(x))),
                                    _mm256_set1_ps(off.x));
    const __m256 by = _mm256_set1_ps(float(y)), oy = _mm256_set1_ps(off.y);
    const __m256 py[2] = {_mm256_add_ps(_mm256_add_ps(_mm256_setr_ps(0, 0, 0, 0, 1, 1, 1, 1), by), oy),
                          _mm256_add_ps(_mm256_add_ps(_mm256_setr_ps(2, 2, 2, 2, 3, 3, 3, 3), by), oy)};
    const bool fused = a.fused;
    auto eval = [fused, &px](const fragment::Plane& p, __m256 row_y) {
        const __m256 dadx = _mm256_set1_ps(p.dadx), dady = _mm256_set1_ps(p.dady), a0 = _mm256_set1_ps(p.a0);
        // -ffp-contract=off keeps the unfused form's two roundings apart
        return fused ? _mm256_fmadd_ps(dady, row_y, _mm256_fmadd_ps(dadx, px, a0))
                     : _mm256_add_ps(_mm256_mul_ps(dady, row_y), _mm256_add_ps(_mm256_mul_ps(dadx, px), a0));
    };
    uint16_t pass = raster;
    if (bp.depth) {
        const fragment::Plane zplane = plane_of(a.planes, 2);
        const __m256 depth_offset = _mm256_set1_ps(a.planes[kPlaneFloats]);
        alignas(32) float z[kBlockLanes];
        for (int h = 0; h < 2; ++h) _mm256_store_ps(z + 8 * h, _mm256_add_ps(eval(zplane, py[h]), depth_offset));
        const DepthStencilTarget& dst = a.fb->depth_stencil;
        uint8_t* zorigin = dst.depth + size_t(y) * dst.depth_row_pitch + size_t(x) * depth_bytes(dst.format);
        pass = fragment::depth_block_raster_avx2(plan.depth, z, raster, zorigin, dst.depth_row_pitch, bp.depth_write);
        if (!pass) return;
    }
    const ColorTarget& t = a.fb->color[bp.target];
    __m128i rows[4];
    if (!bp.copy) {
        uniform_rows(w, a, bp.target, bp.bgra, rows);
    } else {
        const float* attribs = a.planes + kPrimHeaderFloats;
        const fragment::Plane wplane = plane_of(a.planes, 3);
        for (int h = 0; h < 2; ++h) {
            __m256 c[4];
            for (int k = 0; k < 4; ++k) c[k] = eval(plane_of(attribs + bp.plane[k], k), py[h]);
            if (bp.perspective) {
                const __m256 oow = _mm256_div_ps(_mm256_set1_ps(1.0f), eval(wplane, py[h]));
                for (auto& v : c) v = fragment::mul_oow(v, oow);
            }
            const __m256i px8 = fragment::detail::pack_row8(bp.bgra, c[0], c[1], c[2], c[3]);
            rows[2 * h] = _mm256_castsi256_si128(px8);
            rows[2 * h + 1] = _mm256_extracti128_si256(px8, 1);
        }
    }
    fragment::store_rgba8_raster_rows_avx2(rows, pass, t.data + size_t(y) * t.row_pitch + size_t(x) * 4, t.row_pitch,
                                           true);
}
#endif

// The AVX2 kernels for 16 inside pixels (blend_rgba8_block, store_rgba8_avx2) read the colour only through
// may_alias vector loads, so in the AVX2 build they take the shader's output words in place. A copy into a float
// array first costs more than the kernel's conversion: GCC expands it as 16-byte moves, and each of the kernel's
// 32-byte loads then spans two stores the CPU cannot forward (a stall per load, seen with perf in blend16).
// Returns false where the reference route (copy, then any kernel) is taken.
template <class B>
bool write_color_in_place(FragmentWorker& w, const BlockArgs& a, const B& k, uint32_t c,
                          const float src[4][kBlockLanes], const fragment::BlendOptions& opt) {
#if TILEVK_SIMD_AVX2
    const ColorTarget& t = a.fb->color[c];
    const ColorPath path = a.plan->color[c];
    const bool opaque = path == ColorPath::kOpaqueRgba8 || path == ColorPath::kOpaqueBgra8;
    if (!k.inside || a.draw->pipe->alpha_to_one || (path != ColorPath::kRgba8 && !opaque) ||
        (path == ColorPath::kRgba8 && !a.plan->rgba8[c].ok) || (opaque && opt.unorm_path != fragment::UnormPath::Avx8))
        return false;
    const size_t bytes = a.plan->color_bytes[c];
    __m128i rows[4];  // opaque: every sample stores the same converted pixels, packed once
    if (opaque) opaque_rows(w, a, c, path == ColorPath::kOpaqueBgra8, src, rows);
    for (int s = 0; s < k.samples; ++s) {
        if (!k.final_mask[s]) continue;
        uint8_t* origin = t.data + size_t(s) * t.sample_stride + size_t(k.y) * t.row_pitch + size_t(k.x) * bytes;
        if (opaque)
            fragment::store_rgba8_rows_avx2(rows, k.final_mask[s], origin, t.row_pitch, true);
        else
            fragment::blend_rgba8_block(a.plan->rgba8[c], src, k.final_mask[s], origin, t.row_pitch);
    }
    return true;
#else
    (void)w, (void)a, (void)k, (void)c, (void)src, (void)opt;
    return false;
#endif
}

template <class B>
void write_colors(FragmentWorker& w, const BlockArgs& a, const B& k) {
    const Framebuffer& fb = *a.fb;
    const DrawPlan& plan = *a.plan;
    const PipelineState& pipe = *a.draw->pipe;
    fragment::BlendOptions opt;
    opt.fused = a.fused;
    alignas(32) float src[4][kBlockLanes];
    for (uint32_t c = 0; c < fb.num_color && c < shader::kMaxColorOutputs; ++c) {
        const ColorTarget& t = fb.color[c];
        if (!t.data || plan.color[c] == ColorPath::kNone) continue;
        const uint32_t* words = k.local ? k.local + size_t(plan.output_word[c]) * kBlockLanes : w.block.outputs[c][0];
        if (write_color_in_place(w, a, k, c, reinterpret_cast<const float(*)[kBlockLanes]>(words), opt)) continue;
        std::memcpy(src, words, sizeof src);
        if (pipe.alpha_to_one) std::fill(src[3], src[3] + kBlockLanes, 1.0f);
        const size_t bytes = plan.color_bytes[c];
        for (int s = 0; s < k.samples; ++s) {
            if (!k.final_mask[s]) continue;
            uint8_t* origin = t.data + size_t(s) * t.sample_stride + size_t(k.y) * t.row_pitch + size_t(k.x) * bytes;
            if (plan.color[c] == ColorPath::kRgba8 && k.inside &&
                fragment::blend_rgba8_block(plan.rgba8[c], src, k.final_mask[s], origin, t.row_pitch))
                continue;
            if (plan.color[c] == ColorPath::kGeneric || plan.color[c] == ColorPath::kRgba8)
                fragment::blend_block(pipe.blend[c], t.format, pipe.blend_constants, src, k.final_mask[s], origin,
                                      t.row_pitch, opt);
            else
                fragment::store_rgba8_fast(plan.color[c] == ColorPath::kOpaqueBgra8, src, k.final_mask[s], origin,
                                           t.row_pitch, opt.unorm_path, k.inside);
        }
    }
}

template <int kSamples>
void shade_block_n(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]) {
#if TILEVK_SIMD_AVX2
    if constexpr (kSamples == 4)
        if (a.plan->uniform_store_4x >= 0 && x + 4 <= a.fb->width && y + 4 <= a.fb->height)
            return store_uniform_4x(w, a, x, y, raster_masks);
    if constexpr (kSamples == 1)
        if (a.plan->block1x.ok && x + 4 <= a.fb->width && y + 4 <= a.fb->height) {
            if (raster_masks[0]) shade_block_1x(w, a, x, y, raster_masks[0]);
            return;
        }
#endif
    Block<kSamples> k;
    k.x = x;
    k.y = y;
    const uint16_t covered = coverage(a, raster_masks, k);  // pass = cover until the early test
    if (!covered) return;
    const bool depth_active = a.draw->depth_mode != 0;
    if (depth_active) depth_values(a, k);
    const uint16_t shade_lanes = depth_active ? early_depth(a, k) : covered;
    if (!shade_lanes) return;

    const shader::Program* fs = a.draw->pipe->fragment;
    const uint64_t shade_start = w.shade_sample_start();
    uint16_t live = shade_lanes;
    if (fs && a.plan->uniform_shader)
        run_uniform(w, a);
    else if (fs)
        live = run_shader(w, a, k, shade_lanes);
    w.shade_sample_end(shade_start);

    for (int s = 0; s < k.samples; ++s) k.final_mask[s] = k.pass[s] & live;
    shader_coverage(fs, a.draw->pipe->alpha_to_coverage, w.block, k.samples, k.final_mask);
    if (depth_active) late_depth(a, k);
    if (a.draw->samples_passed) count_passed(w, a.prim->draw, k.final_mask, k.samples);  // only inside a query
    if (fs) write_colors(w, a, k);
}

}  // namespace

#if TILEVK_SIMD_AVX2
// fragment_plan.h Uniform4xFn. Blocks from the rasterizer are never empty (coverage.h Block4), so the primitive's
// colour is looked up before the first; blocks reaching past the framebuffer take the block pipeline.
void shade_uniform_4x_blocks(FragmentWorker& w, const BlockArgs& a, const Block4* blocks, size_t count) {
    if (count == 0) return;
    const auto c = uint32_t(a.plan->uniform_store_4x);
    __m128i rows[4];
    uniform_rows(w, a, c, a.plan->color[c] == ColorPath::kOpaqueBgra8, rows);
    const ColorTarget& t = a.fb->color[c];
    const int32_t last_x = a.fb->width - 4, last_y = a.fb->height - 4;
    for (size_t i = 0; i < count; ++i) {
        const Block4& b = blocks[i];
        if (b.x <= last_x && b.y <= last_y)
            store_uniform_4x_block(t, rows, b.x, b.y, b.mask);
        else
            shade_block_n<4>(w, a, b.x, b.y, b.mask);
    }
}
#endif

// Framebuffers have 1 or 4 samples (pipeline.cpp refuses other rasterizationSamples, rast/core's Scene clamps).
void shade_block_fast(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]) {
    if (a.fb->samples == 4)
        shade_block_n<4>(w, a, x, y, raster_masks);
    else
        shade_block_n<1>(w, a, x, y, raster_masks);
}

}  // namespace tilevk::rast::render::TILEVK_ISA
