// The fragment stage's per-draw plan, its per-worker state, and the block-function interface.
//
// FragmentStage (fragment_stage.cpp) turns each covered 4x4 block into pixels with a *block function*:
//
//     void block(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]);
//
// It gets the block's origin and its per-sample raster-order coverage, and everything else through BlockArgs (the
// framebuffer's targets, the draw record with its pipeline state and bindings, the draw's plan, the primitive's
// planes in the scene_records.h layout); it interpolates, runs the fragment shader, tests depth/stencil, applies
// alpha to coverage and the sample mask, blends and stores, and counts occlusion samples into w.samples_passed —
// all with lavapipe's arithmetic (the per-step rules of fragment_block.cpp and rast/fragment). It is
// fragment_block.cpp's fast pipeline, built once per instruction set (fast_block_function() picks the one the
// CPU runs, rast/core/cpu.h). Whichever build runs, the bytes must be those of the reference pipeline
// (FragmentStage::shade_block): tests/rast/fragment/stage_test.cpp compares them, on both builds.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/fragment/blend.h"
#include "rast/fragment/block_kernels.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/interp.h"
#include "rast/render/scene_records.h"
#include "rast/render/stage_timer.h"
#include "rast/render/targets.h"
#include "shader/program.h"

namespace tilevk::rast::render {

// One shader input component the fast path interpolates; loc kPointCoordLoc is gl_PointCoord (block.point_coord).
inline constexpr uint32_t kPointCoordLoc = ~0u;
struct InputPlan {
    uint32_t loc = 0, comp = 0;
    uint32_t plane = 0;  // float offset of its plane from the primitive's first attribute plane
    geometry::Interp interp = geometry::Interp::kPerspective;
    uint32_t word = ~0u;  // DrawPlan::direct: the program's local word for it, ~0u: the program does not read it
};
inline uint32_t* input_lanes(shader::FragmentBlock& b, const InputPlan& in) {
    return in.loc == kPointCoordLoc ? b.point_coord[in.comp] : b.inputs[in.loc][in.comp];
}

enum class ColorPath : uint8_t { kGeneric, kNone, kOpaqueRgba8, kOpaqueBgra8, kRgba8 };

// Fully covered squares of 8x8 pixels or more that one fused kernel shades row by row (fragment_square.cpp), when
// the draw is 1x without depth/stencil, queries, alpha to coverage or alpha to one, its shader copies one vec4
// input interpolated alike on all four components (not flat) to colour 0, and colour 0 is the only target written:
// an RGBA8/BGRA8 target, opaque or standard alpha blending (Rgba8Blend::over).
struct SquarePlan {
    bool ok = false;
    bool perspective = false;  // the copied input divides by w
    bool bgra = false;
    bool over = false;        // false: opaque, every channel written
    uint8_t wmask_mem = 0xf;  // over: channel write mask in memory order
    uint32_t plane[4] = {};   // float offset of each component's slot plane from the first attribute plane
};

// 1x blocks inside the framebuffer that fragment_block.cpp's fused block kernel (AVX2 build) takes from coverage to
// memory in raster order, with no lane-order masks or lane arrays in between: a draw without queries, alpha to
// coverage or alpha to one whose only written target is opaque RGBA8/BGRA8, shaded by a uniform shader or by a copy
// (colour 0 only) of a vec4 interpolated alike on its four components, with no depth/stencil or the early depth
// kernel's test (DrawPlan::depth_fast, an early test whose write, if any, is early: no late test runs).
struct Block1xPlan {
    bool ok = false;
    bool copy = false;  // the copied input (SquarePlan's planes), else the uniform run's colour
    bool perspective = false;
    bool bgra = false;
    bool depth = false;        // the early depth test runs (plan.depth)
    bool depth_write = false;  // ... with its write
    uint32_t target = 0;
    uint32_t plane[4] = {};  // copy: float offset of each component's slot plane from the first attribute plane
};

// What the fast path derived from one draw's state, once per scene (fragment_stage.cpp make_plan).
struct DrawPlan {
    bool fast = false;              // false: the reference path (unsupported states)
    std::vector<InputPlan> inputs;  // the declared components only: the shader cannot read the others
    bool perspective = false;       // some input divides by w
    bool uniform_shader = false;    // the shader's outputs are the same for every fragment of a primitive
    int copy_location = -1;         // >= 0: the shader only copies this vec4 input to colour output 0
    bool depth_fast = false;        // depth_block_fast handles the depth test
    fragment::DepthFast depth;
    ColorPath color[kMaxColorTargets] = {};
    fragment::Rgba8Blend rgba8[kMaxColorTargets];  // ColorPath::kRgba8: blending / partial write masks
    uint8_t color_bytes[kMaxColorTargets] = {};    // bytes per pixel of each target
    SquarePlan square;
    Block1xPlan block1x;
    // >= 0: a 4x draw whose only written target is this opaque RGBA8/BGRA8 one, shaded by a uniform shader, with no
    // depth/stencil, query, alpha to coverage or alpha to one. Every step of the block pipeline between coverage and
    // store then leaves the masks as they are, so a block inside the framebuffer is the primitive's packed colour
    // stored under each sample's raster mask (fragment_block.cpp store_uniform_4x).
    int uniform_store_4x = -1;
    // Direct runs (shader::Program::FragmentDirect): the inputs interpolated straight into the program's local
    // words (InputPlan::word), the colours read from its output words, no FragmentBlock copies. For a shader that is
    // run per block (not uniform, not a copy), without alpha to coverage, whose inputs the plan all provides.
    bool direct = false;
    uint64_t bindings_key = 0;                    // names the draw's bindings in this scene (bind_fragment)
    uint32_t output_word[kMaxColorTargets] = {};  // colour c's first local word, for the targets written
};

// One worker's fragment-stage state (shader scratch and block, per-draw counters, stage timing).
struct FragmentWorker {
    shader::Scratch scratch;
    shader::FragmentBlock block;
    shader::InputPlanes input_planes;  // RunSite::input_planes of the reference pipeline's runs
    // The record (PrimRecord::planes) of the primitive whose uniform shader result block.outputs holds
    // (DrawPlan::uniform_shader), or null.
    const float* uniform_prim = nullptr;
    bool uniform_front = false;
    // The uniform run's colours converted for the opaque RGBA8/BGRA8 store (fragment_block.cpp), as the four rows
    // of a block: bit c of uniform_rows_valid says target c's rows hold block.outputs[c] of the current uniform run
    // (cleared whenever that run is redone), so a flat primitive converts its colour once, not once per block.
    alignas(16) uint8_t uniform_rows[kMaxColorTargets][4][16] = {};
    uint32_t uniform_rows_valid = 0;
    std::vector<uint64_t> samples_passed;  // per draw record of the current scene
    std::vector<uint64_t> shader_blocks;   // per draw record: FragmentStage::shader_blocks (pipeline statistics)
    // Stage timing (stage_timer.h), when on: the current tile's start (CPU time), and its fragment-stage and shading
    // ticks.
    uint64_t tile_cpu_start = 0, tile_consumer = 0, tile_shade = 0;
    // Shading is timed on one block in kShadeSampling (a time-stamp read costs ~25 ns on a VM, a block ~100 ns);
    // the sampled ticks count kShadeSampling times.
    uint32_t blocks_seen = 0;
    static constexpr uint32_t kShadeSampling = 16;
    uint64_t shade_sample_start() {
        return stage_timers_on() && (++blocks_seen % kShadeSampling) == 0 ? stage_ticks() : 0;
    }
    void shade_sample_end(uint64_t start) {
        if (start) tile_shade += (stage_ticks() - start) * kShadeSampling;
    }
    // Sample shading: each sample's run's colour outputs (float bits), blended after every run (lp_state_fs.c).
    alignas(64) shader::Lanes sample_outputs[fragment::kMaxSamples][shader::kColorOutputSlots][4]{};
    uint64_t hits_seen = 0;       // scratch.loop_limit_hits() after the last primitive
    unsigned saved_fp_state = 0;  // the thread's MXCSR outside its current tile
};

struct BlockArgs;
using BlockFn = void (*)(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]);

// The arguments of a block function (see the top of this file).
struct BlockArgs {
    const Framebuffer* fb = nullptr;
    const DrawRecord* draw = nullptr;
    const DrawPlan* plan = nullptr;
    const PrimRecord* prim = nullptr;
    const float* planes = nullptr;  // the primitive's planes
    bool front_facing = true;
    bool fused = true;  // lavapipe's fmuladds are fused (host FMA)
};

// The fast pipeline for the instruction set this process runs (rast/core/cpu.h kernel_isa()).
BlockFn fast_block_function();

// Shades the fully covered square [x, x+size)^2 of a draw whose plan.square.ok holds, in one fused pass
// (fragment_square.cpp); false, writing nothing, where it does not (size not a multiple of 8, portable build): the
// caller then shades the square block by block. Null when the running build has no square kernel.
using SquareFn = bool (*)(const BlockArgs& a, int32_t x, int32_t y, int32_t size);
SquareFn fast_square_function();

// Shades one primitive's partially covered 4x4 blocks (PrimCoverage::blocks) for a draw whose
// plan.uniform_store_4x >= 0 (fragment_block.cpp): the primitive's colour is looked up once, then each block inside
// the framebuffer is stored under its sample masks, and the others go through the block function. The same bytes as
// calling the block function on each block, without its per-block set-up. Null when the running build has none.
using Uniform4xFn = void (*)(FragmentWorker& w, const BlockArgs& a, const Block4* blocks, size_t count);
Uniform4xFn fast_uniform_4x_function();

// The fast pipeline of one instruction-set build (fragment_block.cpp).
namespace isa_base {
void shade_block_fast(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]);
bool shade_square_fast(const BlockArgs& a, int32_t x, int32_t y, int32_t size);
}
namespace isa_avx2 {
void shade_block_fast(FragmentWorker& w, const BlockArgs& a, int32_t x, int32_t y, const uint16_t raster_masks[4]);
bool shade_square_fast(const BlockArgs& a, int32_t x, int32_t y, int32_t size);
void shade_uniform_4x_blocks(FragmentWorker& w, const BlockArgs& a, const Block4* blocks, size_t count);
}

// ---- shared by every block function and the reference pipeline (fragment_common.cpp) ----

inline fragment::Plane plane_of(const float* p, int c) {
    // AttribPlane layout: a0[4], dadx[4], dady[4]
    return {p[4 + c], p[8 + c], p[c]};
}
inline uint32_t bits_of(float f) {
    return std::bit_cast<uint32_t>(f);
}

// Depth and stencil of the given lanes of a block (others read 0), and back.
void load_depth_stencil(const DepthStencilTarget& t, int sample, int32_t x, int32_t y, uint16_t lanes,
                        fragment::DepthStencilBlock& zs);
void store_depth_stencil(const DepthStencilTarget& t, int sample, int32_t x, int32_t y, uint16_t lanes,
                         const fragment::DepthStencilBlock& zs);

// Where one fragment-shader run interpolates (lp_bld_interp.c attribs_update_simple and pos update): `sample` < 0 a
// per-pixel run, else the sample a per-sample run shades (sample shading); `masks` the per-sample lane masks that
// centroid inputs choose from (lavapipe's mask_store as the run starts), `cover` the raster coverage that
// SampleMaskIn reports.
struct RunSite {
    int samples = 1;
    int sample = -1;
    const uint16_t* masks = nullptr;
    const uint16_t* cover = nullptr;
    // Storage for the planes InterpolateAt* re-evaluates (shader::InputPlanes; filled only when the program has
    // ProgramInterface::interpolates_at), or null.
    shader::InputPlanes* input_planes = nullptr;
};

// Fills the block's shader inputs for one run of draw's fragment shader over the block at (x, y): FragCoord,
// SampleMaskIn, SampleId, SamplePosition and the interpolated inputs, each at lavapipe's location: the pixel
// centre, the run's sample (Sample-decorated inputs, FragCoord.xyz in a per-sample run; FragCoord.w and the 1/w of
// perspective inputs stay at the centre), or the centroid (Centroid-decorated inputs at 4x).
void set_fragment_inputs(shader::FragmentBlock& b, const DrawRecord& draw, const float* planes, int32_t x, int32_t y,
                         const RunSite& site, bool fused);

// What the shader's outputs do to the per-sample survivors: alpha to coverage (raw float alpha of output 0), then
// the shader-written sample mask (lavapipe's order, lp_state_fs.c).
void shader_coverage(const shader::Program* fs, bool alpha_to_coverage, const shader::FragmentBlock& b, int samples,
                     uint16_t final_mask[4]);

// Occlusion (CoverageConsumer::hides_earlier). scene_may_hide: a single-sampled scene outside linear mode without
// depth or stencil, in which no draw counts a query or runs a fragment shader that writes memory — llvmpipe's
// conditions for resetting a bin (lp_setup_whole_tile: no zsbuf, no queries) plus the side effects its reset would
// drop. draw_hides_earlier: the draw's fragments overwrite every colour target outright (llvmpipe's variant->opaque:
// no discard, sample mask or alpha to coverage, no blending or logic op, every channel written; and here also an
// output declared for every component of every target, so that no byte depends on the target's earlier contents).
bool scene_may_hide(const Framebuffer& fb, const DrawRecords& draws);
bool draw_hides_earlier(const DrawRecord& draw, const Framebuffer& fb);

// Occlusion counting: lavapipe adds popcount of the post-depth/stencil mask per sample (lp_state_fs.c,
// lp_build_occlusion_count inside the sample loop under MSAA), i.e. after discard, alpha to coverage, the shader's
// sample mask and the late test. The final masks here are exactly those.
inline void count_passed(FragmentWorker& w, uint32_t draw, const uint16_t final_mask[4], int samples) {
    uint64_t n = 0;
    for (int s = 0; s < samples; ++s) n += uint64_t(std::popcount(final_mask[s]));
    w.samples_passed[draw] += n;
}

}  // namespace tilevk::rast::render
