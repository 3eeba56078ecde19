#include "rast/fragment/blend.h"

#include <cmath>
#include <cstring>

#include "rast/fragment/blend_codes.h"
#include "rast/fragment/block_kernels.h"

namespace tilevk::rast::fragment {

namespace {

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
        case BlendFactor::Src1Color:
            return kSrc1Color;
        case BlendFactor::OneMinusSrc1Color:
            return kInvSrc1Color;
        case BlendFactor::Src1Alpha:
            return kSrc1Alpha;
        case BlendFactor::OneMinusSrc1Alpha:
            return kInvSrc1Alpha;
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
        // clamped_zero: neither a float nor an SNORM format
        const bool clamped_zero = fi.kind != ChannelKind::Half && fi.kind != ChannelKind::Float32 &&
                                  fi.kind != ChannelKind::Ufloat11 && fi.kind != ChannelKind::Snorm8 &&
                                  fi.kind != ChannelKind::Snorm16 && fi.kind != ChannelKind::PackedSnorm;
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
inline uint32_t bits_of(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
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
// Integer blend types: UNORM8 (8 bits) and the 16-bit normalized ones (UNORM16, 2_10_10_10 widened to 16 bits);
// the narrow packs (565, 4444, 5551) blend in 8 bits like UNORM8 (texel_codec.h, "integer blend types").

template <int N>
struct PxN {
    static constexpr uint32_t kMax = (1u << N) - 1u;
    uint32_t s[4], d[4], k[4];  // src, dst, constant (RGBA order; d[3] valid only with alpha)
    uint32_t s1[4];             // the second source (dual-source blending), converted as src
    uint32_t sa, ka, s1a;
};

// lp_build_mul_norm: p = a*b; p += p >> N; p += 2^(N-1); p >> N
template <int N>
constexpr uint32_t mul_norm(uint32_t a, uint32_t b) {
    uint32_t p = a * b;
    p += p >> N;
    p += 1u << (N - 1);
    return p >> N;
}

// lp_build_lerp on a normalized type: 8 bits through PMULHRSW (lerp8); 16 bits widened to 32:
// v0 + ((x + (x >> 15)) * (v1 - v0)) >> 16, the product and the sum wrapping like the vector lanes.
template <int N>
uint32_t lerp_norm(uint32_t x, uint32_t v0, uint32_t v1) {
    if constexpr (N == 8) {
        return lerp8(uint8_t(x), uint8_t(v0), uint8_t(v1));
    } else {
        const uint32_t xs = x + (x >> 15);
        const uint32_t prod = xs * (v1 - v0);  // mod 2^32, as the 32-bit lanes
        return (v0 + (prod >> 16)) & 0xffffu;
    }
}

template <int N>
[[gnu::always_inline]] inline uint32_t factor_n(PipeFactor f, int c, bool alpha_chan, bool has_alpha, const PxN<N>& p) {
    constexpr uint32_t kMax = PxN<N>::kMax;
    switch (f) {
        case kZero:
            return 0;
        case kOne:
            return kMax;
        case kSrcColor:
            return p.s[c];
        case kSrcAlpha:
            return p.sa;
        case kDstColor:
            return p.d[c];
        case kDstAlpha:
            return p.d[3];
        case kSrcAlphaSat:
            if (alpha_chan) return kMax;
            if (!has_alpha) return 0;
            return p.sa < kMax - p.d[3] ? p.sa : kMax - p.d[3];
        case kConstColor:
            return p.k[c];
        case kConstAlpha:
            return p.ka;
        case kInvSrcColor:
            return kMax - p.s[c];
        case kInvSrcAlpha:
            return kMax - p.sa;
        case kInvDstColor:
            return kMax - p.d[c];
        case kInvDstAlpha:
            return kMax - p.d[3];
        case kInvConstColor:
            return kMax - p.k[c];
        case kInvConstAlpha:
            return kMax - p.ka;
        case kSrc1Color:
            return p.s1[c];
        case kSrc1Alpha:
            return p.s1a;
        case kInvSrc1Color:
            return kMax - p.s1[c];
        case kInvSrc1Alpha:
            return kMax - p.s1a;
        default:
            return 0;
    }
}

template <int N>
[[gnu::always_inline]] inline uint32_t func_n(BlendOp op, uint32_t a, uint32_t b) {
    constexpr uint32_t kMax = PxN<N>::kMax;
    switch (op) {
        case BlendOp::Add:
            return a + b > kMax ? kMax : a + b;  // uadd.sat
        case BlendOp::Subtract:
            return a > b ? a - b : 0;  // usub.sat
        case BlendOp::ReverseSubtract:
            return b > a ? b - a : 0;
        case BlendOp::Min:
            return a < b ? a : b;
        case BlendOp::Max:
            return a > b ? a : b;
    }
    return 0;
}

// `n` colour channels, RGBA indices 0..n-1 (every channel when the format has alpha).
template <int N>
void blend_norm(const PipeBlend& b, const FormatInfo& fi, int n, const PxN<N>& p, uint32_t out[4]) {
    // Single-channel targets: lavapipe's "not alpha dependent" lerp for complementary factors with ADD.
    if (n == 1 && b.rgb_op == BlendOp::Add && complementary(b.rgb_src, b.rgb_dst)) {
        if (b.rgb_src < b.rgb_dst)
            out[0] = lerp_norm<N>(factor_n<N>(b.rgb_src, 0, false, false, p), p.d[0], p.s[0]);
        else
            out[0] = lerp_norm<N>(factor_n<N>(b.rgb_dst, 0, false, false, p), p.s[0], p.d[0]);
        return;
    }
    for (int c = 0; c < n; ++c) {
        const bool alpha_chan = fi.has_alpha && c == 3;
        const PipeFactor sf = alpha_chan ? b.a_src : b.rgb_src;
        const PipeFactor df = alpha_chan ? b.a_dst : b.rgb_dst;
        const BlendOp op = alpha_chan ? b.a_op : b.rgb_op;
        const uint32_t st = mul_norm<N>(p.s[c], factor_n<N>(sf, c, alpha_chan, fi.has_alpha, p));
        const uint32_t dt = mul_norm<N>(p.d[c], factor_n<N>(df, c, alpha_chan, fi.has_alpha, p));
        out[c] = func_n<N>(op, st, dt);
    }
}

// The number of colour channels a format blends (RGBA indices 0..n-1).
inline int colour_channels(const FormatInfo& fi) {
    return fi.has_alpha ? 4 : fi.channels;
}

// A logic op on one channel of an integer blend type of `bits` bits (lp_build_logicop on the lanes' bits).
inline uint32_t logic_op_bits(LogicOp op, uint32_t s, uint32_t d, int bits) {
    const uint32_t mask = bits >= 32 ? 0xffffffffu : (1u << bits) - 1u;
    uint32_t r = 0;
    for (int byte = 0; byte < 4; ++byte)
        r |= uint32_t(logic_op8(op, uint8_t(s >> (8 * byte)), uint8_t(d >> (8 * byte)))) << (8 * byte);
    return r & mask;
}

// ---------------------------------------------------------------------------------------------------------------
// Float (sRGB, half, float32)

struct PxF {
    float s[4], d[4], k[4];
    float s1[4];  // the second source (dual-source blending)
    float sa, ka, s1a;
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
        case kSrc1Color:
            return p.s1[c];
        case kSrc1Alpha:
            return p.s1a;
        case kInvSrc1Color:
            return fsub(p, 1.0f, p.s1[c]);
        case kInvSrc1Alpha:
            return fsub(p, 1.0f, p.s1a);
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

// Stored pixels are read and written by the texel codec: UNORM8 bytes as they are (load_unorm8/store_unorm8),
// sRGB/half/float through decode_color (the blend destination read) and encode_color (the fragment output).

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

bool uses_second_source(const BlendAttachment& a) {
    if (!a.blend_enable || a.logic_op_enable) return false;
    auto dual = [](BlendFactor f) { return f >= BlendFactor::Src1Color && f <= BlendFactor::OneMinusSrc1Alpha; };
    return dual(a.src_color) || dual(a.dst_color) || dual(a.src_alpha) || dual(a.dst_alpha);
}

namespace {

// Everything blend_pixel derives from the state alone, computed once per block instead of once per pixel.
struct PreparedBlend {
    const FormatInfo* fi;
    uint8_t wmask;  // write mask restricted to the format's channels
    bool blend;
    bool logic;    // logic_op_enable on a target with an integer blend type
    int int_bits;  // the integer blend type's bits (format::blend_type_bits), 0: float blending
    LogicOp logic_op;
    PipeBlend pb;    // lowered state (valid when blend)
    uint8_t k8[4];   // UNORM8 constants
    uint32_t kn[4];  // constants in the integer blend type
    float kf[4];     // float constants (sRGB: clamped)
    bool ftz;
};

PreparedBlend prepare_blend(const BlendAttachment& a, ColorFormat f, const float constants[4],
                            const BlendOptions& opt) {
    PreparedBlend pr{};
    pr.fi = &format_info(f);
    pr.wmask = format_write_mask(*pr.fi, a.write_mask);
    pr.int_bits = format::blend_type_bits(*pr.fi);
    // A logic op disables blending on every target; it combines the bits of targets with an integer blend type
    // (lp_bld_blend_aos.c: "if (!type.floating)"), float targets take the source. Only UNORM kinds blend (lavapipe
    // reports no COLOR_ATTACHMENT_BLEND for SNORM and integer formats).
    const bool unorm = pr.fi->kind == ChannelKind::Unorm8 || pr.fi->kind == ChannelKind::Unorm16 ||
                       pr.fi->kind == ChannelKind::PackedUnorm;
    pr.blend = a.blend_enable && !a.logic_op_enable && (unorm || pr.int_bits == 0);
    pr.logic = a.logic_op_enable && pr.int_bits != 0;
    pr.logic_op = a.logic_op;
    if (pr.blend) pr.pb = lower(a, *pr.fi);
    // half and B10G11R11 targets run with denormals enabled (lp_build_fpstate around small-float formats)
    pr.ftz = pr.fi->kind != ChannelKind::Half && pr.fi->kind != ChannelKind::Ufloat11;
    for (int c = 0; c < 4; ++c) {
        pr.k8[c] = float_to_unorm8(constants[c], opt.unorm_path);
        if (pr.int_bits) pr.kn[c] = format::output_to_blend_type(*pr.fi, bits_of(constants[c]), opt.unorm_path);
        // constants: lp_build_clamp (min then max) for sRGB
        pr.kf[c] = pr.fi->kind == ChannelKind::Srgb8 ? sse_max(sse_min(constants[c], 1.0f), 0.0f) : constants[c];
    }
    return pr;
}

template <int N>
void blend_norm_pixel(const PreparedBlend& pr, const uint32_t s[4], const uint32_t s1[4], const uint32_t d[4],
                      uint32_t out[4]) {
    PxN<N> p;
    for (int c = 0; c < 4; ++c) {
        p.s[c] = s[c];
        p.s1[c] = s1[c];
        p.d[c] = d[c];
        p.k[c] = pr.kn[c];
    }
    p.sa = p.s[3];
    p.s1a = p.s1[3];
    p.ka = p.k[3];
    blend_norm<N>(pr.pb, *pr.fi, colour_channels(*pr.fi), p, out);
}

// Targets with an integer blend type other than UNORM8: the source in the blend type, the stored texel widened to
// it, blend or logic op, the write mask selecting the stored value, and every channel narrowed back.
void blend_int_prepared(const PreparedBlend& pr, const float src[4], const float src1[4], uint8_t* dst,
                        const BlendOptions& opt) {
    const FormatInfo& fi = *pr.fi;
    uint32_t s[4], s1[4], d[4], out[4];
    for (int c = 0; c < 4; ++c) {
        s[c] = out[c] = format::output_to_blend_type(fi, bits_of(src[c]), opt.unorm_path);
        s1[c] = format::output_to_blend_type(fi, bits_of(src1[c]), opt.unorm_path);
    }
    format::load_blend_type(fi, dst, d);
    if (pr.blend) {
        if (pr.int_bits == 8)
            blend_norm_pixel<8>(pr, s, s1, d, out);
        else
            blend_norm_pixel<16>(pr, s, s1, d, out);
    } else if (pr.logic) {
        for (int c = 0; c < 4; ++c) out[c] = logic_op_bits(pr.logic_op, s[c], d[c], pr.int_bits);
    }
    for (int c = 0; c < 4; ++c)
        if (!(pr.wmask & (1u << c))) out[c] = d[c];
    format::store_blend_type(fi, out, dst);
}

// src1: the second source of dual-source blending (kZeroSource when the state has no SRC1 factor).
void blend_prepared(const PreparedBlend& pr, const float src[4], const float src1[4], uint8_t* dst,
                    const BlendOptions& opt) {
    const FormatInfo& fi = *pr.fi;
    if (fi.kind == ChannelKind::Unorm8) {
        PxN<8> p;
        for (int c = 0; c < 4; ++c) {
            p.s[c] = float_to_unorm8(src[c], opt.unorm_path);
            p.s1[c] = float_to_unorm8(src1[c], opt.unorm_path);
            p.k[c] = pr.k8[c];
        }
        p.sa = p.s[3];
        p.s1a = p.s1[3];
        p.ka = p.k[3];
        uint32_t out[4] = {p.s[0], p.s[1], p.s[2], p.s[3]};
        if (pr.blend || pr.logic) {
            uint8_t d8[4];
            format::load_unorm8(fi, dst, d8);
            for (int c = 0; c < 4; ++c) p.d[c] = d8[c];
        }
        if (pr.blend) {
            blend_norm<8>(pr.pb, fi, fi.channels, p, out);
        } else if (pr.logic) {
            for (int c = 0; c < 4; ++c) out[c] = logic_op8(pr.logic_op, uint8_t(p.s[c]), uint8_t(p.d[c]));
        }
        const uint8_t out8[4] = {uint8_t(out[0]), uint8_t(out[1]), uint8_t(out[2]), uint8_t(out[3])};
        format::store_unorm8(fi, out8, dst, pr.wmask);
        return;
    }
    if (pr.int_bits) return blend_int_prepared(pr, src, src1, dst, opt);
    PxF p;
    p.ftz = pr.ftz;
    for (int c = 0; c < 4; ++c) {
        p.s[c] = src[c];
        p.s1[c] = src1[c];
        p.k[c] = pr.kf[c];
        if (fi.kind == ChannelKind::Srgb8) {
            // both sources: clamp_zero_one_nanzero
            p.s[c] = sse_min(src[c] > 0.0f ? src[c] : 0.0f, 1.0f);
            p.s1[c] = sse_min(src1[c] > 0.0f ? src1[c] : 0.0f, 1.0f);
        }
    }
    p.sa = p.s[3];
    p.s1a = p.s1[3];
    p.ka = p.k[3];
    float out[4] = {p.s[0], p.s[1], p.s[2], p.s[3]};
    if (pr.blend) {
        format::decode_color(fi, dst, p.d, opt.fused);
        blend_float(pr.pb, fi, p, out, opt.fused);
    }
    // Masked-out channels keep their stored bits (lavapipe re-encodes the decoded dst; the round trip is exact,
    // see the sRGB round-trip test).
    format::encode_color(fi, out, dst, opt.fused, UnormPath::Avx8, pr.wmask);
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
    static constexpr float kZeroSource[4] = {};
    blend_prepared(pr, src, kZeroSource, dst, opt);
}

void blend_block(const BlendAttachment& a, ColorFormat f, const float constants[4], const float src[4][kBlockLanes],
                 uint16_t lane_mask, uint8_t* block, size_t pitch, const BlendOptions& opt,
                 const float (*src1)[kBlockLanes]) {
    const PreparedBlend pr = prepare_blend(a, f, constants, opt);
    if (pr.wmask == 0 || lane_mask == 0) return;
    if (pr.fi->kind == ChannelKind::Unorm8 && !pr.blend && !pr.logic && pr.fi->channels == 4 && pr.wmask == 0xf) {
        store_rgba8_block(pr.fi->bgra, src, lane_mask, block, pitch, opt.unorm_path);
        return;
    }
    for (int l = 0; l < kBlockLanes; ++l) {
        if (!(lane_mask & (1u << l))) continue;
        const float s[4] = {src[0][l], src[1][l], src[2][l], src[3][l]};
        float s1[4] = {};
        if (src1)
            for (int c = 0; c < 4; ++c) s1[c] = src1[c][l];
        uint8_t* px = block + size_t(lane_y(l)) * pitch + size_t(lane_x(l)) * pr.fi->bytes;
        blend_prepared(pr, s, s1, px, opt);
    }
}

// ---------------------------------------------------------------------------------------------------------------
// RGBA8 / BGRA8, 16 pixels at once

Rgba8Blend prepare_rgba8_blend(const BlendAttachment& a, ColorFormat f, const float constants[4],
                               const BlendOptions& opt) {
    Rgba8Blend b;
    if ((f != ColorFormat::R8G8B8A8_UNORM && f != ColorFormat::B8G8R8A8_UNORM) || opt.unorm_path != UnormPath::Avx8 ||
        uses_second_source(a) || a.logic_op_enable)
        return b;
    const PreparedBlend pr = prepare_blend(a, f, constants, opt);
    b.ok = true;
    b.bgra = pr.fi->bgra;
    b.blend = pr.blend;
    if (pr.blend) {
        b.rgb_src = pr.pb.rgb_src;
        b.rgb_dst = pr.pb.rgb_dst;
        b.a_src = pr.pb.a_src;
        b.a_dst = pr.pb.a_dst;
        b.rgb_op = pr.pb.rgb_op;
        b.a_op = pr.pb.a_op;
        b.over = b.rgb_src == kSrcAlpha && b.a_src == kSrcAlpha && b.rgb_dst == kInvSrcAlpha &&
                 b.a_dst == kInvSrcAlpha && b.rgb_op == BlendOp::Add && b.a_op == BlendOp::Add;
    }
    for (int i = 0; i < 4; ++i) {
        const int c = mem_to_rgba(*pr.fi, i);
        b.k[i] = pr.k8[c];
        if (pr.wmask & (1u << c)) b.wmask_mem |= uint8_t(1u << i);
    }
    return b;
}

}  // namespace tilevk::rast::fragment
