#include "rast/fragment/linear.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>

namespace tilevk::rast::fragment {
namespace {

constexpr int kFixed15One = 0x7fff;

// (unsigned)(f * 32767.0f) on x86-64: a 64-bit truncating conversion (cvttss2si r64) whose low 32 bits are kept;
// NaN and out-of-range give 0x8000000000000000 -> 0.
uint32_t to_unsigned(float f) {
    if (!(f > -9.2233720e18f && f < 9.2233720e18f)) return 0;
    return static_cast<uint32_t>(static_cast<int64_t>(f));
}

// (signed)(f * 32767.0f): cvttss2si r32, INT_MIN for NaN and out-of-range.
int32_t to_signed(float f) {
    if (!(f > -2147483904.0f && f < 2147483648.0f)) return INT_MIN;
    return static_cast<int32_t>(f);
}

// float_to_ufixed_1_15 / float_to_sfixed_1_15 (CLAMP on the unsigned / signed value).
int16_t ufixed_1_15(float f) {
    const uint32_t u = to_unsigned(f * float(kFixed15One));
    return static_cast<int16_t>(std::min<uint32_t>(u, kFixed15One));
}
int16_t sfixed_1_15(float f) {
    const int32_t s = to_signed(f * float(kFixed15One));
    return static_cast<int16_t>(std::clamp(s, -kFixed15One, kFixed15One));
}

// u_math.h MIN2..MAX4, operand order kept (NaN picks the same operand as the macros do).
float min2(float a, float b) {
    return a < b ? a : b;
}
float max2(float a, float b) {
    return a > b ? a : b;
}
float min4(float a, float b, float c, float d) {
    return a < b ? (a < c ? min2(a, d) : min2(c, d)) : (b < c ? min2(b, d) : min2(c, d));
}
float max4(float a, float b, float c, float d) {
    return a > b ? (a > c ? max2(a, d) : max2(c, d)) : (b > c ? max2(b, d) : max2(c, d));
}

}  // namespace

float unorm8_source(uint8_t u) {
    return unorm8_to_float(u);
}

bool linear_shade_copy(const LinearRegion& r, const float pos[12], const float input[12], bool perspective,
                       uint8_t* bgra, size_t row_pitch, const BlendAttachment* blend, const float blend_constants[4]) {
    return linear_shade(r, pos, input, perspective, LinearChannels{}, bgra, row_pitch, blend, blend_constants);
}

bool linear_shade(const LinearRegion& r, const float pos[12], const float* input, bool perspective,
                  const LinearChannels& ch, uint8_t* bgra, size_t row_pitch, const BlendAttachment* blend,
                  const float blend_constants[4]) {
    if (pos[4 + 3] != 0.0f || pos[8 + 3] != 0.0f) return false;  // "Require constant w in these rectangles"
    static constexpr float kNoPlane[12] = {};
    const bool interpolated = input && ch.usage != 0;
    const float* plane = interpolated ? input : kNoPlane;
    const float* a0 = plane;
    const float* dadx = plane + 4;
    const float* dady = plane + 8;
    const float oow = 1.0f / pos[3];
    float s0[4], dsdx[4], dsdy[4];
    for (int j = 0; j < 4; ++j) {
        if (perspective && oow != 1.0f) {
            s0[j] = a0[j] * oow;
            dsdx[j] = dadx[j] * oow;
            dsdy[j] = dady[j] * oow;
        } else {
            s0[j] = a0[j];
            dsdx[j] = dadx[j];
            dsdy[j] = dady[j];
        }
    }
    const float fx = static_cast<float>(r.x), fy = static_cast<float>(r.y);
    for (int j = 0; j < 4; ++j) {
        const float tx = fx * dsdx[j];
        const float ty = fy * dsdy[j];
        const float t = tx + ty;
        s0[j] = s0[j] + t;
    }
    int16_t start[4] = {}, stepx[4] = {}, stepy[4] = {};
    const float w1 = static_cast<float>(r.width - 1), h1 = static_cast<float>(r.height - 1);
    for (int j = 0; j < 4; ++j) {
        if (!interpolated || !(ch.usage & (1u << j))) continue;  // usage_mask: unread components stay 0
        // the corners in float, as lp_linear_init_interp checks them (MIN4 < 0.0, MAX4 > 1.0)
        const float a = s0[j];
        const float b = s0[j] + w1 * dsdx[j];
        const float c = s0[j] + h1 * dsdy[j];
        const float d = c + w1 * dsdx[j];
        if (min4(a, b, c, d) < 0.0f) return false;
        if (max4(a, b, c, d) > 1.0f) return false;
        stepx[j] = sfixed_1_15(dsdx[j]);
        stepy[j] = sfixed_1_15(dsdy[j]);
        start[j] = ufixed_1_15(s0[j]);
    }
    static constexpr int kByte[4] = {2, 1, 0, 3};
    uint8_t constant_u8[4];
    for (int c = 0; c < 4; ++c) constant_u8[c] = float_to_ubyte(ch.constant[c]);
    const bool direct = !blend || (!blend->blend_enable && blend->write_mask == 0xF);
    static constexpr float kZero[4] = {0, 0, 0, 0};
    for (int32_t jy = 0; jy < r.height; ++jy) {
        uint8_t* row = bgra + size_t(r.y + jy) * row_pitch + size_t(r.x) * 4;
        uint8_t value[4];
        // 16-bit lanes: the row start advances by stepy per row, pixels by stepx (wrapping like paddw)
        uint16_t v[4];
        for (int c = 0; c < 4; ++c) v[c] = static_cast<uint16_t>(start[c] + jy * stepy[c]);
        for (int32_t ix = 0; ix < r.width; ++ix) {
            uint8_t comp[4];
            for (int c = 0; c < 4; ++c) {
                const int32_t shifted = static_cast<int16_t>(v[c]) >> 7;      // psraw 7
                comp[c] = static_cast<uint8_t>(std::clamp(shifted, 0, 255));  // packuswb
                v[c] = static_cast<uint16_t>(v[c] + static_cast<uint16_t>(stepx[c]));
            }
            for (int c = 0; c < 4; ++c) value[c] = ch.source[c] >= 0 ? comp[ch.source[c] & 3] : constant_u8[c];
            uint8_t* px = row + size_t(ix) * 4;
            if (direct) {
                for (int c = 0; c < 4; ++c) px[kByte[c]] = value[c];
            } else {
                const float src[4] = {unorm8_source(value[0]), unorm8_source(value[1]), unorm8_source(value[2]),
                                      unorm8_source(value[3])};
                blend_pixel(*blend, ColorFormat::B8G8R8A8_UNORM, blend_constants ? blend_constants : kZero, src, px);
            }
        }
    }
    return true;
}

}  // namespace tilevk::rast::fragment
