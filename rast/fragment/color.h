// Colour storage formats and the exact conversions lavapipe uses between them and float.
//
//   shader float -> UNORM8      u8 = sat(rne(fl(min(1,x) * 255)))   NaN and negatives -> 0   (lp_bld_conv.c, 8-wide)
//   UNORM8 -> float             fl((float)u8 * fl(1/255))                                   (unsigned_norm_to_float)
//   clear float -> UNORM8       util float_to_ubyte: 0 if !(f>0), 255 if f>=1, else low byte of fl(fl(f*255/256)+32768)
//   sRGB8 -> linear float       cubic polynomial, linear below 16 (lp_bld_format_srgb.c lp_build_srgb_to_linear)
//   linear float -> sRGB8       rsqrt-based rational approximation (lp_build_linear_to_srgb), alpha rne(a*255)
//   float -> half (RGBA16F)     vcvtps2ph with round-toward-zero (lp_build_float_to_half, mode 3), denormals kept
//
// CPU caveat: linear->sRGB uses the x86 RSQRTPS approximation; its result differs between CPU vendors/models.
// linear_to_srgb8 executes the host's own RSQRTSS so it matches lavapipe running on the same machine.
// The +Inf quirk: on lavapipe's 4-wide (SSE-only) path min(1,x) is dropped and x*255 >= 2^31 (e.g. +Inf) gives 0;
// on the 8-wide AVX path (every AVX CPU, the default here) +Inf gives 255.
#pragma once

#include <climits>
#include <cmath>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace tilevk::rast::fragment {

enum class ColorFormat : uint8_t {
    R8G8B8A8_UNORM,
    B8G8R8A8_UNORM,
    R8G8B8A8_SRGB,
    B8G8R8A8_SRGB,
    R8_UNORM,
    R8G8_UNORM,
    R16G16B16A16_SFLOAT,
    R32_SFLOAT,
    R32G32_SFLOAT,
    R32G32B32A32_SFLOAT,
};

enum class ChannelKind : uint8_t { Unorm8, Srgb8, Half, Float32 };

struct FormatInfo {
    uint8_t bytes;     // per pixel
    uint8_t channels;  // stored channels (R, RG or RGBA)
    bool has_alpha;
    bool bgra;  // stored order B, G, R, A
    ChannelKind kind;
};

FormatInfo format_info(ColorFormat f);

enum class UnormPath : uint8_t {
    Avx8,  // lavapipe with AVX (256-bit vectors): min(1,x) before scaling, +Inf -> 255
    Sse4,  // lavapipe without AVX: the min is dropped, x*255 >= 2^31 -> 0
};

namespace detail {
// cvtps2dq (round half to even under the default MXCSR), INT32_MIN for NaN / out of range.
inline int32_t cvtps2dq_u8path(float f) {
#if defined(__x86_64__) || defined(__i386__)
    return _mm_cvtss_si32(_mm_set_ss(f));
#else
    if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT32_MIN;
    return int32_t(std::nearbyint(f));
#endif
}
// packssdw then packuswb: signed saturate to 16 bits, then unsigned saturate to 8 bits.
inline uint8_t pack_sat_u8(int32_t v) {
    const int32_t s16 = v < -32768 ? -32768 : v > 32767 ? 32767 : v;
    return uint8_t(s16 < 0 ? 0 : s16 > 255 ? 255 : s16);
}
}  // namespace detail

// Shader output to UNORM8, also used for the blend constants. Inline: it runs once per channel per pixel.
inline uint8_t float_to_unorm8(float x, UnormPath path = UnormPath::Avx8) {
    // Avx8: a = min.ps(1.0, x)  (NaN -> x, i.e. stays NaN);  then cvtps2dq(fl(a*255)) and saturating packs
    float a = x;
    if (path == UnormPath::Avx8) a = 1.0f < x ? 1.0f : x;
    return detail::pack_sat_u8(detail::cvtps2dq_u8path(a * 255.0f));
}
// UNORM8 to float: fl(float(u) * fl(1/255)).
float unorm8_to_float(uint8_t u);
// util_pack_color's float_to_ubyte (colour clears).
uint8_t float_to_ubyte_clear(float f);

// sRGB8 -> linear: x = float(u); x <= 15 ? fl(x * fl(1/(12.6*255))) : poly(x)   (poly uses fmuladd: `fused`)
float srgb8_to_linear(uint8_t u, bool fused);
// linear -> sRGB8 (RGB channels): clamp [0,1] (NaN -> 1), rsqrt approximation, rne.
uint8_t linear_to_srgb8(float x, bool fused);
// sRGB alpha channel store: rne(fl(clamp_nanzero(a) * 255)).
uint8_t srgb_alpha_to_u8(float a);

// The host's RSQRTSS (the approximation lavapipe's JIT uses on this CPU).
float hw_rsqrt(float x);

// IEEE half <-> float. to_half rounds toward zero like VCVTPS2PH imm=3 (NaN stays NaN, overflow -> max finite).
uint16_t float_to_half_rz(float f);
float half_to_float(uint16_t h);

// FTZ/DAZ helpers (lavapipe runs float blending for 32-bit float targets with MXCSR FTZ|DAZ).
float flush_denorm(float f);

}  // namespace tilevk::rast::fragment
