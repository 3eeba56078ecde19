#include "format/texel_codec.h"

#include "format/texel_bits.h"

#include <algorithm>
#include <cstring>

namespace tilevk::format {

namespace {

inline uint32_t float_bits(float f) {
    return bits::of(f);
}
inline float bits_float(uint32_t u) {
    return bits::to_float(u);
}
inline float fmuladd(float a, float b, float c, bool fused) {
    return fused ? std::fma(a, b, c) : a * b + c;
}
using bits::sse_max;
using bits::sse_min;

// RGBA index of a colour component (R, G, B, A); -1 for depth, stencil and the shared exponent.
inline int rgba_index(Component c) {
    return c <= Component::kA ? int(c) : -1;
}

using bits::extract;
inline uint32_t extract_bits(const uint8_t* texel, uint32_t shift, uint32_t count) {
    return extract(texel, shift, count);
}
using bits::sign_extend;

// util_format_linear_float_to_srgb_8unorm's table (rygorous' scheme, which Mesa generates offline with
// format_srgb.py): 13 exponents x 8 mantissa buckets between 2^-13 and 1; per bucket a least-squares line
// val(t) = a + b*t over the next 8 mantissa bits t, fitted to srgb(x)*255 + 0.5 at every 32nd float of the bucket
// (srgb with the exponent 0.41666666, as Mesa's generator). Entry = (round(a*128) << 16) | round(b*65536).
struct SrgbTable {
    static constexpr int kExponents = 13, kMantissaMsb = 3, kStepShift = 5, kMantShift = 12;
    static constexpr int kBuckets = kExponents << kMantissaMsb;                   // 104
    static constexpr int kBucketSize = (1 << (23 - kMantissaMsb)) >> kStepShift;  // 32768 samples
    uint32_t entry[kBuckets];

    SrgbTable() {
        double sum_aa = kBucketSize, sum_ab = 0.0, sum_bb = 0.0;
        for (int i = 0; i < kBucketSize; ++i) {
            const int j = (i << kStepShift) >> kMantShift;
            sum_ab += j;
            sum_bb += double(j) * j;
        }
        const double inv_det = 1.0 / (sum_aa * sum_bb - sum_ab * sum_ab);
        for (int bucket = 0; bucket < kBuckets; ++bucket) {
            const uint32_t start =
                (uint32_t(127 - kExponents) << 23) + uint32_t(bucket) * uint32_t(kBucketSize << kStepShift);
            double sum_a = 0.0, sum_b = 0.0;
            for (int i = 0; i < kBucketSize; ++i) {
                const int j = (i << kStepShift) >> kMantShift;
                const double x = bits_float(start + (uint32_t(i) << kStepShift));
                const double srgb = x >= 0.0031308 ? 1.055 * std::pow(x, 0.41666666) - 0.055 : 12.92 * x;
                const double val = srgb * 255.0 + 0.5;
                sum_a += val;
                sum_b += j * val;
            }
            const double a = inv_det * (sum_bb * sum_a - sum_ab * sum_b);
            const double b = inv_det * (sum_aa * sum_b - sum_ab * sum_a);
            const uint32_t int_a = uint32_t(int64_t(a * 65536.0 / 512.0 + 0.5));
            const uint32_t int_b = uint32_t(int64_t(b * 65536.0 + 0.5));
            entry[bucket] = (int_a << 16) + int_b;
        }
    }
};

}  // namespace

float unorm_to_float(uint32_t c, int bits) {
    const float scale = float(1.0 / double((1u << bits) - 1u));
    return float(c) * scale;
}

float snorm_to_float(uint32_t raw, int bits) {
    const int32_t s = sign_extend(raw, uint32_t(bits));
    const float scale = float(1.0 / double((1u << (bits - 1)) - 1u));
    const float v = float(s) * scale;
    return v < -1.0f ? -1.0f : v;
}

uint8_t float_to_ubyte(float f) {
    if (!(f > 0.0f)) return 0;  // NaN too
    if (f >= 1.0f) return 255;
    // 32768 + f*255/256 puts round(f*255) in the low mantissa byte (the ulp of 32768.0f is 1/256)
    const float t = f * (255.0f / 256.0f);
    const float u = t + 32768.0f;
    return uint8_t(float_bits(u) & 0xff);
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
#if defined(__x86_64__) || defined(__i386__)
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
    return uint8_t(detail::cvtps2dq(r));  // r is within [0, 255.x] here
}

uint8_t srgb_alpha_to_u8(float a) {
    // clamp_zero_one_nanzero: max(a, 0) with NaN -> 0, then min(., 1); then rne(fl(a*255))
    float c = (a > 0.0f) ? a : 0.0f;
    c = sse_min(c, 1.0f);
    return uint8_t(detail::cvtps2dq(c * 255.0f));
}

uint8_t linear_to_srgb8_table(float x) {
    static const SrgbTable table;
    const uint32_t min_bits = uint32_t(127 - 13) << 23;  // 2^-13 and below (and NaN) map to 0
    const float min_val = bits_float(min_bits);
    const float almost_one = bits_float(0x3f7fffffu);  // 1 - 2^-24 and above map to 255
    if (!(x > min_val)) x = min_val;
    if (x > almost_one) x = almost_one;
    const uint32_t u = float_bits(x);
    const uint32_t tab = table.entry[(u - min_bits) >> 20];
    const uint32_t bias = (tab >> 16) << 9, scale = tab & 0xffffu;
    const uint32_t t = (u >> 12) & 0xffu;  // the next 8 mantissa bits interpolate inside the bucket
    return uint8_t((bias + scale * t) >> 16);
}

uint16_t float_to_half_rtz(float f) {
    const uint32_t u = float_bits(f);
    const uint16_t sign = uint16_t((u >> 16) & 0x8000u);
    const uint32_t exp = (u >> 23) & 0xffu;
    const uint32_t man = u & 0x7fffffu;
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

uint32_t depth_to_stored(float z, DepthFormat f) {
    switch (f) {
        case DepthFormat::D16: {
            // t = fl(z * (1 - 2^-16)); u = fl(t + 2^7); the low 16 mantissa bits are rne(t * 2^16)
            const float t = z * (65535.0f / 65536.0f);
            const float u = t + 128.0f;
            return float_bits(u) & 0xffffu;
        }
        case DepthFormat::X8D24:
            // rne(fl(z * (2^24 - 1)))
            return uint32_t(detail::cvtps2dq(z * 16777215.0f)) & 0xffffffu;
        case DepthFormat::D32F:
            return float_bits(z);
        case DepthFormat::None:
            break;
    }
    return 0;
}

uint32_t pack_clear_depth(DepthFormat f, double z) {
    if (f == DepthFormat::D32F) return float_bits(float(z));
    if (!(z > 0.0)) return 0;  // util_pack_z: z <= 0 -> 0 (NaN reaches lrint there, whose low bits are 0 as well)
    switch (f) {
        case DepthFormat::D16:
            return z >= 1.0 ? 0xffffu : uint32_t(std::lrint(z * 65535.0));
        case DepthFormat::X8D24:
            return z >= 1.0 ? 0xffffffu : uint32_t(std::lrint(z * 16777215.0));
        default:
            return 0;
    }
}

void decode_color(const FormatInfo& f, const uint8_t* p, float rgba[4], bool fused) {
    if (uses_channel_codec(f)) {
        uint32_t w[4];
        decode_channels(f, p, w);
        std::memcpy(rgba, w, sizeof w);
        return;
    }
    rgba[0] = rgba[1] = rgba[2] = 0.0f;
    rgba[3] = 1.0f;
    if (f.kind == ChannelKind::None) {
        uint16_t d16;
        switch (f.depth) {
            case DepthFormat::D16:
                std::memcpy(&d16, p, 2);
                rgba[0] = unorm_to_float(d16, 16);
                return;
            case DepthFormat::D32F:
                std::memcpy(&rgba[0], p, 4);
                return;
            default:  // X8D24 is never sampled (it has no SAMPLED_IMAGE support); no other codec
                rgba[3] = 0.0f;
                return;
        }
    }
    for (int i = 0; i < f.channels; ++i) {
        const int c = rgba_index(f.channel[i].component);
        const uint8_t* q = p + f.channel[i].shift / 8;
        switch (f.kind) {
            case ChannelKind::Unorm8:
                rgba[c] = unorm8_to_float(*q);
                break;
            case ChannelKind::Srgb8:
                rgba[c] = c == 3 ? unorm8_to_float(*q) : srgb8_to_linear(*q, fused);
                break;
            case ChannelKind::Half: {
                uint16_t h;
                std::memcpy(&h, q, 2);
                rgba[c] = half_to_float(h);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(&rgba[c], q, 4);
                break;
            default:  // the other kinds went through decode_channels
                break;
        }
    }
}

namespace {

// Stores the channels of a colour texel whose bit c is set in `mask`; the 8-bit conversions (UNORM8, sRGB RGB,
// sRGB alpha) are the caller's, halves round toward zero and floats are stored as they are in every case.
template <class Unorm8, class SrgbRgb, class SrgbAlpha>
void store_channels(const FormatInfo& f, const float rgba[4], uint8_t* p, uint8_t mask, Unorm8 unorm8, SrgbRgb srgb_rgb,
                    SrgbAlpha srgb_alpha) {
    for (int i = 0; i < f.channels; ++i) {
        const int c = rgba_index(f.channel[i].component);
        if (!(mask & (1u << c))) continue;
        uint8_t* q = p + f.channel[i].shift / 8;
        switch (f.kind) {
            case ChannelKind::Unorm8:
                *q = unorm8(rgba[c]);
                break;
            case ChannelKind::Srgb8:
                *q = c == 3 ? srgb_alpha(rgba[c]) : srgb_rgb(rgba[c]);
                break;
            case ChannelKind::Half: {
                const uint16_t h = float_to_half_rtz(rgba[c]);
                std::memcpy(q, &h, 2);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(q, &rgba[c], 4);
                break;
            default:  // the other kinds go through encode_channels / pack_clear_channels
                break;
        }
    }
}

}  // namespace

void encode_color(const FormatInfo& f, const float rgba[4], uint8_t* p, bool fused, UnormPath path, uint8_t mask) {
    if (uses_channel_codec(f)) {
        uint32_t w[4];
        std::memcpy(w, rgba, sizeof w);
        encode_channels(f, w, p, path, mask);
        return;
    }
    if (f.kind == ChannelKind::None) {
        // depth output clamped to [0,1] (no depth_range_unrestricted), then the depth buffer's store conversion
        const float z = std::clamp(rgba[0], 0.0f, 1.0f);
        if (f.depth == DepthFormat::D16) {
            const uint16_t d = uint16_t(depth_to_stored(z, DepthFormat::D16));
            std::memcpy(p, &d, 2);
        } else if (f.depth == DepthFormat::D32F) {
            std::memcpy(p, &z, 4);
        }
        return;
    }
    store_channels(
        f, rgba, p, mask, [path](float x) { return float_to_unorm8(x, path); },
        [fused](float x) { return linear_to_srgb8(x, fused); }, srgb_alpha_to_u8);
}

bool pack_clear_color(const FormatInfo& f, const float rgba[4], uint8_t* p) {
    if (f.kind == ChannelKind::None) return false;
    if (uses_channel_codec(f)) {
        uint32_t w[4];
        std::memcpy(w, rgba, sizeof w);
        return pack_clear_channels(f, w, p);
    }
    // util_format_pack_rgba: float_to_ubyte for UNORM8 and sRGB alpha, the table encoder for sRGB RGB, halves via
    // _mesa_float_to_float16_rtz
    store_channels(f, rgba, p, 0xf, float_to_ubyte, linear_to_srgb8_table, float_to_ubyte);
    return true;
}

bool is_integer(const FormatInfo& f) {
    return f.channels > 0 && (f.channel[0].numeric == Numeric::kUint || f.channel[0].numeric == Numeric::kSint);
}

void fetch_words(const FormatInfo& f, const uint8_t* texel, uint32_t out[4]) {
    if (f.kind == ChannelKind::Ufloat11 || f.kind == ChannelKind::SharedExp) return decode_channels(f, texel, out);
    const bool integer = is_integer(f);
    out[0] = out[1] = out[2] = 0;
    out[3] = integer ? 1u : float_bits(1.0f);
    for (int i = 0; i < f.channels; ++i) {
        const Channel& ch = f.channel[i];
        const int c = rgba_index(ch.component);
        if (c < 0 || ch.bits > 32) continue;
        // Packed channels go through the same per-channel rules with their own widths (lp_build_extract_soa_chan
        // shifts each channel out of the word, then converts it like any other channel of that width).
        const uint32_t raw = extract_bits(texel, ch.shift, ch.bits);
        switch (ch.numeric) {
            case Numeric::kSfloat:
                out[c] = ch.bits == 16 ? float_bits(half_to_float(uint16_t(raw))) : raw;
                break;
            case Numeric::kUnorm:
                out[c] = float_bits(unorm_to_float(raw, ch.bits));
                break;
            case Numeric::kSnorm:
                out[c] = float_bits(snorm_to_float(raw, ch.bits));
                break;
            case Numeric::kUscaled:
                out[c] = float_bits(float(raw));
                break;
            case Numeric::kSscaled:
                out[c] = float_bits(float(sign_extend(raw, ch.bits)));
                break;
            case Numeric::kUint:
                out[c] = raw;
                break;
            case Numeric::kSint:
                out[c] = uint32_t(sign_extend(raw, ch.bits));
                break;
            case Numeric::kUfloat:  // B10G11R11 / E5B9G9R9 went through decode_channels
            case Numeric::kSrgb:    // sRGB vertex/texel-buffer formats: not supported
                break;
        }
    }
}

}  // namespace tilevk::format
