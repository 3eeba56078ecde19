// Image instructions: texture()/textureLod()/textureGrad()/texelFetch()/textureSize()/textureQueryLevels().
// Follows the Vulkan spec's filtering equations in float arithmetic (see README.md for how this differs from
// llvmpipe's fixed-point 8-bit filtering). Every access is bounds-checked; a missing descriptor reads zero.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "shader/ir.h"
#include "shader/texture_fixed8.h"

namespace tilevk::shader {

namespace {

using Vec4 = std::array<float, 4>;

// sRGB -> linear as llvmpipe decodes sampled texels (lp_bld_format_srgb.c lp_build_srgb_to_linear, reached from
// lp_build_extract_soa_chan): x = float(c); x <= 15 ? x * fl(1/(12.6*255)) : a cubic polynomial evaluated with
// fmuladd (fused, as on the FMA hosts this file's other lerps assume). Same rule as rast/fragment's blend decode.
float srgb_to_linear(uint32_t c) {
    static const std::array<float, 256> table = [] {
        const float c0 = 0.0023f, c1 = 0.0030f / 255.0f, c2 = 0.6935f / (255.0f * 255.0f),
                    c3 = 0.3012f / (255.0f * 255.0f * 255.0f), lin_k = 1.0f / (12.6f * 255.0f);
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const float x = float(i), x2 = x * x;
            const float poly = std::fma(std::fma(x2, c3, c1), x, std::fma(x2, c2, c0));
            t[size_t(i)] = x <= 15.0f ? x * lin_k : poly;
        }
        return t;
    }();
    return table[c & 0xff];
}

float half_to_float(uint16_t h) {
    uint32_t s = (h >> 15) & 1, e = (h >> 10) & 31, m = h & 1023;
    float v;
    if (e == 0)
        v = std::ldexp(float(m), -24);
    else if (e == 31)
        v = m ? NAN : INFINITY;
    else
        v = std::ldexp(float(m | 1024), int(e) - 25);
    return s ? -v : v;
}

uint32_t texel_size(Format f) {
    switch (f) {
        case Format::R8_UNORM:
            return 1;
        case Format::RG8_UNORM:
            return 2;
        case Format::RGBA8_UNORM:
        case Format::RGBA8_SRGB:
        case Format::BGRA8_UNORM:
        case Format::BGRA8_SRGB:
        case Format::R32F:
            return 4;
        case Format::RGBA16F:
        case Format::RG32F:
            return 8;
        case Format::RGBA32F:
            return 16;
        case Format::D16_UNORM:
            return 2;
        case Format::D32_SFLOAT:
            return 4;
        default:
            return 0;
    }
}

// UNORM n-bit -> float as gallivm converts (lp_build_unsigned_norm_to_float): a multiply by the float constant
// fl(1/(2^n-1)), not a division (they differ in the last bit for some values, visible in float render targets).
constexpr float kUnorm8Scale = float(1.0 / 255.0);
constexpr float kUnorm16Scale = float(1.0 / 65535.0);

Vec4 decode(Format f, const uint8_t* p) {
    static const std::array<float, 256> unorm = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = float(i) * kUnorm8Scale;
        return t;
    }();
    auto un = [](uint8_t c) { return unorm[c]; };
    float v[4];
    switch (f) {
        case Format::RGBA8_UNORM:
            return {un(p[0]), un(p[1]), un(p[2]), un(p[3])};
        case Format::BGRA8_UNORM:
            return {un(p[2]), un(p[1]), un(p[0]), un(p[3])};
        case Format::RGBA8_SRGB:
            return {srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2]), un(p[3])};
        case Format::BGRA8_SRGB:
            return {srgb_to_linear(p[2]), srgb_to_linear(p[1]), srgb_to_linear(p[0]), un(p[3])};
        case Format::R8_UNORM:
            return {un(p[0]), 0.0f, 0.0f, 1.0f};
        case Format::RG8_UNORM:
            return {un(p[0]), un(p[1]), 0.0f, 1.0f};
        case Format::RGBA16F: {
            uint16_t h[4];
            std::memcpy(h, p, 8);
            return {half_to_float(h[0]), half_to_float(h[1]), half_to_float(h[2]), half_to_float(h[3])};
        }
        case Format::R32F:
            std::memcpy(v, p, 4);
            return {v[0], 0.0f, 0.0f, 1.0f};
        case Format::RG32F:
            std::memcpy(v, p, 8);
            return {v[0], v[1], 0.0f, 1.0f};
        case Format::RGBA32F:
            std::memcpy(v, p, 16);
            return {v[0], v[1], v[2], v[3]};
        case Format::D16_UNORM: {
            uint16_t x;
            std::memcpy(&x, p, 2);
            return {float(x) * kUnorm16Scale, 0.0f, 0.0f, 1.0f};
        }
        case Format::D32_SFLOAT:
            std::memcpy(v, p, 4);
            return {v[0], 0.0f, 0.0f, 1.0f};
        default:
            return {0, 0, 0, 0};
    }
}

Vec4 border_color(BorderColor b) {
    switch (b) {
        case BorderColor::OpaqueBlack:
            return {0, 0, 0, 1};
        case BorderColor::OpaqueWhite:
            return {1, 1, 1, 1};
        default:
            return {0, 0, 0, 0};
    }
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

struct Level {
    const uint8_t* base;  // layer already applied
    uint64_t row_pitch;
    int32_t w, h;
    uint32_t bpp;
    uint64_t bytes;  // readable bytes from base
};

Vec4 texel(const ImageView& img, const Level& lv, int32_t x, int32_t y) {
    uint64_t off = uint64_t(y) * lv.row_pitch + uint64_t(x) * lv.bpp;
    return decode(img.format, lv.base + off);
}

bool compare(CompareOp op, float ref, float d) {
    switch (op) {
        case CompareOp::Never:
            return false;
        case CompareOp::Less:
            return ref < d;
        case CompareOp::Equal:
            return ref == d;
        case CompareOp::LessOrEqual:
            return ref <= d;
        case CompareOp::Greater:
            return ref > d;
        case CompareOp::NotEqual:
            return ref != d;
        case CompareOp::GreaterOrEqual:
            return ref >= d;
        case CompareOp::Always:
            return true;
    }
    return false;
}

struct SampleArgs {
    int32_t off_x = 0, off_y = 0;  // constant texel offsets
    bool dref = false;             // depth compare against `ref`: each texel becomes 0 or 1 before filtering
    float ref = 0.0f;
};

struct Axis {
    int32_t i0, i1;  // texel indices (i1 already wrapped when `wrapped`)
    float w;
};

// MIRRORED_REPEAT in lavapipe's float filter (lp_bld_sample_soa.c lp_build_sample_wrap_linear): mirror the
// normalized coordinate first, m = |2(s/2 - round(s/2))|, then u = m*n - 0.5, i0 = max(floor(u), 0),
// i1 = min(floor(u) + 1, n - 1). The returned indices are final (the wrap of fetch() leaves them unchanged).
Axis mirror_axis(float s, int32_t n, int32_t off) {
    if (off) s = s + float(off) / float(n);
    float h = s * 0.5f;
    float f = h - std::nearbyint(h);
    float m = std::fabs(f + f);
    if (!(m == m)) m = 0.0f;
    float u = m * float(n) - 0.5f;
    float fl = std::floor(u);
    int32_t i = safe_floor(u);
    return {std::max(i, 0), std::min(i + 1, n - 1), u - fl};
}

Vec4 sample_level(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s, float t,
                  bool linear, bool one_d, const SampleArgs& args) {
    const ImageLevel& il = img.level[level];
    Level lv;
    lv.w = int32_t(std::max(1u, img.width >> level));
    lv.h = one_d ? 1 : int32_t(std::max(1u, img.height >> level));
    lv.bpp = texel_size(img.format);
    lv.row_pitch = il.row_pitch;
    lv.base = img.base + il.offset + uint64_t(layer) * il.layer_pitch;
    Vec4 border = border_color(smp.border);
    // unnormalized: coordinates are already in texels
    float u = smp.unnormalized ? s : s * float(lv.w);
    float v = smp.unnormalized ? t : t * float(lv.h);
    auto fetch = [&](int32_t x, int32_t y) -> Vec4 {
        int32_t wx = wrap(x + args.off_x, lv.w, smp.address_u);
        int32_t wy = one_d ? 0 : wrap(y + args.off_y, lv.h, smp.address_v);
        Vec4 c = (wx < 0 || wy < 0) ? border : texel(img, lv, wx, wy);
        if (args.dref) return {compare(smp.compare_op, args.ref, c[0]) ? 1.0f : 0.0f, 0.0f, 0.0f, 1.0f};
        return c;
    };
    if (!linear) return fetch(floor_index(u, smp.address_u), one_d ? 0 : floor_index(v, smp.address_v));
    // linear: i0 = floor(u - 0.5), alpha = frac(u - 0.5); blend the 2x2 footprint. A NaN coordinate on a
    // CLAMP_TO_BORDER axis reads the border with the weight NaN - floor(NaN) = NaN (lp_build_ifloor_fract), which
    // the lerps carry into the result.
    float uu = u - 0.5f, vv = v - 0.5f;
    int32_t i0 = floor_index(uu, smp.address_u), j0 = one_d ? 0 : floor_index(vv, smp.address_v);
    auto weight = [](float x, AddressMode m) {
        return (x == x) ? x - std::floor(x) : m == AddressMode::ClampToBorder ? x : 0.0f;
    };
    float a = weight(uu, smp.address_u);
    float b = one_d ? 0.0f : weight(vv, smp.address_v);
    int32_t i1 = i0 + 1, j1 = j0 + 1;
    Axis ax = {i0 + args.off_x, i1 + args.off_x, a}, ay = {j0 + args.off_y, j1 + args.off_y, b};
    if (smp.address_u == AddressMode::MirroredRepeat && !smp.unnormalized) ax = mirror_axis(s, lv.w, args.off_x);
    if (!one_d && smp.address_v == AddressMode::MirroredRepeat && !smp.unnormalized)
        ay = mirror_axis(t, lv.h, args.off_y);
    a = ax.w, b = one_d ? 0.0f : ay.w;
    // fetch() adds the offsets again: hand it offset-free indices
    i0 = ax.i0 - args.off_x, i1 = ax.i1 - args.off_x, j0 = ay.i0 - args.off_y, j1 = ay.i1 - args.off_y;
    if (one_d) j1 = j0;
    Vec4 t00 = fetch(i0, j0), t10 = fetch(i1, j0), t01 = fetch(i0, j1), t11 = fetch(i1, j1);
    Vec4 r;
    // lavapipe's float (SoA) filter: lerp(w, p, q) = fmuladd(w, q - p, p) (fused on FMA hosts), along x, then
    // along y (lp_build_lerp_2d via lp_build_reduce_filter_2d), for every format that reaches it; never the
    // weighted sum of the four texels, which differs in the last bits.
    auto lerp = [](float w, float p, float q) { return std::fma(w, q - p, p); };
    if (args.dref) {
        // the compared texels are masks: each row is (m0 ? 1 - a : 0) + (m1 ? a : 0) (lp_build_masklerp2d), then
        // the rows are lerped along y
        auto row = [&](float m0, float m1) { return (m0 != 0.0f ? 1.0f - a : 0.0f) + (m1 != 0.0f ? a : 0.0f); };
        float x0 = row(t00[0], t10[0]);
        r = {one_d ? x0 : lerp(b, x0, row(t01[0], t11[0])), 0.0f, 0.0f, 1.0f};
        return r;
    }
    for (int c = 0; c < 4; ++c) {
        float x0 = lerp(a, t00[c], t10[c]);
        r[c] = one_d ? x0 : lerp(b, x0, lerp(a, t01[c], t11[c]));
    }
    return r;
}

using Bytes = std::array<int32_t, 4>;

// The 8-bit channels of one texel in RGBA order (absent channels read 0, 0, 0, 255), for fits_8unorm formats.
Bytes texel_bytes(Format f, const uint8_t* p) {
    switch (f) {
        case Format::RGBA8_UNORM:
            return {p[0], p[1], p[2], p[3]};
        case Format::BGRA8_UNORM:
            return {p[2], p[1], p[0], p[3]};
        case Format::R8_UNORM:
            return {p[0], 0, 0, 255};
        case Format::RG8_UNORM:
            return {p[0], p[1], 0, 255};
        default:
            return {0, 0, 0, 0};
    }
}

bool simple_wrap(AddressMode m) {
    return m == AddressMode::Repeat || m == AddressMode::ClampToEdge;
}

// lavapipe's choice of the 8-bit fixed-point filter (lp_bld_sample_soa.c use_aos): an 8-bit UNORM non-sRGB
// format, no depth compare, REPEAT or CLAMP_TO_EDGE on every used axis.
bool use_fixed8(const ImageView& img, const SamplerState& smp, bool one_d, bool dref) {
    bool fits = img.format == Format::RGBA8_UNORM || img.format == Format::BGRA8_UNORM ||
                img.format == Format::R8_UNORM || img.format == Format::RG8_UNORM;
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

// One mip level through the 8-bit path: nearest texels as the float path picks them, linear with 8-bit weights
// and two lerps along x then one along y.
Bytes sample_level_fixed8(const ImageView& img, const SamplerState& smp, uint32_t level, uint32_t layer, float s,
                          float t, bool linear, bool one_d, const SampleArgs& args) {
    const ImageLevel& il = img.level[level];
    int32_t w = int32_t(std::max(1u, img.width >> level));
    int32_t h = one_d ? 1 : int32_t(std::max(1u, img.height >> level));
    uint32_t bpp = texel_size(img.format);
    const uint8_t* base = img.base + il.offset + uint64_t(layer) * il.layer_pitch;
    auto at = [&](int32_t x, int32_t y) {
        return texel_bytes(img.format, base + uint64_t(y) * il.row_pitch + uint64_t(x) * bpp);
    };
    if (!linear) {
        float u = smp.unnormalized ? s : s * float(w), v = smp.unnormalized ? t : t * float(h);
        // REPEAT with a non-power-of-two size wraps the float coordinate: trunc(min(fract(s + off/n), 1-2^-24)*n)
        auto axis = [&](float st, float un, int32_t n, int32_t off, AddressMode m) {
            if (m != AddressMode::Repeat || (n & (n - 1)) == 0 || smp.unnormalized)
                return wrap(safe_floor(un) + off, n, m);
            if (off) st = st + float(off) / float(n);
            float f = st - std::floor(st);
            f = (f == f) ? std::min(f, 0x1.fffffep-1f) : 0x1.fffffep-1f;
            return std::clamp(int32_t(f * float(n)), 0, n - 1);
        };
        int32_t x = axis(s, u, w, args.off_x, smp.address_u);
        int32_t y = one_d ? 0 : axis(t, v, h, args.off_y, smp.address_v);
        return at(x, y);
    }
    fixed8::Pair px = axis_fixed8(s, w, args.off_x, smp.unnormalized, smp.address_u);
    fixed8::Pair py = one_d ? fixed8::Pair{0, 0, 0} : axis_fixed8(t, h, args.off_y, smp.unnormalized, smp.address_v);
    Bytes t00 = at(px.i0, py.i0), t10 = at(px.i1, py.i0);
    Bytes r;
    if (one_d) {
        for (int c = 0; c < 4; ++c) r[c] = fixed8::lerp(px.w, t00[c], t10[c]);
        return r;
    }
    Bytes t01 = at(px.i0, py.i1), t11 = at(px.i1, py.i1);
    for (int c = 0; c < 4; ++c)
        r[c] = fixed8::lerp(py.w, fixed8::lerp(px.w, t00[c], t10[c]), fixed8::lerp(px.w, t01[c], t11[c]));
    return r;
}

Vec4 bytes_to_float(const Bytes& b) {
    return {float(b[0]) * kUnorm8Scale, float(b[1]) * kUnorm8Scale, float(b[2]) * kUnorm8Scale,
            float(b[3]) * kUnorm8Scale};
}

Vec4 swizzled(const Vec4& r, const ImageView& img) {
    Vec4 out;
    for (int c = 0; c < 4; ++c) {
        const uint8_t w = img.swizzle[size_t(c)];
        out[size_t(c)] = w < 4 ? r[w] : w == kSwizzleOne ? 1.0f : 0.0f;
    }
    return out;
}

bool image_ok(const ImageView* img) {
    return img && img->base && texel_size(img->format) && img->width && img->height && img->levels &&
           img->levels <= kMaxMipLevels && img->layers;
}

}  // namespace

void exec_image(const Inst& in, uint32_t* R, const Descriptor* const* slots, uint32_t num_slots) {
    auto reg = [&](uint32_t r) { return R + size_t(r) * kLanes; };
    auto fl = [&](uint32_t r, int l) { return std::bit_cast<float>(reg(r)[l]); };
    const uint32_t* h = reg(in.a);
    uint32_t* d[4] = {reg(in.d), nullptr, nullptr, nullptr};
    auto image_of = [&](int l) -> const ImageView* {
        uint32_t s = h[l] & 0xFFFF;
        return s < num_slots && slots[s] && image_ok(slots[s]->image) ? slots[s]->image : nullptr;
    };

    if (in.op == Op::QueryLevels) {
        for (int l = 0; l < kLanes; ++l) {
            const ImageView* img = image_of(l);
            d[0][l] = img ? img->levels : 0;
        }
        return;
    }
    if (in.op == Op::QuerySize) {
        const uint32_t* lod = reg(in.b);
        for (int l = 0; l < kLanes; ++l) {
            const ImageView* img = image_of(l);
            uint32_t lv = lod[l];
            uint32_t vals[3] = {0, 0, 0};
            if (img && lv < img->levels) {
                vals[0] = std::max(1u, img->width >> lv);
                int k = 1;
                if (!(in.imm & kSample1D)) vals[k++] = std::max(1u, img->height >> lv);
                if (in.imm & kSampleArray) vals[k++] = img->layers;
            }
            for (uint32_t c = 0; c < in.extra && c < 3; ++c) reg(in.d + c)[l] = vals[c];
        }
        return;
    }
    for (int c = 1; c < 4; ++c) d[c] = reg(in.d + c);
    bool one_d = in.imm & kSample1D;
    bool arrayed = in.imm & kSampleArray;
    uint32_t layer_comp = one_d ? 1 : 2;
    bool has_offset = in.imm & kSampleOffset;
    int32_t off_x = has_offset ? int32_t(int8_t(uint8_t(in.imm >> 16))) : 0;
    int32_t off_y = has_offset ? int32_t(int8_t(uint8_t(in.imm >> 24))) : 0;
    bool dref = in.imm & kSampleDref;
    // register run: coordinates [, q for projection] [, depth reference]
    uint32_t q_reg = in.b + in.extra - 1 - (dref ? 1 : 0);

    if (in.op == Op::Fetch) {
        const uint32_t* lod = reg(in.c);
        for (int l = 0; l < kLanes; ++l) {
            Vec4 r{0, 0, 0, 0};
            const ImageView* img = image_of(l);
            int32_t x = int32_t(reg(in.b)[l]) + off_x;
            int32_t y = one_d ? 0 : int32_t(reg(in.b + 1)[l]) + off_y;
            int32_t layer = arrayed ? int32_t(reg(in.b + layer_comp)[l]) : 0;
            uint32_t lv = lod[l];
            if (img && lv < img->levels) {
                int32_t w = int32_t(std::max(1u, img->width >> lv)), hh = int32_t(std::max(1u, img->height >> lv));
                if (one_d) hh = 1;
                if (x >= 0 && y >= 0 && x < w && y < hh && layer >= 0 && uint32_t(layer) < img->layers) {
                    const ImageLevel& il = img->level[lv];
                    r = decode(img->format, img->base + il.offset + uint64_t(layer) * il.layer_pitch +
                                                uint64_t(y) * il.row_pitch + uint64_t(x) * texel_size(img->format));
                    r = swizzled(r, *img);
                }
            }
            for (int c = 0; c < 4; ++c) d[c][l] = std::bit_cast<uint32_t>(r[c]);
        }
        return;
    }

    // Sample: coordinates (projected if asked).
    float s[kLanes], t[kLanes], layer_f[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        float q = (in.imm & kSampleProj) ? fl(q_reg, l) : 1.0f;
        s[l] = fl(in.b, l);
        t[l] = one_d ? 0.0f : fl(in.b + 1, l);
        layer_f[l] = arrayed ? fl(in.b + layer_comp, l) : 0.0f;
        if (in.imm & kSampleProj) {
            s[l] = s[l] / q;
            t[l] = t[l] / q;
        }
    }
    for (int l = 0; l < kLanes; ++l) {
        Vec4 r{0, 0, 0, 0};
        const ImageView* img = image_of(l);
        uint32_t ss = h[l] >> 16;
        const SamplerState* smp = ss < num_slots && slots[ss] ? slots[ss]->sampler : nullptr;
        SampleArgs args;
        args.off_x = off_x, args.off_y = off_y;
        if (dref && smp) {
            args.dref = smp->compare_enable;
            args.ref = fl(in.b + in.extra - 1, l);
            if (in.imm & kSampleProj) args.ref = args.ref / fl(q_reg, l);
            if (img && img->format == Format::D16_UNORM) args.ref = std::clamp(args.ref, 0.0f, 1.0f);
        }
        if (img && smp) {
            float w0 = float(img->width), h0 = one_d ? 1.0f : float(img->height);
            float lambda;
            if (smp->unnormalized) {
                lambda = 0.0f;
            } else if (in.imm & kSampleExplicitLod) {
                lambda = fl(in.c, l);
            } else {
                // rho = max(|d(s,t)/dx|, |d(s,t)/dy|) in texels; lambda = log2(rho)
                float dsdx, dtdx, dsdy, dtdy;
                if (in.imm & kSampleGrad) {
                    dsdx = fl(in.n, l), dtdx = fl(in.n + 1, l), dsdy = fl(in.n + 2, l), dtdy = fl(in.n + 3, l);
                } else {
                    // implicit: one LOD per 2x2 quad from the quad's top-left pixel (coarse derivatives)
                    int q = l & ~3;
                    dsdx = s[q + 1] - s[q], dtdx = t[q + 1] - t[q];
                    dsdy = s[q + 2] - s[q], dtdy = t[q + 2] - t[q];
                }
                dsdx *= w0, dsdy *= w0, dtdx *= h0, dtdy *= h0;
                if (smp->mipmap_mode == MipmapMode::Linear) {
                    // lavapipe (lp_bld_sample.c lp_build_lod_selector, no rho_approx/brilinear):
                    // lambda = 0.5 * fast_log2(max(dsdx^2 + dtdx^2, dsdy^2 + dtdy^2)), 1D: rho = max(|dsdx|, |dsdy|)
                    float rho2;
                    if (one_d) {
                        float rho = std::max(std::fabs(dsdx), std::fabs(dsdy));
                        rho2 = rho * rho;
                    } else {
                        rho2 = std::max(dsdx * dsdx + dtdx * dtdx, dsdy * dsdy + dtdy * dtdy);
                    }
                    if ((in.imm & kSampleGrad) && !std::isfinite(rho2)) rho2 = 0.0f;
                    lambda = fixed8::fast_log2(rho2) * 0.5f;
                } else {
                    float rx = std::sqrt(dsdx * dsdx + dtdx * dtdx), ry = std::sqrt(dsdy * dsdy + dtdy * dtdy);
                    lambda = std::log2(std::max(rx, ry));
                }
                if (in.imm & kSampleBias) lambda += fl(in.c, l);
            }
            if (!smp->unnormalized) lambda += smp->mip_lod_bias;
            if (!(lambda == lambda)) lambda = 0.0f;
            lambda = std::min(std::max(lambda, smp->min_lod), smp->max_lod);
            bool mag = lambda <= 0.0f;
            bool linear = (mag ? smp->mag_filter : smp->min_filter) == Filter::Linear;
            uint32_t max_level = img->levels - 1;
            float lyr =
                std::nearbyint(std::clamp(layer_f[l] == layer_f[l] ? layer_f[l] : 0.0f, 0.0f, float(img->layers - 1)));
            uint32_t layer = uint32_t(lyr);
            if (use_fixed8(*img, *smp, one_d, dref)) {
                // lod = lo + frac: levels clamped to the view (frac dropped there), weight trunc(frac*256)
                uint32_t lv = 0, hi = 0;
                int32_t mw = 0;
                if (smp->unnormalized || mag) {
                } else if (smp->mipmap_mode == MipmapMode::Nearest) {
                    lv = uint32_t(std::clamp(std::ceil(lambda + 0.5f) - 1.0f, 0.0f, float(max_level)));
                } else {
                    float fl0 = std::floor(lambda);
                    if (fl0 >= float(max_level)) {
                        lv = max_level;
                    } else if (fl0 >= 0.0f) {
                        lv = uint32_t(fl0);
                        hi = lv + 1;
                        mw = fixed8::mip_weight(lambda - fl0);
                    }
                }
                Bytes a = sample_level_fixed8(*img, *smp, lv, layer, s[l], t[l], linear, one_d, args);
                if (mw > 0) {
                    Bytes b = sample_level_fixed8(*img, *smp, hi, layer, s[l], t[l], linear, one_d, args);
                    for (int c = 0; c < 4; ++c) a[c] = fixed8::lerp(mw, a[c], b[c]);
                }
                r = bytes_to_float(a);
            } else if (smp->unnormalized || mag) {
                r = sample_level(*img, *smp, 0, layer, s[l], t[l], linear, one_d, args);
            } else if (smp->mipmap_mode == MipmapMode::Nearest) {
                // d = ceil(lambda + 0.5) - 1, clamped to the view's levels
                float dl = std::ceil(lambda + 0.5f) - 1.0f;
                uint32_t lv = uint32_t(std::clamp(dl, 0.0f, float(max_level)));
                r = sample_level(*img, *smp, lv, layer, s[l], t[l], linear, one_d, args);
            } else {
                float fl0 = std::floor(lambda);
                uint32_t lo = uint32_t(std::clamp(fl0, 0.0f, float(max_level)));
                uint32_t hi = std::min(lo + 1, max_level);
                float frac = lambda - fl0;
                Vec4 a = sample_level(*img, *smp, lo, layer, s[l], t[l], linear, one_d, args);
                if (hi != lo && frac > 0.0f) {
                    Vec4 b = sample_level(*img, *smp, hi, layer, s[l], t[l], linear, one_d, args);
                    // lp_build_sample_mipmap: lp_build_lerp(frac, level0, level1), a fused multiply-add
                    for (int c = 0; c < 4; ++c) a[c] = std::fma(frac, b[c] - a[c], a[c]);
                }
                r = a;
            }
            if (!dref) r = swizzled(r, *img);  // a depth comparison's result is not remapped
        }
        for (int c = 0; c < 4; ++c) d[c][l] = std::bit_cast<uint32_t>(r[c]);
    }
}

}  // namespace tilevk::shader
