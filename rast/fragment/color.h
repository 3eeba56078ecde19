// Colour storage formats as the fragment stage sees them: rows of the format table (format/format.h) whose texels
// the texel codec (format/texel_codec.h) converts. The conversions lavapipe uses (fragment output to UNORM8 with
// the AVX or SSE rule, the sRGB polynomial decode and rsqrt encode, half rounded toward zero, the util clear
// packers) live there, once; this header names them for rast/fragment.
#pragma once

#include <cmath>
#include <cstdint>

#include "format/texel_codec.h"

namespace tilevk::rast::fragment {

// A colour attachment's format (a row with a colour codec: ChannelKind other than None).
using ColorFormat = format::Format;
using format::ChannelKind;
using format::format_info;
using format::FormatInfo;
using format::UnormPath;

using format::float_to_half_rtz;
using format::float_to_ubyte;
using format::float_to_unorm8;
using format::half_to_float;
using format::hw_rsqrt;
using format::linear_to_srgb8;
using format::linear_to_srgb8_table;
using format::srgb8_to_linear;
using format::srgb_alpha_to_u8;
using format::unorm8_to_float;

// FTZ (lavapipe runs float blending for 32-bit float and sRGB targets with MXCSR FTZ|DAZ).
inline float flush_denorm(float f) {
    if (f != 0.0f && std::fabs(f) < 0x1p-126f) return std::signbit(f) ? -0.0f : 0.0f;
    return f;
}

}  // namespace tilevk::rast::fragment
