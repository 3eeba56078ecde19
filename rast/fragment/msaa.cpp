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

void apply_sample_mask(uint32_t sample_mask, uint16_t sample_masks[kMaxSamples]) {
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

uint16_t float_to_half_rne(float f) {
    const uint32_t u = float_bits(f);
    const uint16_t sign = uint16_t((u >> 16) & 0x8000u);
    const uint32_t exp = (u >> 23) & 0xffu;
    const uint32_t man = u & 0x7fffffu;
    // NaN as VCVTPS2PH (what _mesa_float_to_half uses on F16C CPUs): quiet, top payload bits kept
    if (exp == 0xff) return uint16_t(sign | (man ? (0x7e00u | (man >> 13)) : 0x7c00u));
    const int e = int(exp) - 127;
    if (exp == 0) return sign;     // float denormals are far below half's range
    uint32_t m = 0x800000u | man;  // 24-bit significand, value = m * 2^(e-23)
    int shift;                     // bits to drop to reach the half's precision
    uint32_t biased;
    if (e >= -14) {
        shift = 13;
        biased = uint32_t(e + 15);
    } else {
        shift = 13 + (-14 - e);
        biased = 0;
        if (shift > 25) return sign;
    }
    uint32_t q = m >> shift;
    const uint32_t rem = m & ((1u << shift) - 1);
    const uint32_t half = 1u << (shift - 1);
    if (rem > half || (rem == half && (q & 1))) ++q;
    uint32_t h;
    if (biased == 0) {
        h = q;  // denormal; a carry into bit 10 yields the smallest normal correctly
    } else {
        // q has the implicit bit at 10; a carry to bit 11 bumps the exponent
        if (q & 0x800u) {
            q >>= 1;
            ++biased;
        }
        if (biased >= 31) return uint16_t(sign | 0x7c00u);
        h = (biased << 10) | (q & 0x3ffu);
    }
    return uint16_t(sign | h);
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
                out[i] = 0;
                break;
            case ChannelKind::Half: {
                const uint16_t h = float_to_half_rne(rgba[c]);
                std::memcpy(out + 2 * i, &h, 2);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(out + 4 * i, &rgba[c], 4);
                break;
        }
    }
    return fi.kind != ChannelKind::Srgb8;
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
