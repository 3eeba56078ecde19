// The border colour where CLAMP_TO_BORDER reads outside a level (texture.cpp, texture_3d.cpp, texture_gather.cpp):
// the sampler's colour, standard or VK_EXT_custom_border_color's, as gallivm substitutes it for a texel of the
// view's format (docs/lavapipe-rules.md §10).
#include <algorithm>
#include <bit>

#include "shader/texture_internal.h"

namespace tilevk::shader::tex {

// The sampler's border colour as gallivm returns it: its bits whatever the format (an INT border's 1 is the integer
// 1, a FLOAT border's 1.0f its float bits, also on integer images; a custom colour's VkClearColorValue bits).
Vec4 border_color(const SamplerState& smp) {
    const float one = smp.integer_border ? std::bit_cast<float>(1u) : 1.0f;
    switch (smp.border) {
        case BorderColor::OpaqueBlack:
            return {0, 0, 0, one};
        case BorderColor::OpaqueWhite:
            return {one, one, one, one};
        case BorderColor::Custom:
            return std::bit_cast<Vec4>(smp.custom_border);
        default:
            return {0, 0, 0, 0};
    }
}

namespace {

// lp_build_max / lp_build_min on float texels are maxps / minps: the second operand when either is NaN.
float max_ps(float a, float b) {
    return a > b ? a : b;
}
float min_ps(float a, float b) {
    return a < b ? a : b;
}

// One border channel clamped to the range of the format channel `ch` (lp_bld_sample_soa.c
// lp_build_clamp_border_color): UNORM and sRGB [0, 1], SNORM [-1, 1], integers narrower than 32 bits to their
// range (compared as the texel type: unsigned for UINT), B10G11R11 at least 0, E5B9G9R9 [0, 65408]; float, 32-bit
// integer and scaled channels unclamped. gallivm derives one clamp from the format's first channel, which for every
// Vulkan format it samples equals this per-channel clamp (A2B10G10R10_UINT's own case clamps alpha to 3).
float clamp_border_channel(const format::FormatInfo& f, const format::Channel& ch, float v) {
    using format::Numeric;
    switch (ch.numeric) {
        case Numeric::kUnorm:
        case Numeric::kSrgb:
            return min_ps(max_ps(v, 0.0f), 1.0f);
        case Numeric::kSnorm:
            return min_ps(max_ps(v, -1.0f), 1.0f);
        case Numeric::kUint:
            if (ch.bits >= 32) return v;
            return std::bit_cast<float>(std::min(std::bit_cast<uint32_t>(v), (1u << ch.bits) - 1u));
        case Numeric::kSint: {
            if (ch.bits >= 32) return v;
            const int32_t lim = int32_t(1u << (ch.bits - 1));
            return std::bit_cast<float>(std::clamp(std::bit_cast<int32_t>(v), -lim, lim - 1));
        }
        case Numeric::kUfloat:
            v = max_ps(v, 0.0f);
            // MAX_RGB9E5: the largest shared-exponent value, 511/512 * 2^16
            return f.layout == format::Layout::kSharedExponent ? min_ps(v, 65408.0f) : v;
        default:
            return v;
    }
}

// A border channel of a BC format clamped as lp_build_clamp_border_color clamps by format (the rows list no
// channels): SNORM [-1, 1], BC6H_UFLOAT at least 0, BC6H_SFLOAT unclamped, the others [0, 1].
float clamp_border_bc(const format::FormatInfo& f, float v) {
    if (format::is_bc_signed(f)) return min_ps(max_ps(v, -1.0f), 1.0f);
    if (f.id == format::Format::BC6H_UFLOAT_BLOCK) return max_ps(v, 0.0f);
    if (f.id == format::Format::BC6H_SFLOAT_BLOCK) return v;
    return min_ps(max_ps(v, 0.0f), 1.0f);
}

// The RGBA channel a format channel fills, or -1 (the shared exponent). Depth and stencil fill red.
int border_index(format::Component c) {
    using format::Component;
    switch (c) {
        case Component::kR:
        case Component::kD:
        case Component::kS:
            return 0;
        case Component::kG:
            return 1;
        case Component::kB:
            return 2;
        case Component::kA:
            return 3;
        default:
            return -1;
    }
}

}  // namespace

// The border colour as the filters substitute it for a texel of format f (lp_bld_sample_soa.c
// lp_build_sample_texel_soa, lp_build_clamp_border_color): clamped to the format's range, and only in the channels
// the format stores (its swizzle names a channel); the others keep the texel's constant, 0 (colour) or 1 (alpha,
// the integer 1 on integer formats). R8 with an opaque white border is (1, 0, 0, 1); a depth format takes red only.
Vec4 format_border(const format::FormatInfo& f, const SamplerState& smp) {
    const Vec4 raw = border_color(smp);
    const float one = format::is_integer(f) ? std::bit_cast<float>(1u) : 1.0f;
    Vec4 b = {0.0f, 0.0f, 0.0f, one};
    if (f.layout == format::Layout::kCompressed) {
        const uint8_t keep = format::bc_stored_channels(f);
        for (size_t c = 0; c < 4; ++c)
            if (keep & (1u << c)) b[c] = clamp_border_bc(f, raw[c]);
        return b;
    }
    const bool depth_stencil = (f.aspects & (format::kDepth | format::kStencil)) != 0;
    for (int i = 0; i < f.channels; ++i) {
        const int c = border_index(f.channel[i].component);
        if (c < 0 || (depth_stencil && i > 0)) continue;  // a depth/stencil view samples its first channel
        b[size_t(c)] = clamp_border_channel(f, f.channel[i], raw[size_t(c)]);
    }
    return b;
}

}  // namespace tilevk::shader::tex
