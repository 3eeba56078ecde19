#include "rast/fragment/msaa.h"

#include <cmath>
#include <cstring>

namespace tilevk::rast::fragment {

namespace {
inline uint32_t float_bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
inline int mem_to_rgba(const FormatInfo& fi, int i) {
    return (fi.bgra && i < 3) ? 2 - i : i;
}
}  // namespace

namespace {
// lp_build_cmp(GREATER) is fcmp ugt under DAZ: NaN passes, a denormal alpha counts as zero.
inline bool ugt_daz(float a, float ref) {
    if (std::isnan(a)) return true;
    if (a != 0.0f && std::fabs(a) < 0x1p-126f) a = 0.0f;
    return a > ref;
}
}  // namespace

uint16_t alpha_to_coverage_1x(const float alpha[kBlockLanes], uint16_t lane_mask) {
    uint16_t out = 0;
    for (int l = 0; l < kBlockLanes; ++l)
        if ((lane_mask & (1u << l)) && ugt_daz(alpha[l], 0.5f)) out |= uint16_t(1u << l);
    return out;
}

void alpha_to_coverage_4x(const float alpha[kBlockLanes], uint16_t sample_masks[kMaxSamples]) {
    for (int s = 0; s < kMaxSamples; ++s) {
        // reference = (float)(1.0/4 * s): 0, 0.25, 0.5, 0.75 exactly
        const float ref = float(0.25 * s);
        uint16_t keep = 0;
        for (int l = 0; l < kBlockLanes; ++l)
            if (ugt_daz(alpha[l], ref)) keep |= uint16_t(1u << l);
        sample_masks[s] &= keep;
    }
}

void apply_sample_mask(uint32_t sample_mask, int samples, uint16_t sample_masks[kMaxSamples]) {
    if (sample_mask == 0) {  // rasterizer discard
        for (int s = 0; s < kMaxSamples; ++s) sample_masks[s] = 0;
        return;
    }
    if (samples <= 1) return;  // ignored at 1x
    for (int s = 0; s < kMaxSamples; ++s)
        if (!(sample_mask & (1u << s))) sample_masks[s] = 0;
}

uint16_t any_sample(const uint16_t sample_masks[kMaxSamples]) {
    return uint16_t(sample_masks[0] | sample_masks[1] | sample_masks[2] | sample_masks[3]);
}

void fetch_texel(ColorFormat f, const uint8_t* px, float rgba[4], bool fused) {
    const FormatInfo fi = format_info(f);
    rgba[0] = rgba[1] = rgba[2] = 0.0f;
    rgba[3] = 1.0f;
    for (int i = 0; i < fi.channels; ++i) {
        const int c = mem_to_rgba(fi, i);
        switch (fi.kind) {
            case ChannelKind::Unorm8:
                rgba[c] = unorm8_to_float(px[i]);
                break;
            case ChannelKind::Srgb8:
                rgba[c] = c == 3 ? unorm8_to_float(px[i]) : srgb8_to_linear(px[i], fused);
                break;
            case ChannelKind::Half: {
                uint16_t h;
                std::memcpy(&h, px + 2 * i, 2);
                rgba[c] = half_to_float(h);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(&rgba[c], px + 4 * i, 4);
                break;
        }
    }
}

bool resolve_pixel(ColorFormat f, const uint8_t* const samples[kMaxSamples], uint8_t* out, bool fused) {
    const FormatInfo fi = format_info(f);
    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int s = 0; s < kMaxSamples; ++s) {
        float t[4];
        fetch_texel(f, samples[s], t, fused);
        for (int c = 0; c < 4; ++c) sum[c] = sum[c] + t[c];  // fl(sum + texel), sample order
    }
    float avg[4];
    for (int c = 0; c < 4; ++c) avg[c] = sum[c] * 0.25f;
    for (int i = 0; i < fi.channels; ++i) {
        const int c = mem_to_rgba(fi, i);
        switch (fi.kind) {
            case ChannelKind::Unorm8:
                out[i] = float_to_unorm8(avg[c]);
                break;
            case ChannelKind::Srgb8:
                out[i] = c == 3 ? srgb_alpha_to_u8(avg[c]) : linear_to_srgb8(avg[c], fused);
                break;
            case ChannelKind::Half: {
                const uint16_t h = float_to_half_rz(avg[c]);
                std::memcpy(out + 2 * i, &h, 2);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(out + 4 * i, &avg[c], 4);
                break;
        }
    }
    return true;
}

void resolve_rect(ColorFormat f, const uint8_t* src, size_t sample_stride, size_t src_pitch, uint8_t* dst,
                  size_t dst_pitch, int w, int h, bool fused) {
    const size_t bpp = format_info(f).bytes;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const uint8_t* base = src + size_t(y) * src_pitch + size_t(x) * bpp;
            const uint8_t* s[kMaxSamples] = {base, base + sample_stride, base + 2 * sample_stride,
                                             base + 3 * sample_stride};
            resolve_pixel(f, s, dst + size_t(y) * dst_pitch + size_t(x) * bpp, fused);
        }
    }
}

namespace {

// util_format_linear_float_to_srgb_8unorm's 104-entry table: per bucket (13 exponents x 8 mantissa-top values) a
// least-squares line through srgb(x)*255 + 0.5 over every 32nd float of the bucket, as (bias << 16) | scale.
// Mesa generates it offline (format_srgb.py); we recompute it once with the same double arithmetic.
const uint32_t* srgb_clear_table() {
    static const auto table = [] {
        struct T {
            uint32_t v[104];
        } t{};
        const int numexp = 13, mantissa_msb = 3, stepshift = 5, mantshift = 12;
        const int nbuckets = numexp << mantissa_msb;
        const int bucketsize = (1 << (23 - mantissa_msb)) >> stepshift;
        double sum_aa = double(bucketsize), sum_ab = 0.0, sum_bb = 0.0;
        for (int i = 0; i < bucketsize; ++i) {
            const int j = (i << stepshift) >> mantshift;
            sum_ab += j;
            sum_bb += double(j) * j;
        }
        const double inv_det = 1.0 / (sum_aa * sum_bb - sum_ab * sum_ab);
        for (int bucket = 0; bucket < nbuckets; ++bucket) {
            const uint32_t start =
                (uint32_t(127 - numexp) << 23) + uint32_t(bucket) * uint32_t(bucketsize << stepshift);
            double sum_a = 0.0, sum_b = 0.0;
            for (int i = 0; i < bucketsize; ++i) {
                const int j = (i << stepshift) >> mantshift;
                const uint32_t fint = start + uint32_t(i << stepshift);
                float ff;
                std::memcpy(&ff, &fint, 4);
                const double x = ff;
                const double srgb = x >= 0.0031308 ? 1.055 * std::pow(x, 0.41666666) - 0.055 : 12.92 * x;
                const double val = srgb * 255.0 + 0.5;
                sum_a += val;
                sum_b += j * val;
            }
            const double a = inv_det * (sum_bb * sum_a - sum_ab * sum_b);
            const double b = inv_det * (sum_aa * sum_b - sum_ab * sum_a);
            const int int_a = int(a * 65536.0 / 512.0 + 0.5);
            const int int_b = int(b * 65536.0 + 0.5);
            t.v[bucket] = (uint32_t(int_a) << 16) + uint32_t(int_b);
        }
        return t;
    }();
    return table.v;
}

// Clamp to [2^-13, 1 - ulp] (NaN -> 2^-13), look up the bucket, interpolate with the next 8 mantissa bits.
uint8_t linear_to_srgb8_clear(float x) {
    const uint32_t almost_one = 0x3f7fffffu, min_bits = uint32_t(127 - 13) << 23;
    float minval, one;
    std::memcpy(&minval, &min_bits, 4);
    std::memcpy(&one, &almost_one, 4);
    if (!(x > minval)) x = minval;
    if (x > one) x = one;
    const uint32_t u = float_bits(x);
    const uint32_t tab = srgb_clear_table()[(u - min_bits) >> 20];
    const uint32_t bias = (tab >> 16) << 9, scale = tab & 0xffffu;
    const uint32_t t = (u >> 12) & 0xffu;
    return uint8_t((bias + scale * t) >> 16);
}

}  // namespace

uint8_t srgb_clear_encode(float x) {
    return linear_to_srgb8_clear(x);
}

bool pack_clear_color(ColorFormat f, const float rgba[4], uint8_t* out) {
    const FormatInfo fi = format_info(f);
    for (int i = 0; i < fi.channels; ++i) {
        const int c = mem_to_rgba(fi, i);
        switch (fi.kind) {
            case ChannelKind::Unorm8:
                out[i] = float_to_ubyte_clear(rgba[c]);
                break;
            case ChannelKind::Srgb8:
                out[i] = c == 3 ? float_to_ubyte_clear(rgba[c]) : linear_to_srgb8_clear(rgba[c]);
                break;
            case ChannelKind::Half: {
                const uint16_t h = float_to_half_rz(rgba[c]);  // _mesa_float_to_float16_rtz
                std::memcpy(out + 2 * i, &h, 2);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(out + 4 * i, &rgba[c], 4);
                break;
        }
    }
    return true;
}

uint32_t pack_clear_depth(DepthFormat f, double z) {
    if (f == DepthFormat::D32F) return float_bits(float(z));
    if (!(z > 0.0)) return 0;  // util_pack_z: z <= 0 -> 0 (NaN falls through to lrint there; we return 0)
    switch (f) {
        case DepthFormat::D16:
            return z >= 1.0 ? 0xffffu : uint32_t(std::lrint(z * 65535.0));
        case DepthFormat::X8D24:
            return z >= 1.0 ? 0xffffffu : uint32_t(std::lrint(z * 16777215.0));
        default:
            return 0;
    }
}

}  // namespace tilevk::rast::fragment
