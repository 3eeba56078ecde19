// The texel codec: every conversion between a stored texel and float (or integer) values that tilevk performs,
// each the one lavapipe (Mesa 22.3.6) performs at that place. lavapipe rounds differently depending on who
// converts, so each variant is named after the rule it follows (docs/lavapipe-rules.md, "Texel conversions"):
//
//   UNORM n -> float      fl(float(c) * fl(1/(2^n-1))), a multiply by the rounded reciprocal, not a division
//                         (gallivm lp_build_unsigned_norm_to_float: sampling, texel fetch, blend dst, vertex fetch)
//   SNORM n -> float      max(fl(float(c) * fl(1/(2^(n-1)-1))), -1)               (lp_build_extract_soa_chan)
//   float -> UNORM8       fragment output: sat(rne(fl(min(1, x) * 255)))          (lp_bld_conv.c, cvtps2dq + packs)
//                         clears: util float_to_ubyte, the low byte of fl(fl(f*255/256) + 32768)    (u_math.h)
//   sRGB8 -> linear       the cubic polynomial of lp_build_srgb_to_linear, linear below 16 (fmuladd: `fused`)
//   linear -> sRGB8       fragment output: the rsqrt approximation of lp_build_linear_to_srgb (the host's RSQRTSS)
//                         clears: util_format_linear_float_to_srgb_8unorm's bucketed table
//   half -> float         VCVTPH2PS (F16C; LLVM's fpext): exact, signalling NaNs quieted, payload kept
//   float -> half         round toward zero (VCVTPS2PH imm 3: lp_build_float_to_half and _mesa_float_to_float16_rtz),
//                         denormals kept, overflow to the largest finite half, NaN quieted with its top payload
//   depth store           D16 low16(fl(fl(z*65535/65536) + 128)), D24 rne(fl(z*16777215)), D32F as is
//   depth clear           util_pack_z in double: D16 lrint(z*65535), D24 lrint(z*16777215), D32F (float)z
//
// CPU caveat: the sRGB output encoder runs the host's RSQRTSS, whose result differs between CPU models; it matches
// lavapipe running on the same machine. The +Inf quirk of UNORM8 output: lavapipe's 4-wide (SSE-only) path drops
// the min(1, x) and turns x*255 >= 2^31 (e.g. +Inf) into 0 (UnormPath::Sse4); its 8-wide AVX path gives 255.
#pragma once

#include <climits>
#include <cmath>
#include <cstdint>

#include "format/format.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace tilevk::format {

// ---- scalar conversions ----------------------------------------------------------------------------------------

enum class UnormPath : uint8_t {
    Avx8,  // lavapipe with AVX (256-bit vectors): min(1,x) before scaling, +Inf -> 255
    Sse4,  // lavapipe without AVX: the min is dropped, x*255 >= 2^31 -> 0
};

namespace detail {
// cvtps2dq (round half to even under the default MXCSR), INT32_MIN for NaN / out of range.
inline int32_t cvtps2dq(float f) {
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

// Fragment output (and blend constants) to UNORM8. Inline: it runs once per channel per pixel.
inline uint8_t float_to_unorm8(float x, UnormPath path = UnormPath::Avx8) {
    // Avx8: a = min.ps(1.0, x)  (NaN -> x, i.e. stays NaN);  then cvtps2dq(fl(a*255)) and saturating packs
    float a = x;
    if (path == UnormPath::Avx8) a = 1.0f < x ? 1.0f : x;
    return detail::pack_sat_u8(detail::cvtps2dq(a * 255.0f));
}
// UNORM8 to float: fl(float(u) * fl(1/255)).
inline float unorm8_to_float(uint8_t u) {
    return float(u) * float(1.0 / 255.0);
}
// UNORM n-bit (n <= 24) to float: fl(float(c) * fl(1/(2^n-1))).
float unorm_to_float(uint32_t c, int bits);
// SNORM n-bit (the low `bits` of raw, two's complement) to float: max(fl(float(c) * fl(1/(2^(n-1)-1))), -1).
float snorm_to_float(uint32_t raw, int bits);
// util float_to_ubyte (colour clears, linear-mode constants): 0 if !(f > 0), 255 if f >= 1, else the low byte of
// fl(fl(f * (255/256)) + 32768).
uint8_t float_to_ubyte(float f);

// sRGB8 -> linear: x = float(u); x <= 15 ? fl(x * fl(1/(12.6*255))) : poly(x)   (poly uses fmuladd: `fused`)
float srgb8_to_linear(uint8_t u, bool fused);
// linear -> sRGB8 as the fragment output stores it: clamp [0,1] (NaN -> 1), rsqrt approximation, rne.
uint8_t linear_to_srgb8(float x, bool fused);
// The alpha channel of an sRGB fragment output: rne(fl(clamp_nanzero(a) * 255)).
uint8_t srgb_alpha_to_u8(float a);
// linear -> sRGB8 as clears pack it: util_format_linear_float_to_srgb_8unorm (104-bucket table computed at first
// use from Mesa's fitting procedure, linear interpolation inside a bucket).
uint8_t linear_to_srgb8_table(float x);
// The host's RSQRTSS (the approximation lavapipe's JIT uses on this CPU).
float hw_rsqrt(float x);

// IEEE half <-> float.
uint16_t float_to_half_rtz(float f);
float half_to_float(uint16_t h);

// Float depth (already clamped) to the stored bits of a depth buffer.
uint32_t depth_to_stored(float z, DepthFormat f);
// The stored bits of a depth clear value (util_pack_z; NaN packs as 0).
uint32_t pack_clear_depth(DepthFormat f, double z);

// ---- whole texels ------------------------------------------------------------------------------------------------

// A colour texel (or a D16/D32F depth texel, in [0]) as lavapipe's sampler, texel fetch and blend destination read
// return it: missing channels (0, 0, 0, 1). UINT/SINT formats give their integers' bits in the float slots
// (missing alpha: integer 1), as a shader's integer sampler returns them. `fused`: the host fuses fmuladd (sRGB
// decode). Formats without a codec (kind None and no depth) give (0, 0, 0, 0).
void decode_color(const FormatInfo& f, const uint8_t* texel, float rgba[4], bool fused);

// True if decode_color has a codec for the format (a colour codec, or D16/D32F depth).
inline bool can_decode_color(const FormatInfo& f) {
    return f.kind != ChannelKind::None || f.depth == DepthFormat::D16 || f.depth == DepthFormat::D32F;
}
// True for the kinds decode_channels / encode_channels / pack_clear_channels convert (everything but UNORM8,
// sRGB, half and float, whose rules are the ones above).
inline bool uses_channel_codec(const FormatInfo& f) {
    switch (f.kind) {
        case ChannelKind::None:
        case ChannelKind::Unorm8:
        case ChannelKind::Srgb8:
        case ChannelKind::Half:
        case ChannelKind::Float32:
            return false;
        default:
            return true;
    }
}

// A fragment's colour stored as lavapipe's fragment output does (channels whose bit c is clear in `mask` keep their
// value; D16/D32F depth from [0], clamped to [0, 1]). For UINT/SINT formats the slots hold the integers' bits.
void encode_color(const FormatInfo& f, const float rgba[4], uint8_t* texel, bool fused,
                  UnormPath path = UnormPath::Avx8, uint8_t mask = 0xf);

// A colour clear value packed as util_format_pack_rgba does (UNORM8 float_to_ubyte, sRGB table, half toward
// zero, floats as is). False for formats without a colour codec.
bool pack_clear_color(const FormatInfo& f, const float rgba[4], uint8_t* texel);
inline bool pack_clear_color(Format f, const float rgba[4], uint8_t* texel) {
    return pack_clear_color(format_info(f), rgba, texel);
}

// The four 32-bit words a vertex attribute (or any uncompressed array/packed colour format's texel) fetches to:
// float bits for UNORM/SNORM/SCALED/FLOAT channels, integers for UINT/SINT (missing channels 0, 0, 0 and 1 or 1.0;
// lp_build_fetch_rgba_soa's per-channel conversions).
void fetch_words(const FormatInfo& f, const uint8_t* texel, uint32_t out[4]);
// True for formats whose channels are UINT or SINT (fetch_words gives integers).
bool is_integer(const FormatInfo& f);

// The 8-bit channels of a Unorm8 texel in RGBA order (missing channels 0, 0, 0, 255).
inline void load_unorm8(const FormatInfo& f, const uint8_t* texel, uint8_t rgba[4]) {
    rgba[0] = rgba[1] = rgba[2] = 0;
    rgba[3] = 255;
    for (int i = 0; i < f.channels; ++i) rgba[int(f.channel[i].component)] = texel[f.channel[i].shift / 8];
}
// The inverse, writing only the channels whose bit c is set in `mask`.
inline void store_unorm8(const FormatInfo& f, const uint8_t rgba[4], uint8_t* texel, uint8_t mask = 0xf) {
    for (int i = 0; i < f.channels; ++i) {
        const int c = int(f.channel[i].component);
        if (mask & (1u << c)) texel[f.channel[i].shift / 8] = rgba[c];
    }
}

// ---- normalized and integer formats: lavapipe's integer blend types ------------------------------------------
//
// llvmpipe stores, blends and logic-ops normalized and integer colour formats in an integer "blend type"
// (lp_state_fs.c lp_blend_type_from_format_desc): 8 bits when the widest channel has at most 8, else 16 (else 32
// for integers); signed for SNORM/SINT. The fragment output is converted to it (lp_bld_conv.c lp_build_conv),
// the stored texel is widened to it (convert_to_blend_type: narrow normalized channels by bit replication), and
// the result is narrowed back (convert_from_blend_type: shifts, lavapipe's own rounding) into the texel:
//   float -> UNORM8    float_to_unorm8 (above)
//   float -> UNORM16   max(x, 0) (NaN -> 0), min(., 1), then low16(fl(fl(x*(1-2^-16)) + 128))
//   float -> SNORM8    min(1, x) (NaN stays NaN), cvtps2dq(fl(x*127)) saturated to [-128, 127] (NaN -> -128)
//   float -> SNORM16   max(x, -1) (NaN -> -1), min(., 1), cvtps2dq(fl(x*32767))
//   integers           UINT min(u, 2^n-1), SINT clamped to [-2^(n-1), 2^(n-1)-1] (32-bit: as they are)
//   widening           c << d | c >> (n - d), repeated for 1- and 2-bit channels (5->8, 6->8, 4->8, 10->16, 2->16)
//   narrowing          c >> d where d <= the kept bits (8->5, 8->6, 16->10), 4-bit channels through float, else
//                      ((c >> m) * (2^m-1) + 2^(d-1)) >> d (8->1, 16->2; SNORM without the rounding term)
// B10G11R11_UFLOAT stores through lp_build_float_to_smallfloat (mantissa cut, scaled into the denormal range with
// round-to-nearest-even, clamped to the largest finite value, NaN/+Inf kept, negative -> 0) and decodes through
// lp_build_smallfloat_to_float; E5B9G9R9 decodes as float(m) * 2^(e-24) (lp_build_rgb9e5_to_float).

// The bits of the blend type (8, 16 or 32), 0 for formats that blend in float (sRGB, half, float, B10G11R11).
int blend_type_bits(const FormatInfo& f);
uint16_t float_to_unorm16(float x);
int8_t float_to_snorm8(float x);
int16_t float_to_snorm16(float x);
// One fragment-output channel (a float's bits, or an integer output's bits) in the blend type, zero-extended.
uint32_t output_to_blend_type(const FormatInfo& f, uint32_t word, UnormPath path = UnormPath::Avx8);
// The stored texel's channels widened to the blend type, RGBA order (missing: 0, 0, 0 and the type's maximum).
void load_blend_type(const FormatInfo& f, const uint8_t* texel, uint32_t rgba[4]);
// Every channel of the texel narrowed from the blend type (a channel that keeps its value passes load -> store).
void store_blend_type(const FormatInfo& f, const uint32_t rgba[4], uint8_t* texel);

// The words decode_color gives for a format of the kinds above (fetch_words, plus B10G11R11 and E5B9G9R9).
void decode_channels(const FormatInfo& f, const uint8_t* texel, uint32_t out[4]);
// encode_color for those kinds: `words` are float bits (normalized, float formats) or integers (UINT/SINT).
void encode_channels(const FormatInfo& f, const uint32_t words[4], uint8_t* texel, UnormPath path, uint8_t mask);
// pack_clear_color for those kinds (util_format_pack_rgba: CLAMP then util_iround(x * (2^n-1)) for normalized
// channels other than 8-bit UNORM, which take float_to_ubyte; integers clamped; f32_to_uf11/uf10 and
// float3_to_rgb9e5 for the small floats).
bool pack_clear_channels(const FormatInfo& f, const uint32_t words[4], uint8_t* texel);

// ---- shader image stores (imageStore) ---------------------------------------------------------------------------
//
// A texel written by a shader's imageStore as lavapipe writes it (lp_bld_format_soa.c lp_build_store_rgba_soa,
// lp_build_insert_soa_chan), per channel, from the shader's words (float bits, or integers for UINT/SINT):
//   UNORM n (n <= 16)  clamp(x, 0, 1) (NaN -> 1), then the low n bits of fl(fl(x * (2^n-1)/2^n) + 2^(23-n))
//   SNORM n (n <= 16)  rne(fl(clamp(x, -1, 1) * (2^(n-1)-1))) (NaN -> 2^(n-1)-1), masked to n bits
//   UINT / SINT        unsigned min with 2^n-1 / clamped to [-2^(n-1), 2^(n-1)-1]; 32-bit channels as they are
//   SFLOAT             16-bit float_to_half_rtz (lp_build_float_to_half), 32-bit the float's bits
// The clamps take the upper bound first (lp_build_clamp: MINPS then MAXPS), which sends NaN to the upper bound.
// Loads (imageLoad) decode through decode_color, as texel fetches do (lp_build_fetch_rgba_soa).

// True for the formats store_image_texel encodes: array or packed texels whose channels are all of the kinds above.
bool can_store_image(const FormatInfo& f);
void store_image_texel(const FormatInfo& f, const uint32_t words[4], uint8_t* texel);

}  // namespace tilevk::format
