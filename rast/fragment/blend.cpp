#include "rast/fragment/blend.h"

#include <cmath>
#include <cstring>

#include "rast/fragment/block_kernels.h"

namespace tilevk::rast::fragment {

namespace {

// Gallium's PIPE_BLENDFACTOR numbering: lavapipe's shortcut rules depend on it (complement = value ^ 0x10,
// "src < dst" picks the lerp direction).
enum PipeFactor : uint8_t {
    kOne = 0x01,
    kSrcColor = 0x02,
    kSrcAlpha = 0x03,
    kDstAlpha = 0x04,
    kDstColor = 0x05,
    kSrcAlphaSat = 0x06,
    kConstColor = 0x07,
    kConstAlpha = 0x08,
    kZero = 0x11,
    kInvSrcColor = 0x12,
    kInvSrcAlpha = 0x13,
    kInvDstAlpha = 0x14,
    kInvDstColor = 0x15,
    kInvConstColor = 0x17,
    kInvConstAlpha = 0x18,
    kUnsupported = 0xff,
};

PipeFactor to_pipe(BlendFactor f) {
    switch (f) {
        case BlendFactor::Zero:
            return kZero;
        case BlendFactor::One:
            return kOne;
        case BlendFactor::SrcColor:
            return kSrcColor;
        case BlendFactor::OneMinusSrcColor:
            return kInvSrcColor;
        case BlendFactor::DstColor:
            return kDstColor;
        case BlendFactor::OneMinusDstColor:
            return kInvDstColor;
        case BlendFactor::SrcAlpha:
            return kSrcAlpha;
        case BlendFactor::OneMinusSrcAlpha:
            return kInvSrcAlpha;
        case BlendFactor::DstAlpha:
            return kDstAlpha;
        case BlendFactor::OneMinusDstAlpha:
            return kInvDstAlpha;
        case BlendFactor::ConstantColor:
            return kConstColor;
        case BlendFactor::OneMinusConstantColor:
            return kInvConstColor;
        case BlendFactor::ConstantAlpha:
            return kConstAlpha;
        case BlendFactor::OneMinusConstantAlpha:
            return kInvConstAlpha;
        case BlendFactor::SrcAlphaSaturate:
            return kSrcAlphaSat;
        default:
            return kUnsupported;
    }
}

// The blend state after lavapipe's and llvmpipe's rewrites.
struct PipeBlend {
    PipeFactor rgb_src, rgb_dst, a_src, a_dst;
    BlendOp rgb_op, a_op;
};

PipeBlend lower(const BlendAttachment& a, const FormatInfo& fi) {
    PipeBlend b{to_pipe(a.src_color), to_pipe(a.dst_color), to_pipe(a.src_alpha),
                to_pipe(a.dst_alpha), a.color_op,           a.alpha_op};
    // lvp_execute.c: MIN/MAX apply the factors first in llvmpipe, so they are stomped to ONE.
    if (b.rgb_op == BlendOp::Min || b.rgb_op == BlendOp::Max) b.rgb_src = b.rgb_dst = kOne;
    if (b.a_op == BlendOp::Min || b.a_op == BlendOp::Max) b.a_src = b.a_dst = kOne;
    if (!fi.has_alpha) {
        // lp_state_fs.c force_dst_alpha_one; alpha equation := rgb equation
        const bool clamped_zero = fi.kind == ChannelKind::Unorm8 || fi.kind == ChannelKind::Srgb8;
        auto fix = [&](PipeFactor f) {
            if (f == kDstAlpha) return kOne;
            if (f == kInvDstAlpha) return kZero;
            if (f == kSrcAlphaSat && clamped_zero) return kZero;
            return f;
        };
        b.rgb_src = fix(b.rgb_src);
        b.rgb_dst = fix(b.rgb_dst);
        b.a_src = b.rgb_src;
        b.a_dst = b.rgb_dst;
        b.a_op = b.rgb_op;
    }
    return b;
}

bool complementary(PipeFactor s, PipeFactor d) {
    return d == (s ^ 0x10);
}

inline float sse_min(float a, float b) {
    return a < b ? a : b;
}
inline float sse_max(float a, float b) {
    return a > b ? a : b;
}
inline float fmuladd(float a, float b, float c, bool fused) {
    return fused ? std::fma(a, b, c) : a * b + c;
}

// Stored channel i (memory order) -> RGBA channel index.
inline int mem_to_rgba(const FormatInfo& fi, int i) {
    if (fi.bgra && i < 3) return 2 - i;
    return i;
}

// ---------------------------------------------------------------------------------------------------------------
// UNORM8

struct Px8 {
    uint8_t s[4], d[4], k[4];  // src, dst, constant (RGBA order; d[3] valid only with alpha)
    uint8_t sa, ka;
};

[[gnu::always_inline]] inline uint8_t factor8(PipeFactor f, int c, bool alpha_chan, bool has_alpha, const Px8& p) {
    switch (f) {
        case kZero:
            return 0;
        case kOne:
            return 255;
        case kSrcColor:
            return p.s[c];
        case kSrcAlpha:
            return p.sa;
        case kDstColor:
            return p.d[c];
        case kDstAlpha:
            return p.d[3];
        case kSrcAlphaSat:
            if (alpha_chan) return 255;
            if (!has_alpha) return 0;
            return p.sa < uint8_t(255 - p.d[3]) ? p.sa : uint8_t(255 - p.d[3]);
        case kConstColor:
            return p.k[c];
        case kConstAlpha:
            return p.ka;
        case kInvSrcColor:
            return uint8_t(255 - p.s[c]);
        case kInvSrcAlpha:
            return uint8_t(255 - p.sa);
        case kInvDstColor:
            return uint8_t(255 - p.d[c]);
        case kInvDstAlpha:
            return uint8_t(255 - p.d[3]);
        case kInvConstColor:
            return uint8_t(255 - p.k[c]);
        case kInvConstAlpha:
            return uint8_t(255 - p.ka);
        default:
            return 0;
    }
}

[[gnu::always_inline]] inline uint8_t func8(BlendOp op, uint8_t a, uint8_t b) {
    switch (op) {
        case BlendOp::Add:
            return uint8_t(a + b > 255 ? 255 : a + b);  // uadd.sat
        case BlendOp::Subtract:
            return uint8_t(a > b ? a - b : 0);  // usub.sat
        case BlendOp::ReverseSubtract:
            return uint8_t(b > a ? b - a : 0);
        case BlendOp::Min:
            return a < b ? a : b;
        case BlendOp::Max:
            return a > b ? a : b;
    }
    return 0;
}

void blend_unorm8(const PipeBlend& b, const FormatInfo& fi, Px8& p, uint8_t out[4]) {
    const int n = fi.channels;
    const int chans[4] = {0, 1, 2, 3};
    // Single-channel targets: lavapipe's "not alpha dependent" lerp for complementary factors with ADD.
    if (n == 1 && b.rgb_op == BlendOp::Add && complementary(b.rgb_src, b.rgb_dst)) {
        if (b.rgb_src < b.rgb_dst)
            out[0] = lerp8(factor8(b.rgb_src, 0, false, false, p), p.d[0], p.s[0]);
        else
            out[0] = lerp8(factor8(b.rgb_dst, 0, false, false, p), p.s[0], p.d[0]);
        return;
    }
    for (int i = 0; i < n; ++i) {
        const int c = chans[i];
        const bool alpha_chan = fi.has_alpha && c == 3;
        const PipeFactor sf = alpha_chan ? b.a_src : b.rgb_src;
        const PipeFactor df = alpha_chan ? b.a_dst : b.rgb_dst;
        const BlendOp op = alpha_chan ? b.a_op : b.rgb_op;
        const uint8_t st = mul_norm8(p.s[c], factor8(sf, c, alpha_chan, fi.has_alpha, p));
        const uint8_t dt = mul_norm8(p.d[c], factor8(df, c, alpha_chan, fi.has_alpha, p));
        out[c] = func8(op, st, dt);
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Float (sRGB, half, float32)

struct PxF {
    float s[4], d[4], k[4];
    float sa, ka;
    bool ftz;
};

inline float fz(const PxF& p, float x) {
    return p.ftz ? flush_denorm(x) : x;
}
inline float fsub(const PxF& p, float a, float b) {
    return fz(p, fz(p, a) - fz(p, b));
}
inline float fadd(const PxF& p, float a, float b) {
    return fz(p, fz(p, a) + fz(p, b));
}
inline float fmul(const PxF& p, float a, float b) {
    return fz(p, fz(p, a) * fz(p, b));
}

float factorf(PipeFactor f, int c, bool alpha_chan, bool has_alpha, const PxF& p) {
    switch (f) {
        case kZero:
            return 0.0f;
        case kOne:
            return 1.0f;
        case kSrcColor:
            return p.s[c];
        case kSrcAlpha:
            return p.sa;
        case kDstColor:
            return p.d[c];
        case kDstAlpha:
            return p.d[3];
        case kSrcAlphaSat:
            if (alpha_chan) return 1.0f;
            // min.ps(src_alpha, 1 - dst_alpha), or min.ps(src_alpha, 0) without dst alpha
            return has_alpha ? sse_min(fz(p, p.sa), fsub(p, 1.0f, p.d[3])) : sse_min(fz(p, p.sa), 0.0f);
        case kConstColor:
            return p.k[c];
        case kConstAlpha:
            return p.ka;
        case kInvSrcColor:
            return fsub(p, 1.0f, p.s[c]);
        case kInvSrcAlpha:
            return fsub(p, 1.0f, p.sa);
        case kInvDstColor:
            return fsub(p, 1.0f, p.d[c]);
        case kInvDstAlpha:
            return fsub(p, 1.0f, p.d[3]);
        case kInvConstColor:
            return fsub(p, 1.0f, p.k[c]);
        case kInvConstAlpha:
            return fsub(p, 1.0f, p.ka);
        default:
            return 0.0f;
    }
}

float funcf(const PxF& p, BlendOp op, float a, float b) {
    switch (op) {
        case BlendOp::Add:
            return fadd(p, a, b);
        case BlendOp::Subtract:
            return fsub(p, a, b);
        case BlendOp::ReverseSubtract:
            return fsub(p, b, a);
        case BlendOp::Min:
            return sse_min(fz(p, a), fz(p, b));
        case BlendOp::Max:
            return sse_max(fz(p, a), fz(p, b));
    }
    return 0.0f;
}

// What lp_build_mul sees as its second operand: the whole factor vector, which LLVM folds to the uniqued
// zero / one constant when every channel's factor is ZERO / ONE.
enum class VecConst { Zero, One, Other };

VecConst vec_const(PipeFactor rgb, PipeFactor alpha, bool has_alpha) {
    const PipeFactor a = has_alpha ? alpha : rgb;
    if (rgb == kZero && a == kZero) return VecConst::Zero;
    if (rgb == kOne && a == kOne) return VecConst::One;
    return VecConst::Other;
}

// One lp_build_blend call for channel c. rgb/alpha factor pair describes the vector operands; (fs, fd) are the
// factors this call is keyed on (rgb factors, or alpha factors for the separate alpha pass).
float blend_call_f(const PxF& p, const FormatInfo& fi, BlendOp op, PipeFactor fs, PipeFactor fd, VecConst vs,
                   VecConst vd, bool not_alpha_dependent, int c, PipeFactor chan_sf, PipeFactor chan_df,
                   bool alpha_chan, bool fused) {
    const float s = p.s[c], d = p.d[c];
    auto mulv = [&](float x, VecConst v, float f) {
        if (v == VecConst::Zero) return 0.0f;
        if (v == VecConst::One) return x;
        return fmul(p, x, f);
    };
    const float sfv = factorf(chan_sf, c, alpha_chan, fi.has_alpha, p);
    const float dfv = factorf(chan_df, c, alpha_chan, fi.has_alpha, p);
    if (not_alpha_dependent) {
        if (complementary(fs, fd)) {
            if (op == BlendOp::Add) {
                // lerp(x, v0, v1) = fmuladd(x, v1 - v0, v0)
                if (fs < fd) return fz(p, fmuladd(fz(p, sfv), fsub(p, s, d), fz(p, d), fused));
                return fz(p, fmuladd(fz(p, dfv), fsub(p, d, s), fz(p, s), fused));
            }
            if (op == BlendOp::Subtract) {
                const float sum = fadd(p, s, d);
                if (fs < fd) return fsub(p, mulv(sum, vs, sfv), d);
                return fsub(p, s, mulv(sum, vd, dfv));
            }
            if (op == BlendOp::ReverseSubtract) {
                const float sum = fadd(p, s, d);
                if (fs < fd) return fsub(p, d, mulv(sum, vs, sfv));
                return fsub(p, mulv(sum, vd, dfv), s);
            }
        }
        if (fs == fd && (op == BlendOp::Add || op == BlendOp::Subtract || op == BlendOp::ReverseSubtract)) {
            return mulv(funcf(p, op, s, d), vs, sfv);  // (src op dst) * src_factor
        }
    }
    // General: func(src * sf, dst * df), with lp_build_add/sub/min/max's identical-operand shortcuts.
    const float st = mulv(s, vs, sfv);
    const float dt = mulv(d, vd, dfv);
    if (vs == VecConst::Zero && vd == VecConst::Zero) {
        // both terms are the same zero constant: add/sub/min/max all return it
        return 0.0f;
    }
    if (op == BlendOp::Add) {
        if (vs == VecConst::Zero) return dt;  // add(zero, b) = b
        if (vd == VecConst::Zero) return st;
    }
    if ((op == BlendOp::Subtract) && vd == VecConst::Zero) return st;         // sub(a, zero) = a
    if ((op == BlendOp::ReverseSubtract) && vs == VecConst::Zero) return dt;  // sub(b, zero) = b
    return funcf(p, op, st, dt);
}

void blend_float(const PipeBlend& b, const FormatInfo& fi, const PxF& p, float out[4], bool fused) {
    const int n = fi.channels;
    const bool rgb_alpha_same = (b.rgb_src == b.rgb_dst && b.a_src == b.a_dst) || n == 1;
    const VecConst vs = vec_const(b.rgb_src, b.a_src, fi.has_alpha);
    const VecConst vd = vec_const(b.rgb_dst, b.a_dst, fi.has_alpha);
    const bool separate_alpha = b.rgb_op != b.a_op && n > 1 && fi.has_alpha;
    for (int c = 0; c < n; ++c) {
        const bool alpha_chan = fi.has_alpha && c == 3;
        const PipeFactor sf = alpha_chan ? b.a_src : b.rgb_src;
        const PipeFactor df = alpha_chan ? b.a_dst : b.rgb_dst;
        if (alpha_chan && separate_alpha) {
            out[c] = blend_call_f(p, fi, b.a_op, b.a_src, b.a_dst, vs, vd, rgb_alpha_same, c, sf, df, true, fused);
        } else {
            out[c] = blend_call_f(p, fi, b.rgb_op, b.rgb_src, b.rgb_dst, vs, vd, rgb_alpha_same, c, sf, df, alpha_chan,
                                  fused);
        }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Storage

void load_u8(const FormatInfo& fi, const uint8_t* px, uint8_t rgba[4]) {
    rgba[0] = rgba[1] = rgba[2] = 0;
    rgba[3] = 255;
    for (int i = 0; i < fi.channels; ++i) rgba[mem_to_rgba(fi, i)] = px[i];
}

void store_u8(const FormatInfo& fi, const uint8_t rgba[4], uint8_t mask, uint8_t* px) {
    for (int i = 0; i < fi.channels; ++i) {
        const int c = mem_to_rgba(fi, i);
        if (mask & (1u << c)) px[i] = rgba[c];
    }
}

void load_f(const FormatInfo& fi, const uint8_t* px, float rgba[4], bool fused) {
    rgba[0] = rgba[1] = rgba[2] = 0.0f;
    rgba[3] = 1.0f;
    for (int i = 0; i < fi.channels; ++i) {
        const int c = mem_to_rgba(fi, i);
        switch (fi.kind) {
            case ChannelKind::Srgb8:
                rgba[c] = c == 3 ? unorm8_to_float(px[i]) : srgb8_to_linear(px[i], fused);
                break;
            case ChannelKind::Half: {
                uint16_t h;
                std::memcpy(&h, px + 2 * i, 2);
                rgba[c] = half_to_float(h);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(&rgba[c], px + 4 * i, 4);
                break;
            case ChannelKind::Unorm8:
                rgba[c] = unorm8_to_float(px[i]);
                break;
        }
    }
}

void store_f(const FormatInfo& fi, const float rgba[4], uint8_t mask, uint8_t* px, bool fused) {
    for (int i = 0; i < fi.channels; ++i) {
        const int c = mem_to_rgba(fi, i);
        if (!(mask & (1u << c))) continue;
        switch (fi.kind) {
            case ChannelKind::Srgb8:
                px[i] = c == 3 ? srgb_alpha_to_u8(rgba[c]) : linear_to_srgb8(rgba[c], fused);
                break;
            case ChannelKind::Half: {
                const uint16_t h = float_to_half_rz(rgba[c]);
                std::memcpy(px + 2 * i, &h, 2);
                break;
            }
            case ChannelKind::Float32:
                std::memcpy(px + 4 * i, &rgba[c], 4);
                break;
            case ChannelKind::Unorm8:
                px[i] = float_to_unorm8(rgba[c]);
                break;
        }
    }
}

uint8_t format_write_mask(const FormatInfo& fi, uint8_t m) {
    uint8_t present = 0;
    if (fi.has_alpha)
        present = 0xf;
    else
        present = uint8_t((1u << fi.channels) - 1);
    return uint8_t(m & present);
}

}  // namespace

uint8_t lerp8(uint8_t x, uint8_t v0, uint8_t v1) {
    // x' = x + (x >> 7) maps 255 to 256; pmulhrsw(a, b) = (a*b + 2^14) >> 15 on int16; the add wraps in 8 bits
    const int32_t xs = int32_t(x) + (x >> 7);
    const int16_t delta = int16_t(int32_t(v1) - int32_t(v0));
    const int16_t b = int16_t(delta * 128);
    const int16_t r = int16_t((xs * int32_t(b) + 0x4000) >> 15);
    return uint8_t((v0 + (r & 0xff)) & 0xff);
}

bool blend_supported(const BlendAttachment& a) {
    if (!a.blend_enable) return true;
    return to_pipe(a.src_color) != kUnsupported && to_pipe(a.dst_color) != kUnsupported &&
           to_pipe(a.src_alpha) != kUnsupported && to_pipe(a.dst_alpha) != kUnsupported;
}

namespace {

// Everything blend_pixel derives from the state alone, computed once per block instead of once per pixel.
struct PreparedBlend {
    FormatInfo fi;
    uint8_t wmask;  // write mask restricted to the format's channels
    bool blend;
    PipeBlend pb;   // lowered state (valid when blend)
    uint8_t k8[4];  // UNORM8 constants
    float kf[4];    // float constants (sRGB: clamped)
    bool ftz;
};

PreparedBlend prepare_blend(const BlendAttachment& a, ColorFormat f, const float constants[4],
                            const BlendOptions& opt) {
    PreparedBlend pr{};
    pr.fi = format_info(f);
    pr.wmask = format_write_mask(pr.fi, a.write_mask);
    pr.blend = a.blend_enable;
    if (pr.blend) pr.pb = lower(a, pr.fi);
    pr.ftz = pr.fi.kind != ChannelKind::Half;  // half targets run with denormals enabled (lp_build_fpstate)
    for (int c = 0; c < 4; ++c) {
        pr.k8[c] = float_to_unorm8(constants[c], opt.unorm_path);
        // constants: lp_build_clamp (min then max) for sRGB
        pr.kf[c] = pr.fi.kind == ChannelKind::Srgb8 ? sse_max(sse_min(constants[c], 1.0f), 0.0f) : constants[c];
    }
    return pr;
}

void blend_prepared(const PreparedBlend& pr, const float src[4], uint8_t* dst, const BlendOptions& opt) {
    const FormatInfo& fi = pr.fi;
    if (fi.kind == ChannelKind::Unorm8) {
        Px8 p;
        for (int c = 0; c < 4; ++c) {
            p.s[c] = float_to_unorm8(src[c], opt.unorm_path);
            p.k[c] = pr.k8[c];
        }
        p.sa = p.s[3];
        p.ka = p.k[3];
        uint8_t out[4] = {p.s[0], p.s[1], p.s[2], p.s[3]};
        if (pr.blend) {
            load_u8(fi, dst, p.d);
            blend_unorm8(pr.pb, fi, p, out);
        }
        store_u8(fi, out, pr.wmask, dst);
        return;
    }
    PxF p;
    p.ftz = pr.ftz;
    for (int c = 0; c < 4; ++c) {
        p.s[c] = src[c];
        p.k[c] = pr.kf[c];
        if (fi.kind == ChannelKind::Srgb8) {
            // sources: clamp_zero_one_nanzero
            float s = src[c] > 0.0f ? src[c] : 0.0f;
            p.s[c] = sse_min(s, 1.0f);
        }
    }
    p.sa = p.s[3];
    p.ka = p.k[3];
    float out[4] = {p.s[0], p.s[1], p.s[2], p.s[3]};
    if (pr.blend) {
        load_f(fi, dst, p.d, opt.fused);
        blend_float(pr.pb, fi, p, out, opt.fused);
    }
    // Masked-out channels keep their stored bits (lavapipe re-encodes the decoded dst; the round trip is exact,
    // see the sRGB round-trip test).
    store_f(fi, out, pr.wmask, dst, opt.fused);
}

// Opaque RGBA8/BGRA8 UNORM write of every channel: the bytes are the converted source, nothing is read.
void store_rgba8_block(bool bgra, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block, size_t pitch,
                       UnormPath path) {
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(lane_mask & (1u << l))) continue;
        uint8_t* px = block + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * 4;
        const uint8_t r = float_to_unorm8(src[0][l], path), g = float_to_unorm8(src[1][l], path),
                      b = float_to_unorm8(src[2][l], path), a = float_to_unorm8(src[3][l], path);
        px[0] = bgra ? b : r;
        px[1] = g;
        px[2] = bgra ? r : b;
        px[3] = a;
    }
}

}  // namespace

void blend_pixel(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4], uint8_t* dst,
                 const BlendOptions& opt) {
    const PreparedBlend pr = prepare_blend(a, f, constants, opt);
    if (pr.wmask == 0) return;
    blend_prepared(pr, src, dst, opt);
}

void blend_block(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4][kBlockLanes],
                 uint16_t lane_mask, uint8_t* block, size_t pitch, const BlendOptions& opt) {
    const PreparedBlend pr = prepare_blend(a, f, constants, opt);
    if (pr.wmask == 0 || lane_mask == 0) return;
    if (pr.fi.kind == ChannelKind::Unorm8 && !pr.blend && pr.fi.channels == 4 && pr.wmask == 0xf) {
        store_rgba8_block(pr.fi.bgra, src, lane_mask, block, pitch, opt.unorm_path);
        return;
    }
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(lane_mask & (1u << l))) continue;
        const float s[4] = {src[0][l], src[1][l], src[2][l], src[3][l]};
        uint8_t* px = block + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * pr.fi.bytes;
        blend_prepared(pr, s, px, opt);
    }
}

// ---------------------------------------------------------------------------------------------------------------
// RGBA8 / BGRA8, 16 pixels at once

Rgba8Blend prepare_rgba8_blend(const BlendAttachment& a, ColorFormat f, const float constants[4],
                               const BlendOptions& opt) {
    Rgba8Blend b;
    if ((f != ColorFormat::R8G8B8A8_UNORM && f != ColorFormat::B8G8R8A8_UNORM) || opt.unorm_path != UnormPath::Avx8 ||
        !blend_supported(a))
        return b;
    const PreparedBlend pr = prepare_blend(a, f, constants, opt);
    b.ok = true;
    b.bgra = pr.fi.bgra;
    b.blend = pr.blend;
    if (pr.blend) {
        b.rgb_src = pr.pb.rgb_src;
        b.rgb_dst = pr.pb.rgb_dst;
        b.a_src = pr.pb.a_src;
        b.a_dst = pr.pb.a_dst;
        b.rgb_op = pr.pb.rgb_op;
        b.a_op = pr.pb.a_op;
    }
    for (int i = 0; i < 4; ++i) {
        const int c = mem_to_rgba(pr.fi, i);
        b.k[i] = pr.k8[c];
        if (pr.wmask & (1u << c)) b.wmask_mem |= uint8_t(1u << i);
    }
    return b;
}

#if TILEVK_SIMD_AVX2
namespace {

// mul_norm8 on 32 bytes: p = a*b; p += p >> 8; p += 0x80; p >> 8, in 16-bit lanes.
inline __m256i mul_norm_epu8(__m256i a, __m256i b) {
    const __m256i zero = _mm256_setzero_si256(), half = _mm256_set1_epi16(0x80);
    auto part = [&](__m256i x, __m256i y) {
        __m256i p = _mm256_mullo_epi16(x, y);
        p = _mm256_add_epi16(p, _mm256_srli_epi16(p, 8));
        return _mm256_srli_epi16(_mm256_add_epi16(p, half), 8);
    };
    const __m256i lo = part(_mm256_unpacklo_epi8(a, zero), _mm256_unpacklo_epi8(b, zero));
    const __m256i hi = part(_mm256_unpackhi_epi8(a, zero), _mm256_unpackhi_epi8(b, zero));
    return _mm256_packus_epi16(lo, hi);
}

// factor8 for every byte: `alpha` selects the alpha channel's rules (SRC_ALPHA_SATURATE is ONE there).
inline __m256i factor_epu8(uint8_t f, bool alpha, __m256i s, __m256i d, __m256i k) {
    const __m256i ones = _mm256_set1_epi8(-1);
    const __m256i bcast_alpha = _mm256_setr_epi8(3, 3, 3, 3, 7, 7, 7, 7, 11, 11, 11, 11, 15, 15, 15, 15, 3, 3, 3, 3, 7,
                                                 7, 7, 7, 11, 11, 11, 11, 15, 15, 15, 15);
    switch (PipeFactor(f)) {
        case kZero:
            return _mm256_setzero_si256();
        case kOne:
            return ones;
        case kSrcColor:
            return s;
        case kSrcAlpha:
            return _mm256_shuffle_epi8(s, bcast_alpha);
        case kDstColor:
            return d;
        case kDstAlpha:
            return _mm256_shuffle_epi8(d, bcast_alpha);
        case kSrcAlphaSat:
            // min(src alpha, 255 - dst alpha)
            if (alpha) return ones;
            return _mm256_min_epu8(_mm256_shuffle_epi8(s, bcast_alpha),
                                   _mm256_xor_si256(_mm256_shuffle_epi8(d, bcast_alpha), ones));
        case kConstColor:
            return k;
        case kConstAlpha:
            return _mm256_shuffle_epi8(k, bcast_alpha);
        case kInvSrcColor:
            return _mm256_xor_si256(s, ones);  // 255 - x
        case kInvSrcAlpha:
            return _mm256_xor_si256(_mm256_shuffle_epi8(s, bcast_alpha), ones);
        case kInvDstColor:
            return _mm256_xor_si256(d, ones);
        case kInvDstAlpha:
            return _mm256_xor_si256(_mm256_shuffle_epi8(d, bcast_alpha), ones);
        case kInvConstColor:
            return _mm256_xor_si256(k, ones);
        case kInvConstAlpha:
            return _mm256_xor_si256(_mm256_shuffle_epi8(k, bcast_alpha), ones);
        default:
            return _mm256_setzero_si256();
    }
}

// func8 on bytes: saturating add / subtract, min, max.
inline __m256i op_epu8(BlendOp op, __m256i a, __m256i b) {
    switch (op) {
        case BlendOp::Add:
            return _mm256_adds_epu8(a, b);
        case BlendOp::Subtract:
            return _mm256_subs_epu8(a, b);
        case BlendOp::ReverseSubtract:
            return _mm256_subs_epu8(b, a);
        case BlendOp::Min:
            return _mm256_min_epu8(a, b);
        case BlendOp::Max:
            return _mm256_max_epu8(a, b);
    }
    return a;
}

// Bytes of the channels in `mem_mask` (bit i = memory channel i) of every pixel.
inline __m256i channel_bytes(uint8_t mem_mask) {
    uint32_t word = 0;
    for (int i = 0; i < 4; ++i)
        if (mem_mask & (1u << i)) word |= 0xffu << (8 * i);
    return _mm256_set1_epi32(int(word));
}

}  // namespace
#endif

bool blend_rgba8_block(const Rgba8Blend& b, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block,
                       size_t pitch) {
#if TILEVK_SIMD_AVX2
    __m128i rows[4];
    detail::pack_rgba8_rows(b.bgra, src, rows);
    const uint32_t raster = lanes_to_raster(lane_mask);
    const __m256i k = _mm256_set1_epi32(
        int(uint32_t(b.k[0]) | uint32_t(b.k[1]) << 8 | uint32_t(b.k[2]) << 16 | uint32_t(b.k[3]) << 24));
    const __m256i alpha_bytes = channel_bytes(0x8), write_bytes = channel_bytes(b.wmask_mem);
    for (int pair = 0; pair < 2; ++pair) {
        const uint32_t pixels = (raster >> (8 * pair)) & 0xffu;  // rows 2*pair and 2*pair+1, 4 pixels each
        if (!pixels) continue;
        uint8_t* row0 = block + size_t(2 * pair) * pitch;
        uint8_t* row1 = row0 + pitch;
        const __m256i s = _mm256_set_m128i(rows[2 * pair + 1], rows[2 * pair]);
        const __m256i d = _mm256_set_m128i(_mm_loadu_si128(reinterpret_cast<const __m128i*>(row1)),
                                           _mm_loadu_si128(reinterpret_cast<const __m128i*>(row0)));
        __m256i res = s;
        if (b.blend) {
            // per channel: func(mul_norm(s, src factor), mul_norm(d, dst factor)), the alpha channel by its own rules
            const __m256i sf = _mm256_blendv_epi8(factor_epu8(b.rgb_src, false, s, d, k),
                                                  factor_epu8(b.a_src, true, s, d, k), alpha_bytes);
            const __m256i df = _mm256_blendv_epi8(factor_epu8(b.rgb_dst, false, s, d, k),
                                                  factor_epu8(b.a_dst, true, s, d, k), alpha_bytes);
            const __m256i st = mul_norm_epu8(s, sf), dt = mul_norm_epu8(d, df);
            res = _mm256_blendv_epi8(op_epu8(b.rgb_op, st, dt), op_epu8(b.a_op, st, dt), alpha_bytes);
        }
        const __m256i keep = _mm256_and_si256(write_bytes, detail::lane_mask8(pixels));
        res = _mm256_blendv_epi8(d, res, keep);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row0), _mm256_castsi256_si128(res));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row1), _mm256_extracti128_si256(res, 1));
    }
    return true;
#else
    (void)b, (void)src, (void)lane_mask, (void)block, (void)pitch;
    return false;
#endif
}

}  // namespace tilevk::rast::fragment
