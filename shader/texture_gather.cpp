// OpImageGather / OpImageDrefGather (texture.cpp's exec_sample calls gather_texels): gallivm's gather footprint,
// whose address rules differ from the filter's in places (gather_axis below).
#include <algorithm>
#include <bit>
#include <cmath>

#include "shader/texture_internal.h"

namespace tilevk::shader::tex {
namespace {

// One axis of OpImageGather's 2x2 footprint (lp_build_sample_wrap_linear with is_gather): the two texel indices
// before the offsets and wrap of `fetch_gather` where *final is false, else final. `s` is the normalized
// coordinate, `u` = s * n (texels). Gather's own forms, where they differ from the filter's:
// CLAMP_TO_EDGE truncates c - 0.5 and c + 0.5 of the clamped coordinate (texels 0 and 0 next to the edge, not 0
// and 1); MIRRORED_REPEAT mirrors the coordinate with its sign kept, and it and MIRROR_CLAMP_TO_EDGE fold negative
// indices by ones' complement (a NaN, INT_MIN from cvttps2dq, ends at n - 1).
void gather_axis(float s, float u, int32_t n, int32_t off, AddressMode m, int32_t* i0, int32_t* i1, bool* final) {
    const auto ifloor = [](float x) {
        return x == x && std::fabs(x) < 2147483648.0f ? int32_t(std::floor(x)) : INT32_MIN;
    };
    const auto fold = [n](int32_t i) { return std::min(i < 0 ? ~i : i, n - 1); };
    *final = true;
    switch (m) {
        case AddressMode::ClampToEdge: {
            float c = u;
            if (off) c = c + float(off);
            c = c < float(n) ? c : float(n);
            c = c > 0.0f ? c : 0.0f;
            *i0 = int32_t(c - 0.5f);
            *i1 = std::min(int32_t(c + 0.5f), n - 1);
            return;
        }
        case AddressMode::MirroredRepeat: {
            if (off) s = s + float(off) / float(n);
            const float h = s * 0.5f;
            const float f = h - std::nearbyint(h);
            const float c = (f + f) * float(n);
            const int32_t j = ifloor(c - 0.5f);
            *i0 = fold(j), *i1 = fold(j + 1);
            return;
        }
        case AddressMode::MirrorClampToEdge: {
            float c = u;
            if (off) c = c + float(off);
            const int32_t j = ifloor(c - 0.5f);
            *i0 = fold(j), *i1 = fold(j + 1);
            return;
        }
        case AddressMode::Repeat:
            if (!power_of_two(n)) {
                const Axis a = repeat_npot_axis(s, n, off);
                *i0 = a.i0, *i1 = a.i1;
                return;
            }
            [[fallthrough]];
        default:
            *final = false;
            *i0 = floor_index(u - 0.5f, m);
            *i1 = *i0 + 1;
            return;
    }
}

}  // namespace

// OpImageGather / OpImageDrefGather at level 0 of the view (gallivm's gather: mip filter NONE, min and mag filter
// LINEAR, lp_build_sample_image_linear): component `comp` (through the view's swizzle) of the footprint's texels,
// or their depth comparisons, in the order (i0, j1), (i1, j1), (i1, j0), (i0, j0). A ZERO or ONE swizzle gives
// zeros or ones.
Vec4 gather_texels(const ImageView& img, const SamplerState& smp, float s, float t, uint32_t layer, uint32_t comp,
                   const SampleArgs& args) {
    const uint8_t swz = img.swizzle[comp & 3];
    const float one = integer_format(img) ? std::bit_cast<float>(1u) : 1.0f;
    if (swz == kSwizzleOne) return {one, one, one, one};
    if (swz >= 4) return {0, 0, 0, 0};
    const ImageLevel& il = img.level[0];
    Level lv;
    lv.w = int32_t(img.width), lv.h = int32_t(img.height);
    lv.fi = &format::format_info(img.format);
    lv.bpp = lv.fi->bytes;
    lv.row_pitch = il.row_pitch;
    lv.base = img.base + il.offset + uint64_t(layer) * il.layer_pitch;
    const float u = smp.unnormalized ? s : s * float(lv.w);
    const float v = smp.unnormalized ? t : t * float(lv.h);
    int32_t x[2], y[2];
    bool x_final, y_final;
    gather_axis(s, u, lv.w, args.off_x, smp.address_u, &x[0], &x[1], &x_final);
    gather_axis(t, v, lv.h, args.off_y, smp.address_v, &y[0], &y[1], &y_final);
    const Vec4 border = format_border(*lv.fi, smp);
    auto value = [&](int32_t i, int32_t j) {
        const int32_t wx = x_final ? i : wrap(i + args.off_x, lv.w, smp.address_u);
        const int32_t wy = y_final ? j : wrap(j + args.off_y, lv.h, smp.address_v);
        const Vec4 c = (wx < 0 || wy < 0) ? border : texel(lv, wx, wy);
        if (args.dref) return compare_values(smp.compare_op, args.ref, c[0]) ? 1.0f : 0.0f;
        return c[swz];
    };
    return {value(x[0], y[1]), value(x[1], y[1]), value(x[1], y[0]), value(x[0], y[0])};
}

}  // namespace tilevk::shader::tex
