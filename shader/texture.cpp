// Image instructions: texture()/textureLod()/textureGrad()/texelFetch()/textureSize()/textureQueryLevels().
// Follows the Vulkan spec's filtering equations in float arithmetic (see README.md for how this differs from
// llvmpipe's fixed-point 8-bit filtering). Every access is bounds-checked; a missing descriptor reads zero. The
// namespace `tex` is not anonymous: texture_3d.cpp shares its address and filter rules (texture_internal.h).
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "format/texel_codec.h"
#include "shader/ir.h"
#include "shader/texture_aniso.h"
#include "shader/texture_cube.h"
#include "shader/texture_fixed8.h"
#include "shader/texture_internal.h"
#include "shader/texture_reduce.h"

namespace tilevk::shader {
namespace tex {

// Texels are converted by the texel codec (format/texel_codec.h): UNORM c * fl(1/(2^n-1)), sRGB llvmpipe's cubic
// polynomial evaluated with fmuladd (fused, as on the FMA hosts this file's other lerps assume), half as VCVTPH2PS,
// D16 c * fl(1/65535) (gallivm's lp_build_unsigned_norm_to_float and lp_build_srgb_to_linear).
Vec4 decode(const format::FormatInfo& f, const uint8_t* p) {
    Vec4 r;
    format::decode_color(f, p, r.data(), true);
    return r;
}

// The view's format returns integers (UINT/SINT): a swizzle's ONE is the integer 1 there (the texel type's one).
bool integer_format(const ImageView& img) {
    return format::is_integer(format::format_info(img.format));
}

// Texel index after addressing; -1 means "border".
int32_t wrap(int32_t i, int32_t size, AddressMode m) {
    switch (m) {
        case AddressMode::Repeat: {
            int32_t r = i % size;
            return r < 0 ? r + size : r;
        }
        case AddressMode::MirroredRepeat: {
            int32_t r = i % (2 * size);
            if (r < 0) r += 2 * size;
            return r >= size ? 2 * size - 1 - r : r;
        }
        case AddressMode::ClampToEdge:
            return std::clamp(i, 0, size - 1);
        case AddressMode::ClampToBorder:
            return i < 0 || i >= size ? -1 : i;
        case AddressMode::MirrorClampToEdge:
            return std::clamp(i >= 0 ? i : -(1 + i), 0, size - 1);
    }
    return 0;
}

// Float texel coordinate -> int without overflow (NaN -> 0).
int32_t safe_floor(float u) {
    if (!(u == u)) return 0;
    u = std::clamp(u, -16777216.0f, 16777216.0f);
    return int32_t(std::floor(u));
}

// gallivm converts texel coordinates with cvttps2dq, which turns a NaN into INT_MIN: CLAMP_TO_BORDER's bounds test
// (lp_build_sample_texel_soa) then takes the border colour, where safe_floor's 0 would read texel 0. The stand-in
// stays negative after any constant offset is added.
constexpr int32_t kNanBorderIndex = INT32_MIN / 2;
int32_t floor_index(float u, AddressMode m) {
    return (m == AddressMode::ClampToBorder && !(u == u)) ? kNanBorderIndex : safe_floor(u);
}

// Block-compressed planes (icd/image.h) hold rows of 4x4 blocks: texel (x, y) is texel (x % 4, y % 4) of block
// (x / 4, y / 4), decoded by format/texel_bc.h.
Vec4 plane_texel(const format::FormatInfo& f, const uint8_t* plane, uint64_t pitch, int32_t x, int32_t y) {
    if (f.layout == format::Layout::kCompressed) {
        Vec4 r;
        const uint8_t* block = plane + uint64_t(y / f.block_height) * pitch + uint64_t(x / f.block_width) * f.bytes;
        format::decode_bc_color(f, block, x % f.block_width, y % f.block_height, r.data(), true);
        return r;
    }
    return decode(f, plane + uint64_t(y) * pitch + uint64_t(x) * f.bytes);
}

Bytes plane_bytes(const format::FormatInfo& f, const uint8_t* plane, uint64_t pitch, int32_t x, int32_t y) {
    if (f.layout == format::Layout::kCompressed) {
        uint8_t c[4];
        const uint8_t* block = plane + uint64_t(y / f.block_height) * pitch + uint64_t(x / f.block_width) * f.bytes;
        format::decode_bc_rgba8(f, block, x % f.block_width, y % f.block_height, c);
        return {c[0], c[1], c[2], c[3]};
    }
    return fixed8::texel_bytes(f, plane + uint64_t(y) * pitch + uint64_t(x) * f.bytes);
}

Vec4 texel(const Level& lv, int32_t x, int32_t y) {
    return plane_texel(*lv.fi, lv.base, lv.row_pitch, x, y);
}

// MIRRORED_REPEAT in lavapipe's float filter (lp_bld_sample_soa.c lp_build_sample_wrap_linear): mirror the
// normalized coordinate first, m = |2(s/2 - round(s/2))|, then u = m*n - 0.5, i0 = max(floor(u), 0),
// i1 = min(floor(u) + 1, n - 1). The returned indices are final (the wrap of fetch() leaves them unchanged).
// The mirrored coordinate m of s + off / n (lp_build_coord_mirror with posOnly; NaN gives 0).
float coord_mirror(float s, int32_t n, int32_t off) {
    if (off) s = s + float(off) / float(n);
    const float h = s * 0.5f, f = h - std::nearbyint(h), m = std::fabs(f + f);
    return m == m ? m : 0.0f;
}

Axis mirror_axis(float s, int32_t n, int32_t off) {
    float u = coord_mirror(s, n, off) * float(n) - 0.5f;
    float fl = std::floor(u);
    int32_t i = safe_floor(u);
    return {std::max(i, 0), std::min(i + 1, n - 1), u - fl};
}

// CLAMP_TO_EDGE in lavapipe's float filter (lp_bld_sample_soa.c lp_build_sample_wrap_linear): on the scaled
// coordinate c (texels), c = min(c + off, n) with a NaN c giving n, then max(c - 0.5, 0); i0 = floor, weight =
// frac, i1 = min(i0 + 1, n - 1). Next to an edge that is texels 0 and 1 with weight 0 (an infinite texel 1 makes
// the lerp NaN), not texel 0 twice.
Axis clamp_edge_axis(float c, int32_t n, int32_t off) {
    if (off) c = c + float(off);
    c = c < float(n) ? c : float(n);
    c = c - 0.5f;
    c = c > 0.0f ? c : 0.0f;
    const float fl = std::floor(c);
    const int32_t i = int32_t(fl);
    return {i, std::min(i + 1, n - 1), c - fl};
}

// MIRROR_CLAMP_TO_EDGE in lavapipe's float filter (lp_bld_sample_soa.c lp_build_sample_wrap_linear): the offset
// joins the texel coordinate, which is folded by |c| and then clamped as CLAMP_TO_EDGE is. A negative coordinate
// therefore blends the same texels as its mirror image with the mirror image's weight (not 1 - w).
Axis mirror_clamp_axis(float u, int32_t n, int32_t off) {
    const float c = off ? u + float(off) : u;
    return clamp_edge_axis(std::fabs(c), n, 0);
}

// MIRROR_CLAMP_TO_EDGE nearest (lp_build_sample_wrap_nearest): trunc(|u + off|) as cvttps2dq (NaN and
// |c| >= 2^31 give INT_MIN), then an unsigned min with n - 1. -1.0 takes texel 1 (floor and mirror would take 0).
int32_t mirror_clamp_nearest(float u, int32_t n, int32_t off) {
    const float c = std::fabs(off ? u + float(off) : u);
    const uint32_t i = c < 2147483648.0f ? uint32_t(int32_t(c)) : 0x80000000u;  // a NaN fails the compare too
    return int32_t(std::min(i, uint32_t(n - 1)));
}

// REPEAT on a level whose size is not a power of two, in lavapipe's float filter (lp_bld_sample_soa.c
// lp_build_coord_repeat_npot_linear): the offset joins the normalized coordinate (off / n), the wrap is its
// fraction, c = fract(s) * n - 0.5; c < 0 or NaN (an unordered compare) takes texel n - 1, else floor(c); the
// second texel is the next one, 0 after n - 1. Near a texel-centre crossover this can pick the texel before the
// one floor(s * n - 0.5) picks, with a weight just below 1.
Axis repeat_npot_axis(float s, int32_t n, int32_t off) {
    if (off) s = s + float(off) / float(n);
    const float f = s - std::floor(s);
    const float c = f * float(n) - 0.5f;
    const float fl = std::floor(c);
    const int32_t i = !(c >= 0.0f) ? n - 1 : int32_t(fl);
    return {i, i != n - 1 ? i + 1 : 0, c - fl};
}

bool power_of_two(int32_t n) {
    return (n & (n - 1)) == 0;
}

// REPEAT nearest on a size that is not a power of two (lp_build_sample_wrap_nearest): the offset joins the
// normalized coordinate, the texel is trunc(min(fract(s + off/n), 1 - 2^-24) * n) (a NaN fraction takes the
// bound: texel n - 1).
int32_t repeat_npot_nearest(float s, int32_t n, int32_t off) {
    if (off) s = s + float(off) / float(n);
    float f = s - std::floor(s);
    f = (f == f) ? std::min(f, 0x1.fffffep-1f) : 0x1.fffffep-1f;
    return std::clamp(int32_t(f * float(n)), 0, n - 1);
}

// nearest (lp_build_sample_wrap_nearest): floor(u) + offset (REPEAT on a power of two, CLAMP_TO_BORDER);
// CLAMP_TO_EDGE truncates u + offset in float (the wrap clamps); MIRRORED_REPEAT truncates m * n of the mirrored
// s + offset / n below n; REPEAT on other sizes: repeat_npot_nearest.
int32_t nearest_axis(float s, float u, int32_t n, int32_t off, AddressMode m, bool unnormalized) {
    if (m == AddressMode::MirrorClampToEdge) return mirror_clamp_nearest(u, n, off);
    if (m == AddressMode::Repeat && !unnormalized && !power_of_two(n)) return repeat_npot_nearest(s, n, off);
    if (m == AddressMode::MirroredRepeat && !unnormalized)
        return std::min(int32_t(coord_mirror(s, n, off) * float(n)), n - 1);
    if (m == AddressMode::ClampToEdge) {
        const float c = off ? u + float(off) : u;
        return c == c ? int32_t(std::clamp(c, -16777216.0f, 16777216.0f)) : 0;  // trunc; the wrap clamps
    }
    return floor_index(u, m) + off;
}

// linear: i0 = floor(u - 0.5), alpha = frac(u - 0.5), unless the address mode has its own rule (above). A NaN
// coordinate on a CLAMP_TO_BORDER axis reads the border with the weight NaN - floor(NaN) = NaN
// (lp_build_ifloor_fract), which the lerps carry into the result.
Axis linear_axis(float s, float u, int32_t n, int32_t off, AddressMode m, bool unnormalized) {
    if (m == AddressMode::MirroredRepeat && !unnormalized) return mirror_axis(s, n, off);
    if (m == AddressMode::ClampToEdge) return clamp_edge_axis(u, n, off);
    if (m == AddressMode::MirrorClampToEdge) return mirror_clamp_axis(u, n, off);
    if (m == AddressMode::Repeat && !unnormalized && !power_of_two(n)) return repeat_npot_axis(s, n, off);
    const float uu = u - 0.5f;
    const int32_t i0 = floor_index(uu, m);
    const float w = (uu == uu) ? uu - std::floor(uu) : m == AddressMode::ClampToBorder ? uu : 0.0f;
    return {i0 + off, i0 + 1 + off, w};
}

Vec4 sample_level(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s, float t,
                  bool linear, bool one_d, const SampleArgs& args) {
    if (args.three_d) return sample_level_3d(img, smp, level, s, t, linear, args);
    const ImageLevel& il = img.level[level];
    Level lv;
    lv.w = int32_t(std::max(1u, img.width >> level));
    lv.h = one_d ? 1 : int32_t(std::max(1u, img.height >> level));
    lv.fi = &format::format_info(img.format);
    lv.bpp = lv.fi->bytes;
    lv.row_pitch = il.row_pitch;
    lv.base = img.base + il.offset + uint64_t(layer) * il.layer_pitch;
    Vec4 border = format_border(*lv.fi, smp);
    // unnormalized: coordinates are already in texels
    float u = smp.unnormalized ? s : s * float(lv.w);
    float v = smp.unnormalized ? t : t * float(lv.h);
    // x, y: texel indices with the constant offsets already added, before the wrap
    auto fetch = [&](int32_t x, int32_t y) -> Vec4 {
        int32_t wx = wrap(x, lv.w, smp.address_u);
        int32_t wy = one_d ? 0 : wrap(y, lv.h, smp.address_v);
        Vec4 c = (wx < 0 || wy < 0) ? border : texel(lv, wx, wy);
        if (args.dref) return {compare_values(smp.compare_op, args.ref, c[0]) ? 1.0f : 0.0f, 0.0f, 0.0f, 1.0f};
        return c;
    };
    if (!linear) {
        return fetch(nearest_axis(s, u, lv.w, args.off_x, smp.address_u, smp.unnormalized),
                     one_d ? 0 : nearest_axis(t, v, lv.h, args.off_y, smp.address_v, smp.unnormalized));
    }
    const Axis ax = linear_axis(s, u, lv.w, args.off_x, smp.address_u, smp.unnormalized);
    const Axis ay = one_d ? Axis{0, 0, 0.0f} : linear_axis(t, v, lv.h, args.off_y, smp.address_v, smp.unnormalized);
    const float a = ax.w, b = ay.w;
    const int32_t i0 = ax.i0, i1 = ax.i1, j0 = ay.i0, j1 = ay.i1;
    Vec4 t00 = fetch(i0, j0), t10 = fetch(i1, j0), t01 = fetch(i0, j1), t11 = fetch(i1, j1);
    Vec4 r;
    // lavapipe's float (SoA) filter: lerp(w, p, q) = fmuladd(w, q - p, p) (fused on FMA hosts), along x, then
    // along y (lp_build_lerp_2d via lp_build_reduce_filter_2d), for every format that reaches it; never the
    // weighted sum of the four texels, which differs in the last bits. MIN / MAX reduce in the same order.
    auto lerp = [](float w, float p, float q) { return std::fma(w, q - p, p); };
    auto reduce = [m = smp.reduction](float w, float p, float q) { return reduce_step(m, w, p, q); };
    if (args.dref) {
        // the compared texels are masks: each row is (m0 ? 1 - a : 0) + (m1 ? a : 0) (lp_build_masklerp2d), then
        // the rows are lerped along y
        auto row = [&](float m0, float m1) { return (m0 != 0.0f ? 1.0f - a : 0.0f) + (m1 != 0.0f ? a : 0.0f); };
        float x0 = row(t00[0], t10[0]);
        r = {one_d ? x0 : lerp(b, x0, row(t01[0], t11[0])), 0.0f, 0.0f, 1.0f};
        return r;
    }
    for (int c = 0; c < 4; ++c) {
        float x0 = reduce(a, t00[c], t10[c]);
        r[c] = one_d ? x0 : reduce(b, x0, reduce(a, t01[c], t11[c]));
    }
    return r;
}

bool simple_wrap(AddressMode m) {
    return m == AddressMode::Repeat || m == AddressMode::ClampToEdge;
}

// lavapipe's choice of the 8-bit fixed-point filter (lp_bld_sample_soa.c use_aos): a format that fits 8-bit UNORM
// (8-bit UNORM, 565, 5551, 4444), no depth compare, REPEAT or CLAMP_TO_EDGE on every used axis.
bool use_fixed8(const ImageView& img, const SamplerState& smp, bool one_d, bool dref) {
    const bool fits = fixed8::fits_8unorm(format::format_info(img.format));
    return fits && !(dref && smp.compare_enable) && simple_wrap(smp.address_u) && (one_d || simple_wrap(smp.address_v));
}

// One axis of the bilinear footprint in 8.8 fixed point (lp_bld_sample_aos.c lp_build_sample_image_linear).
fixed8::Pair axis_fixed8(float s, int32_t n, int32_t off, bool unnormalized, AddressMode m) {
    // normalized: s * float(n*256); unnormalized: s * 256
    float c256 = unnormalized ? s * 256.0f : s * float(n * 256);
    int32_t c = fixed8::coord(c256);
    int32_t i = int32_t(uint32_t(c >> 8) + uint32_t(off));
    if (m == AddressMode::ClampToEdge) return fixed8::wrap_clamp(int32_t(uint32_t(i) << 8) | (c & 255), n);
    if ((n & (n - 1)) == 0) return fixed8::wrap_repeat_pot(i, c & 255, n);
    // the offset joins the float coordinate as off / n before the wrap
    float sf = off ? s + float(off) / float(n) : s;
    return fixed8::wrap_repeat_npot(sf, n);
}

int32_t nearest_fixed8(float s, float u, int32_t n, int32_t off, AddressMode m, bool unnormalized) {
    if (m != AddressMode::Repeat || power_of_two(n) || unnormalized) return wrap(safe_floor(u) + off, n, m);
    return repeat_npot_nearest(s, n, off);
}

// One mip level through the 8-bit path: nearest texels as the float path picks them, linear with 8-bit weights
// and two lerps along x then one along y.
Bytes sample_level_fixed8(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s,
                          float t, bool linear, bool one_d, const SampleArgs& args) {
    if (args.three_d) return sample_level_3d_fixed8(img, smp, level, s, t, linear, args);
    const ImageLevel& il = img.level[level];
    int32_t w = int32_t(std::max(1u, img.width >> level));
    int32_t h = one_d ? 1 : int32_t(std::max(1u, img.height >> level));
    const format::FormatInfo& fi = format::format_info(img.format);
    const uint8_t* base = img.base + il.offset + uint64_t(layer) * il.layer_pitch;
    auto at = [&](int32_t x, int32_t y) { return plane_bytes(fi, base, il.row_pitch, x, y); };
    if (!linear) {
        float u = smp.unnormalized ? s : s * float(w), v = smp.unnormalized ? t : t * float(h);
        int32_t x = nearest_fixed8(s, u, w, args.off_x, smp.address_u, smp.unnormalized);
        int32_t y = one_d ? 0 : nearest_fixed8(t, v, h, args.off_y, smp.address_v, smp.unnormalized);
        return at(x, y);
    }
    fixed8::Pair px = axis_fixed8(s, w, args.off_x, smp.unnormalized, smp.address_u);
    fixed8::Pair py = one_d ? fixed8::Pair{0, 0, 0} : axis_fixed8(t, h, args.off_y, smp.unnormalized, smp.address_v);
    Bytes t00 = at(px.i0, py.i0), t10 = at(px.i1, py.i0);
    Bytes r;
    const Reduction m = smp.reduction;
    if (one_d) {
        for (int c = 0; c < 4; ++c) r[c] = reduce_step8(m, px.w, t00[c], t10[c]);
        return r;
    }
    Bytes t01 = at(px.i0, py.i1), t11 = at(px.i1, py.i1);
    for (int c = 0; c < 4; ++c)
        r[c] = reduce_step8(m, py.w, reduce_step8(m, px.w, t00[c], t10[c]), reduce_step8(m, px.w, t01[c], t11[c]));
    return r;
}

Vec4 bytes_to_float(const Bytes& b) {
    return {format::unorm8_to_float(uint8_t(b[0])), format::unorm8_to_float(uint8_t(b[1])),
            format::unorm8_to_float(uint8_t(b[2])), format::unorm8_to_float(uint8_t(b[3]))};
}

Vec4 swizzled(const Vec4& r, const ImageView& img) {
    const float one = integer_format(img) ? std::bit_cast<float>(1u) : 1.0f;
    Vec4 out;
    for (int c = 0; c < 4; ++c) {
        const uint8_t w = img.swizzle[size_t(c)];
        out[size_t(c)] = w < 4 ? r[w] : w == kSwizzleOne ? one : 0.0f;
    }
    return out;
}

bool image_ok(const ImageView* img) {
    const format::FormatInfo& f = format::format_info(img ? img->format : Format::UNDEFINED);
    return img && img->base && (format::can_decode_color(f) || format::is_bc_decoded(f)) && img->width && img->height &&
           img->levels && img->levels <= kMaxMipLevels && img->layers;
}

// The texel at (x, y, layer) of level lv, swizzled. Outside the level or the view's layers (robustBufferAccess for
// texel buffers): the format's zero texel, (0, 0, 0, 0) with alpha 1 (the integer 1 for integer formats) when the
// format has no alpha, swizzled as a texel (lp_build_fetch_texel's out_of_bound_ret_zero: a format swizzle of
// zeros; docs/lavapipe-rules.md §12).
// A texel fetch; `sample` picks the sample plane of a multisampled view (lp_bld_sample_soa.c
// lp_build_sample_ms_offset: an index below 0 or past the view's sample count is outside, as a coordinate is); a 3D
// view's `layer` is the slice z, inside the level's depth (lp_build_fetch_texel: the minified depth).
Vec4 fetch_at(const ImageView& img, int32_t x, int32_t y, int32_t layer, uint32_t lv, bool one_d, int32_t sample = 0,
              bool three_d = false) {
    const format::FormatInfo& fi = format::format_info(img.format);
    auto outside = [&] {
        Vec4 r{0, 0, 0, 0};
        if (!fi.has_alpha) r[3] = format::is_integer(fi) ? std::bit_cast<float>(1u) : 1.0f;
        return swizzled(r, img);
    };
    if (lv >= img.levels) return outside();
    const int32_t w = int32_t(std::max(1u, img.width >> lv));
    const int32_t h = one_d ? 1 : int32_t(std::max(1u, img.height >> lv));
    const uint32_t layers = three_d ? std::max(1u, img.depth >> lv) : img.layers;
    if (x < 0 || y < 0 || x >= w || y >= h || layer < 0 || uint32_t(layer) >= layers) return outside();
    if (sample < 0 || uint32_t(sample) >= img.samples) return outside();
    const ImageLevel& il = img.level[lv];
    const Vec4 r =
        plane_texel(fi, img.base + il.offset + uint64_t(layer) * il.layer_pitch + uint64_t(sample) * img.sample_pitch,
                    il.row_pitch, x, y);
    return swizzled(r, img);
}

// The level of detail before bias and clamps, in texels of level 0: implicit (per 2x2 quad from its top-left
// lane's differences), from explicit gradients, or the explicit LOD operand.
struct LodInput {
    bool explicit_lod = false, grad = false, one_d = false, three_d = false;
    float lod = 0.0f;                                                  // explicit LOD
    float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0, drdx = 0, drdy = 0;  // derivatives in normalized coordinates
};

float raw_lambda(const ImageView& img, const SamplerState& smp, const LodInput& in) {
    if (smp.unnormalized) return 0.0f;
    if (in.explicit_lod) return in.lod;
    const float w0 = float(img.width), h0 = in.one_d ? 1.0f : float(img.height);
    const float dsdx = in.dsdx * w0, dsdy = in.dsdy * w0, dtdx = in.dtdx * h0, dtdy = in.dtdy * h0;
    // 3D (lp_build_rho, dims 3): the r terms are added last, (s^2 + t^2) + r^2, with r scaled by the depth
    const float d0 = float(img.depth), drdx = in.drdx * d0, drdy = in.drdy * d0;
    float rx2 = dsdx * dsdx + dtdx * dtdx, ry2 = dsdy * dsdy + dtdy * dtdy;
    if (in.three_d) rx2 = rx2 + drdx * drdx, ry2 = ry2 + drdy * drdy;
    if (smp.mipmap_mode == MipmapMode::Linear) {
        // lavapipe (lp_bld_sample.c lp_build_lod_selector, no rho_approx/brilinear):
        // lambda = 0.5 * fast_log2(max(dsdx^2 + dtdx^2, dsdy^2 + dtdy^2)), 1D: rho = max(|dsdx|, |dsdy|)
        float rho2;
        if (in.one_d) {
            const float rho = std::max(std::fabs(dsdx), std::fabs(dsdy));
            rho2 = rho * rho;
        } else {
            rho2 = std::max(rx2, ry2);
        }
        if (in.grad && !std::isfinite(rho2)) rho2 = 0.0f;
        return fixed8::fast_log2(rho2) * 0.5f;
    }
    // rho = max(|d(s,t)/dx|, |d(s,t)/dy|) in texels; lambda = log2(rho)
    const float rx = std::sqrt(rx2), ry = std::sqrt(ry2);
    return std::log2(std::max(rx, ry));
}

// lambda with the sampler's bias and clamps (NaN -> 0).
float final_lambda(const SamplerState& smp, float lambda) {
    if (!smp.unnormalized) lambda += smp.mip_lod_bias;
    if (!(lambda == lambda)) lambda = 0.0f;
    return std::min(std::max(lambda, smp.min_lod), smp.max_lod);
}

// One filtered lookup at a final lambda: level selection (mag / nearest / linear mip), lavapipe's 8-bit path or
// its float path, the view's swizzle (not for depth comparisons).
// The array layer a sampling coordinate selects: rounded to nearest even, clamped to the view's layers, NaN as 0.
uint32_t layer_index(const ImageView& img, float layer_f) {
    return uint32_t(std::nearbyint(std::clamp(layer_f == layer_f ? layer_f : 0.0f, 0.0f, float(img.layers - 1))));
}

Vec4 sample_lambda(const ImageView& img, const SamplerState& smp, float lambda, float s, float t, float layer_f,
                   bool one_d, bool dref, const SampleArgs& args) {
    const bool mag = lambda <= 0.0f;
    const bool linear = (mag ? smp.mag_filter : smp.min_filter) == Filter::Linear;
    const uint32_t max_level = img.levels - 1;
    const uint32_t layer = layer_index(img, layer_f);
    Vec4 r;
    if (integer_format(img) && (smp.min_filter == Filter::Linear || smp.mag_filter == Filter::Linear ||
                                smp.mipmap_mode == MipmapMode::Linear)) {
        // gallivm returns zeros for a linear filter on an integer format (lp_build_sample_soa_code: "impossible
        // filtering"); Vulkan makes such a sampler invalid there
        return {0, 0, 0, 0};
    }
    if (use_fixed8(img, smp, one_d, dref) && (!args.three_d || simple_wrap(smp.address_w))) {
        // lod = lo + frac: levels clamped to the view (frac dropped there), weight trunc(frac*256)
        uint32_t lv = 0, hi = 0;
        int32_t mw = 0;
        if (smp.unnormalized || mag) {
        } else if (smp.mipmap_mode == MipmapMode::Nearest) {
            lv = uint32_t(std::clamp(std::ceil(lambda + 0.5f) - 1.0f, 0.0f, float(max_level)));
        } else {
            const float fl0 = std::floor(lambda);
            if (fl0 >= float(max_level)) {
                lv = max_level;
            } else if (fl0 >= 0.0f) {
                lv = uint32_t(fl0);
                hi = lv + 1;
                mw = fixed8::mip_weight(lambda - fl0);
            }
        }
        Bytes a = sample_level_fixed8(img, smp, lv, layer, s, t, linear, one_d, args);
        if (mw > 0) {
            const Bytes b = sample_level_fixed8(img, smp, hi, layer, s, t, linear, one_d, args);
            // the 8-bit path reduces between levels too (lp_bld_sample_aos.c lp_build_sample_mipmap)
            for (int c = 0; c < 4; ++c) a[c] = reduce_step8(smp.reduction, mw, a[c], b[c]);
        }
        r = bytes_to_float(a);
    } else if (smp.unnormalized || mag) {
        r = sample_level(img, smp, 0, layer, s, t, linear, one_d, args);
    } else if (smp.mipmap_mode == MipmapMode::Nearest) {
        // d = ceil(lambda + 0.5) - 1, clamped to the view's levels
        const float dl = std::ceil(lambda + 0.5f) - 1.0f;
        const uint32_t lv = uint32_t(std::clamp(dl, 0.0f, float(max_level)));
        r = sample_level(img, smp, lv, layer, s, t, linear, one_d, args);
    } else {
        const float fl0 = std::floor(lambda);
        const uint32_t lo = uint32_t(std::clamp(fl0, 0.0f, float(max_level)));
        const uint32_t hi = std::min(lo + 1, max_level);
        const float frac = lambda - fl0;
        Vec4 a = sample_level(img, smp, lo, layer, s, t, linear, one_d, args);
        if (hi != lo && frac > 0.0f) {
            const Vec4 b = sample_level(img, smp, hi, layer, s, t, linear, one_d, args);
            // lp_build_sample_mipmap: lp_build_lerp(frac, level0, level1), a fused multiply-add
            for (int c = 0; c < 4; ++c) a[c] = std::fma(frac, b[c] - a[c], a[c]);
        }
        r = a;
    }
    return dref ? r : swizzled(r, img);  // a depth comparison's result is not remapped
}

// One image instruction's operands: the register file, the descriptor slots and the decoded immediate.
struct ImageOperands {
    const Inst& in;
    uint32_t* R;
    const Descriptor* const* slots;
    uint32_t num_slots;

    uint32_t* reg(uint32_t r) const { return R + size_t(r) * kLanes; }
    float fl(uint32_t r, int l) const { return std::bit_cast<float>(reg(r)[l]); }
    const ImageView* image(int l) const {
        const uint32_t s = reg(in.a)[l] & 0xFFFF;
        return s < num_slots && slots[s] && image_ok(slots[s]->image) ? slots[s]->image : nullptr;
    }
    // storage images: the writable bytes of lane l's image (Descriptor::image_writable), or null
    uint8_t* writable(int l) const {
        const uint32_t s = reg(in.a)[l] & 0xFFFF;
        return s < num_slots && slots[s] ? slots[s]->image_writable : nullptr;
    }
    const SamplerState* sampler(int l) const {
        const uint32_t s = reg(in.a)[l] >> 16;
        return s < num_slots && slots[s] ? slots[s]->sampler : nullptr;
    }
    bool one_d() const { return in.imm & kSample1D; }
    bool three_d() const { return in.imm & kSample3D; }
    bool arrayed() const { return in.imm & kSampleArray; }
    bool dref() const { return in.imm & kSampleDref; }
    bool proj() const { return in.imm & kSampleProj; }
    uint32_t layer_comp() const { return one_d() ? 1 : 2; }
    int32_t off_x() const { return (in.imm & kSampleOffset) ? int32_t(int8_t(uint8_t(in.imm >> 16))) : 0; }
    int32_t off_y() const { return (in.imm & kSampleOffset) ? int32_t(int8_t(uint8_t(in.imm >> 24))) : 0; }
    // register run: coordinates [, q for projection] [, depth reference]
    uint32_t q_reg() const { return in.b + in.extra - 1 - (dref() ? 1 : 0); }
    void write(int l, const Vec4& r) const {
        for (int c = 0; c < 4; ++c) reg(in.d + uint32_t(c))[l] = std::bit_cast<uint32_t>(r[c]);
    }
};

void exec_query_levels(const ImageOperands& op) {
    for (int l = 0; l < kLanes; ++l) {
        const ImageView* img = op.image(l);
        op.reg(op.in.d)[l] = img ? ((op.in.imm & kSampleMs) ? img->samples : img->levels) : 0;
    }
}

void exec_query_size(const ImageOperands& op) {
    const uint32_t* lod = op.reg(op.in.b);
    for (int l = 0; l < kLanes; ++l) {
        const ImageView* img = op.image(l);
        const uint32_t lv = lod[l];
        uint32_t vals[3] = {0, 0, 0};
        if (img && lv < img->levels) {
            vals[0] = std::max(1u, img->width >> lv);
            int k = 1;
            if (!op.one_d()) vals[k++] = std::max(1u, img->height >> lv);
            if (op.three_d()) vals[k++] = std::max(1u, img->depth >> lv);
            // a cube array's size counts cubes (lp_build_size_query_soa)
            if (op.arrayed()) vals[k++] = (op.in.imm & kSampleCube) ? img->layers / 6 : img->layers;
        }
        for (uint32_t c = 0; c < op.in.extra && c < 3; ++c) op.reg(op.in.d + c)[l] = vals[c];
    }
}

void exec_fetch(const ImageOperands& op) {
    const uint32_t* lod = op.reg(op.in.c);
    for (int l = 0; l < kLanes; ++l) {
        const ImageView* img = op.image(l);
        const int32_t x = int32_t(op.reg(op.in.b)[l]) + op.off_x();
        const int32_t y = op.one_d() ? 0 : int32_t(op.reg(op.in.b + 1)[l]) + op.off_y();
        // an array layer, or a 3D view's slice z (its third coordinate)
        const int32_t layer = op.arrayed() || op.three_d() ? int32_t(op.reg(op.in.b + op.layer_comp())[l]) : 0;
        // a multisampled fetch reads level 0 and takes the sample index in place of the LOD
        const bool ms = op.in.imm & kSampleMs;
        op.write(l,
                 img ? fetch_at(*img, x, y, layer, ms ? 0u : lod[l], op.one_d(), ms ? int32_t(lod[l]) : 0, op.three_d())
                     : Vec4{0, 0, 0, 0});
    }
}

// A storage image texel's address, or null outside level 0 of the view or its layers: lp_build_img_op_soa compares
// the coordinates as unsigned (negative ones are outside too) against the view's width, height and layer count.
const uint8_t* storage_texel(const ImageOperands& op, const ImageView& img, int l) {
    const uint32_t x = op.reg(op.in.b)[l], y = op.reg(op.in.b + 1)[l];
    const uint32_t layer = op.arrayed() ? op.reg(op.in.b + 2)[l] : 0u;
    if (x >= img.width || y >= img.height || layer >= img.layers) return nullptr;
    const ImageLevel& il = img.level[0];
    return img.base + il.offset + uint64_t(layer) * il.layer_pitch + uint64_t(y) * il.row_pitch +
           uint64_t(x) * format::format_info(img.format).bytes;
}

// imageLoad: the texel decoded as a texel fetch decodes it (lp_build_fetch_rgba_soa); outside the view (0, 0, 0, 0),
// with alpha 1 (the integer 1 for integer formats) when the format has no alpha channel (lp_build_img_op_soa).
void exec_image_load(const ImageOperands& op) {
    for (int l = 0; l < kLanes; ++l) {
        const ImageView* img = op.image(l);
        Vec4 r{0, 0, 0, 0};
        if (img != nullptr) {
            const format::FormatInfo& fi = format::format_info(img->format);
            if (const uint8_t* p = storage_texel(op, *img, l))
                r = decode(fi, p);
            else if (!fi.has_alpha)
                r[3] = format::is_integer(fi) ? std::bit_cast<float>(1u) : 1.0f;
        }
        op.write(l, r);
    }
}

// imageStore: the lanes of mask d in lane order (the last one wins, as lavapipe's per-lane store loop); nothing
// outside the view, through a descriptor that is not a storage image, or for a format without the store codec.
void exec_image_store(const ImageOperands& op) {
    const uint32_t* mask = op.reg(op.in.d);
    for (int l = 0; l < kLanes; ++l) {
        if (!mask[l]) continue;
        const ImageView* img = op.image(l);
        uint8_t* const out = op.writable(l);
        if (img == nullptr || out == nullptr) continue;
        const format::FormatInfo& fi = format::format_info(img->format);
        const uint8_t* p = storage_texel(op, *img, l);
        if (p == nullptr || !format::can_store_image(fi)) continue;
        const uint32_t words[4] = {op.reg(op.in.c)[l], op.reg(op.in.c + 1)[l], op.reg(op.in.c + 2)[l],
                                   op.reg(op.in.c + 3)[l]};
        format::store_image_texel(fi, words, out + (p - img->base));
    }
}

// The level lane `l` of an anisotropic lookup reads: the explicit LOD or the minor axis's of its quad (the quad's
// implicit differences, lp_build_pmin), biased and clamped. Gathers and single-level views compute none
// (lp_build_sample_common; lavapipe's mipmap mode is never NONE on a view of several levels, lvp_device.c).
uint32_t aniso_lane_level(const ImageOperands& op, const ImageView& img, const SamplerState& smp, const QuadDerivs& d,
                          int l) {
    const Inst& in = op.in;
    if ((in.imm & kSampleGather) || img.levels == 1) return 0;
    float lambda = (in.imm & kSampleExplicitLod) ? op.fl(in.c, l) : aniso_raw_lambda(img, d, smp.max_anisotropy);
    if (!(in.imm & kSampleExplicitLod) && (in.imm & kSampleBias)) lambda += op.fl(in.c, l);
    return aniso_level(img, final_lambda(smp, lambda));
}

QuadDerivs quad_derivs(const float* s, const float* t, int l) {
    const int q = l & ~3;
    QuadDerivs d;
    d.dsdx = s[q + 1] - s[q], d.dtdx = t[q + 1] - t[q];
    d.dsdy = s[q + 2] - s[q], d.dtdy = t[q + 2] - t[q];
    return d;
}

// An anisotropic sampler on a 2D view (lp_bld_sample_soa.c lp_build_sample_general: the anisotropic filter
// replaces every other, gathers included), fed by the quad's implicit differences even beside an explicit LOD or
// gradients. With a LOD per lane (an explicit LOD, a bias or gradients on a view of several levels) lavapipe
// divides the probes' coordinates by the level size of lane 0 of its 8-lane vector in the vector's first half and
// of lane 1 in its second half (lp_build_sample_aniso's swizzle04 / swizzle15 over per-lane sizes); otherwise by
// the lane's own level's.
Vec4 sample_aniso_lane(const ImageOperands& op, const ImageView& img, const SamplerState& smp, const float* s,
                       const float* t, float layer_f, int l, const SampleArgs& args) {
    const Inst& in = op.in;
    if (integer_format(img)) return {0, 0, 0, 0};  // invalid usage: no filtering of integer formats
    const QuadDerivs d = quad_derivs(s, t, l);
    const uint32_t lv = aniso_lane_level(op, img, smp, d, l);
    uint32_t size_lv = lv;
    if (!(in.imm & kSampleGather) && img.levels > 1 && (in.imm & (kSampleExplicitLod | kSampleBias | kSampleGrad))) {
        const int src = (l & ~7) + ((l & 4) ? 1 : 0);
        size_lv = aniso_lane_level(op, img, smp, quad_derivs(s, t, src), src);
    }
    const Vec4 r = sample_aniso(img, smp, lv, size_lv, layer_index(img, layer_f), s[l], t[l], d, args);
    // gathers skip the view's swizzle (lp_build_sample_soa_code), as their component choice replaces it
    return (op.dref() || (in.imm & kSampleGather)) ? r : swizzled(r, img);
}

void exec_sample(const ImageOperands& op) {
    const Inst& in = op.in;
    const bool one_d = op.one_d();
    // coordinates, projected if asked
    const bool three_d = op.three_d();
    float s[kLanes], t[kLanes], r[kLanes], layer_f[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        const float q = op.proj() ? op.fl(op.q_reg(), l) : 1.0f;
        s[l] = op.fl(in.b, l);
        t[l] = one_d ? 0.0f : op.fl(in.b + 1, l);
        r[l] = three_d ? op.fl(in.b + 2, l) : 0.0f;
        layer_f[l] = op.arrayed() ? op.fl(in.b + op.layer_comp(), l) : 0.0f;
        if (op.proj()) {
            s[l] = s[l] / q;
            t[l] = t[l] / q;
            r[l] = r[l] / q;
        }
    }
    for (int l = 0; l < kLanes; ++l) {
        const ImageView* img = op.image(l);
        const SamplerState* smp = op.sampler(l);
        SampleArgs args;
        args.off_x = op.off_x(), args.off_y = op.off_y();
        args.three_d = three_d, args.r = r[l];
        if (op.dref() && smp) {
            args.dref = smp->compare_enable;
            args.ref = op.fl(in.b + in.extra - 1, l);
            if (op.proj()) args.ref = args.ref / op.fl(op.q_reg(), l);
            if (img && img->format == Format::D16_UNORM) args.ref = std::clamp(args.ref, 0.0f, 1.0f);
        }
        if (!img || !smp) {
            op.write(l, {0, 0, 0, 0});
            continue;
        }
        if (smp->max_anisotropy > 1.0f && !one_d && !three_d) {
            op.write(l, sample_aniso_lane(op, *img, *smp, s, t, layer_f[l], l, args));
            continue;
        }
        if (in.imm & kSampleGather) {
            op.write(l, gather_texels(*img, *smp, s[l], t[l], layer_index(*img, layer_f[l]),
                                      (in.imm >> kSampleGatherCompShift) & 3, args));
            continue;
        }
        LodInput lod;
        lod.one_d = one_d;
        lod.three_d = three_d;
        lod.explicit_lod = in.imm & kSampleExplicitLod;
        lod.grad = in.imm & kSampleGrad;
        if (lod.explicit_lod) {
            lod.lod = op.fl(in.c, l);
        } else if (lod.grad) {  // n: dPdx (two components, 3D three), then dPdy
            const uint32_t dy = in.n + (three_d ? 3 : 2);
            lod.dsdx = op.fl(in.n, l), lod.dtdx = op.fl(in.n + 1, l), lod.dsdy = op.fl(dy, l),
            lod.dtdy = op.fl(dy + 1, l);
            if (three_d) lod.drdx = op.fl(in.n + 2, l), lod.drdy = op.fl(dy + 2, l);
        } else {
            // implicit: one LOD per 2x2 quad from the quad's top-left pixel (coarse derivatives)
            const int q = l & ~3;
            lod.dsdx = s[q + 1] - s[q], lod.dtdx = t[q + 1] - t[q];
            lod.dsdy = s[q + 2] - s[q], lod.dtdy = t[q + 2] - t[q];
            lod.drdx = r[q + 1] - r[q], lod.drdy = r[q + 2] - r[q];
        }
        float lambda = raw_lambda(*img, *smp, lod);
        if (!smp->unnormalized && !lod.explicit_lod && (in.imm & kSampleBias)) lambda += op.fl(in.c, l);
        op.write(l,
                 sample_lambda(*img, *smp, final_lambda(*smp, lambda), s[l], t[l], layer_f[l], one_d, op.dref(), args));
    }
}

// Anisotropic filtering is modelled on 2D views only (shader/README.md "Anisotropic filtering"): elsewhere the
// sampler filters as without anisotropy, said once on stderr.
void note_aniso_unmodelled(const ImageOperands& op) {
    static std::atomic<bool> said{false};
    for (int l = 0; l < kLanes; ++l) {
        const SamplerState* smp = op.sampler(l);
        if (smp == nullptr || !(smp->max_anisotropy > 1.0f) || said.exchange(true)) continue;
        std::fprintf(stderr,
                     "tilevk: samplerAnisotropy: a sampler with anisotropyEnable on a 1D, 3D or cube image view "
                     "filters without anisotropy (tilevk models lavapipe's anisotropic filter on 2D views only)\n");
        return;
    }
}

}  // namespace tex

using namespace tex;

void exec_image(const Inst& in, uint32_t* R, const Descriptor* const* slots, uint32_t num_slots) {
    const ImageOperands op{in, R, slots, num_slots};
    switch (in.op) {
        case Op::QueryLevels:
            return exec_query_levels(op);
        case Op::QuerySize:
            return exec_query_size(op);
        case Op::Fetch:
            return exec_fetch(op);
        case Op::ImageLoad:
            return exec_image_load(op);
        case Op::ImageStore:
            return exec_image_store(op);
        default:
            if ((in.imm & (kSampleCube | kSample1D)) || op.three_d()) note_aniso_unmodelled(op);
            if (in.imm & kSampleCube) return cube::exec_sample_cube(in, R, slots, num_slots);
            return exec_sample(op);
    }
}

std::array<float, 4> sample_2d(const ImageView& img, const SamplerState& smp, float s, float t, uint32_t layer) {
    if (!image_ok(&img)) return {0, 0, 0, 0};
    return sample_lambda(img, smp, final_lambda(smp, 0.0f), s, t, float(layer), false, false, SampleArgs{});
}

uint32_t* storage_image_word(const Descriptor* const* slots, uint32_t num_slots, uint32_t handle, uint32_t x,
                             uint32_t y, uint32_t layer) {
    const uint32_t s = handle & 0xFFFF;
    if (s >= num_slots || slots[s] == nullptr || slots[s]->image_writable == nullptr) return nullptr;
    const ImageView* img = slots[s]->image;
    // the formats with STORAGE_IMAGE_ATOMIC (format/support.txt); R32_SFLOAT takes the float atomics
    if (!image_ok(img) ||
        (img->format != Format::R32_UINT && img->format != Format::R32_SINT && img->format != Format::R32_SFLOAT))
        return nullptr;
    if (x >= img->width || y >= img->height || layer >= img->layers) return nullptr;  // unsigned: negative is out
    const ImageLevel& il = img->level[0];
    uint8_t* p = slots[s]->image_writable + il.offset + uint64_t(layer) * il.layer_pitch + uint64_t(y) * il.row_pitch +
                 uint64_t(x) * 4;
    if (reinterpret_cast<uintptr_t>(p) % std::atomic_ref<uint32_t>::required_alignment != 0) return nullptr;
    return reinterpret_cast<uint32_t*>(p);
}

std::array<float, 4> fetch_2d(const ImageView& img, int32_t x, int32_t y, uint32_t layer) {
    if (!image_ok(&img)) return {0, 0, 0, 0};
    return fetch_at(img, x, y, int32_t(layer), 0, false);
}

std::array<float, 4> sample_3d(const ImageView& img, const SamplerState& smp, float s, float t, float r) {
    if (!image_ok(&img)) return {0, 0, 0, 0};
    SampleArgs args;
    args.three_d = true;
    args.r = r;
    return sample_lambda(img, smp, final_lambda(smp, 0.0f), s, t, 0.0f, false, false, args);
}

std::array<float, 4> fetch_3d(const ImageView& img, int32_t x, int32_t y, int32_t z) {
    if (!image_ok(&img)) return {0, 0, 0, 0};
    return fetch_at(img, x, y, z, 0, false, 0, true);
}

// The view rules the cube sampler shares (texture_cube.h).
std::array<float, 4> apply_view_swizzle(const std::array<float, 4>& v, const ImageView& img) {
    return swizzled(v, img);
}

bool view_usable(const ImageView* img) {
    return image_ok(img);
}

}  // namespace tilevk::shader
