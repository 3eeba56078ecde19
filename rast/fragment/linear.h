// llvmpipe's linear shading of one region (lp_linear.c lp_fs_linear_run, lp_linear_interp.c), for the shader
// class tilevk recognises (shader::Program::linear_copy_input: colour = one input, unchanged) with blending off
// and all four channels written: the input is interpolated in 1.15 fixed point from the region's origin and
// truncated to 0.8, then stored as B8G8R8A8 (rast/geometry/README.md, "Linear mode").
#pragma once

#include <cstddef>
#include <cstdint>

#include "rast/fragment/blend.h"

namespace tilevk::rast::fragment {

// A pixel region [x, x+width) x [y, y+height) inside one tile: a rectangle's box clipped to the tile, or the tile.
struct LinearRegion {
    int32_t x = 0, y = 0, width = 0, height = 0;
};

// Planes as setup made them (a0 at pixel (0,0)'s centre, per-pixel steps): `pos` is the position slot (lane 3
// = the 1/w plane), `input` the copied input's plane (perspective ones premultiplied by 1/w). Layout of both:
// a0[4], dadx[4], dady[4].
//
// Returns false, writing nothing, where lp_fs_linear_run fails and llvmpipe falls back to its general shader:
// 1/w not constant (dadx or dady of lane 3 non-zero), or one of the four components outside [0, 1] at one of
// the region's corner pixels. Otherwise writes every pixel of the region:
//   oow = 1/a0.w; perspective inputs (when oow != 1) scale a0, dadx, dady by oow;
//   s0 = fl(a0 + fl(fl(x*dadx) + fl(y*dady)));   start = clamp((unsigned)(s0*32767), 0, 32767)
//   step = clamp((int)(d*32767), -32767, 32767) for dadx and dady
//   pixel (x+i, y+j) = clamp_u8(int16(start + i*stepx + j*stepy) >> 7)   (16-bit wrap-around, arithmetic shift)
// `bgra` points at the target's pixel (0, 0); channel c goes to byte {2, 1, 0, 3}[c]. With blending or a partial
// write mask (`blend`, may be null for "off, RGBA"), the 8-bit colour is blended as llvmpipe's linear variant
// does (lp_build_blend_aos on the 8-bit source, the same 8-bit blend as its general path for UNORM8 targets):
// blend_pixel with the source u/255, which converts back to exactly u.
bool linear_shade_copy(const LinearRegion& r, const float pos[12], const float input[12], bool perspective,
                       uint8_t* bgra, size_t row_pitch, const BlendAttachment* blend = nullptr,
                       const float blend_constants[4] = nullptr);

// The general form: output channel c is interpolated component source[c] of `input` (usage: the components the
// shader reads, the only ones lp_linear_init_interp range-checks), or, for source[c] < 0, the constant
// float_to_ubyte(constant[c]) (lp_bld_nir_aos.c emit_load_const). `input` may be null when no channel reads it.
struct LinearChannels {
    int8_t source[4] = {0, 1, 2, 3};
    float constant[4] = {0, 0, 0, 0};
    uint8_t usage = 0xF;
};
bool linear_shade(const LinearRegion& r, const float pos[12], const float* input, bool perspective,
                  const LinearChannels& ch, uint8_t* bgra, size_t row_pitch, const BlendAttachment* blend = nullptr,
                  const float blend_constants[4] = nullptr);

// The float handed to blend_pixel for the 8-bit colour u: unorm8_to_float(u), whose UNORM8 fragment-output
// conversion (rne(x*255)) is u again (exposed for tests).
float unorm8_source(uint8_t u);

}  // namespace tilevk::rast::fragment
