// Multisample coverage adjustments and resolves, as lavapipe does them.
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
//                    colour output conversion of the destination format (UNORM8: rne(fl(out*255)), half: toward 0);
//                    integer formats copy sample 0
//   clears           util_format_pack_rgba and util_pack_z (format/texel_codec.h)
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
// The pipeline's sample mask as the samples a primitive may cover (rast/render hands it to setup): 0 for a mask
// word of 0 (rasterizer discard), else at 4x the low 4 bits, at 1x sample 0 (the mask is ignored).
uint16_t coverage_sample_mask(uint32_t sample_mask, int samples);
// The same rule on a block's per-sample masks: sample_mask == 0 clears them all; else at 4x sample s is cleared
// unless bit s is set; at 1x they are unchanged.
void apply_sample_mask(uint32_t sample_mask, int samples, uint16_t sample_masks[kMaxSamples]);
// Lanes covered by at least one sample (the fragment shader's execution mask at 4x).
uint16_t any_sample(const uint16_t sample_masks[kMaxSamples]);

// Resolve one pixel from `samples` (4) stored pixels into `out`: each sample decoded as the resolve shader's
// texel fetch does (format::decode_color), summed in sample order, * 0.25, then the destination's fragment output
// conversion (format::encode_color). Verified against lavapipe for RGBA8, R8, RGBA16F, R32F and RGBA8 sRGB
// (decode polynomial -> average -> rsqrt encode, on this CPU). Always returns true.
bool resolve_pixel(ColorFormat f, const uint8_t* const samples[kMaxSamples], uint8_t* out, bool fused);

// Resolve a w x h rectangle. Sample s of pixel (x,y) is at src + s*sample_stride + y*src_pitch + x*pixel_stride,
// pixel_stride 0 meaning the format's texel bytes (sample planes); icd/ images keep a pixel's samples adjacent
// (sample_stride = texel bytes, pixel_stride = 4 * texel bytes).
void resolve_rect(ColorFormat f, const uint8_t* src, size_t sample_stride, size_t src_pitch, uint8_t* dst,
                  size_t dst_pitch, int w, int h, bool fused, size_t pixel_stride = 0);

// Clear values packed as lavapipe packs them (format/texel_codec.h: util_format_pack_rgba, util_pack_z).
using format::pack_clear_color;
using format::pack_clear_depth;

}  // namespace tilevk::rast::fragment
