// BC (S3TC / RGTC) block decoding as lavapipe 22.3.6 samples it: llvmpipe decodes a block to 8-bit RGBA with its
// own integer arithmetic (gallivm/lp_bld_format_s3tc.c, the uncached path: lavapipe builds without
// LP_USE_TEXTURE_CACHE), then reads the bytes as an R8G8B8A8 UNORM, sRGB or SNORM texel
// (lp_bld_format_soa.c lp_build_fetch_rgba_soa, the "compressed" branch). The arithmetic, per 8-bit channel:
//
//   565 -> 888        bit replication (c << 3 | c >> 2, g << 2 | g >> 4)
//   BC1 colour 2, 3   four-colour mode (c0 > c1 as 16-bit integers; BC2/BC3 always):
//                       c2 = c0 + (lo16(85 * (c1 - c0)) >> 8), c3 = c0 + ((lo16(85 * (c1 - c0)) >> 7) & 255)
//                     (lp_build_lerp23; sums mod 256), which is 1/3 and 2/3 of the way, rounded its own way;
//                     three-colour mode: c2 = (c0 + c1 + 1) >> 1 (pavgb, rounding up), c3 = 0 (alpha 0 for
//                     BC1_RGBA, 255 for BC1_RGB)
//   BC2 alpha         a4 * 17
//   BC3 alpha, BC4/5  a0 > a1 (signed compare for SNORM): codes 2..7 interpolate with weight
//                     w = lo16(2331 * (code - 1)) >> 6, else codes 2..5 with lo16(3264 * (code - 1)) >> 6, code 6
//                     gives 0 (SNORM -127), code 7 255 (SNORM 127); the lerp is a0 + (lo16((a1 - a0) * w) >> 8)
//                     mod 256 (lp_build_lerpdxta, 16-bit lanes)
//   BC4 / BC5         (r, 0, 0, 255) / (r, g, 0, 255); SNORM (r, 0, 0, 127) / (r, g, 0, 127) as signed bytes
//
// sRGB formats decode their colour through srgb8_to_linear (texel_codec.h); UNORM c * fl(1/255); SNORM
// max(c * fl(1/127), -1). UNORM BC1-5 also take lavapipe's 8-bit filter (util_format_fits_8unorm: S3TC and RGTC
// UNORM, not sRGB, not SNORM), which reads decode_bc_rgba8's bytes.
#pragma once

#include <cstdint>

#include "format/format.h"

namespace tilevk::format {

// True for the BC formats decoded here (BC1-BC5, every variant).
bool is_bc_decoded(const FormatInfo& f);
// True for the BC formats whose texels are signed bytes (BC4_SNORM, BC5_SNORM).
bool is_bc_signed(const FormatInfo& f);
// True for the sRGB BC formats (BC1, BC2, BC3 _SRGB).
bool is_bc_srgb(const FormatInfo& f);

// The channels the format stores, bit c for channel c: BC1_RGB 0x7, BC4 0x1, BC5 0x3, else 0xf. Where the sampler
// reads the border colour, lavapipe replaces only these channels (lp_bld_sample_soa.c lp_build_sample_texel_soa: the
// others keep the format's constants, 0 for colour, 1 for alpha).
uint8_t bc_stored_channels(const FormatInfo& f);

// Texel (i, j) (0..3 each) of the block at `block`, as llvmpipe's decoder leaves it: R, G, B, A bytes (signed
// bytes for the SNORM formats). Formats not decoded here give (0, 0, 0, 0).
void decode_bc_rgba8(const FormatInfo& f, const uint8_t* block, int i, int j, uint8_t rgba[4]);

// The same texel converted as lavapipe's sampler converts it (see above); `fused`: sRGB decode with fmuladd.
void decode_bc_color(const FormatInfo& f, const uint8_t* block, int i, int j, float rgba[4], bool fused);

}  // namespace tilevk::format
