// 3D images (sampler3D): one mip level of a 3D view, nearest or trilinear. gallivm samples a 3D texture with the
// code of 2D plus a third axis (lp_bld_sample_soa.c lp_build_sample_image_nearest / _linear with dims == 3,
// lp_bld_sample_aos.c likewise): r is scaled by the level's depth and addressed by the sampler's address mode W
// exactly as s and t are by U and V (the same wrap functions), the texel is at
// x * texel size + y * row pitch + z * slice pitch, and the linear filter lerps the two slices' bilinear results
// along r (lp_build_lerp_3d: lerp(r, lerp_2d(slice z0), lerp_2d(slice z1)), in the float filter with fmuladd, in the
// 8-bit one with its 8-bit lerp). Level selection, bias, clamps and the view's swizzle stay in texture.cpp.
#include <algorithm>
#include <cmath>

#include "shader/texture_internal.h"
#include "shader/texture_reduce.h"

namespace tilevk::shader::tex {

namespace {

// One level of a 3D view: sizes halved per level (depth too, gallivm's lp_build_minify), slices layer_pitch apart.
struct Level3 {
    const format::FormatInfo* fi;
    const uint8_t* base;
    uint64_t row_pitch, slice_pitch;
    int32_t w, h, d;
    float u, v, q;  // the coordinates in texels of this level (unnormalized: as given)
};

Level3 level_3d(const ImageView& img, const SamplerState& smp, uint32_t level, float s, float t, float r) {
    const ImageLevel& il = img.level[level];
    Level3 lv;
    lv.fi = &format::format_info(img.format);
    lv.base = img.base + il.offset;
    lv.row_pitch = il.row_pitch;
    lv.slice_pitch = il.layer_pitch;
    lv.w = int32_t(std::max(1u, img.width >> level));
    lv.h = int32_t(std::max(1u, img.height >> level));
    lv.d = int32_t(std::max(1u, img.depth >> level));
    lv.u = smp.unnormalized ? s : s * float(lv.w);
    lv.v = smp.unnormalized ? t : t * float(lv.h);
    lv.q = smp.unnormalized ? r : r * float(lv.d);
    return lv;
}

const uint8_t* texel_address(const Level3& lv, int32_t x, int32_t y, int32_t z) {
    return lv.base + uint64_t(z) * lv.slice_pitch + uint64_t(y) * lv.row_pitch + uint64_t(x) * lv.fi->bytes;
}

}  // namespace

Vec4 sample_level_3d(const ImageView& img, const SamplerState& smp, uint32_t level, float s, float t, bool linear,
                     const SampleArgs& args) {
    const Level3 lv = level_3d(img, smp, level, s, t, args.r);
    const Vec4 border = format_border(*lv.fi, smp);
    // x, y, z: indices with the offsets added, before the wrap; any axis outside (CLAMP_TO_BORDER) reads the border
    auto fetch = [&](int32_t x, int32_t y, int32_t z) -> Vec4 {
        const int32_t wx = wrap(x, lv.w, smp.address_u), wy = wrap(y, lv.h, smp.address_v);
        const int32_t wz = wrap(z, lv.d, smp.address_w);
        return (wx < 0 || wy < 0 || wz < 0) ? border : decode(*lv.fi, texel_address(lv, wx, wy, wz));
    };
    const bool un = smp.unnormalized;
    if (!linear) {
        return fetch(nearest_axis(s, lv.u, lv.w, args.off_x, smp.address_u, un),
                     nearest_axis(t, lv.v, lv.h, args.off_y, smp.address_v, un),
                     nearest_axis(args.r, lv.q, lv.d, 0, smp.address_w, un));
    }
    const Axis ax = linear_axis(s, lv.u, lv.w, args.off_x, smp.address_u, un);
    const Axis ay = linear_axis(t, lv.v, lv.h, args.off_y, smp.address_v, un);
    const Axis az = linear_axis(args.r, lv.q, lv.d, 0, smp.address_w, un);
    // lavapipe's float filter: fmuladd(w, q - p, p) along x, then y, per slice, then along r between the slices
    // (lp_build_reduce_filter_3d: MIN / MAX in the same order)
    auto lerp = [m = smp.reduction](float w, float p, float q) { return reduce_step(m, w, p, q); };
    Vec4 out;
    const Vec4 a00 = fetch(ax.i0, ay.i0, az.i0), a10 = fetch(ax.i1, ay.i0, az.i0);
    const Vec4 a01 = fetch(ax.i0, ay.i1, az.i0), a11 = fetch(ax.i1, ay.i1, az.i0);
    const Vec4 b00 = fetch(ax.i0, ay.i0, az.i1), b10 = fetch(ax.i1, ay.i0, az.i1);
    const Vec4 b01 = fetch(ax.i0, ay.i1, az.i1), b11 = fetch(ax.i1, ay.i1, az.i1);
    for (size_t c = 0; c < 4; ++c) {
        const float z0 = lerp(ay.w, lerp(ax.w, a00[c], a10[c]), lerp(ax.w, a01[c], a11[c]));
        const float z1 = lerp(ay.w, lerp(ax.w, b00[c], b10[c]), lerp(ax.w, b01[c], b11[c]));
        out[c] = lerp(az.w, z0, z1);
    }
    return out;
}

Bytes sample_level_3d_fixed8(const ImageView& img, const SamplerState& smp, uint32_t level, float s, float t,
                             bool linear, const SampleArgs& args) {
    const Level3 lv = level_3d(img, smp, level, s, t, args.r);
    auto at = [&](int32_t x, int32_t y, int32_t z) { return texel_bytes(*lv.fi, texel_address(lv, x, y, z)); };
    const bool un = smp.unnormalized;
    if (!linear) {
        return at(nearest_fixed8(s, lv.u, lv.w, args.off_x, smp.address_u, un),
                  nearest_fixed8(t, lv.v, lv.h, args.off_y, smp.address_v, un),
                  nearest_fixed8(args.r, lv.q, lv.d, 0, smp.address_w, un));
    }
    const fixed8::Pair px = axis_fixed8(s, lv.w, args.off_x, un, smp.address_u);
    const fixed8::Pair py = axis_fixed8(t, lv.h, args.off_y, un, smp.address_v);
    const fixed8::Pair pz = axis_fixed8(args.r, lv.d, 0, un, smp.address_w);
    // lp_build_lerp_3d on 8-bit values: x, then y within each slice, then r
    const Bytes a00 = at(px.i0, py.i0, pz.i0), a10 = at(px.i1, py.i0, pz.i0);
    const Bytes a01 = at(px.i0, py.i1, pz.i0), a11 = at(px.i1, py.i1, pz.i0);
    const Bytes b00 = at(px.i0, py.i0, pz.i1), b10 = at(px.i1, py.i0, pz.i1);
    const Bytes b01 = at(px.i0, py.i1, pz.i1), b11 = at(px.i1, py.i1, pz.i1);
    Bytes out;
    auto lerp = [m = smp.reduction](int32_t w, int32_t a, int32_t b) { return reduce_step8(m, w, a, b); };
    for (size_t c = 0; c < 4; ++c) {
        const int32_t z0 = lerp(py.w, lerp(px.w, a00[c], a10[c]), lerp(px.w, a01[c], a11[c]));
        const int32_t z1 = lerp(py.w, lerp(px.w, b00[c], b10[c]), lerp(px.w, b01[c], b11[c]));
        out[c] = lerp(pz.w, z0, z1);
    }
    return out;
}

}  // namespace tilevk::shader::tex
