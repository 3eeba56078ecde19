// BC1-BC5 block decoding (texel_bc.h has the rules and their Mesa sources).
#include "format/texel_bc.h"

#include <cstring>

#include "format/texel_codec.h"

namespace tilevk::format {
namespace {

uint32_t load32(const uint8_t* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}
uint64_t load64(const uint8_t* p) {
    uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}

// A 565 colour widened to 8-bit R, G, B by bit replication.
void expand565(uint32_t c, uint8_t out[3]) {
    const uint32_t r = (c >> 11) & 31, g = (c >> 5) & 63, b = c & 31;
    out[0] = uint8_t(r << 3 | r >> 2);
    out[1] = uint8_t(g << 2 | g >> 4);
    out[2] = uint8_t(b << 3 | b >> 2);
}

// lp_build_lerp23 on one channel: 1/3 (`two_thirds` false) or 2/3 of the way from v0 to v1, in 16-bit lanes.
uint8_t lerp23(int v0, int v1, bool two_thirds) {
    const uint32_t mul = uint32_t(85 * (v1 - v0)) & 0xffffu;
    const uint32_t step = two_thirds ? (mul >> 7) & 0xffu : mul >> 8;
    return uint8_t(uint32_t(v0) + step);
}

// The colour half of a BC1/BC2/BC3 block (8 bytes at p); `dxt1`: BC1's three-colour mode and alpha, `alpha_bit`:
// BC1_RGBA (colour 3 of the three-colour mode transparent).
void decode_colour(const uint8_t* p, int texel, bool dxt1, bool rgba_variant, uint8_t out[4]) {
    const uint32_t words = load32(p), codes = load32(p + 4);
    const uint32_t c0 = words & 0xffffu, c1 = words >> 16;
    uint8_t e0[3], e1[3];
    expand565(c0, e0);
    expand565(c1, e1);
    const uint32_t code = (codes >> (2 * texel)) & 3u;
    const bool four = !dxt1 || c0 > c1;
    // alpha: BC2/BC3 fill it later; BC1_RGB is opaque; BC1_RGBA opaque except colour 3 of the three-colour mode
    out[3] = dxt1 ? 255 : 0;
    for (int c = 0; c < 3; ++c) {
        switch (code) {
            case 0:
                out[c] = e0[c];
                break;
            case 1:
                out[c] = e1[c];
                break;
            case 2:
                out[c] = four ? lerp23(e0[c], e1[c], false) : uint8_t((e0[c] + e1[c] + 1) >> 1);
                break;
            default:
                out[c] = four ? lerp23(e0[c], e1[c], true) : 0;
                break;
        }
    }
    if (dxt1 && rgba_variant && !four && code == 3) out[3] = 0;
}

// lp_build_lerpdxta / s3tc_dxt5_alpha_channel: one channel of a BC3 alpha / BC4 / BC5 block (8 bytes at p) as a
// byte; `is_signed`: the endpoints are signed bytes (BC4/BC5 SNORM).
uint8_t decode_alpha(const uint8_t* p, int texel, bool is_signed) {
    const uint64_t bits = load64(p);
    int32_t a0 = int32_t(bits & 0xff), a1 = int32_t((bits >> 8) & 0xff);
    if (is_signed) {
        a0 = int8_t(a0);
        a1 = int8_t(a1);
    }
    const uint32_t code = uint32_t(bits >> (16 + 3 * texel)) & 7u;
    const bool seven = a0 > a1;
    if (code == 0) return uint8_t(a0);
    if (code == 1) return uint8_t(a1);
    if (!seven && code == 6) return is_signed ? uint8_t(int8_t(-127)) : 0;
    if (!seven && code == 7) return is_signed ? 127 : 255;
    // 255*64/7 and 255*64/5 scaled by code - 1, then back by 64, all in 16-bit lanes
    const uint32_t weight = ((uint32_t(seven ? 2331 : 3264) * (code - 1)) & 0xffffu) >> 6;
    const uint32_t delta = uint32_t(a1 - a0) & 0xffffu;
    const uint32_t step = ((delta * weight) & 0xffffu) >> 8;
    return uint8_t(uint32_t(a0) + step);
}

}  // namespace

bool is_bc_decoded(const FormatInfo& f) {
    return f.id >= Format::BC1_RGB_UNORM_BLOCK && f.id <= Format::BC5_SNORM_BLOCK;
}

bool is_bc_signed(const FormatInfo& f) {
    return f.id == Format::BC4_SNORM_BLOCK || f.id == Format::BC5_SNORM_BLOCK;
}

bool is_bc_srgb(const FormatInfo& f) {
    return f.id == Format::BC1_RGB_SRGB_BLOCK || f.id == Format::BC1_RGBA_SRGB_BLOCK ||
           f.id == Format::BC2_SRGB_BLOCK || f.id == Format::BC3_SRGB_BLOCK;
}

uint8_t bc_stored_channels(const FormatInfo& f) {
    switch (f.id) {
        case Format::BC1_RGB_UNORM_BLOCK:
        case Format::BC1_RGB_SRGB_BLOCK:
            return 0x7;
        case Format::BC4_UNORM_BLOCK:
        case Format::BC4_SNORM_BLOCK:
            return 0x1;
        case Format::BC5_UNORM_BLOCK:
        case Format::BC5_SNORM_BLOCK:
            return 0x3;
        default:
            return 0xf;
    }
}

void decode_bc_rgba8(const FormatInfo& f, const uint8_t* block, int i, int j, uint8_t rgba[4]) {
    const int texel = (j & 3) * 4 + (i & 3);
    rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0;
    switch (f.id) {
        case Format::BC1_RGB_UNORM_BLOCK:
        case Format::BC1_RGB_SRGB_BLOCK:
            decode_colour(block, texel, true, false, rgba);
            break;
        case Format::BC1_RGBA_UNORM_BLOCK:
        case Format::BC1_RGBA_SRGB_BLOCK:
            decode_colour(block, texel, true, true, rgba);
            break;
        case Format::BC2_UNORM_BLOCK:
        case Format::BC2_SRGB_BLOCK: {
            decode_colour(block + 8, texel, false, false, rgba);
            const uint32_t a4 = uint32_t(load64(block) >> (4 * texel)) & 15u;
            rgba[3] = uint8_t(a4 * 17);
            break;
        }
        case Format::BC3_UNORM_BLOCK:
        case Format::BC3_SRGB_BLOCK:
            decode_colour(block + 8, texel, false, false, rgba);
            rgba[3] = decode_alpha(block, texel, false);
            break;
        case Format::BC4_UNORM_BLOCK:
        case Format::BC4_SNORM_BLOCK:
        case Format::BC5_UNORM_BLOCK:
        case Format::BC5_SNORM_BLOCK: {
            const bool sgn = is_bc_signed(f);
            rgba[0] = decode_alpha(block, texel, sgn);
            if (f.id == Format::BC5_UNORM_BLOCK || f.id == Format::BC5_SNORM_BLOCK)
                rgba[1] = decode_alpha(block + 8, texel, sgn);
            rgba[3] = sgn ? 127 : 255;
            break;
        }
        default:
            break;
    }
}

void decode_bc_color(const FormatInfo& f, const uint8_t* block, int i, int j, float rgba[4], bool fused) {
    uint8_t bytes[4];
    decode_bc_rgba8(f, block, i, j, bytes);
    if (!is_bc_decoded(f)) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.0f;
        return;
    }
    // the bytes are read as this RGBA8 texel (lp_build_fetch_rgba_soa's frgba8_desc)
    const Format as = is_bc_signed(f) ? Format::R8G8B8A8_SNORM
                      : is_bc_srgb(f) ? Format::R8G8B8A8_SRGB
                                      : Format::R8G8B8A8_UNORM;
    decode_color(format_info(as), bytes, rgba, fused);
}

}  // namespace tilevk::format
