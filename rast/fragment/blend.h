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
    Src1Color,  // dual-source factors: the second source is the fragment shader's Location 0, Index 1 output
    OneMinusSrc1Color,
    Src1Alpha,
    OneMinusSrc1Alpha,
};

// Numbering mirrors VkBlendOp's first five values.
enum class BlendOp : uint8_t { Add, Subtract, ReverseSubtract, Min, Max };

// Numbering mirrors VkLogicOp (s = source, d = destination): CLEAR 0, AND s&d, AND_REVERSE s&~d, COPY s,
// AND_INVERTED ~s&d, NO_OP d, XOR, OR, NOR, EQUIVALENT ~(s^d), INVERT ~d, OR_REVERSE s|~d, COPY_INVERTED ~s,
// OR_INVERTED ~s|d, NAND, SET.
enum class LogicOp : uint8_t {
    Clear,
    And,
    AndReverse,
    Copy,
    AndInverted,
    NoOp,
    Xor,
    Or,
    Nor,
    Equivalent,
    Invert,
    OrReverse,
    CopyInverted,
    OrInverted,
    Nand,
    Set,
};

// The logic op on one 8-bit channel.
constexpr uint8_t logic_op8(LogicOp op, uint8_t s, uint8_t d) {
    switch (op) {
        case LogicOp::Clear:
            return 0;
        case LogicOp::And:
            return uint8_t(s & d);
        case LogicOp::AndReverse:
            return uint8_t(s & ~d);
        case LogicOp::Copy:
            return s;
        case LogicOp::AndInverted:
            return uint8_t(~s & d);
        case LogicOp::NoOp:
            return d;
        case LogicOp::Xor:
            return uint8_t(s ^ d);
        case LogicOp::Or:
            return uint8_t(s | d);
        case LogicOp::Nor:
            return uint8_t(~(s | d));
        case LogicOp::Equivalent:
            return uint8_t(~(s ^ d));
        case LogicOp::Invert:
            return uint8_t(~d);
        case LogicOp::OrReverse:
            return uint8_t(s | ~d);
        case LogicOp::CopyInverted:
            return uint8_t(~s);
        case LogicOp::OrInverted:
            return uint8_t(~s | d);
        case LogicOp::Nand:
            return uint8_t(~(s & d));
        case LogicOp::Set:
            return 0xff;
    }
    return s;
}

inline constexpr uint8_t kWriteR = 1, kWriteG = 2, kWriteB = 4, kWriteA = 8;

struct BlendAttachment {
    // A logic op replaces blending (lavapipe lp_bld_blend_aos.c): on UNORM8 targets it combines the converted
    // source bytes with the stored bytes; float, half and sRGB targets take the source unblended (Vulkan: logic ops
    // do not apply to those formats).
    bool logic_op_enable = false;
    LogicOp logic_op = LogicOp::Copy;
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

// Dual-source blending: blending is on (and no logic op replaces it) with a SRC1 factor in any of the four
// slots (llvmpipe util_blend_state_is_dual). Such a state blends with a second source, converted as the first.
bool uses_second_source(const BlendAttachment& a);

// One pixel: src RGBA float (shader output), dst the stored pixel bytes (format_info(f).bytes), updated in place.
void blend_pixel(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4], uint8_t* dst,
                 const BlendOptions& opt = {});

// The lanes of `lane_mask` (shader lane order) of a 4x4 block whose pixel (0,0) is at `block`, rows `pitch`
// bytes apart. src[c][lane] is the shader's colour output, SoA; src1 the second source of a dual-source state
// (null: zeros).
void blend_block(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4][kBlockLanes],
                 uint16_t lane_mask, uint8_t* block, size_t pitch, const BlendOptions& opt = {},
                 const float (*src1)[kBlockLanes] = nullptr);

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
    // Every channel SRC_ALPHA / ONE_MINUS_SRC_ALPHA / ADD after lowering (standard alpha blending): the AVX2 build
    // takes a specialisation of its general kernel (blend_rgba8.cpp blend_over) with the same operations per byte.
    bool over = false;
};
Rgba8Blend prepare_rgba8_blend(const BlendAttachment& a, ColorFormat f, const float constants[4],
                               const BlendOptions& opt = {});

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
