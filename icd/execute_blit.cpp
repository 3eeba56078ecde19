// vkCmdBlitImage: recording, and execution as lavapipe 22.3 computes it (see execute_blit.h and icd/README.md).
//
// lavapipe (lvp_execute.c handle_blit_image) turns each region into a pipe_blit_info: the destination box is made
// positive (x = min of the two offsets) and a mirror becomes a negative SOURCE width; array layers are the box's z.
// llvmpipe's lp_blit then copies (same format, 1:1, NEAREST) or runs util_blitter_blit_generic, which draws the
// destination box as a triangle fan of two triangles with a pass-through vertex shader and a fragment shader that
// samples the source. Everything below follows that draw: the vertex positions the blitter computes in C, the
// viewport transform of draw's JIT, llvmpipe's fixed-point setup and edge tests (the blitter's rasterizer state
// uses the bottom-left fill rule), the attribute planes of lp_state_setup.c, the per-pixel interpolation of
// lp_bld_interp.c, the sampler (lp_bld_sample_aos.c for 8-bit UNORM, lp_bld_sample_soa.c otherwise) and the
// fragment output conversions (rast/fragment/color.h).
#include "execute_blit.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "command_buffer.h"
#include "entrypoints.h"
#include "image.h"
#include "rast/fragment/color.h"
#include "rast/geometry/viewport.h"
#include "shader/texture_fixed8.h"

namespace tilevk::icd {

namespace fragment = rast::fragment;

namespace {
float fmuladd(float a, float b, float c, bool fused) {
    return fused ? std::fma(a, b, c) : a * b + c;
}
}  // namespace

// ---- recording ----------------------------------------------------------------------------------------------------
VKAPI_ATTR void VKAPI_CALL tvk_CmdBlitImage(VkCommandBuffer commandBuffer, VkImage srcImage, VkImageLayout,
                                            VkImage dstImage, VkImageLayout, uint32_t regionCount,
                                            const VkImageBlit* pRegions, VkFilter filter) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    if (auto* c = cb->append<CmdBlitImage>()) {
        c->src = from_handle<Image>(srcImage);
        c->dst = from_handle<Image>(dstImage);
        c->count = regionCount;
        c->regions = cb->copy(pRegions, regionCount);
        c->filter = filter;
    }
}

bool blit_supported(const FormatInfo& f) {
    switch (f.pack) {
        case PackKind::kUnorm8:
        case PackKind::kSrgb8:
        case PackKind::kFloat16:
        case PackKind::kFloat32:
        case PackKind::kD16:
        case PackKind::kD32F:
            return true;
        default:
            return false;
    }
}

bool blit_linear_supported(const FormatInfo& f) {
    return blit_supported(f) && (f.aspects & VK_IMAGE_ASPECT_COLOR_BIT);
}

namespace blit {
namespace {

// cvtps2dq under the default rounding mode (nearest-even); NaN/out of range give INT32_MIN.
int32_t rne_i32(float x) {
    return shader::fixed8::iround(x);
}

struct Vertex {
    float x, y, s, t;
};

// The attribute planes of lp_state_setup.c (init_args, calc_coef4) from the float window coordinates of (v0, v1, v2),
// origin at pixel (0,0)'s centre; separate (unfused) multiplies and subtractions.
void attrib_planes(const Vertex& v0, const Vertex& v1, const Vertex& v2, AttribPlane& s, AttribPlane& t) {
    const float x0c = v0.x - 0.5f, y0c = v0.y - 0.5f;
    const float dx01 = v0.x - v1.x, dy01 = v0.y - v1.y, dx20 = v2.x - v0.x, dy20 = v2.y - v0.y;
    const float e = dx01 * dy20, f = dy01 * dx20;
    const float ooa = 1.0f / (e - f);
    const float dx20o = dx20 * ooa, dy20o = dy20 * ooa, dx01o = dx01 * ooa, dy01o = dy01 * ooa;
    auto plane = [&](float a0, float a1, float a2) {
        AttribPlane p;
        const float da01 = a0 - a1, da20 = a2 - a0;
        p.dadx = da01 * dy20o - da20 * dy01o;
        p.dady = da20 * dx01o - da01 * dx20o;
        const float dadx_x0 = p.dadx * x0c, dady_y0 = p.dady * y0c;
        p.a0 = a0 - (dadx_x0 + dady_y0);
        return p;
    };
    s = plane(v0.s, v1.s, v2.s);
    t = plane(v0.t, v1.t, v2.t);
}

// util_iround(256 * a): round half away from zero after a float add (lp_setup_rect.c subpixel_snap)
int32_t subpixel_snap(float a) {
    const float f = 256.0f * a;
    return f >= 0.0f ? int32_t(f + 0.5f) : int32_t(f - 0.5f);
}

// The setup of one triangle (lp_setup_tri.c do_triangle_ccw / triangle_both, lp_state_setup.c init_args/calc_coef4).
Triangle setup(Vertex v0, Vertex v1, Vertex v2, uint32_t surf_w, uint32_t surf_h) {
    Triangle tri;
    // snap: X = cvtps2dq(fl(x - 0.5) * 256): the pixel-centre offset moves pixel (px,py)'s centre to (px*256, py*256)
    auto snap = [](float w) { return rne_i32((w - 0.5f) * 256.0f); };
    int32_t x[3] = {snap(v0.x), snap(v1.x), snap(v2.x)}, y[3] = {snap(v0.y), snap(v1.y), snap(v2.y)};
    // area = dx01*dy20 - dx20*dy01 in exact 64-bit fixed point; 0 is dropped, < 0 (cw) is reordered (v1, v0, v2)
    // because the blitter's rasterizer state leaves flatshade_first at 0
    const int64_t area = int64_t(x[0] - x[1]) * int64_t(y[2] - y[0]) - int64_t(x[2] - x[0]) * int64_t(y[0] - y[1]);
    if (area == 0) return tri;
    if (area < 0) {
        std::swap(v0, v1);
        std::swap(x[0], x[1]);
        std::swap(y[0], y[1]);
    }
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const int32_t dy = y[i] - y[j], dx = x[i] - x[j];
        // bottom_edge_rule = 1 (u_blitter's rasterizer state): the bias goes to DY < 0 or (DY == 0 and DX < 0)
        tri.bias[i] = (dy < 0 || (dy == 0 && dx < 0)) ? 1 : 0;
        tri.x[i] = x[i];
        tri.y[i] = y[i];
    }
    // bounding box, inclusive; with the bottom-left rule y is shifted by one fixed-point unit
    const int32_t min_x = std::min({x[0], x[1], x[2]}), max_x = std::max({x[0], x[1], x[2]});
    const int32_t min_y = std::min({y[0], y[1], y[2]}), max_y = std::max({y[0], y[1], y[2]});
    tri.bx0 = std::max(min_x >> 8, 0);
    tri.bx1 = std::min((max_x - 1) >> 8, int32_t(surf_w) - 1);
    tri.by0 = std::max((min_y + 1) >> 8, 0);
    tri.by1 = std::min(max_y >> 8, int32_t(surf_h) - 1);
    attrib_planes(v0, v1, v2, tri.s, tri.t);
    tri.valid = true;
    return tri;
}

}  // namespace

bool Triangle::covers(int32_t px, int32_t py) const {
    if (!valid || px < bx0 || px > bx1 || py < by0 || py > by1) return false;
    const int64_t sx = int64_t(px) * 256, sy = int64_t(py) * 256;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const int64_t dy = int64_t(y[i]) - y[j], dx = int64_t(x[i]) - x[j];
        // E = DY*(x_i - X) - DX*(y_i - Y) + bias > 0
        if (dy * (x[i] - sx) - dx * (y[i] - sy) + bias[i] <= 0) return false;
    }
    return true;
}

bool Quad::texcoord(int32_t px, int32_t py, float& s, float& t) const {
    if (rect) {
        if (px < rx0 || px > rx1 || py < ry0 || py > ry1) return false;
        s = fmuladd(rs.dady, float(py), fmuladd(rs.dadx, float(px), rs.a0, fused), fused);
        t = fmuladd(rt.dady, float(py), fmuladd(rt.dadx, float(px), rt.a0, fused), fused);
        return true;
    }
    for (const Triangle& tr : tri) {
        if (!tr.covers(px, py)) continue;
        // a = fmuladd(dady, py, fmuladd(dadx, px, a0))   (lp_bld_interp.c attribs_update_simple, LINEAR)
        s = fmuladd(tr.s.dady, float(py), fmuladd(tr.s.dadx, float(px), tr.s.a0, fused), fused);
        t = fmuladd(tr.t.dady, float(py), fmuladd(tr.t.dadx, float(px), tr.t.a0, fused), fused);
        return true;
    }
    return false;
}

Quad make_quad(uint32_t surf_w, uint32_t surf_h, int32_t x1, int32_t y1, int32_t x2, int32_t y2, float s1, float t1,
               float s2, float t2, bool fused, bool rect) {
    // blitter_set_rectangle: ndc = fl(fl(fl(x / W) * 2) - 1) in C; viewport scale = translate = 0.5f * W;
    // draw's JIT: window = fmuladd(ndc * (1/w = 1), scale, translate)
    auto window = [fused](int32_t v, uint32_t size) {
        const float ndc = float(v) / float(size) * 2.0f - 1.0f;
        const float half = 0.5f * float(size);
        return fmuladd(ndc, half, half, fused);
    };
    const float wx1 = window(x1, surf_w), wx2 = window(x2, surf_w);
    const float wy1 = window(y1, surf_h), wy2 = window(y2, surf_h);
    const Vertex v0{wx1, wy1, s1, t1}, v1{wx2, wy1, s2, t1}, v2{wx2, wy2, s2, t2}, v3{wx1, wy2, s1, t2};
    Quad q;
    q.fused = fused;
    if (rect) {
        // linear mode (lp_setup_vbuf.c rect -> lp_setup_rect.c): both triangles are cw, do_rect_ccw finds the
        // rectangle and lp_rect_cw sets it up from the corners (v2, v0, v1) with no reorder; coverage is the box
        // of the util_iround-snapped corners (bottom_edge_rule adds 1 to y before the shift)
        q.rect = true;
        attrib_planes(v2, v0, v1, q.rs, q.rt);
        const int32_t sx1 = subpixel_snap(wx1 - 0.5f), sx2 = subpixel_snap(wx2 - 0.5f);
        const int32_t sy1 = subpixel_snap(wy1 - 0.5f), sy2 = subpixel_snap(wy2 - 0.5f);
        q.rx0 = std::max((std::min(sx1, sx2) + 255) >> 8, 0);
        q.rx1 = std::min(((std::max(sx1, sx2) + 255) >> 8) - 1, int32_t(surf_w) - 1);
        q.ry0 = std::max((std::min(sy1, sy2) + 256) >> 8, 0);
        q.ry1 = std::min(((std::max(sy1, sy2) + 256) >> 8) - 1, int32_t(surf_h) - 1);
        return q;
    }
    // lp_setup_vbuf.c, TRIANGLE_FAN with flatshade_first == 0: (v0, v1, v2), (v0, v2, v3)
    q.tri[0] = setup(v0, v1, v2, surf_w, surf_h);
    q.tri[1] = setup(v0, v2, v3, surf_w, surf_h);
    return q;
}

Rgba decode(const FormatInfo& f, const uint8_t* p, bool fused) {
    Rgba c = {0.0f, 0.0f, 0.0f, 1.0f};
    switch (f.pack) {
        case PackKind::kUnorm8:
        case PackKind::kSrgb8:
            for (uint32_t i = 0; i < f.channels; ++i) {
                const uint32_t ch = f.bgra && i < 3 ? 2 - i : i;
                const bool srgb = f.pack == PackKind::kSrgb8 && i < 3;
                c[i] = srgb ? fragment::srgb8_to_linear(p[ch], fused) : fragment::unorm8_to_float(p[ch]);
            }
            break;
        case PackKind::kFloat16:
            for (uint32_t i = 0; i < f.channels; ++i) {
                uint16_t h;
                std::memcpy(&h, p + 2 * i, 2);
                c[i] = fragment::half_to_float(h);
            }
            break;
        case PackKind::kFloat32:
        case PackKind::kD32F:
            for (uint32_t i = 0; i < f.channels; ++i) std::memcpy(&c[i], p + 4 * i, 4);
            break;
        case PackKind::kD16: {
            uint16_t d;
            std::memcpy(&d, p, 2);
            // lp_build_unsigned_norm_to_float: float(u16) * fl(1/65535)
            c[0] = float(d) * float(1.0 / 65535.0);
            break;
        }
        default:
            break;
    }
    return c;
}

void encode(const FormatInfo& f, const Rgba& c, uint8_t* p, bool fused) {
    switch (f.pack) {
        case PackKind::kUnorm8:
        case PackKind::kSrgb8:
            for (uint32_t i = 0; i < f.channels; ++i) {
                const uint32_t ch = f.bgra && i < 3 ? 2 - i : i;
                if (f.pack == PackKind::kSrgb8)
                    p[ch] = i < 3 ? fragment::linear_to_srgb8(c[i], fused) : fragment::srgb_alpha_to_u8(c[i]);
                else
                    p[ch] = fragment::float_to_unorm8(c[i]);
            }
            break;
        case PackKind::kFloat16:
            for (uint32_t i = 0; i < f.channels; ++i) {
                const uint16_t h = fragment::float_to_half_rz(c[i]);
                std::memcpy(p + 2 * i, &h, 2);
            }
            break;
        case PackKind::kFloat32:
            for (uint32_t i = 0; i < f.channels; ++i) std::memcpy(p + 4 * i, &c[i], 4);
            break;
        case PackKind::kD32F: {
            // depth output clamped to [0,1] (no depth_range_unrestricted), stored as is
            const float z = std::clamp(c[0], 0.0f, 1.0f);
            std::memcpy(p, &z, 4);
            break;
        }
        case PackKind::kD16: {
            // lp_build_clamped_float_to_unsigned_norm: t = fl(z * 65535/65536); the low 16 bits of fl(t + 128)
            const float z = std::clamp(c[0], 0.0f, 1.0f);
            const float u = z * (65535.0f / 65536.0f) + 128.0f;
            uint32_t bits;
            std::memcpy(&bits, &u, 4);
            const uint16_t d = uint16_t(bits & 0xffff);
            std::memcpy(p, &d, 2);
            break;
        }
        default:
            break;
    }
}

}  // namespace blit

namespace {

using blit::Rgba;

// One source subresource as the blitter's sampler view sees it (a single level).
struct Source {
    const Image* img;
    uint32_t level;
    int32_t w, h, layers;
    bool fused;

    const uint8_t* at(int32_t x, int32_t y, int32_t layer) const {
        x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, h - 1);
        layer = std::clamp(layer, 0, layers - 1);
        return img->texel(level, uint32_t(layer), uint32_t(x), uint32_t(y));
    }
    Rgba fetch(int32_t x, int32_t y, int32_t layer) const { return blit::decode(*img->format, at(x, y, layer), fused); }
};

// Float -> int for texel indices without overflow (NaN -> 0); the callers clamp.
int32_t floor_i32(float u) {
    if (!(u == u)) return 0;
    return int32_t(std::floor(std::clamp(u, -16777216.0f, 16777216.0f)));
}

// TEX with a CLAMP_TO_EDGE NEAREST sampler: i = clamp(floor(s * n), 0, n - 1)   (both gallivm paths)
Rgba sample_nearest(const Source& src, float s, float t, int32_t layer) {
    return src.fetch(floor_i32(s * float(src.w)), floor_i32(t * float(src.h)), layer);
}

// The 8-bit fixed-point bilinear filter (lp_bld_sample_aos.c) for UNORM8 sources: c = iround(s * n*256) - 128,
// i = c >> 8 clamped, w = c & 255; lerp x then y in 8 bits; the result is converted like a texel (u * fl(1/255)).
Rgba sample_linear_unorm8(const Source& src, float s, float t, int32_t layer) {
    namespace f8 = shader::fixed8;
    const f8::Pair px = f8::wrap_clamp(f8::coord(s * float(src.w * 256)), src.w);
    const f8::Pair py = f8::wrap_clamp(f8::coord(t * float(src.h * 256)), src.h);
    const FormatInfo& f = *src.img->format;
    const uint8_t* q[4] = {src.at(px.i0, py.i0, layer), src.at(px.i1, py.i0, layer), src.at(px.i0, py.i1, layer),
                           src.at(px.i1, py.i1, layer)};
    Rgba c = {0.0f, 0.0f, 0.0f, 1.0f};
    for (uint32_t i = 0; i < f.channels; ++i) {
        const uint32_t ch = f.bgra && i < 3 ? 2 - i : i;
        const int32_t top = f8::lerp(px.w, q[0][ch], q[1][ch]), bottom = f8::lerp(px.w, q[2][ch], q[3][ch]);
        c[i] = fragment::unorm8_to_float(uint8_t(f8::lerp(py.w, top, bottom)));
    }
    return c;
}

// The float bilinear filter (lp_bld_sample_soa.c, CLAMP_TO_EDGE): u = max(min(s*n, n) - 0.5, 0), i0 = floor(u),
// i1 = min(i0 + 1, n - 1), w = u - floor(u); lerp(w, p, q) = fmuladd(w, q - p, p), along x then y.
Rgba sample_linear_float(const Source& src, float s, float t, int32_t layer) {
    struct Axis {
        int32_t i0, i1;
        float w;
    };
    auto axis = [](float st, int32_t n) {
        float u = st * float(n);
        u = std::min(u, float(n));
        u = u - 0.5f;
        u = std::max(u, 0.0f);
        if (!(u == u)) u = 0.0f;
        const float fl = std::floor(u);
        const int32_t i0 = floor_i32(u);
        return Axis{i0, std::min(i0 + 1, n - 1), u - fl};
    };
    const Axis ax = axis(s, src.w), ay = axis(t, src.h);
    const Rgba c00 = src.fetch(ax.i0, ay.i0, layer), c10 = src.fetch(ax.i1, ay.i0, layer);
    const Rgba c01 = src.fetch(ax.i0, ay.i1, layer), c11 = src.fetch(ax.i1, ay.i1, layer);
    auto lerp = [&](float w, float p, float q) { return fmuladd(w, q - p, p, src.fused); };
    Rgba c;
    for (int i = 0; i < 4; ++i) c[i] = lerp(ay.w, lerp(ax.w, c00[i], c10[i]), lerp(ax.w, c01[i], c11[i]));
    return c;
}

// Checks a blit region's box against its subresource (invalid usage must not crash): offsets inside the level,
// layers inside the image, memory bound.
bool region_ok(const Image* img, const VkImageSubresourceLayers& sub, const VkOffset3D (&o)[2], const char* which) {
    bool ok = img != nullptr && img->memory != nullptr && sub.mipLevel < img->mip_levels &&
              sub.baseArrayLayer < img->array_layers && sub.layerCount >= 1 &&
              sub.layerCount <= img->array_layers - sub.baseArrayLayer && img->samples == 1 &&
              blit_supported(*img->format) && img->memory_offset <= img->memory->size &&
              img->layout.size <= img->memory->size - img->memory_offset;
    if (ok) {
        const int64_t w = img->level_width(sub.mipLevel), h = img->level_height(sub.mipLevel);
        for (const VkOffset3D& p : o) ok = ok && p.x >= 0 && p.x <= w && p.y >= 0 && p.y <= h;
        ok = ok && std::min(o[0].z, o[1].z) == 0 && std::max(o[0].z, o[1].z) == 1;
    }
    if (!ok)
        log_error(
            "vkCmdBlitImage: %s region (level %u, layers %u+%u, (%d,%d)-(%d,%d)) is invalid for the image; "
            "region skipped",
            which, sub.mipLevel, sub.baseArrayLayer, sub.layerCount, o[0].x, o[0].y, o[1].x, o[1].y);
    return ok;
}

// One side of lavapipe's box normalisation: the destination runs forward, a mirror moves to the source.
struct Span {
    int32_t dst, dst_len, src, src_len;  // src_len < 0: mirrored
};
Span span(int32_t s0, int32_t s1, int32_t d0, int32_t d1) {
    if (d0 < d1) return {d0, d1 - d0, s0, s1 - s0};
    return {d1, d0 - d1, s1, s0 - s1};
}

void copy_region(const Image& src, const Image& dst, const VkImageBlit& r, const Span& sx, const Span& sy) {
    const size_t row = size_t(sx.dst_len) * src.format->texel_bytes;
    for (uint32_t l = 0; l < r.srcSubresource.layerCount; ++l) {
        for (int32_t y = 0; y < sy.dst_len; ++y) {
            const uint8_t* s = src.texel(r.srcSubresource.mipLevel, r.srcSubresource.baseArrayLayer + l,
                                         uint32_t(sx.src), uint32_t(sy.src + y));
            uint8_t* d = dst.texel(r.dstSubresource.mipLevel, r.dstSubresource.baseArrayLayer + l, uint32_t(sx.dst),
                                   uint32_t(sy.dst + y));
            std::memmove(d, s, row);
        }
    }
}

void blit_region(const Image& src, const Image& dst, const VkImageBlit& r, VkFilter filter, bool fused) {
    if (!region_ok(&src, r.srcSubresource, r.srcOffsets, "source") ||
        !region_ok(&dst, r.dstSubresource, r.dstOffsets, "destination")) {
        return;
    }
    if (r.srcSubresource.layerCount != r.dstSubresource.layerCount) {
        log_error("vkCmdBlitImage: source and destination layer counts differ; region skipped");
        return;
    }
    const Span sx = span(r.srcOffsets[0].x, r.srcOffsets[1].x, r.dstOffsets[0].x, r.dstOffsets[1].x);
    const Span sy = span(r.srcOffsets[0].y, r.srcOffsets[1].y, r.dstOffsets[0].y, r.dstOffsets[1].y);
    if (sx.dst_len == 0 || sy.dst_len == 0) return;
    const bool scaled = sx.dst_len != std::abs(sx.src_len) || sy.dst_len != std::abs(sy.src_len);
    // util_try_blit_via_copy_region: same format, NEAREST, no scaling or flipping
    if (src.format == dst.format && filter == VK_FILTER_NEAREST && sx.src_len == sx.dst_len &&
        sy.src_len == sy.dst_len) {
        copy_region(src, dst, r, sx, sy);
        return;
    }
    // util_blitter_blit_generic: unscaled blits filter NEAREST and fetch texels (TXF) at unnormalized coordinates
    const bool use_txf = !scaled;
    const bool linear = scaled && filter == VK_FILTER_LINEAR;
    const uint32_t level = r.srcSubresource.mipLevel;
    const Source source{
        &src, level, int32_t(src.level_width(level)), int32_t(src.level_height(level)), int32_t(src.array_layers),
        fused};
    // get_texcoords: x / (float)width for TEX, x itself for TXF
    auto coord = [use_txf](int32_t v, int32_t size) { return use_txf ? float(v) : float(v) / float(size); };
    const float s1 = coord(sx.src, source.w), s2 = coord(sx.src + sx.src_len, source.w);
    const float t1 = coord(sy.src, source.h), t2 = coord(sy.src + sy.src_len, source.h);
    const uint32_t dl = r.dstSubresource.mipLevel;
    const uint32_t surf_w = dst.level_width(dl), surf_h = dst.level_height(dl);
    // llvmpipe's linear mode: a single-layer, single-sample B8G8R8A8_UNORM colour target without depth
    const bool rect = dst.format->format == VK_FORMAT_B8G8R8A8_UNORM && dst.array_layers == 1 && dst.samples == 1;
    const blit::Quad quad = blit::make_quad(surf_w, surf_h, sx.dst, sy.dst, sx.dst + sx.dst_len, sy.dst + sy.dst_len,
                                            s1, t1, s2, t2, fused, rect);
    const bool fixed8 = src.format->pack == PackKind::kUnorm8;
    int32_t x0 = quad.rx0, x1 = quad.rx1, y0 = quad.ry0, y1 = quad.ry1;
    for (const blit::Triangle& t : quad.tri) {
        if (!t.valid) continue;
        x0 = std::min(x0, t.bx0), x1 = std::max(x1, t.bx1), y0 = std::min(y0, t.by0), y1 = std::max(y1, t.by1);
    }
    const uint32_t tb = dst.format->texel_bytes;
    for (uint32_t l = 0; l < r.srcSubresource.layerCount; ++l) {
        // the layer coordinate: srcbox.z + dst_z * (src depth / dst depth), an integer here (equal counts)
        const int32_t layer = int32_t(r.srcSubresource.baseArrayLayer + l);
        const uint32_t dst_layer = r.dstSubresource.baseArrayLayer + l;
        for (int32_t py = y0; py <= y1; ++py) {
            uint8_t* row = dst.texel(dl, dst_layer, 0, uint32_t(py));
            for (int32_t px = x0; px <= x1; ++px) {
                float s, t;
                if (!quad.texcoord(px, py, s, t)) continue;
                Rgba c;
                if (use_txf)  // FLR, F2I, TXF
                    c = source.fetch(floor_i32(s), floor_i32(t), layer);
                else if (!linear)
                    c = sample_nearest(source, s, t, layer);
                else if (fixed8)
                    c = sample_linear_unorm8(source, s, t, layer);
                else
                    c = sample_linear_float(source, s, t, layer);
                blit::encode(*dst.format, c, row + size_t(px) * tb, fused);
            }
        }
    }
}

}  // namespace

void exec_blit_image(const CmdBlitImage& c) {
    if (c.src == nullptr || c.dst == nullptr || c.regions == nullptr) return;
    const bool fused = rast::geometry::host_has_fma();
    for (uint32_t i = 0; i < c.count; ++i) blit_region(*c.src, *c.dst, c.regions[i], c.filter, fused);
}

}  // namespace tilevk::icd
