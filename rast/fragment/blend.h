// Blending and colour write for one 4x4 block of one colour attachment (one sample plane), as lavapipe does it
// (llvmpipe lp_state_fs.c generate_unswizzled_blend, lp_bld_blend_aos.c, lp_bld_blend.c; lavapipe lvp_execute.c).
//
// UNORM8 targets blend in 8-bit fixed point:  term = mul_norm(c, f)  with  p = a*b; p += p>>8; p += 0x80; p >> 8,
// 1-f = 255-f, ADD/SUB saturating.  Single-channel UNORM8 targets (R8) with complementary factors and ADD use
// lavapipe's lerp instead: v0 + pmulhrsw(x + (x>>7), (v1-v0)<<7), a different rounding.
// sRGB, half and 32-bit float targets blend in float (sRGB: src clamped to [0,1], dst decoded with the polynomial),
// with lavapipe's algebraic shortcuts: ZERO/ONE factor vectors skip the multiply, equal src/dst factors compute
// (src op dst)*f, and single-channel float targets with complementary factors use fmuladd-based lerp formulas.
// MIN/MAX force both factors to ONE (lavapipe stomps them), formats without alpha turn DST_ALPHA into ONE,
// ONE_MINUS_DST_ALPHA into ZERO (and SRC_ALPHA_SATURATE into ZERO for UNORM), and use the RGB equation for alpha.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rast/fragment/block.h"
#include "rast/fragment/color.h"

namespace tilevk::rast::fragment {

// Numbering mirrors VkBlendFactor.
enum class BlendFactor : uint8_t {
    Zero,
    One,
    SrcColor,
    OneMinusSrcColor,
    DstColor,
    OneMinusDstColor,
    SrcAlpha,
    OneMinusSrcAlpha,
    DstAlpha,
    OneMinusDstAlpha,
    ConstantColor,
    OneMinusConstantColor,
    ConstantAlpha,
    OneMinusConstantAlpha,
    SrcAlphaSaturate,
    Src1Color,  // dual-source factors: not supported by these kernels
    OneMinusSrc1Color,
    Src1Alpha,
    OneMinusSrc1Alpha,
};

// Numbering mirrors VkBlendOp's first five values.
enum class BlendOp : uint8_t { Add, Subtract, ReverseSubtract, Min, Max };

inline constexpr uint8_t kWriteR = 1, kWriteG = 2, kWriteB = 4, kWriteA = 8;

struct BlendAttachment {
    bool blend_enable = false;
    BlendFactor src_color = BlendFactor::One;
    BlendFactor dst_color = BlendFactor::Zero;
    BlendOp color_op = BlendOp::Add;
    BlendFactor src_alpha = BlendFactor::One;
    BlendFactor dst_alpha = BlendFactor::Zero;
    BlendOp alpha_op = BlendOp::Add;
    uint8_t write_mask = 0xf;  // kWriteR | kWriteG | kWriteB | kWriteA
};

struct BlendOptions {
    bool fused = true;  // lavapipe's fmuladd is a true FMA on FMA CPUs
    UnormPath unorm_path = UnormPath::Avx8;
};

// False for the dual-source factors (the caller reports VK_ERROR_FEATURE_NOT_PRESENT or similar).
bool blend_supported(const BlendAttachment& a);

// One pixel: src RGBA float (shader output), dst the stored pixel bytes (format_info(f).bytes), updated in place.
void blend_pixel(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4], uint8_t* dst,
                 const BlendOptions& opt = {});

// The lanes of `lane_mask` (shader lane order) of a 4x4 block whose pixel (0,0) is at `block`, rows `pitch`
// bytes apart. src[c][lane] is the shader's colour output, SoA.
void blend_block(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4][kBlockLanes],
                 uint16_t lane_mask, uint8_t* block, size_t pitch, const BlendOptions& opt = {});

// The fast path for 4-channel UNORM8 targets (R8G8B8A8 / B8G8R8A8): every state blend_block supports for them
// (all single-source factors, the five ops, any write mask, blending on or off), prepared once per draw.
// ok = false: the state or options are not covered (UnormPath::Sse4, other formats, dual source) -> blend_block.
struct Rgba8Blend {
    bool ok = false;
    bool bgra = false;
    bool blend = false;
    uint8_t rgb_src = 0, rgb_dst = 0, a_src = 0, a_dst = 0;  // lowered factors (blend.cpp's PipeFactor codes)
    BlendOp rgb_op = BlendOp::Add, a_op = BlendOp::Add;
    uint8_t k[4] = {};      // UNORM8 constants in memory order
    uint8_t wmask_mem = 0;  // channel write mask in memory order
};
Rgba8Blend prepare_rgba8_blend(const BlendAttachment& a, ColorFormat f, const float constants[4],
                               const BlendOptions& opt = {});

// blend_block for a prepared RGBA8 / BGRA8 state on a block whose 16 pixels all exist: 16 pixels at once with
// AVX2 (mul_norm in 16-bit lanes, saturating 8-bit ops). Returns false, writing nothing, when built without AVX2:
// blend_block is its scalar twin (tests/rast/fragment/kernel_test.cpp compares them).
bool blend_rgba8_block(const Rgba8Blend& b, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block,
                       size_t pitch);

// 8-bit helpers, exposed for tests.
// mul_norm(a, b) = (p + (p >> 8) + 0x80) >> 8 with p = a*b  (lp_build_mul_norm, 16-bit lanes)
constexpr uint8_t mul_norm8(uint8_t a, uint8_t b) {
    uint32_t p = uint32_t(a) * b;
    p += p >> 8;
    p += 0x80;
    return uint8_t(p >> 8);
}
// lavapipe's 8-bit lerp (lp_build_lerp, SSSE3/AVX2 pmulhrsw path): v0 + ((x + (x>>7)) * ((v1-v0)<<7) + 2^14) >> 15
uint8_t lerp8(uint8_t x, uint8_t v0, uint8_t v1);

}  // namespace tilevk::rast::fragment
