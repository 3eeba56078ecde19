// llvmpipe's 8-bit fixed-point ("AoS") texture filtering arithmetic, as pure functions (see README.md).
// lavapipe filters 8-bit UNORM, non-sRGB textures (R8, RG8, RGBA8, BGRA8) this way whenever the wrap modes are
// REPEAT or CLAMP_TO_EDGE and no depth compare is asked (gallivm lp_bld_sample_soa.c `use_aos`,
// lp_bld_sample_aos.c); everything else is filtered in float.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "format/texel_bc.h"
#include "format/texel_codec.h"

namespace tilevk::shader::fixed8 {

// util_format_fits_8unorm: every channel UNORM of at most 8 bits, not sRGB (the formats of the 8-bit path); of the
// compressed formats, BC1-BC5 UNORM (S3TC and RGTC, not sRGB, not SNORM; texel_bc.h).
inline bool fits_8unorm(const format::FormatInfo& f) {
    if (f.layout == format::Layout::kCompressed)
        return format::is_bc_decoded(f) && !format::is_bc_signed(f) && !format::is_bc_srgb(f);
    if (f.kind == format::ChannelKind::Unorm8) return true;
    if (f.kind != format::ChannelKind::PackedUnorm) return false;
    for (int i = 0; i < f.channels; ++i)
        if (f.channel[i].bits > 8) return false;
    return true;
}

// A texel as lavapipe's 8-bit path fetches it (lp_build_fetch_rgba_aos), its channels in RGBA order (absent
// channels read 0, 0, 0, 255): 8-bit channels as they are, narrower UNORM channels widened to 8 bits by bit
// replication (the 8-bit blend type's widening).
inline std::array<int32_t, 4> texel_bytes(const format::FormatInfo& f, const uint8_t* p) {
    if (f.kind == format::ChannelKind::PackedUnorm) {
        uint32_t w[4];
        format::load_blend_type(f, p, w);
        return {uint8_t(w[0]), uint8_t(w[1]), uint8_t(w[2]), uint8_t(w[3])};
    }
    uint8_t c[4];
    format::load_unorm8(f, p, c);
    return {c[0], c[1], c[2], c[3]};
}

// Float -> int32 rounding to nearest-even, as x86 cvtps2dq: NaN and out-of-range give INT32_MIN.
inline int32_t iround(float x) {
    if (!(x >= -2147483648.0f && x < 2147483648.0f)) return INT32_MIN;
    return int32_t(std::nearbyint(x));
}

// One lerp step on 8-bit values with an 8-bit weight w in [0,255] (w/256 of the way from a to b):
// a + floor((w*(b-a) + 128) / 256)   (pmulhrsw of w by (b-a)<<7)
inline int32_t lerp(int32_t w, int32_t a, int32_t b) {
    return a + ((w * (b - a) + 128) >> 8);
}

// Texel coordinate with 8 fraction bits, already moved back by half a texel: iround(u*256) - 128, where u is
// in texels. The texel index is `c >> 8` (arithmetic), the filter weight `c & 255`.
inline int32_t coord(float u256) {
    return int32_t(uint32_t(iround(u256)) - 128u);
}

struct Pair {
    int32_t i0, i1;  // the two texels of the footprint along one axis
    int32_t w;       // weight of i1, 0..255
};

// CLAMP_TO_EDGE: clamp both indices to [0, n-1].
inline Pair wrap_clamp(int32_t c, int32_t n) {
    int32_t i = c >> 8;
    int32_t i0 = i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
    int32_t i1 = (i >= 0 && i < n - 1) ? i0 + 1 : i0;
    return {i0, i1, c & 255};
}

// REPEAT with a power-of-two size: i0 = i & (n-1), i1 = the next texel, wrapping to 0.
inline Pair wrap_repeat_pot(int32_t i, int32_t w, int32_t n) {
    int32_t i0 = i & (n - 1);
    return {i0, i0 == n - 1 ? 0 : i0 + 1, w};
}

// REPEAT with any other size is redone from the float coordinate s (normalized, texel offset already added
// as off/n): c = iround(fract(s)*n*256) - 128; i0 = c >> 8, -1 becoming n-1, at most n-1.
inline Pair wrap_repeat_npot(float s, int32_t n) {
    float f = s - std::floor(s);
    f = f * float(n);
    f = f * 256.0f;
    int32_t c = coord(f);
    int32_t i0 = c >> 8;
    if (i0 < 0) i0 = n - 1;
    if (i0 > n - 1) i0 = n - 1;
    return {i0, i0 == n - 1 ? 0 : i0 + 1, c & 255};
}

// gallivm's fast log2: floor(log2 x) + (mantissa - 1), i.e. float(exponent - 1) + mantissa in [1,2); exact
// at powers of two, linear in between (never above the true log2).
inline float fast_log2(float x) {
    uint32_t b = std::bit_cast<uint32_t>(x);
    int32_t e = int32_t((b >> 23) & 0xff) - 127 - 1;
    float m = std::bit_cast<float>((b & 0x7fffffu) | 0x3f800000u);
    return float(e) + m;
}

// Mip blend weight from the LOD's fraction: trunc(frac*256), never negative.
inline int32_t mip_weight(float frac) {
    float w = frac * 256.0f;
    if (!(w > 0.0f)) return 0;
    return w >= 256.0f ? 255 : int32_t(w);
}

}  // namespace tilevk::shader::fixed8
