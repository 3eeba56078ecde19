// Depth and stencil test for one 4x4 block (one sample plane), as llvmpipe does it
// (lp_state_fs.c generate_fs_loop / lp_build_depth_clamp, lp_bld_depth.c lp_build_depth_stencil_test).
//
// Order per lane: z = clamp01(z) (unless unrestricted D32F) -> optional depthClamp to [min_depth, max_depth]
// -> convert to the stored format -> stencil test (ref & cmask  OP  stored & cmask) -> stencil fail op
// -> depth test (z_src OP z_stored, in the stored format's precision) -> depth write
// -> depth-fail / depth-pass stencil ops, each masked by the stencil write mask.
// Clamps use SSE min/max semantics: min(z, hi) returns hi when z is NaN, so a NaN z becomes 1.0 (or max_depth);
// they run under DAZ, so a denormal z becomes 0. D32F compares also treat denormals as zero.
#pragma once

#include <cstdint>

#include "format/texel_codec.h"
#include "rast/fragment/block.h"
#include "shader/program.h"

namespace tilevk::rast::fragment {

using CompareOp = shader::CompareOp;  // numbering mirrors VkCompareOp
// Numbering mirrors VkStencilOp.
enum class StencilOp : uint8_t {
    Keep,
    Zero,
    Replace,
    IncrementAndClamp,
    DecrementAndClamp,
    Invert,
    IncrementAndWrap,
    DecrementAndWrap
};

// Depth storage (format/format.h): D16, X8D24 (24 bits in the low bits of a 32-bit word), D32F. Stencil (S8) is
// always a separate 8-bit value per sample for these kernels; D24S8 packing is the storage layer's business (z in
// bits 0..23, stencil in 24..31 for lavapipe's Z24_S8).
using format::DepthFormat;

struct StencilFace {
    StencilOp fail_op = StencilOp::Keep;
    StencilOp pass_op = StencilOp::Keep;
    StencilOp depth_fail_op = StencilOp::Keep;
    CompareOp compare_op = CompareOp::Always;
    uint8_t compare_mask = 0xff;
    uint8_t write_mask = 0xff;
    uint8_t reference = 0;
};

struct DepthStencilState {
    bool depth_test = false;
    bool depth_write = false;
    CompareOp depth_compare = CompareOp::Less;
    bool stencil_test = false;
    StencilFace front, back;
    bool depth_clamp = false;         // VkPipelineRasterizationStateCreateInfo::depthClampEnable
    float min_depth = 0.0f;           // viewport min(minDepth, maxDepth), used only with depth_clamp
    float max_depth = 1.0f;           // viewport max(minDepth, maxDepth)
    bool unrestricted_depth = false;  // VK_EXT_depth_range_unrestricted enabled; only matters for D32F
};

// One sample plane of a block, in lane order. Depth values are the raw stored bits (D16 in the low 16 bits,
// D24 in the low 24 bits, D32F as float bits).
struct DepthStencilBlock {
    uint32_t depth[kBlockLanes];
    uint8_t stencil[kBlockLanes];
};

// z after lavapipe's restriction and depthClamp (lp_build_depth_clamp).
float clamp_depth(float z, const DepthStencilState& s, DepthFormat f);

// Float depth (already clamped to [0,1]) to the stored integer / bits (format/texel_codec.h):
//   D16: t = fl(z * (65535/65536)); u = fl(t + 128.0f); bits(u) & 0xFFFF   (== rne(t * 65536))
//   D24: cvtps2dq(fl(z * 16777215.0f))  (round half to even)
//   D32F: the float bits unchanged
using format::depth_to_stored;

bool compare(CompareOp op, uint32_t a, uint32_t b);  // unsigned integer compare: a OP b
bool compare_float(CompareOp op, float a, float b);  // unordered compares (NaN -> true), denormals as zero

uint8_t apply_stencil_op(StencilOp op, uint8_t value, uint8_t reference);

// Runs the stencil and depth tests for the lanes in `mask` (lane order), updating `zs` when writes are enabled
// (depth_write, stencil write masks). `z` are the interpolated (or shader-written) depths, before clamping.
// `write` = false performs the tests only (early test whose write is deferred: see DepthMode).
// Returns the mask of lanes that pass both tests.
uint16_t depth_stencil_test(const DepthStencilState& s, DepthFormat f, bool front_facing, const float z[kBlockLanes],
                            uint16_t mask, DepthStencilBlock& zs, bool write = true);

// When lavapipe tests and writes depth/stencil relative to the fragment shader (lp_state_fs.c generate_fs_loop).
enum DepthModeBits : uint8_t {
    kEarlyDepthTest = 0x1,
    kLateDepthTest = 0x2,
    kEarlyDepthWrite = 0x4,
    kLateDepthWrite = 0x8,
    kEarlyDepthTestInferred = 0x10,
};

struct ShaderDepthTraits {
    bool early_fragment_tests = false;  // OpExecutionMode EarlyFragmentTests
    bool writes_depth = false;
    bool writes_stencil = false;
    bool uses_fbfetch = false;
    bool writes_memory = false;  // storage buffer / image stores
    bool uses_discard = false;
    bool writes_sample_mask = false;
};

// The depth_mode bit set lavapipe compiles for this state (0 when neither test is enabled).
uint8_t choose_depth_mode(const DepthStencilState& s, const ShaderDepthTraits& t, bool alpha_to_coverage);

}  // namespace tilevk::rast::fragment
