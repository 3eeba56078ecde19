// The texel codec for colour formats beyond 8-bit UNORM, sRGB, half and float (texel_codec.h): normalized and integer
// formats through lavapipe's integer blend types, the packed small floats, and their clear packers.
#include <algorithm>
#include <cmath>

#include "format/texel_bits.h"
#include "format/texel_codec.h"

namespace tilevk::format {

namespace {

inline int rgba_index(Component c) {
    return c <= Component::kA ? int(c) : -1;
}

bool is_normalized(Numeric n) {
    return n == Numeric::kUnorm || n == Numeric::kSnorm;
}

// lp_state_fs.c scale_bits, widening (convert_to_blend_type): shift left, then fill the low bits by repeating the
// high ones.
uint32_t scale_up(uint32_t c, int from, int to) {
    const int db = to - from;
    uint32_t r = c << db;
    if (db <= from) {
        r |= c >> (from - db);
    } else {
        for (int n = from; n < to; n *= 2) r |= r >> n;
    }
    return r;
}

// lp_state_fs.c scale_bits, narrowing (convert_from_blend_type). Where the lost bits are no more than the kept ones a
// plain shift (lavapipe: "gives the wrong rounding"), except 4-bit channels, which go through float:
// clamped_float_to_unsigned_norm(unsigned_norm_to_float(c)); otherwise ((c >> to) * (2^to - 1) + half) >> lost, the
// rounding term only for unsigned types. `c` holds the blend type's bits zero-extended.
uint32_t scale_down(uint32_t c, int from, int to, bool is_signed) {
    const int lost = from - to;
    if (lost <= to) {
        if (to == 4) {
            const float x = float(int32_t(c)) * float(1.0 / double((1u << from) - 1u));
            const float t = x * float(15.0 / 16.0);
            return bits::of(t + float(1u << 19)) & 0xfu;
        }
        return c >> lost;
    }
    uint32_t r = (c >> to) * ((1u << to) - 1u);
    if (!is_signed) r += 1u << (lost - 1);
    return r >> lost;
}

// fl(x * 2^-k) for a non-negative finite float x (as bits), rounded to nearest even into the denormal range as
// IEEE arithmetic with denormals enabled does (computed in integers: the caller's MXCSR may flush denormals).
uint32_t scale_down_pow2(uint32_t x, int k) {
    const int e = int(x >> 23);
    if (e == 0) return 0;  // zero (denormal inputs are never passed: their cut mantissa is below the result range)
    const int e2 = e - k;
    if (e2 >= 1) return x - (uint32_t(k) << 23);
    const int shift = 1 - e2;  // significand bits to drop
    if (shift > 24) return 0;
    const uint32_t sig = (x & 0x7fffffu) | 0x800000u;
    uint32_t q = sig >> shift;
    const uint32_t rem = sig & ((1u << shift) - 1u), half = 1u << (shift - 1);
    if (rem > half || (rem == half && (q & 1u))) ++q;
    return q;  // a denormal (or the smallest normal when q rounds up to 2^23)
}

// The float -> smallfloat conversion of lp_bld_format_float.c lp_build_float_to_smallfloat for unsigned formats
// (denormals enabled, as llvmpipe runs it): max(0, x) with the mantissa cut to `mbits`, times 2^(bias-127), clamped
// to the largest finite value; +Inf -> Inf, NaN -> a quiet NaN, -Inf -> 0. Returns the field's bits.
uint32_t float_to_ufloat_bits(float x, int mbits, int ebits) {
    const uint32_t src = bits::of(x);
    const uint32_t small_exp_mask = ((1u << ebits) - 1u) << 23;
    const uint32_t abs = src & 0x7fffffffu;
    const bool is_nan = abs > 0x7f800000u;
    const bool is_inf = src == 0x7f800000u;
    uint32_t r;
    if (is_nan || is_inf) {
        r = small_exp_mask | (is_nan ? 1u << 22 : 0u);
    } else {
        // max.ps(0, x) keeps x's bits unless 0 is greater (negative x, -0 stays -0); the sign is masked off
        const uint32_t clamped = (src >> 31) && abs != 0 ? 0u : src;
        const uint32_t cut = clamped & (~((1u << (23 - mbits)) - 1u) & 0x7fffffffu);
        const uint32_t small_max = (((1u << ebits) - 2u) << 23) | (((1u << mbits) - 1u) << (23 - mbits));
        const int k = 127 - int((1u << (ebits - 1)) - 1u);  // the magic factor is 2^-k
        r = std::min(scale_down_pow2(cut, k), small_max);   // min.ps of non-negative floats: their bits order them
    }
    return (r >> (23 - mbits)) & ((1u << (mbits + ebits)) - 1u);
}

// lp_build_smallfloat_to_float for unsigned formats: denormals as float(m) scaled exactly, Inf/NaN widened with
// their mantissa.
float ufloat_bits_to_float(uint32_t v, int mbits, int ebits) {
    const uint32_t srcabs = (v & ((1u << (mbits + ebits)) - 1u)) << (23 - mbits);
    const uint32_t small_exp_mask = ((1u << ebits) - 1u) << 23;
    if (srcabs < (1u << 23)) {
        const uint32_t magic = (127u - ((1u << (ebits - 1)) - 2u)) << 23;
        return bits::to_float(srcabs | magic) - bits::to_float(magic);
    }
    const uint32_t exp_adj = (127u - ((1u << (ebits - 1)) - 1u)) << 23;
    return bits::to_float((srcabs + exp_adj) | (srcabs >= small_exp_mask ? 0x7f800000u : 0u));
}

// util format_r11g11b10f.h f32_to_uf11 / f32_to_uf10 (the clear packer): truncated mantissa, nothing below
// 2^-14, negative -> 0, +Inf kept, NaN -> a NaN, large values -> the largest finite value.
uint32_t util_float_to_ufloat(float val, int mbits) {
    const uint32_t u = bits::of(val);
    const int exponent = int((u >> 23) & 0xffu) - 127;
    const uint32_t mantissa = u & 0x7fffffu;
    const uint32_t max_exp = 0x1fu << mbits;
    if (exponent == 128) return mantissa ? max_exp | 1u : ((u >> 31) ? 0u : max_exp);
    if (u >> 31) return 0;
    const float largest = mbits == 6 ? 65024.0f : 64512.0f;
    if (val > largest) return (30u << mbits) | ((1u << mbits) - 1u);
    if (exponent > -15) return uint32_t(exponent + 15) << mbits | (mantissa >> (23 - mbits));
    return 0;
}

// util format_rgb9e5.h float3_to_rgb9e5 (the clear packer).
uint32_t util_float3_to_rgb9e5(const float rgb[3]) {
    const float max_rgb9e5 = float(511.0 / 512.0 * double(1 << 16));
    auto clamp_range = [&](float x) {
        const uint32_t f = bits::of(x), m = bits::of(max_rgb9e5);
        return f > 0x7f800000u ? 0u : f >= m ? m : f;
    };
    const uint32_t rc = clamp_range(rgb[0]), gc = clamp_range(rgb[1]), bc = clamp_range(rgb[2]);
    uint32_t maxrgb = std::max({rc, gc, bc});
    maxrgb += maxrgb & (1u << (23 - 9));
    const int exp_shared = std::max(int(maxrgb >> 23), -15 - 1 + 127) + 1 + 15 - 127;
    const uint32_t revdenom = uint32_t(127 - (exp_shared - 15 - 9) + 1) << 23;
    auto mant = [&](uint32_t c) {
        const int m = int(bits::to_float(c) * bits::to_float(revdenom));
        return uint32_t((m & 1) + (m >> 1));
    };
    return uint32_t(exp_shared) << 27 | mant(bc) << 18 | mant(gc) << 9 | mant(rc);
}

// util_iround on x86-64: (int)(f + 0.5f), or (int)(f - 0.5f) below zero.
int32_t util_iround(float f) {
    return f >= 0.0f ? int32_t(f + 0.5f) : int32_t(f - 0.5f);
}

// util_format_pack_rgba for one channel of a normalized or integer format (u_format_pack.py conversion_expr).
uint32_t pack_clear_channel(const Channel& ch, uint32_t word) {
    const float x = bits::to_float(word);
    const uint32_t mask = ch.bits >= 32 ? 0xffffffffu : (1u << ch.bits) - 1u;
    switch (ch.numeric) {
        case Numeric::kUnorm: {
            if (ch.bits == 8) return float_to_ubyte(x);
            const float c = x > 0.0f ? (x > 1.0f ? 1.0f : x) : 0.0f;  // CLAMP: NaN -> 0
            return uint32_t(util_iround(c * float(mask))) & mask;
        }
        case Numeric::kSnorm: {
            const float c = x > -1.0f ? (x > 1.0f ? 1.0f : x) : -1.0f;
            return uint32_t(util_iround(c * float(mask >> 1))) & mask;
        }
        case Numeric::kUint:
            return ch.bits >= 32 ? word : std::min(word, mask);
        case Numeric::kSint: {
            if (ch.bits >= 32) return word;
            const int32_t hi = int32_t(mask >> 1), lo = -hi - 1;
            return uint32_t(std::clamp(int32_t(word), lo, hi)) & mask;
        }
        case Numeric::kSfloat:
            return ch.bits == 16 ? float_to_half_rtz(x) : word;
        default:
            return 0;
    }
}

// lp_bld_format_soa.c lp_build_insert_soa_chan (shader image stores): one channel of a word the shader stored.
uint32_t image_store_channel(const Channel& ch, uint32_t word) {
    const float x = bits::to_float(word);
    const uint32_t mask = ch.bits >= 32 ? 0xffffffffu : (1u << ch.bits) - 1u;
    // lp_build_clamp: min with the upper bound first, then max with the lower (MINPS/MAXPS), so NaN -> hi
    const auto clamp = [](float v, float lo, float hi) { return bits::sse_max(bits::sse_min(v, hi), lo); };
    switch (ch.numeric) {
        case Numeric::kUnorm: {
            // lp_build_clamped_float_to_unsigned_norm for n <= 23 bits: fl(fl(x * (2^n-1)/2^n) + 2^(23-n)), whose
            // low n mantissa bits are rne(x * (2^n-1)); plain mul and add (never fused)
            const float c = clamp(x, 0.0f, 1.0f);
            const float scale = float(double(mask) / double(mask + 1u));
            return bits::of(c * scale + float(1u << (23 - ch.bits))) & mask;
        }
        case Numeric::kSnorm: {
            // fl(clamp(x, -1, 1) * (2^(n-1)-1)), llvm.rint (round half to even), fptosi, masked
            const float c = clamp(x, -1.0f, 1.0f) * float(mask >> 1);
            return uint32_t(int32_t(std::nearbyint(c))) & mask;
        }
        case Numeric::kUint:  // pure integers: unsigned min with the channel's maximum
            return ch.bits >= 32 ? word : std::min(word, mask);
        case Numeric::kSint: {  // clamped to the channel's range below 32 bits, as they are at 32
            if (ch.bits >= 32) return word;
            const int32_t hi = int32_t(mask >> 1), lo = -hi - 1;
            return uint32_t(std::clamp(int32_t(word), lo, hi)) & mask;
        }
        case Numeric::kSfloat:  // lp_build_float_to_half (toward zero) or the float's bits
            return ch.bits == 16 ? float_to_half_rtz(x) : word;
        default:
            return 0;
    }
}

}  // namespace

uint16_t float_to_unorm16(float x) {
    const float c = bits::sse_min(bits::sse_max(x, 0.0f), 1.0f);
    const float t = c * float(65535.0 / 65536.0);
    return uint16_t(bits::of(t + 128.0f) & 0xffffu);
}

int8_t float_to_snorm8(float x) {
    const float c = bits::sse_min(1.0f, x);
    return int8_t(std::clamp(detail::cvtps2dq(c * 127.0f), -128, 127));
}

int16_t float_to_snorm16(float x) {
    const float c = bits::sse_min(bits::sse_max(x, -1.0f), 1.0f);
    return int16_t(detail::cvtps2dq(c * 32767.0f));
}

int blend_type_bits(const FormatInfo& f) {
    int widest = 0;
    for (int i = 0; i < f.channels; ++i) widest = std::max(widest, int(f.channel[i].bits));
    switch (f.kind) {
        case ChannelKind::Unorm8:
        case ChannelKind::Snorm8:
            return 8;
        case ChannelKind::Unorm16:
        case ChannelKind::Snorm16:
            return 16;
        case ChannelKind::PackedUnorm:
        case ChannelKind::PackedSnorm:
        case ChannelKind::Uint:
        case ChannelKind::Sint:
            return widest <= 8 ? 8 : widest <= 16 ? 16 : 32;
        default:
            return 0;
    }
}

uint32_t output_to_blend_type(const FormatInfo& f, uint32_t word, UnormPath path) {
    const int n = blend_type_bits(f);
    const float x = bits::to_float(word);
    switch (f.kind) {
        case ChannelKind::Unorm8:
        case ChannelKind::Unorm16:
        case ChannelKind::PackedUnorm:
            return n == 8 ? float_to_unorm8(x, path) : float_to_unorm16(x);
        case ChannelKind::Snorm8:
        case ChannelKind::Snorm16:
        case ChannelKind::PackedSnorm:
            return n == 8 ? uint8_t(float_to_snorm8(x)) : uint16_t(float_to_snorm16(x));
        case ChannelKind::Uint:
            return n == 32 ? word : std::min(word, (1u << n) - 1u);
        case ChannelKind::Sint: {
            if (n == 32) return word;
            const int32_t hi = (1 << (n - 1)) - 1;
            return uint32_t(std::clamp(int32_t(word), -hi - 1, hi)) & ((1u << n) - 1u);
        }
        default:
            return 0;
    }
}

void load_blend_type(const FormatInfo& f, const uint8_t* texel, uint32_t rgba[4]) {
    const int n = blend_type_bits(f);
    const uint32_t one = n >= 32 ? 0xffffffffu : (1u << n) - 1u;
    rgba[0] = rgba[1] = rgba[2] = 0;
    rgba[3] = one;
    for (int i = 0; i < f.channels; ++i) {
        const Channel& ch = f.channel[i];
        const int c = rgba_index(ch.component);
        if (c < 0) continue;
        const uint32_t raw = bits::extract(texel, ch.shift, ch.bits);
        rgba[c] = is_normalized(ch.numeric) && ch.bits < n ? scale_up(raw, ch.bits, n) : raw;
    }
}

void store_blend_type(const FormatInfo& f, const uint32_t rgba[4], uint8_t* texel) {
    const int n = blend_type_bits(f);
    for (int i = 0; i < f.channels; ++i) {
        const Channel& ch = f.channel[i];
        const int c = rgba_index(ch.component);
        if (c < 0) continue;
        uint32_t v = rgba[c];
        if (ch.bits < n) {
            if (is_normalized(ch.numeric)) {
                v = scale_down(v, n, ch.bits, ch.numeric == Numeric::kSnorm);
            } else {
                v = std::min(v, (1u << ch.bits) - 1u);  // integers: an unsigned clamp to the channel
            }
        }
        bits::insert(texel, ch.shift, ch.bits, v);
    }
}

void decode_channels(const FormatInfo& f, const uint8_t* texel, uint32_t out[4]) {
    if (f.kind == ChannelKind::Ufloat11) {
        const uint32_t v = bits::extract(texel, 0, 32);
        out[0] = bits::of(ufloat_bits_to_float(v, 6, 5));
        out[1] = bits::of(ufloat_bits_to_float(v >> 11, 6, 5));
        out[2] = bits::of(ufloat_bits_to_float(v >> 22, 5, 5));
        out[3] = bits::of(1.0f);
        return;
    }
    if (f.kind == ChannelKind::SharedExp) {
        // lp_build_rgb9e5_to_float: float(m) * 2^(e - 15 - 9), the scale built as float bits
        const uint32_t v = bits::extract(texel, 0, 32);
        const float scale = bits::to_float(uint32_t(int32_t(v >> 27) + 127 - (15 + 9)) << 23);
        for (int c = 0; c < 3; ++c) out[c] = bits::of(float(int32_t((v >> (9 * c)) & 0x1ffu)) * scale);
        out[3] = bits::of(1.0f);
        return;
    }
    fetch_words(f, texel, out);
}

void encode_channels(const FormatInfo& f, const uint32_t words[4], uint8_t* texel, UnormPath path, uint8_t mask) {
    if (f.kind == ChannelKind::Ufloat11) {
        const float x[3] = {bits::to_float(words[0]), bits::to_float(words[1]), bits::to_float(words[2])};
        uint32_t v = bits::extract(texel, 0, 32);
        const int mb[3] = {6, 6, 5}, sh[3] = {0, 11, 22};
        for (int c = 0; c < 3; ++c) {
            if (!(mask & (1u << c))) continue;
            const uint32_t field = (1u << (mb[c] + 5)) - 1u;
            v = (v & ~(field << sh[c])) | (float_to_ufloat_bits(x[c], mb[c], 5) << sh[c]);
        }
        bits::insert(texel, 0, 32, v);
        return;
    }
    // Normalized and integer formats: the blend type, then narrowed into the texel; channels outside `mask` keep
    // their stored value through the same round trip (lp_build_blend_aos selects the loaded destination).
    uint32_t v[4];
    load_blend_type(f, texel, v);
    for (int c = 0; c < 4; ++c)
        if (mask & (1u << c)) v[c] = output_to_blend_type(f, words[c], path);
    store_blend_type(f, v, texel);
}

bool pack_clear_channels(const FormatInfo& f, const uint32_t words[4], uint8_t* texel) {
    if (f.kind == ChannelKind::Ufloat11) {
        const float x[3] = {bits::to_float(words[0]), bits::to_float(words[1]), bits::to_float(words[2])};
        const uint32_t v = (util_float_to_ufloat(x[0], 6) & 0x7ffu) | (util_float_to_ufloat(x[1], 6) & 0x7ffu) << 11 |
                           (util_float_to_ufloat(x[2], 5) & 0x3ffu) << 22;
        bits::insert(texel, 0, 32, v);
        return true;
    }
    if (f.kind == ChannelKind::SharedExp) {
        const float x[3] = {bits::to_float(words[0]), bits::to_float(words[1]), bits::to_float(words[2])};
        bits::insert(texel, 0, 32, util_float3_to_rgb9e5(x));
        return true;
    }
    for (int i = 0; i < f.channels; ++i) {
        const Channel& ch = f.channel[i];
        const int c = rgba_index(ch.component);
        if (c >= 0) bits::insert(texel, ch.shift, ch.bits, pack_clear_channel(ch, words[c]));
    }
    return true;
}

bool can_store_image(const FormatInfo& f) {
    if ((f.layout != Layout::kArray && f.layout != Layout::kPacked) || f.depth != DepthFormat::None) return false;
    // B10G11R11: lp_build_store_rgba_soa packs it with lp_build_float_to_r11g11b10, the fragment output's conversion
    if (f.kind == ChannelKind::Ufloat11) return true;
    if (f.kind == ChannelKind::None || f.kind == ChannelKind::Srgb8 || f.kind == ChannelKind::SharedExp) return false;
    for (int i = 0; i < f.channels; ++i) {
        const Channel& ch = f.channel[i];
        const bool ok = ((ch.numeric == Numeric::kUnorm || ch.numeric == Numeric::kSnorm) && ch.bits <= 16) ||
                        ch.numeric == Numeric::kUint || ch.numeric == Numeric::kSint ||
                        (ch.numeric == Numeric::kSfloat && (ch.bits == 16 || ch.bits == 32));
        if (!ok || rgba_index(ch.component) < 0) return false;
    }
    return true;
}

void store_image_texel(const FormatInfo& f, const uint32_t words[4], uint8_t* texel) {
    if (f.kind == ChannelKind::Ufloat11) {  // all three fields rewritten, no channel kept (no mask)
        encode_channels(f, words, texel, UnormPath::Avx8, 0x7);
        return;
    }
    for (int i = 0; i < f.channels; ++i) {
        const Channel& ch = f.channel[i];
        bits::insert(texel, ch.shift, ch.bits, image_store_channel(ch, words[rgba_index(ch.component)]));
    }
}

}  // namespace tilevk::format
