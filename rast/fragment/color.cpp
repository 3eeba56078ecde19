#include "rast/fragment/color.h"

#include <cmath>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define TILEVK_HAVE_SSE_RSQRT 1
#else
#define TILEVK_HAVE_SSE_RSQRT 0
#endif

namespace tilevk::rast::fragment {

namespace {
inline uint32_t float_bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
inline float bits_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
inline float fmuladd(float a, float b, float c, bool fused) {
    return fused ? std::fma(a, b, c) : a * b + c;
}
// SSE minps/maxps: the second operand is returned when either is NaN.
inline float sse_min(float a, float b) {
    return a < b ? a : b;
}
inline float sse_max(float a, float b) {
    return a > b ? a : b;
}
// cvtps2dq (round half to even), INT32_MIN for NaN / out of range.
inline int32_t cvtps2dq(float f) {
#if TILEVK_HAVE_SSE_RSQRT
    // The instruction itself (round to nearest even under the default MXCSR; out of range and NaN -> INT32_MIN):
    // the portable form below calls libm's nearbyint, which dominated UNORM8 stores.
    return _mm_cvtss_si32(_mm_set_ss(f));
#else
    if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT32_MIN;
    return int32_t(std::nearbyint(f));
#endif
}
}  // namespace

FormatInfo format_info(ColorFormat f) {
    switch (f) {
        case ColorFormat::R8G8B8A8_UNORM:
            return {4, 4, true, false, ChannelKind::Unorm8};
        case ColorFormat::B8G8R8A8_UNORM:
            return {4, 4, true, true, ChannelKind::Unorm8};
        case ColorFormat::R8G8B8A8_SRGB:
            return {4, 4, true, false, ChannelKind::Srgb8};
        case ColorFormat::B8G8R8A8_SRGB:
            return {4, 4, true, true, ChannelKind::Srgb8};
        case ColorFormat::R8_UNORM:
            return {1, 1, false, false, ChannelKind::Unorm8};
        case ColorFormat::R8G8_UNORM:
            return {2, 2, false, false, ChannelKind::Unorm8};
        case ColorFormat::R16G16B16A16_SFLOAT:
            return {8, 4, true, false, ChannelKind::Half};
        case ColorFormat::R32_SFLOAT:
            return {4, 1, false, false, ChannelKind::Float32};
        case ColorFormat::R32G32_SFLOAT:
            return {8, 2, false, false, ChannelKind::Float32};
        case ColorFormat::R32G32B32A32_SFLOAT:
            return {16, 4, true, false, ChannelKind::Float32};
    }
    return {4, 4, true, false, ChannelKind::Unorm8};
}

float unorm8_to_float(uint8_t u) {
    // fl(float(u) * fl(1/255)): a multiply by the rounded reciprocal, not a division
    const float k = float(1.0 / 255.0);
    return float(u) * k;
}

uint8_t float_to_ubyte_clear(float f) {
    if (!(f > 0.0f)) return 0;
    if (f >= 1.0f) return 255;
    // fl(fl(f * (255/256)) + 32768): the low mantissa byte is the rounded result
    float t = f * (255.0f / 256.0f);
    t = t + 32768.0f;
    return uint8_t(float_bits(t) & 0xff);
}

float srgb8_to_linear(uint8_t u, bool fused) {
    // Coefficients as gallivm builds them: float expressions, then stored as float vectors.
    const float c0 = 0.0023f;
    const float c1 = 0.0030f / 255.0f;
    const float c2 = 0.6935f / (255.0f * 255.0f);
    const float c3 = 0.3012f / (255.0f * 255.0f * 255.0f);
    const float lin_k = 1.0f / (12.6f * 255.0f);
    const float x = float(u);
    const float part_lin = x * lin_k;
    // lp_build_polynomial: x2 = x*x; odd = fmuladd(x2, c3, c1); even = fmuladd(x2, c2, c0); fmuladd(odd, x, even)
    const float x2 = x * x;
    const float odd = fmuladd(x2, c3, c1, fused);
    const float even = fmuladd(x2, c2, c0, fused);
    const float part_pow = fmuladd(odd, x, even, fused);
    return x <= 15.0f ? part_lin : part_pow;
}

float hw_rsqrt(float x) {
#if TILEVK_HAVE_SSE_RSQRT
    return _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
#else
    return 1.0f / std::sqrt(x);  // not bit-exact with lavapipe: no RSQRTPS on this architecture
#endif
}

uint8_t linear_to_srgb8(float x, bool fused) {
    // lp_build_clamp(x, 0, 1) = max(min(x, 1), 0)
    const float src = sse_max(sse_min(x, 1.0f), 0.0f);
    // y = a*x^0.375 + b*x^0.5 + c with x^0.5 = x*rsqrt(x), x^0.375 = rsqrt(rsqrt(x^0.5 * x))
    const float x05 = src * hw_rsqrt(src);
    const float t = x05 * src;
    const float x0375 = hw_rsqrt(hw_rsqrt(t));
    const float a_k = float(double(0.675f) * 1.0622 * double(255.0f));
    const float b_k = float(double(0.325f) * 1.0622 * double(255.0f));
    const float c_k = -0.0620f * 255.0f;
    const float p1 = a_k * x0375;
    const float p2 = fmuladd(b_k, x05, c_k, fused);
    const float pow_final = p1 + p2;
    const float lin = src * (12.92f * 255.0f);
    const float r = src <= 0.0031308f ? lin : pow_final;
    return uint8_t(cvtps2dq(r));  // r is within [0, 255.x] here
}

uint8_t srgb_alpha_to_u8(float a) {
    // clamp_zero_one_nanzero: max(a, 0) with NaN -> 0, then min(., 1); then rne(fl(a*255))
    float c = (a > 0.0f) ? a : 0.0f;
    c = sse_min(c, 1.0f);
    return uint8_t(cvtps2dq(c * 255.0f));
}

uint16_t float_to_half_rz(float f) {
    const uint32_t u = float_bits(f);
    const uint16_t sign = uint16_t((u >> 16) & 0x8000u);
    const uint32_t exp = (u >> 23) & 0xffu;
    uint32_t man = u & 0x7fffffu;
    if (exp == 0xff) {
        if (man == 0) return uint16_t(sign | 0x7c00u);  // Inf
        return uint16_t(sign | 0x7e00u | (man >> 13));  // quiet NaN, top payload bits kept
    }
    const int e = int(exp) - 127;
    if (e > 15) return uint16_t(sign | 0x7bffu);                                   // toward zero: largest finite
    if (e >= -14) return uint16_t(sign | uint32_t((e + 15) << 10) | (man >> 13));  // truncate mantissa
    if (exp == 0) return sign;                                                     // float denormal/zero -> 0
    // half denormal: value = 1.man * 2^e = m * 2^-24 with m = (0x800000 | man) >> (-e - 14 + 13)
    const int shift = -e - 14 + 13;
    if (shift > 24) return sign;
    return uint16_t(sign | ((0x800000u | man) >> shift));
}

float half_to_float(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16;
    const uint32_t exp = (h >> 10) & 0x1fu;
    const uint32_t man = h & 0x3ffu;
    if (exp == 0x1f) {
        if (man == 0) return bits_float(sign | 0x7f800000u);
        return bits_float(sign | 0x7fc00000u | (man << 13));  // VCVTPH2PS quiets signalling NaNs
    }
    if (exp == 0) {
        // denormal or zero: man * 2^-24, exact in float
        const float v = float(man) * 0x1p-24f;
        return sign ? -v : v;
    }
    return bits_float(sign | ((exp + 112u) << 23) | (man << 13));
}

float flush_denorm(float f) {
    if (f != 0.0f && std::fabs(f) < 0x1p-126f) return std::signbit(f) ? -0.0f : 0.0f;
    return f;
}

}  // namespace tilevk::rast::fragment
