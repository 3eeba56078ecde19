// Cube and cube-array sampling, computed as llvmpipe computes it (texture_cube.h; docs/lavapipe-rules.md §10
// "Cube maps"). Texels are read and decoded by texture.cpp's rules; this file adds the face selection, the
// per-pixel LOD of cube maps and the seamless filter.
#include "shader/texture_cube.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "format/texel_codec.h"
#include "shader/texture_fixed8.h"
#include "shader/texture_internal.h"
#include "shader/texture_reduce.h"

namespace tilevk::shader::cube {

namespace {

using Vec4 = std::array<float, 4>;
constexpr uint32_t kSignBit = 0x80000000u;

float flip_if(float v, uint32_t sign) {
    return std::bit_cast<float>(std::bit_cast<uint32_t>(v) ^ sign);
}

// The major axis (0 x, 1 y, 2 z): z when |z| >= max(|x|, |y|) (MAXPS: |y| unless |x| > |y|), else x when |x| > |y|,
// else y. Ties go to z, then y, as lp_build_cube_lookup orders its selects.
int major_axis(float x, float y, float z) {
    const float as = std::fabs(x), at = std::fabs(y), ar = std::fabs(z);
    const float m = as > at ? as : at;
    if (ar >= m) return 2;
    return as > at ? 0 : 1;
}

// sc, tc of the spec's table by sign flips of the direction (or of its derivatives, with the major axis's sign):
// x: (-z, -y) mirrored in sc for -x; y: (x, z) mirrored in tc for -y; z: (x, -y) mirrored in sc for -z.
void face_st(int axis, uint32_t sign_ma, const float v[3], float* sc, float* tc) {
    switch (axis) {
        case 0:
            *sc = flip_if(v[2], kSignBit ^ sign_ma), *tc = flip_if(v[1], kSignBit);
            return;
        case 1:
            *sc = v[0], *tc = flip_if(v[2], sign_ma);
            return;
        default:
            *sc = flip_if(v[0], sign_ma), *tc = flip_if(v[1], kSignBit);
            return;
    }
}

}  // namespace

FaceCoord lookup(float x, float y, float z) {
    const float v[3] = {x, y, z};
    const int axis = major_axis(x, y, z);
    const float ma = v[axis];
    const uint32_t sign = std::bit_cast<uint32_t>(ma) & kSignBit;
    float sc, tc;
    face_st(axis, sign, v, &sc, &tc);
    // lp_build_cube_imapos: 0.5 / |ma|, 0 for a zero major axis
    const float ama = std::fabs(ma);
    const float imapos = ama > 0.0f ? 0.5f / ama : 0.0f;
    FaceCoord r;
    r.face = uint32_t(axis) * 2 + (sign >> 31);
    r.s = sc * imapos + 0.5f;
    r.t = tc * imapos + 0.5f;
    return r;
}

FaceCoord lookup_with_derivs(float x, float y, float z, const float ddx[3], const float ddy[3], FaceDerivs* out) {
    const float v[3] = {x, y, z};
    const int axis = major_axis(x, y, z);
    const float ma = v[axis];
    const uint32_t sign = std::bit_cast<uint32_t>(ma) & kSignBit;
    const float ima = 1.0f / ma;
    const float imahalf = 0.5f * ima;
    const float imahalfpos = std::fabs(imahalf);
    float sc, tc, sdx, tdx, sdy, tdy;
    face_st(axis, sign, v, &sc, &tc);
    face_st(axis, sign, ddx, &sdx, &tdx);
    face_st(axis, sign, ddy, &sdy, &tdy);
    // ds = 0.5 * (dsc - sc * dma / ma) / ma, as products with 1 / ma in lp_build_cube_lookup's order
    const float madxdivma = ddx[axis] * ima, madydivma = ddy[axis] * ima;
    out->dsdx = (sdx - madxdivma * sc) * imahalf;
    out->dtdx = (tdx - madxdivma * tc) * imahalf;
    out->dsdy = (sdy - madydivma * sc) * imahalf;
    out->dtdy = (tdy - madydivma * tc) * imahalf;
    FaceCoord r;
    r.face = uint32_t(axis) * 2 + (sign >> 31);
    r.s = sc * imahalfpos + 0.5f;
    r.t = tc * imahalfpos + 0.5f;
    return r;
}

// lp_build_cube_new_coords, one texel at a time. Next faces: x < 0: 4 5 1 1 1 0, x > max: 5 4 0 0 0 1,
// y < 0: 2 2 5 4 2 2, y > max: 3 3 4 5 3 3 (for faces 0..5).
Texel across_edge(uint32_t face, int edge, int32_t x, int32_t y, int32_t max) {
    const bool f23 = (face & ~4u) > 1, f2 = face == 2, odd = (face & 1) != 0, f2345 = face > 1;
    Texel r;
    if (edge < 2) {
        const uint32_t nf0 = f2345 ? (face == 5 ? 0u : 1u) : 4u + (face & 1);
        r.face = edge == 0 ? nf0 : nf0 ^ 1;
        const int32_t ncx1 = f23 ? (f2 ? max - y : y) : 0;
        r.x = edge == 0 ? max - ncx1 : ncx1;
        r.y = f23 ? (f2 ? 0 : max) : y;
        return r;
    }
    const uint32_t nf3 = f23 ? face + 2 : 3u;
    r.face = edge == 3 ? nf3 : nf3 ^ 1;
    const int32_t ncx3 = f2345 ? (odd ? max - x : x) : (odd ? 0 : max);
    const int32_t ncy3 = f2345 ? (odd ? max : 0) : (odd ? max - x : x);
    r.x = edge == 3 ? ncx3 : (f23 ? max - ncx3 : ncx3);
    r.y = edge == 3 ? ncy3 : (f23 ? ncy3 : max - ncy3);
    return r;
}

namespace {

// floor(v) as an integer and v - floor(v) (lp_build_ifloor_fract); kept inside int range (a NaN gives INT_MIN as
// cvttps2dq does, which only a NaN that max_ext let through could reach).
int32_t ifloor_fract(float v, float* frac) {
    const float f = std::floor(v);
    *frac = v - f;
    if (!(std::fabs(f) < 2147483648.0f)) return INT32_MIN;
    return int32_t(f);
}

}  // namespace

Footprint footprint(uint32_t face, float s, float t, int32_t size) {
    // lp_build_max_ext(..., GALLIVM_NAN_RETURN_OTHER_SECOND_NONNAN): a NaN coordinate becomes 0
    const float cs = s == s ? std::max(s, 0.0f) : 0.0f, ct = t == t ? std::max(t, 0.0f) : 0.0f;
    Footprint fp;
    const int32_t x0 = ifloor_fract(cs * float(size) - 0.5f, &fp.ws);
    const int32_t y0 = ifloor_fract(ct * float(size) - 0.5f, &fp.wt);
    const int32_t x1 = int32_t(uint32_t(x0) + 1u), y1 = int32_t(uint32_t(y0) + 1u);
    const int32_t max = size - 1;
    const bool fo[4] = {x0<0, x1> max, y0<0, y1> max};
    const int32_t y0c = std::max(y0, 0), y1c = std::min(y1, max);
    const auto pick = [&](bool fx, int ex, int32_t x, bool fy, int ey, int32_t yc) {
        if (fx) return across_edge(face, ex, x, yc, max);
        if (fy) return across_edge(face, ey, x, yc, max);
        return Texel{face, x, yc};
    };
    fp.texel[0] = pick(fo[0], 0, x0, fo[2], 2, y0c);
    fp.texel[1] = pick(fo[1], 1, x1, fo[2], 2, y0c);
    fp.texel[2] = pick(fo[0], 0, x0, fo[3], 3, y1c);
    fp.texel[3] = pick(fo[1], 1, x1, fo[3], 3, y1c);
    fp.corner = {fo[0] && fo[2], fo[1] && fo[2], fo[0] && fo[3], fo[1] && fo[3]};
    return fp;
}

namespace {

// What one lane samples: the view, the face coordinates, the levels and the filter (lavapipe's cube state,
// lp_bld_sample_soa.c lp_build_sample_common / lp_build_sample_general).
struct Lane {
    const ImageView* img = nullptr;
    const SamplerState* smp = nullptr;
    FaceCoord fc;
    uint32_t cube_layer = 0;  // first layer of the lane's cube in the view (6 * the cube array index)
    uint32_t level0 = 0, level1 = 0;
    float frac = 0.0f;  // weight of level1 (0 when the lod was clamped or the level filter is nearest)
    bool linear = false;
    bool mip_none = false;  // the level filter is off (level_zero_only with a positive maxLod)
    bool dref = false;
    float ref = 0.0f;
};

// The instruction's registers, lane by lane.
struct Regs {
    const Inst& in;
    uint32_t* R;
    float fl(uint32_t r, int l) const { return std::bit_cast<float>(R[size_t(r) * kLanes + size_t(l)]); }
};

// lp_build_iround: cvtps2dq under round-to-nearest-even; NaN and values out of range give INT_MIN.
int32_t iround_even(float v) {
    if (!(std::fabs(v) < 2147483648.0f)) return INT32_MIN;
    return int32_t(std::nearbyint(v));
}

// A cube array's layer: iround(q) * 6 with 32-bit wrap, clamped to [0, layers - 6] (lp_build_sample_common,
// lp_build_layer_coord with is_cube_array).
uint32_t cube_array_layer(float q, uint32_t layers) {
    const int32_t six = int32_t(uint32_t(iround_even(q)) * 6u);
    const int32_t hi = int32_t(layers) - 6;
    return uint32_t(std::max(0, std::min(six, hi)));
}

// The direction's derivatives per pixel: fine, within the quad's row (x) and column (y) (lp_bld_quad.c lp_build_ddx,
// lp_build_ddy), or the textureGrad operands.
void direction_derivs(const Regs& r, int l, float ddx[3], float ddy[3]) {
    const Inst& in = r.in;
    if (in.imm & kSampleGrad) {
        for (int c = 0; c < 3; ++c) ddx[c] = r.fl(in.n + uint32_t(c), l), ddy[c] = r.fl(in.n + 3 + uint32_t(c), l);
        return;
    }
    const int q = l & ~3, i = l & 3;
    const int row = q + (i & 2), col = q + (i & 1);
    for (int c = 0; c < 3; ++c) {
        const uint32_t reg = in.b + uint32_t(c);
        ddx[c] = r.fl(reg, row + 1) - r.fl(reg, row);
        ddy[c] = r.fl(reg, col + 2) - r.fl(reg, col);
    }
}

// rho squared in texels of the view's level 0 (lp_build_rho with derivatives, no_rho_approx): max over x and y of
// (size * ds)^2 + (size * dt)^2, MAXPS order, infinite or NaN -> 0.
float rho_squared(const FaceDerivs& d, float size) {
    const float sx = size * d.dsdx, tx = size * d.dtdx, sy = size * d.dsdy, ty = size * d.dtdy;
    const float rx = sx * sx + tx * tx, ry = sy * sy + ty * ty;
    const float rho = rx > ry ? rx : ry;
    return std::isfinite(rho) ? rho : 0.0f;
}

// PIPE_MAX_TEXTURE_LEVELS - 1: lavapipe clamps to maxLod only below it (lp_bld_sample.c apply_max_lod).
constexpr float kMaxLodApplied = 15.0f;

// The levels of one lane from its lod (lp_build_lod_selector after rho, lp_build_linear_mip_levels,
// lp_build_nearest_mip_level). `fast_ipart` is set when the nearest-mip fast path (ilog2_sqrt) decided.
void select_levels(Lane& ln, float lod, bool positive, bool mip_none) {
    const SamplerState& smp = *ln.smp;
    const int32_t last = int32_t(ln.img->levels) - 1;
    ln.linear = (positive ? smp.min_filter : smp.mag_filter) == Filter::Linear;
    if (mip_none) return;
    if (smp.mipmap_mode == MipmapMode::Nearest) {
        ln.level0 = ln.level1 = uint32_t(std::clamp(iround_even(lod), 0, last));
        return;
    }
    float frac = 0.0f;
    const int32_t i = lod == lod ? ifloor_fract(lod, &frac) : INT32_MIN;
    if (i < 0) return;
    if (i >= last) {
        ln.level0 = ln.level1 = uint32_t(last);
        return;
    }
    ln.level0 = uint32_t(i), ln.level1 = uint32_t(i) + 1, ln.frac = frac;
}

// Face coordinates and levels of every lane (lp_build_sample_common for cube targets).
void set_up_lanes(const Regs& r, const Descriptor* const* slots, uint32_t num_slots, Lane lanes[kLanes]) {
    const Inst& in = r.in;
    float rho[kLanes] = {};
    for (int l = 0; l < kLanes; ++l) {
        Lane& ln = lanes[l];
        const uint32_t h = r.R[size_t(in.a) * kLanes + size_t(l)];
        const uint32_t si = h & 0xFFFF, ss = h >> 16;
        ln.img = si < num_slots && slots[si] && view_usable(slots[si]->image) ? slots[si]->image : nullptr;
        ln.smp = ss < num_slots && slots[ss] ? slots[ss]->sampler : nullptr;
        if (ln.img == nullptr || ln.smp == nullptr) continue;
        const SamplerState& smp = *ln.smp;
        const ImageView& img = *ln.img;
        const float x = r.fl(in.b, l), y = r.fl(in.b + 1, l), z = r.fl(in.b + 2, l);
        // level_zero_only with a positive maxLod turns the level filter off (lp_bld_sample_soa.c); tilevk's view
        // does not keep its base level, so a one-level view stands for it
        const bool mip_none = img.levels == 1 && smp.max_lod > 0.0f;
        ln.mip_none = mip_none;
        const bool lod_needed = smp.min_filter != smp.mag_filter || !mip_none;
        const bool lod_equal = lod_needed && smp.min_lod == smp.max_lod;
        const bool explicit_lod = in.imm & kSampleExplicitLod;
        if (lod_needed && !lod_equal && !explicit_lod) {
            float ddx[3], ddy[3];
            direction_derivs(r, l, ddx, ddy);
            FaceDerivs d;
            ln.fc = lookup_with_derivs(x, y, z, ddx, ddy, &d);
            rho[l] = rho_squared(d, float(img.width));
        } else {
            ln.fc = lookup(x, y, z);
        }
        if (in.imm & kSampleArray) ln.cube_layer = cube_array_layer(r.fl(in.b + 3, l), img.layers);
        if ((in.imm & kSampleDref) && smp.compare_enable) {
            ln.dref = true;
            ln.ref = r.fl(in.b + in.extra - 1, l);
            if (img.format == Format::D16_UNORM) ln.ref = std::clamp(ln.ref, 0.0f, 1.0f);
        }
        ln.linear = smp.mag_filter == Filter::Linear;
        if (!lod_needed) continue;
        // the lod: min == max lod forces it; explicit; else from rho (per pixel for cube maps with a level filter)
        float lod = 0.0f;
        if (lod_equal) {
            lod = smp.min_lod;
        } else {
            if (explicit_lod) {
                lod = r.fl(in.c, l);
            } else {
                float rq = rho[l];
                if (mip_none) rq = rho[l & ~3];  // one lod per quad (lp_build_pack_aos_scalars of the quad's lane 0)
                const bool bias = (in.imm & kSampleBias) != 0;
                const bool fast = !bias && smp.mip_lod_bias == 0.0f && !(smp.max_lod < kMaxLodApplied) &&
                                  !(smp.min_lod > 0.0f) && (mip_none || smp.mipmap_mode == MipmapMode::Nearest);
                if (fast) {  // lp_build_ilog2_sqrt: (exponent(rho^2) + 1) >> 1, minified when rho > 1
                    const int32_t e = int32_t((std::bit_cast<uint32_t>(rq) >> 23) & 0xff) - 126;
                    select_levels(ln, float(e >> 1), rq > 1.0f, mip_none);
                    continue;
                }
                lod = fixed8::fast_log2(rq) * 0.5f;
                if (bias) lod = lod + r.fl(in.c, l);
            }
            if (smp.mip_lod_bias != 0.0f) lod = lod + smp.mip_lod_bias;
            if (smp.max_lod < kMaxLodApplied) lod = std::min(lod, smp.max_lod);
            if (smp.min_lod > 0.0f) lod = std::max(lod, smp.min_lod);
        }
        select_levels(ln, lod, lod > 0.0f, mip_none);
    }
}

int32_t level_size(const ImageView& img, uint32_t level) {
    return int32_t(std::max(1u, img.width >> level));
}

// The lane's texel (face relative to its cube), clamped into the view: lavapipe never leaves it for coordinates
// that are numbers; the clamp only keeps NaN and infinite directions inside memory.
uint32_t texel_layer(const Lane& ln, uint32_t face) {
    return std::min(ln.cube_layer + face, ln.img->layers - 1);
}

float compared(const Lane& ln, const Vec4& c) {
    return compare_values(ln.smp->compare_op, ln.ref, c[0]) ? 1.0f : 0.0f;
}

// Nearest texel of one level: floor(s * size) clamped to the face (CLAMP_TO_EDGE, the wrap lavapipe forces for
// cube maps; lp_build_sample_wrap_nearest truncates, the same after the clamp).
Texel nearest_texel(const Lane& ln, uint32_t level) {
    const int32_t n = level_size(*ln.img, level);
    const auto axis = [n](float c) {
        const float u = c * float(n);
        const int32_t i = u == u ? int32_t(std::clamp(u, -1.0f, float(n))) : 0;
        return std::clamp(i, 0, n - 1);
    };
    return Texel{ln.fc.face, axis(ln.fc.s), axis(ln.fc.t)};
}

// The texel's bytes (its coordinates clamped to the level) and format.
const uint8_t* texel_at(const Lane& ln, uint32_t level, const Texel& t, const format::FormatInfo& fi) {
    const int32_t max = level_size(*ln.img, level) - 1;
    const ImageLevel& il = ln.img->level[level];
    return ln.img->base + il.offset + uint64_t(texel_layer(ln, t.face)) * il.layer_pitch +
           uint64_t(std::clamp(t.y, 0, max)) * il.row_pitch + uint64_t(std::clamp(t.x, 0, max)) * fi.bytes;
}

// A texel decoded as the float filter reads it (format/texel_codec.h, as texture.cpp decodes).
Vec4 fetch(const Lane& ln, uint32_t level, const Texel& t) {
    const format::FormatInfo& fi = format::format_info(ln.img->format);
    Vec4 r;
    format::decode_color(fi, texel_at(ln, level, t, fi), r.data(), true);
    return r;
}

// lp_build_lerp: fmuladd(w, q - p, p), fused on FMA hosts
float lerp(float w, float p, float q) {
    return std::fma(w, q - p, p);
}

// Bilinear at one level over the seamless footprint (lp_build_sample_image_linear). `corner_path`: some lane of the
// lane's 8-wide vector has a corner, and then every lane of it filters as w00*t00 + w01*t01 + w10*t10 + w11*t11 with
// a corner's weight spread over the other three, instead of lerping (llvmpipe branches on the whole vector).
Vec4 linear_level(const Lane& ln, uint32_t level, bool corner_path) {
    const Footprint fp = footprint(ln.fc.face, ln.fc.s, ln.fc.t, level_size(*ln.img, level));
    Vec4 n[4];
    for (int i = 0; i < 4; ++i) n[i] = fetch(ln, level, fp.texel[size_t(i)]);
    const float a = fp.ws, b = fp.wt;
    const Reduction m = ln.smp->reduction;  // MIN / MAX never take the corner path (lp_build_sample_image_linear)
    if (corner_path && m == Reduction::WeightedAverage) {
        const float wx0 = 1.0f - a, wy0 = 1.0f - b;
        float w[4] = {wx0 * wy0, a * wy0, wx0 * b, a * b};
        float cw = 0.0f;
        for (int i = 0; i < 4; ++i)
            if (fp.corner[size_t(i)]) cw = w[i];
        cw = cw * (1.0f / 3.0f);
        for (int i = 0; i < 4; ++i) w[i] = fp.corner[size_t(i)] ? 0.0f : w[i] + cw;
        if (ln.dref) {
            float v = compared(ln, n[0]) != 0.0f ? w[0] : 0.0f;
            for (int i = 1; i < 4; ++i) v = (compared(ln, n[i]) != 0.0f ? w[i] : 0.0f) + v;
            return {v, 0.0f, 0.0f, 1.0f};
        }
        Vec4 r;
        for (size_t c = 0; c < 4; ++c) {
            float v = w[0] * n[0][c];
            for (int i = 1; i < 4; ++i) v = w[i] * n[i][c] + v;
            r[c] = v;
        }
        return r;
    }
    if (ln.dref) {  // lp_build_masklerp2d: masked weights added per row, then the rows lerped
        const auto row = [&](const Vec4& p, const Vec4& q) {
            return (compared(ln, q) != 0.0f ? a : 0.0f) + (compared(ln, p) != 0.0f ? 1.0f - a : 0.0f);
        };
        return {lerp(b, row(n[0], n[1]), row(n[2], n[3])), 0.0f, 0.0f, 1.0f};
    }
    Vec4 r;
    for (size_t c = 0; c < 4; ++c)
        r[c] = reduce_step(m, b, reduce_step(m, a, n[0][c], n[1][c]), reduce_step(m, a, n[2][c], n[3][c]));
    return r;
}

Vec4 nearest_level(const Lane& ln, uint32_t level) {
    const Vec4 c = fetch(ln, level, nearest_texel(ln, level));
    return ln.dref ? Vec4{compared(ln, c), 0.0f, 0.0f, 1.0f} : c;
}

// Whether lane l's footprint at `level` has a corner.
bool has_corner(const Lane& ln, uint32_t level) {
    const Footprint fp = footprint(ln.fc.face, ln.fc.s, ln.fc.t, level_size(*ln.img, level));
    return fp.corner[0] || fp.corner[1] || fp.corner[2] || fp.corner[3];
}

// Whether lavapipe takes its 8-bit path for a non-seamless cube map (lp_bld_sample_soa.c use_aos: no comparison,
// and one lod per quad unless both filters agree; cube maps with a level filter have a lod per pixel).
bool non_seamless_fixed8(const Lane& ln, uint32_t imm) {
    const SamplerState& smp = *ln.smp;
    if (ln.dref || !fixed8::fits_8unorm(format::format_info(ln.img->format))) return false;
    const bool lod_per_quad = ln.mip_none && !(imm & (kSampleBias | kSampleExplicitLod | kSampleGrad));
    return smp.min_filter == smp.mag_filter || lod_per_quad;
}

// A non-seamless cube map (VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT; lavapipe clears seamless_cube_map):
// after the face and levels are chosen as for a seamless one, the face is filtered as a layer of a 2D array with
// CLAMP_TO_EDGE, whatever the sampler's address modes (lp_build_sample_soa_code forces the wrap for every cube
// target), through the 8-bit path when use_aos allows it (its cube exclusion is for seamless filtering only).
Vec4 non_seamless_sample(const Lane& ln, uint32_t imm) {
    SamplerState smp = *ln.smp;
    smp.address_u = smp.address_v = AddressMode::ClampToEdge;
    tex::SampleArgs args;
    args.dref = ln.dref, args.ref = ln.ref;
    const uint32_t layer = texel_layer(ln, ln.fc.face);
    const float s = ln.fc.s, t = ln.fc.t;
    if (non_seamless_fixed8(ln, imm)) {
        tex::Bytes a = tex::sample_level_fixed8(*ln.img, smp, ln.level0, layer, s, t, ln.linear, false, args);
        if (const int32_t mw = fixed8::mip_weight(ln.frac); mw > 0) {
            const tex::Bytes b = tex::sample_level_fixed8(*ln.img, smp, ln.level1, layer, s, t, ln.linear, false, args);
            for (size_t c = 0; c < 4; ++c) a[c] = reduce_step8(smp.reduction, mw, a[c], b[c]);
        }
        Vec4 r;
        for (size_t c = 0; c < 4; ++c) r[c] = format::unorm8_to_float(uint8_t(a[c]));
        return r;
    }
    Vec4 r = tex::sample_level(*ln.img, smp, ln.level0, layer, s, t, ln.linear, false, args);
    if (ln.frac > 0.0f) {
        const Vec4 b = tex::sample_level(*ln.img, smp, ln.level1, layer, s, t, ln.linear, false, args);
        for (size_t c = 0; c < 4; ++c) r[c] = lerp(ln.frac, r[c], b[c]);
    }
    return r;
}

// lavapipe's vectors are 8 lanes (a 4x4 block's two quad rows, 8 consecutive invocations elsewhere): the corner
// branch and the second level's fetch are taken per vector.
constexpr int kVector = 8;

}  // namespace

void exec_sample_cube(const Inst& in, uint32_t* R, const Descriptor* const* slots, uint32_t num_slots) {
    Lane lanes[kLanes];
    const Regs regs{in, R};
    set_up_lanes(regs, slots, num_slots, lanes);
    // per vector: a corner among the linear lanes at level0; another level needed; a corner at level1
    bool corner0[kLanes / kVector] = {}, lerp1[kLanes / kVector] = {}, corner1[kLanes / kVector] = {};
    for (int l = 0; l < kLanes; ++l) {
        const Lane& ln = lanes[l];
        if (ln.img == nullptr || !ln.linear) continue;
        corner0[l / kVector] |= has_corner(ln, ln.level0);
        lerp1[l / kVector] |= ln.frac > 0.0f;
    }
    for (int l = 0; l < kLanes; ++l) {
        const Lane& ln = lanes[l];
        if (ln.img != nullptr && ln.linear && lerp1[l / kVector]) corner1[l / kVector] |= has_corner(ln, ln.level1);
    }
    for (int l = 0; l < kLanes; ++l) {
        const Lane& ln = lanes[l];
        Vec4 r{0, 0, 0, 0};
        const bool integer = ln.img != nullptr && format::is_integer(format::format_info(ln.img->format));
        const bool any_linear =
            ln.smp != nullptr && (ln.smp->min_filter == Filter::Linear || ln.smp->mag_filter == Filter::Linear ||
                                  ln.smp->mipmap_mode == MipmapMode::Linear);
        // a linear filter on an integer format gives zeros (lp_build_sample_soa_code; texture.cpp sample_lambda)
        if (ln.img != nullptr && !(integer && any_linear)) {
            const int g = l / kVector;
            if (!ln.smp->seamless_cube) {
                r = non_seamless_sample(ln, in.imm);
            } else if (!ln.linear && !ln.dref && fixed8::fits_8unorm(format::format_info(ln.img->format))) {
                // lavapipe's 8-bit path (use_aos): no comparison, and seamless cube maps filter linearly in float;
                // nearest texels, an 8-bit lerp between levels (lp_bld_sample_aos.c)
                const format::FormatInfo& fi = format::format_info(ln.img->format);
                const auto bytes = [&](uint32_t level) {
                    return fixed8::texel_bytes(fi, texel_at(ln, level, nearest_texel(ln, level), fi));
                };
                std::array<int32_t, 4> a = bytes(ln.level0);
                const int32_t mw = fixed8::mip_weight(ln.frac);
                if (mw > 0) {
                    const std::array<int32_t, 4> b = bytes(ln.level1);
                    for (size_t c = 0; c < 4; ++c) a[c] = reduce_step8(ln.smp->reduction, mw, a[c], b[c]);
                }
                for (size_t c = 0; c < 4; ++c) r[c] = format::unorm8_to_float(uint8_t(a[c]));
            } else {
                r = ln.linear ? linear_level(ln, ln.level0, corner0[g]) : nearest_level(ln, ln.level0);
                if (ln.frac > 0.0f) {
                    const Vec4 b = ln.linear ? linear_level(ln, ln.level1, corner1[g]) : nearest_level(ln, ln.level1);
                    for (size_t c = 0; c < 4; ++c) r[c] = lerp(ln.frac, r[c], b[c]);
                }
            }
            if (!ln.dref) r = apply_view_swizzle(r, *ln.img);
        }
        for (uint32_t c = 0; c < 4; ++c) R[size_t(in.d + c) * kLanes + size_t(l)] = std::bit_cast<uint32_t>(r[c]);
    }
}

}  // namespace tilevk::shader::cube
