// Packing of clear values into texels, bit-exact with lavapipe (Mesa 22.3.6):
//   vkCmdClearColorImage -> util_pack_color_union -> util_format_pack_rgba:
//     UNORM8  float_to_ubyte: 0 if !(f > 0), 255 if f >= 1, else low byte of bits(fl(f*(255/256)) + 32768.0f)
//     SRGB8   RGB through the bucketed linear->sRGB fit (util_format_linear_float_to_srgb_8unorm), A as UNORM8
//     FLOAT16 IEEE half, rounded toward zero (_mesa_float_to_float16_rtz); FLOAT32 as is
//   depth clears -> util_pack_z(double): D16 = z <= 0 ? 0 : z >= 1 ? 0xffff : lrint(z * 65535.0); D32F = (float)z
#pragma once
#include <cstdint>

#include "formats.h"

namespace tilevk::icd {

uint8_t float_to_ubyte(float f);
uint8_t linear_float_to_srgb8(float x);
uint16_t float_to_half_rtz(float f);
float half_to_float(uint16_t h);

// Writes one texel of `f` (f.texel_bytes bytes) for a colour clear value.
void pack_clear_color(const FormatInfo& f, const VkClearColorValue& value, uint8_t* texel);
// Writes the depth part (D16: 2 bytes, D32F/D32FS8: 4 bytes at offset 0).
void pack_clear_depth(const FormatInfo& f, float depth, uint8_t* texel);

}  // namespace tilevk::icd
