// Multisample coverage adjustments, resolves and clear-value packing, as lavapipe does them.
//
//   sample mask      a mask word of 0 discards every primitive (llvmpipe's rasterizer_discard, lp_state_derived.c);
//                    otherwise ANDed into each sample's coverage at 4x and IGNORED at 1x (the jit reads it only when
//                    key->multisample): at 1x a mask of 0x2 still draws. Both verified against lavapipe.
//   alpha to coverage on the raw float shader alpha of colour output 0:
//                    1x: a lane survives iff alpha > 0.5;  4x: sample s survives iff alpha > s * 0.25
//                    (unordered compare under DAZ: NaN keeps every sample, a denormal alpha counts as 0;
//                    no dithering)
//   resolve          vkCmdResolveImage and render-pass resolves run u_blitter's MSAA resolve shader:
//                    sum = 0; sum = fl(sum + texel_s) for s = 0..3 in order; out = fl(sum * 0.25f); then the normal
//                    colour output conversion of the destination format (UNORM8: rne(fl(out*255)), half: toward 0)
//   clears           util_format_pack_rgba: UNORM8 float_to_ubyte, sRGB table encoder, floats as is, half toward 0;
//                    depth util_pack_z in double: D16 lrint(z*65535), D24 lrint(z*16777215), D32F (float)z
#pragma once

#include <cstddef>
#include <cstdint>

#include "rast/fragment/block.h"
#include "rast/fragment/color.h"
#include "rast/fragment/depth_stencil.h"

namespace tilevk::rast::fragment {

// 1x alpha to coverage: returns mask with lanes whose alpha is not > 0.5 removed.
uint16_t alpha_to_coverage_1x(const float alpha[kBlockLanes], uint16_t lane_mask);
// 4x: clears sample s of a lane unless alpha > s*0.25. sample_masks[s] is in lane order.
void alpha_to_coverage_4x(const float alpha[kBlockLanes], uint16_t sample_masks[kMaxSamples]);
// sample_mask == 0: all masks cleared. Else at 4x sample_masks[s] &= (bit s ? 0xffff : 0); at 1x unchanged.
void apply_sample_mask(uint32_t sample_mask, int samples, uint16_t sample_masks[kMaxSamples]);
// Lanes covered by at least one sample (the fragment shader's execution mask at 4x).
uint16_t any_sample(const uint16_t sample_masks[kMaxSamples]);

// Decode one stored pixel to float RGBA the way the resolve shader's texel fetch does
// (UNORM8: fl(u * fl(1/255)); sRGB: polynomial; half exact; float as is). Missing channels: 0,0,0,1.
void fetch_texel(ColorFormat f, const uint8_t* px, float rgba[4], bool fused);

// Resolve one pixel from `samples` (4) stored pixels into `out`. Verified against lavapipe for RGBA8, R8, RGBA16F,
// R32F and RGBA8 sRGB (decode polynomial -> average -> rsqrt encode, on this CPU). Always returns true.
bool resolve_pixel(ColorFormat f, const uint8_t* const samples[kMaxSamples], uint8_t* out, bool fused);

// Resolve a w x h rectangle. Sample s of pixel (x,y) is at src + s*sample_stride + y*src_pitch + x*bytes.
void resolve_rect(ColorFormat f, const uint8_t* src, size_t sample_stride, size_t src_pitch, uint8_t* dst,
                  size_t dst_pitch, int w, int h, bool fused);

// Clear colour packed into the stored bytes of one pixel (out must hold format_info(f).bytes). Always true.
// sRGB RGB channels use util_format_linear_float_to_srgb_8unorm (table + linear interpolation), alpha float_to_ubyte.
bool pack_clear_color(ColorFormat f, const float rgba[4], uint8_t* out);
// The sRGB clear encoder alone (exposed for tests).
uint8_t srgb_clear_encode(float x);
// util_pack_z: the stored depth bits of a depth clear value.
uint32_t pack_clear_depth(DepthFormat f, double z);

}  // namespace tilevk::rast::fragment
