// The CPU model the cross-check compares lavapipe with: this folder's geometry functions plus the notes' snap,
// edge, interpolation and colour rules (lavapipe-rules §1, §2, §4, §5), written out here.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "host/cpu.h"
#include "lavapipe_harness.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/draw_module.h"
#include "rast/geometry/line_point_setup.h"
#include "rast/geometry/planes.h"
#include "rast/geometry/primitive_assembly.h"
#include "rast/geometry/vertex_fetch.h"
#include "rast/geometry/viewport.h"

namespace xcheck {

using namespace tilevk::rast::geometry;

// ---- The model ----
constexpr uint32_t kFloats = 8 + 4 * 3;
const Interp kModes[3] = {Interp::kPerspective, Interp::kNoPerspective, Interp::kFlat};

// u8 = sat(rne(fl(x*255))), NaN -> 0 (lavapipe-rules §5)
inline uint8_t to_unorm8(float x) {
    const float s = x * 255.0f;
    if (!(s > 0.0f)) return 0;
    if (s >= 255.0f) return 255;
    return static_cast<uint8_t>(std::nearbyint(s));
}

// wrong_divide: a/oow instead of a*(1/oow), a deliberately wrong rule for the negative test.
struct ModelExtra {
    bool clip_z = true;  // !depthClampEnable
    bool cull_front = false, cull_back = false;
    bool front_ccw = true;
    float vp[4] = {0, 0, kSize, kSize};
    int samples = 1;  // 1 or 4 (then resolved as lavapipe's blitter does)
};

inline Viewport model_viewport(const ModelExtra& mx) {
    return make_viewport(mx.vp[0], mx.vp[1], mx.vp[2], mx.vp[3], 0, 1);
}

// Every primitive is limited to the viewport's whole-pixel rectangle (and the framebuffer).
inline bool in_rect(const PixelRect& r, int px, int py) {
    return px >= r.x0 && px < r.x1 && py >= r.y0 && py < r.y1;
}

inline std::vector<uint8_t> model(const std::vector<InVertex>& verts, int mode, bool fma, bool wrong_divide = false,
                                  const DepthBias* bias = nullptr, const ModelExtra& mx = ModelExtra{}) {
    std::vector<uint8_t> img(kSize * kSize * 4, 0);
    ClipMaskConfig cm{};
    cm.clip_z = mx.clip_z;
    // draw runs its pipeline (clip, then float cull when a cull mode is set) for a whole vertex batch as soon as
    // one vertex has a clip mask; these scenes are one batch each.
    bool pipeline_path = false;
    for (const auto& v : verts) pipeline_path = pipeline_path || compute_clipmask(cm, v.pos) != 0;
    const FloatCull fcull{mx.cull_front, mx.cull_back, mx.front_ccw};
    ViewportConfig vc;
    vc.vp = model_viewport(mx);
    vc.bypass = is_identity_viewport(vc.vp);  // lavapipe's identity-viewport quirk
    const PixelRect rect = viewport_pixel_rect(vc.vp);
    vc.fused = fma;
    ClipConfig cc;
    cc.layout = {3, kModes};
    cc.vp = vc.vp;
    PlaneSetupConfig pc;
    pc.layout = cc.layout;
    if (bias) pc.bias = *bias;  // no depth attachment: lavapipe's default mrd is D24's
    const bool msaa = mx.samples > 1;
    pc.multisample = msaa;
    const float snap_off = msaa ? 0.0f : 0.5f;
    constexpr int kPos4x[4][2] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};  // lp_sample_pos_4x in 1/256 px
    std::vector<uint8_t> img4(msaa ? kSize * kSize * 16 : 0, 0);
    std::vector<float> scratch(kClipScratchVertices * kFloats);
    auto mad = [fma](float a, float b, float c) { return fma ? std::fma(a, b, c) : a * b + c; };
    for (size_t t = 0; t + 2 < verts.size(); t += 3) {
        float rec[3][kFloats];
        uint32_t mask[3];
        for (int k = 0; k < 3; ++k) {
            std::memcpy(rec[k], verts[t + k].pos, 16);
            for (int a = 0; a < 3; ++a) std::memcpy(rec[k] + 8 + 4 * a, verts[t + k].col, 16);
            mask[k] = prepare_vertex(cm, vc, rec[k]);
        }
        ClippedTriangle tris[kMaxClippedTriangles];
        const uint32_t n = clip_triangle(cc, rec[0], rec[1], rec[2], mask[0], mask[1], mask[2], scratch.data(), tris);
        for (uint32_t i = 0; i < n; ++i) {
            const float* v[3] = {tris[i].v[0], tris[i].v[1], tris[i].v[2]};
            if (pipeline_path && (mx.cull_front || mx.cull_back) &&
                !float_cull_keep(fcull, v[0] + 4, v[1] + 4, v[2] + 4))
                continue;
            // snap: rne(fl(x - 0.5) * 256)
            int64_t X[3], Y[3];
            for (int k = 0; k < 3; ++k) {
                X[k] = static_cast<int64_t>(std::nearbyint((v[k][4] - snap_off) * 256.0f));
                Y[k] = static_cast<int64_t>(std::nearbyint((v[k][5] - snap_off) * 256.0f));
            }
            const int64_t area = (X[0] - X[1]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[0] - Y[1]);
            if (area == 0) continue;
            // llvmpipe's own cull on the exact fixed-point area: area > 0 is "ccw"
            const bool front = (area > 0) == mx.front_ccw;
            if ((front && mx.cull_front) || (!front && mx.cull_back)) continue;
            if (area < 0) {  // CW -> CCW with flatshade_first: swap v1, v2
                std::swap(v[1], v[2]);
                std::swap(X[1], X[2]);
                std::swap(Y[1], Y[2]);
            }
            TrianglePlanes tp;
            AttribPlane ap[3];
            setup_triangle_planes(pc, v[0], v[1], v[2], &tp, ap);
            for (int py = 0; py < kSize; ++py)
                for (int px = 0; px < kSize; ++px) {
                    if (!in_rect(rect, px, py)) continue;
                    // coverage per sample: E_i = DY*(x_i - X) - DX*(y_i - Y) + bias > 0 at the sample's fixed point
                    unsigned cover = 0;
                    for (int smp = 0; smp < mx.samples; ++smp) {
                        const int64_t sx = px * 256 + (msaa ? kPos4x[smp][0] : 0);
                        const int64_t sy = py * 256 + (msaa ? kPos4x[smp][1] : 0);
                        bool in = true;
                        for (int e = 0; e < 3; ++e) {
                            const int j = (e + 1) % 3;
                            const int64_t dy = Y[e] - Y[j], dx = X[e] - X[j];
                            const int64_t bias = (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;
                            in = in && dy * (X[e] - sx) - dx * (Y[e] - sy) + bias > 0;
                        }
                        if (in) cover |= 1u << smp;
                    }
                    if (!cover) continue;
                    // MSAA planes have their origin at the pixel corner; the shader evaluates at the centre
                    const float fx = static_cast<float>(px) + (msaa ? 0.5f : 0.0f);
                    const float fy = static_cast<float>(py) + (msaa ? 0.5f : 0.0f);
                    auto put = [&](int c, uint8_t value) {
                        if (!msaa) {
                            img[(py * kSize + px) * 4 + c] = value;
                            return;
                        }
                        for (int smp = 0; smp < 4; ++smp)
                            if (cover & (1u << smp)) img4[((py * kSize + px) * 4 + smp) * 4 + c] = value;
                    };
                    if (mode & 8) {
                        // gl_FragCoord.z = fmuladd(dzdy, py, fmuladd(dzdx, px, z0)) + offset (plain add)
                        const float zi = mad(tp.pos.dady[2], fy, mad(tp.pos.dadx[2], fx, tp.pos.a0[2]));
                        const float z = zi + tp.depth_offset;
                        const float big = z * 65536.0f, mid = z * 256.0f, huge = z * 16777216.0f;
                        const float ch[4] = {big - std::floor(big), mid - std::floor(mid), z, huge - std::floor(huge)};
                        for (int c = 0; c < 4; ++c) put(c, to_unorm8(ch[c]));
                        continue;
                    }
                    const AttribPlane& a = ap[mode & 3];
                    const float oow = mad(tp.pos.dady[3], fy, mad(tp.pos.dadx[3], fx, tp.pos.a0[3]));
                    const float rw = 1.0f / oow;
                    for (int c = 0; c < 4; ++c) {
                        float val = mad(a.dady[c], fy, mad(a.dadx[c], fx, a.a0[c]));
                        if ((mode & 3) == 0) val = wrong_divide ? val / oow : val * rw;
                        if (mode & 4) {
                            const float big = val * 65536.0f;  // exact
                            val = big - std::floor(big);
                        }
                        put(c, to_unorm8(val));
                    }
                }
        }
    }
    if (msaa) {
        // resolve (lavapipe-rules §3): sum of fl(u8 * fl(1/255)) in sample order, * 0.25, back with rne(x*255)
        const float inv255 = static_cast<float>(1.0 / 255.0);
        for (int p = 0; p < kSize * kSize; ++p)
            for (int c = 0; c < 4; ++c) {
                float sum = 0.0f;
                for (int smp = 0; smp < 4; ++smp) sum = sum + static_cast<float>(img4[(p * 4 + smp) * 4 + c]) * inv255;
                img[p * 4 + c] = to_unorm8(sum * 0.25f);
            }
    }
    return img;
}

// Fragment evaluation (lavapipe-rules §4): a = fmuladd(dady, py, fmuladd(dadx, px, a0)); perspective a *= 1/(1/w
// plane). Colour target with per-sample storage; resolve() is lavapipe's blitter resolve (lavapipe-rules §3).
struct Target {
    int samples;
    std::vector<uint8_t> px;  // [pixel][sample][channel]
    explicit Target(int s) : samples(s), px(static_cast<size_t>(kSize) * kSize * 4 * s, 0) {}
    void put(int x, int y, unsigned cover, int c, uint8_t v) {
        for (int smp = 0; smp < samples; ++smp)
            if (cover & (1u << smp)) px[((y * kSize + x) * samples + smp) * 4 + c] = v;
    }
    std::vector<uint8_t> resolve() const {
        if (samples == 1) return px;
        std::vector<uint8_t> out(kSize * kSize * 4);
        const float inv255 = static_cast<float>(1.0 / 255.0);
        for (int p = 0; p < kSize * kSize; ++p)
            for (int c = 0; c < 4; ++c) {
                float sum = 0.0f;
                for (int smp = 0; smp < 4; ++smp) sum = sum + static_cast<float>(px[(p * 4 + smp) * 4 + c]) * inv255;
                out[p * 4 + c] = to_unorm8(sum * 0.25f);
            }
        return out;
    }
};

// Fixed-point sample positions: the pixel's integer point at 1x, lp_sample_pos_4x at 4x.
inline void sample_point(int samples, int px, int py, int smp, int64_t* x, int64_t* y) {
    constexpr int kPos[4][2] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};
    *x = px * 256 + (samples > 1 ? kPos[smp][0] : 0);
    *y = py * 256 + (samples > 1 ? kPos[smp][1] : 0);
}

// Fragment evaluation (lavapipe-rules §4): a = fmuladd(dady, py, fmuladd(dadx, px, a0)); perspective a *= 1/(1/w
// plane); in MSAA the shader evaluates at the pixel centre (px + 0.5).
inline void shade(Target& t, int px, int py, unsigned cover, const AttribPlane& pos, const AttribPlane& a, int mode,
                  bool fma) {
    auto mad = [fma](float x, float y, float z) { return fma ? std::fma(x, y, z) : x * y + z; };
    const float off = t.samples > 1 ? 0.5f : 0.0f;
    const float fx = static_cast<float>(px) + off, fy = static_cast<float>(py) + off;
    const float oow = mad(pos.dady[3], fy, mad(pos.dadx[3], fx, pos.a0[3]));
    const float rw = 1.0f / oow;
    for (int c = 0; c < 4; ++c) {
        float val = mad(a.dady[c], fy, mad(a.dadx[c], fx, a.a0[c]));
        if ((mode & 3) == 0) val = val * rw;
        if (mode & 4) {
            const float big = val * 65536.0f;  // exact
            val = big - std::floor(big);
        }
        t.put(px, py, cover, c, to_unorm8(val));
    }
}

struct ModelState {
    ClipMaskConfig cm{};
    ViewportConfig vc;
    ClipConfig cc;
    std::vector<float> scratch = std::vector<float>(kClipScratchVertices * kFloats);
    PixelRect rect;
    ModelState(bool fma, const ModelExtra& mx) {
        vc.vp = model_viewport(mx);
        vc.bypass = is_identity_viewport(vc.vp);
        rect = viewport_pixel_rect(vc.vp);
        vc.fused = fma;
        cc.layout = {3, kModes};
        cc.vp = vc.vp;
    }
    uint32_t record(const InVertex& in, float* rec) const {
        std::memcpy(rec, in.pos, 16);
        for (int a = 0; a < 3; ++a) std::memcpy(rec + 8 + 4 * a, in.col, 16);
        return prepare_vertex(cm, vc, rec);
    }
};

inline std::vector<uint8_t> model_lines(const std::vector<InVertex>& verts, int mode, bool fma, float width,
                                        bool bresenham = false, const ModelExtra& mx = ModelExtra{}) {
    Target img(mx.samples);
    ModelState st(fma, mx);
    LineSetupConfig lc;
    lc.layout = st.cc.layout;
    lc.width = width;
    lc.multisample = mx.samples > 1;
    lc.mode = bresenham ? LineMode::kBresenham : LineMode::kRectangular;
    for (size_t i = 0; i + 1 < verts.size(); i += 2) {
        float r0[kFloats], r1[kFloats];
        const uint32_t m0 = st.record(verts[i], r0), m1 = st.record(verts[i + 1], r1);
        const float* a;
        const float* b;
        if (!clip_line(st.cc, r0, r1, m0, m1, st.scratch.data(), &a, &b)) continue;
        LineSetup ls;
        AttribPlane ap[3];
        if (setup_line(lc, a, b, &ls, ap) != PrimSetupStatus::kOk) continue;
        for (int py = 0; py < kSize; ++py)
            for (int px = 0; px < kSize; ++px) {
                if (!in_rect(st.rect, px, py)) continue;
                unsigned cover = 0;
                for (int smp = 0; smp < mx.samples; ++smp) {
                    int64_t X, Y;
                    sample_point(mx.samples, px, py, smp, &X, &Y);
                    bool in = true;
                    for (const auto& pl : ls.planes) in = in && pl.c + pl.a * X + pl.b * Y > 0;
                    if (in) cover |= 1u << smp;
                }
                if (cover) shade(img, px, py, cover, ls.pos, ap[mode & 3], mode, fma);
            }
    }
    return img.resolve();
}

// col_format: the colour bytes of each InVertex are an element of this format, converted by vertex_fetch.
inline std::vector<uint8_t> model_points(const std::vector<InVertex>& verts, int mode, bool fma,
                                         VertexFormat col_format = VertexFormat::R32G32B32A32_SFLOAT,
                                         const ModelExtra& mx = ModelExtra{}) {
    Target img(mx.samples);
    ModelState st(fma, mx);
    PointSetupConfig pc;
    pc.layout = st.cc.layout;
    pc.multisample = mx.samples > 1;
    for (const auto& raw : verts) {
        InVertex v = raw;
        const FetchedAttrib f = convert_element(col_format, reinterpret_cast<const uint8_t*>(raw.col));
        std::memcpy(v.col, f.w, 16);
        float r[kFloats];
        const uint32_t m = st.record(v, r);
        if (!clip_point_keep(r, m)) continue;
        PointSetup ps;
        AttribPlane ap[3];
        if (setup_point(pc, r, v.col[3] * 8.0f, &ps, ap) != PrimSetupStatus::kOk) continue;
        for (int py = 0; py < kSize; ++py)
            for (int px = 0; px < kSize; ++px) {
                if (!in_rect(st.rect, px, py)) continue;
                unsigned cover = 0;
                for (int smp = 0; smp < mx.samples; ++smp) {
                    int64_t X, Y;
                    sample_point(mx.samples, px, py, smp, &X, &Y);
                    if (ps.x0 <= X && X < ps.x1 && ps.y0 <= Y && Y < ps.y1) cover |= 1u << smp;
                }
                if (cover) shade(img, px, py, cover, ps.pos, ap[mode & 3], mode, fma);
            }
    }
    return img.resolve();
}

inline InVertex iv(float x, float y, float z, float w, float r, float g, float b, float a = 1.0f) {
    return InVertex{{x, y, z, w}, {r, g, b, a}};
}

inline std::vector<std::vector<InVertex>> make_scenes() {
    std::vector<std::vector<InVertex>> scenes;
    // crosses right and bottom, w = 1
    scenes.push_back(
        {iv(-0.7f, -0.6f, 0.5f, 1, 1, 0, 0), iv(1.9f, 0.1f, 0.5f, 1, 0, 1, 0), iv(0.2f, 1.7f, 0.5f, 1, 0, 0, 1)});
    // perspective, crosses left and top
    scenes.push_back({iv(-3.1f, -0.2f, 0.3f, 2.0f, 1, 0.5f, 0), iv(0.4f, -1.9f, 0.6f, 0.7f, 0, 1, 0.25f),
                      iv(0.6f, 0.8f, 0.2f, 1.3f, 0.1f, 0.2f, 1)});
    // crosses the near plane (z < 0) and the far plane
    scenes.push_back({iv(-0.5f, -0.5f, -0.8f, 1.5f, 1, 1, 0), iv(0.9f, -0.2f, 0.7f, 1.0f, 0, 1, 1),
                      iv(-0.1f, 0.9f, 1.9f, 1.2f, 1, 0, 1)});
    // covers the whole viewport, crosses all four sides
    scenes.push_back({iv(-5, -5, 0.5f, 1, 0.2f, 0.9f, 0.4f), iv(9, -5, 0.5f, 3, 0.8f, 0.1f, 0.6f),
                      iv(-5, 9, 0.5f, 2, 0.5f, 0.5f, 0.0f)});
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int s = 0; s < 24; ++s) {
        std::vector<InVertex> sc;
        for (int k = 0; k < 3 * 4; ++k) {
            const float w = 0.4f + 2.5f * u(rng);
            sc.push_back(iv((u(rng) * 3.4f - 1.7f) * w, (u(rng) * 3.4f - 1.7f) * w, (u(rng) * 1.4f - 0.2f) * w, w,
                            u(rng), u(rng), u(rng), u(rng)));
        }
        scenes.push_back(sc);
    }
    return scenes;
}

// The library's quirk predicate fed from the model's vertex pipeline.
inline NineVertexQuirk quirk_for(const std::vector<InVertex>& v, bool indexed = false, bool flat = false) {
    ModelState st(tilevk::host::has_fma(), ModelExtra{});
    TriangleListBatch b;
    b.vertex_count = static_cast<uint32_t>(v.size());
    b.indexed = indexed;
    b.fs_has_flat_input = flat;
    float xy[12][2] = {};
    for (size_t i = 0; i < v.size(); ++i) {
        float r[kFloats];
        b.any_vertex_clipped = b.any_vertex_clipped || st.record(v[i], r) != 0;
        if (i < 12) xy[i][0] = r[4], xy[i][1] = r[5];
    }
    return nine_vertex_quirk(b, xy);
}

inline int count_diff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int* first) {
    int diff = 0;
    *first = -1;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        if (a[i] != b[i]) {
            if (*first < 0) *first = static_cast<int>(i);
            ++diff;
        }
    return diff + static_cast<int>(a.size() != b.size());
}

}  // namespace xcheck
