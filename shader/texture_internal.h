// The address and filter rules shared by texture.cpp (1D, 2D, arrays) and texture_3d.cpp (3D images): one home for
// each rule, in texture.cpp, declared here for the 3D sampler, which applies them to its third axis too.
#pragma once
#include <array>
#include <cstdint>

#include "format/texel_bc.h"
#include "format/texel_codec.h"
#include "shader/program.h"
#include "shader/texture_fixed8.h"

namespace tilevk::shader::tex {

using Vec4 = std::array<float, 4>;
using Bytes = std::array<int32_t, 4>;  // a texel's 8-bit channels in RGBA order (lavapipe's 8-bit filter)

// The extra operands of one lookup.
struct SampleArgs {
    int32_t off_x = 0, off_y = 0;  // constant texel offsets (none on 3D: translate_image.cpp refuses them)
    bool dref = false;             // depth compare against `ref`: each texel becomes 0 or 1 before filtering
    float ref = 0.0f;
    bool three_d = false;  // a 3D view: `r` is the third coordinate (normalized)
    float r = 0.0f;
};

// One axis of a linear footprint: texel indices (offsets included) and the weight of i1.
struct Axis {
    int32_t i0, i1;
    float w;
};

// One level (and layer) of a 1D/2D view as the float filter reads it.
struct Level {
    const format::FormatInfo* fi;
    const uint8_t* base;  // layer already applied
    uint64_t row_pitch;
    int32_t w, h;
    uint32_t bpp;
    uint64_t bytes;  // readable bytes from base
};

Vec4 decode(const format::FormatInfo& f, const uint8_t* p);
bool integer_format(const ImageView& img);
Vec4 texel(const Level& lv, int32_t x, int32_t y);
// Texel (x, y) of one layer of a level (`pitch` bytes per row of texels, or of blocks for compressed formats):
// decoded for the float filter, or as the 8-bit filter's bytes.
Vec4 plane_texel(const format::FormatInfo& f, const uint8_t* plane, uint64_t pitch, int32_t x, int32_t y);
Bytes plane_bytes(const format::FormatInfo& f, const uint8_t* plane, uint64_t pitch, int32_t x, int32_t y);
int32_t floor_index(float u, AddressMode m);
// One level (and layer) of a 1D/2D view through the float filter, nearest or bilinear, offsets, wraps and depth
// compare applied, before the view's swizzle.
Vec4 sample_level(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s, float t,
                  bool linear, bool one_d, const SampleArgs& args);
bool power_of_two(int32_t n);
Axis repeat_npot_axis(float s, int32_t n, int32_t off);
Vec4 border_color(const SamplerState& smp);
Vec4 format_border(const format::FormatInfo& f, const SamplerState& smp);
// The texel index after addressing; -1 means "border".
int32_t wrap(int32_t i, int32_t size, AddressMode m);
// One axis of a nearest lookup: the texel index before the wrap, offset included; `s` normalized, `u` in texels.
int32_t nearest_axis(float s, float u, int32_t n, int32_t off, AddressMode m, bool unnormalized);
// One axis of a linear lookup in lavapipe's float filter (lp_build_sample_wrap_linear): indices before the wrap.
Axis linear_axis(float s, float u, int32_t n, int32_t off, AddressMode m, bool unnormalized);
// One axis of a linear lookup in lavapipe's 8-bit filter (lp_bld_sample_aos.c): final indices, 8-bit weight.
fixed8::Pair axis_fixed8(float s, int32_t n, int32_t off, bool unnormalized, AddressMode m);
// The 8-bit nearest texel index (final) of lavapipe's 8-bit filter (lp_build_sample_wrap_nearest_int).
int32_t nearest_fixed8(float s, float u, int32_t n, int32_t off, AddressMode m, bool unnormalized);
using fixed8::texel_bytes;  // texture_fixed8.h

// One mip level and array layer of a 1D/2D view, nearest or bilinear, through the float or the 8-bit filter
// (texture.cpp); the cube sampler filters a face of a non-seamless cube map with them (texture_cube.cpp).
Vec4 sample_level(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s, float t,
                  bool linear, bool one_d, const SampleArgs& args);
Bytes sample_level_fixed8(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s,
                          float t, bool linear, bool one_d, const SampleArgs& args);

// texture_gather.cpp: OpImageGather / OpImageDrefGather's four texels at level 0 of a 1D/2D view.
Vec4 gather_texels(const ImageView& img, const SamplerState& smp, float s, float t, uint32_t layer, uint32_t comp,
                   const SampleArgs& args);

// texture_3d.cpp: one mip level of a 3D view, nearest or trilinear, through the float or the 8-bit filter.
Vec4 sample_level_3d(const ImageView& img, const SamplerState& smp, uint32_t level, float s, float t, bool linear,
                     const SampleArgs& args);
Bytes sample_level_3d_fixed8(const ImageView& img, const SamplerState& smp, uint32_t level, float s, float t,
                             bool linear, const SampleArgs& args);

}  // namespace tilevk::shader::tex
