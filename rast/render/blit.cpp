#include "rast/render/blit.h"

#include <cmath>
#include <cstring>

#include "format/texel_codec.h"
#include "rast/core/coverage.h"
#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"
#include "rast/fragment/interp.h"
#include "rast/geometry/planes.h"
#include "rast/geometry/rect_detect.h"
#include "rast/geometry/viewport.h"
#include "shader/program.h"

namespace tilevk::rast::render {
namespace {

using PixelFn = std::function<void(int32_t px, int32_t py, float s, float t)>;

// One vertex of the quad as the geometry stage's record (vertex.h): clip position, window position, (s, t, 0, 0).
constexpr uint32_t kRecordFloats = geometry::kAttribOffset + 4;
const geometry::Interp kTexcoordInterp[1] = {geometry::Interp::kNoPerspective};  // TGSI_INTERPOLATE_LINEAR
constexpr geometry::VertexLayout kQuadLayout{1, kTexcoordInterp};

// blitter_set_rectangle: ndc = fl(fl(x / size) * 2) - 1 in C; then draw's viewport transform with
// scale = translate = 0.5 * size and w = 1 (geometry::viewport_transform: fmuladd, fused on FMA hosts).
void make_vertex(const geometry::ViewportConfig& vp, uint32_t w, uint32_t h, int32_t x, int32_t y, float s, float t,
                 float* record) {
    const float clip[4] = {float(x) / float(w) * 2.0f - 1.0f, float(y) / float(h) * 2.0f - 1.0f, 0.0f, 1.0f};
    std::memcpy(record + geometry::kClipPosOffset, clip, sizeof clip);
    geometry::viewport_transform(vp, clip, record + geometry::kWinPosOffset);
    const float attrib[4] = {s, t, 0.0f, 0.0f};
    std::memcpy(record + geometry::kAttribOffset, attrib, sizeof attrib);
}

// The texture-coordinate planes of one primitive of the quad (lp_state_setup.c), from its vertices in the order
// rast/core rasterizes them.
struct TexcoordPlanes {
    fragment::Plane s, t;
};
TexcoordPlanes planes_of(const float* v0, const float* v1, const float* v2) {
    geometry::PlaneSetupConfig cfg;
    cfg.layout = kQuadLayout;
    cfg.flatshade_first = false;  // the blitter's rasterizer state
    geometry::TrianglePlanes tp;
    geometry::AttribPlane a;
    geometry::setup_triangle_planes(cfg, v0, v1, v2, &tp, &a);
    return {{a.dadx[0], a.dady[0], a.a0[0]}, {a.dadx[1], a.dady[1], a.a0[1]}};
}

// Hands every covered pixel of the quad's primitives to fn with its coordinates: lp_bld_interp.c's evaluation,
// fmuladd(dady, py, fmuladd(dadx, px, a0)) at the pixel's integer coordinates (fragment::eval_plane).
class QuadConsumer final : public CoverageConsumer {
  public:
    QuadConsumer(const TexcoordPlanes* planes, bool fused, const PixelFn& fn)
        : planes_(planes), fused_(fused), fn_(fn) {}
    void begin_tile(unsigned, const TileInfo&) override {}
    void end_tile(unsigned, const TileInfo&) override {}
    void primitive(unsigned, const TileInfo&, const PrimCoverage& c) override {
        const TexcoordPlanes& p = planes_[c.payload];
        for_each_block4(c, [&](int32_t x, int32_t y, const uint16_t masks[]) { shade(p, x, y, masks[0]); });
        for (size_t i = 0; i < c.num_full; ++i) {  // full squares lie inside the surface (coverage.h)
            const FullBlock& f = c.full[i];
            for (int32_t by = f.y; by < f.y + f.size; by += 4)
                for (int32_t bx = f.x; bx < f.x + f.size; bx += 4) shade(p, bx, by, 0xffff);
        }
    }

  private:
    void shade(const TexcoordPlanes& p, int32_t x, int32_t y, uint16_t raster_mask) const {
        float s[fragment::kBlockLanes], t[fragment::kBlockLanes];
        fragment::eval_plane(p.s, x, y, fragment::plane_offset(1, -1), fused_, s);
        fragment::eval_plane(p.t, x, y, fragment::plane_offset(1, -1), fused_, t);
        for (int bit = 0; bit < 16; ++bit) {
            if (!(raster_mask & (1u << bit))) continue;
            const int lane = fragment::lane_of(bit & 3, bit >> 2);
            fn_(x + (bit & 3), y + (bit >> 2), s[lane], t[lane]);
        }
    }

    const TexcoordPlanes* planes_;
    bool fused_;
    const PixelFn& fn_;
};

// One side of lavapipe's box normalisation: the destination runs forward, a mirror moves to the source.
struct Span {
    int32_t dst, dst_len, src, src_len;  // src_len < 0: mirrored
};
Span span(int32_t s0, int32_t s1, int32_t d0, int32_t d1) {
    if (d0 < d1) return {d0, d1 - d0, s0, s1 - s0};
    return {d1, d0 - d1, s1, s0 - s1};
}

uint8_t* texel(const BlitSurface& s, uint32_t layer, int32_t x, int32_t y) {
    return s.base + layer * s.layer_pitch + uint64_t(y) * s.row_pitch +
           uint64_t(x) * format::format_info(s.format).bytes;
}

// util_try_blit_via_copy_region's case: rows copied as they are.
void copy_region(const BlitSurface& src, const BlitSurface& dst, const Span& sx, const Span& sy, const Span& sz) {
    const size_t row = size_t(sx.dst_len) * format::format_info(src.format).bytes;
    for (int32_t l = 0; l < sz.dst_len; ++l)
        for (int32_t y = 0; y < sy.dst_len; ++y)
            std::memmove(texel(dst, uint32_t(sz.dst + l), sx.dst, sy.dst + y),
                         texel(src, uint32_t(sz.src + l), sx.src, sy.src + y), row);
}

// cvttps2dq of floor(x) (the blitter's FLR, F2I): NaN and out-of-range values give INT32_MIN.
int32_t floor_to_int(float x) {
    const float f = std::floor(x);
    return f >= -2147483648.0f && f < 2147483648.0f ? int32_t(f) : INT32_MIN;
}

}  // namespace

void rasterize_blit_quad(const BlitQuad& q, ThreadPool& pool, const PixelFn& fn) {
    geometry::ViewportConfig vp;
    vp.vp = geometry::make_viewport(0.0f, 0.0f, float(q.surf_w), float(q.surf_h), 0.0f, 1.0f);
    vp.fused = q.fused;
    // The fan (x1,y1) (x2,y1) (x2,y2) (x1,y2).
    float v[4][kRecordFloats];
    make_vertex(vp, q.surf_w, q.surf_h, q.x1, q.y1, q.s1, q.t1, v[0]);
    make_vertex(vp, q.surf_w, q.surf_h, q.x2, q.y1, q.s2, q.t1, v[1]);
    make_vertex(vp, q.surf_w, q.surf_h, q.x2, q.y2, q.s2, q.t2, v[2]);
    make_vertex(vp, q.surf_w, q.surf_h, q.x1, q.y2, q.s1, q.t2, v[3]);
    const ClipRect surface{0, 0, int32_t(q.surf_w), int32_t(q.surf_h)};
    Scene scene({.width = int32_t(q.surf_w), .height = int32_t(q.surf_h), .samples = 1, .method = Method::kHier});
    TexcoordPlanes planes[2];
    if (q.rect) {
        // llvmpipe's linear mode (lp_setup_vbuf.c offers the fan to lp_setup_rect.c): both triangles are cw,
        // do_rect_ccw finds the rectangle and lp_rect_cw sets it up from the corners (v2, v0, v1) with no reorder;
        // coverage is the box of the util_iround-snapped corners (bottom_edge_rule moves y by one unit).
        const float* w[3] = {geometry::win_pos(v[2]), geometry::win_pos(v[0]), geometry::win_pos(v[1])};
        const geometry::RectBox box = geometry::rect_box(w[0], w[1], w[2], 0.5f, /*bottom_edge_rule=*/true);
        if (box.culled || box.x0 > box.x1 || box.y0 > box.y1) return;
        planes[0] = planes_of(v[2], v[0], v[1]);
        BoxInput in;
        in.x0 = box.x0 * kFixedOne, in.y0 = box.y0 * kFixedOne;
        in.x1 = (box.x1 + 1) * kFixedOne, in.y1 = (box.y1 + 1) * kFixedOne;
        in.common.clip = surface;
        in.common.sample_mask = 1;
        scene.add_box(in);
    } else {
        // lp_setup_vbuf.c, TRIANGLE_FAN with flatshade_first == 0: (v0, v1, v2), (v0, v2, v3); u_blitter's
        // rasterizer state has the bottom-left fill rule
        const int fan[2][3] = {{0, 1, 2}, {0, 2, 3}};
        for (uint32_t k = 0; k < 2; ++k) {
            TriangleInput tri;
            for (int i = 0; i < 3; ++i) {
                tri.x[i] = geometry::win_pos(v[fan[k][i]])[0];
                tri.y[i] = geometry::win_pos(v[fan[k][i]])[1];
            }
            tri.flatshade_first = false;
            tri.bottom_edge_rule = true;
            tri.common.clip = surface;
            tri.common.sample_mask = 1;
            tri.common.payload = k;
            int order[3];
            triangle_vertex_order(tri, 1, order);
            planes[k] = planes_of(v[fan[k][order[0]]], v[fan[k][order[1]]], v[fan[k][order[2]]]);
            scene.add_triangle(tri);
        }
    }
    QuadConsumer consumer(planes, q.fused, fn);
    scene.rasterize(consumer, pool);
}

float blit_source_z(int32_t src_z, int32_t src_depth, int32_t dst_depth, int32_t dst_z, bool three_d_source) {
    const int32_t n = std::abs(src_depth);
    float step = float(n) / float(dst_depth);
    // "centered" z for 3D sources (do_blits): C's double arithmetic, stored to a float
    float offset = three_d_source ? float(0.5 / double(dst_depth) * double(n)) : 0.0f;
    if (src_depth < 0) step = -step, offset = -offset;
    return float(src_z) + (float(dst_z) * step + offset);
}

void blit(const BlitSurface& src, const BlitSurface& dst, const BlitRegion& r, BlitFilter filter, bool fused,
          ThreadPool& pool) {
    const Span sx = span(r.src[0][0], r.src[1][0], r.dst[0][0], r.dst[1][0]);
    const Span sy = span(r.src[0][1], r.src[1][1], r.dst[0][1], r.dst[1][1]);
    const Span sz = span(r.src[0][2], r.src[1][2], r.dst[0][2], r.dst[1][2]);
    if (sx.dst_len == 0 || sy.dst_len == 0 || sz.dst_len == 0) return;
    const bool scaled =
        sx.dst_len != std::abs(sx.src_len) || sy.dst_len != std::abs(sy.src_len) || sz.dst_len != std::abs(sz.src_len);
    // util_try_blit_via_copy_region: same format, NEAREST, no scaling or flipping
    if (src.format == dst.format && filter == BlitFilter::kNearest && sx.src_len == sx.dst_len &&
        sy.src_len == sy.dst_len && sz.src_len == sz.dst_len) {
        copy_region(src, dst, sx, sy, sz);
        return;
    }
    // util_blitter_blit_generic: unscaled blits filter NEAREST and fetch texels (TXF) at unnormalized coordinates;
    // get_texcoords: x / (float)width for TEX, x itself for TXF
    const bool use_txf = !scaled;
    auto coord = [use_txf](int32_t v, uint32_t size) { return use_txf ? float(v) : float(v) / float(size); };
    BlitQuad q;
    q.surf_w = dst.width, q.surf_h = dst.height;
    q.x1 = sx.dst, q.y1 = sy.dst, q.x2 = sx.dst + sx.dst_len, q.y2 = sy.dst + sy.dst_len;
    q.s1 = coord(sx.src, src.width), q.s2 = coord(sx.src + sx.src_len, src.width);
    q.t1 = coord(sy.src, src.height), q.t2 = coord(sy.src + sy.src_len, src.height);
    q.fused = fused;
    // llvmpipe's linear mode: a single-layer, single-sample B8G8R8A8_UNORM PIPE_TEXTURE_2D colour target without
    // depth (lp_state_derived.c check_linear_rasterizer)
    q.rect = dst.format == format::Format::B8G8R8A8_UNORM && dst.layers == 1 && !dst.three_d;
    // The blitter's sampler view: the one source level (a 3D view of its slices); its sampler: CLAMP_TO_EDGE on
    // every axis, the blit's filter.
    shader::ImageView view;
    view.base = src.base;
    view.format = src.format;
    view.width = src.width, view.height = src.height;
    view.layers = src.three_d ? 1 : src.layers;
    view.depth = src.three_d ? src.layers : 1;
    view.level[0] = {0, src.row_pitch, src.layer_pitch};
    shader::SamplerState smp;
    smp.mag_filter = smp.min_filter =
        scaled && filter == BlitFilter::kLinear ? shader::Filter::Linear : shader::Filter::Nearest;
    smp.address_u = smp.address_v = smp.address_w = shader::AddressMode::ClampToEdge;
    smp.max_lod = 0.0f;
    const format::FormatInfo& out = format::format_info(dst.format);
    for (int32_t z = 0; z < sz.dst_len; ++z) {
        const float layer = blit_source_z(sz.src, sz.src_len, sz.dst_len, z, src.three_d);
        const uint32_t dst_layer = uint32_t(sz.dst + z);
        // a 2D source's layer is an integer here (layer counts are equal): the array index as it is
        const uint32_t src_layer = uint32_t(layer);
        const float r = layer / float(src.layers);  // get_texcoords: TEX on a 3D view normalizes z by the depth
        rasterize_blit_quad(q, pool, [&](int32_t px, int32_t py, float s, float t) {
            std::array<float, 4> c;
            if (src.three_d)
                c = use_txf ? shader::fetch_3d(view, floor_to_int(s), floor_to_int(t), floor_to_int(layer))
                            : shader::sample_3d(view, smp, s, t, r);
            else
                c = use_txf ? shader::fetch_2d(view, floor_to_int(s), floor_to_int(t), src_layer)
                            : shader::sample_2d(view, smp, s, t, src_layer);
            format::encode_color(out, c.data(), texel(dst, dst_layer, px, py), fused);
        });
    }
}

}  // namespace tilevk::rast::render
