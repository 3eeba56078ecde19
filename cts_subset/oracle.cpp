// The coverage oracle: a case's triangles through the viewport transform the driver uses, then rast::Scene with
// Method::kReference, and the device's colour plane judged pixel by pixel against that coverage.
#include "oracle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "host/cpu.h"
#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"
#include "rast/geometry/viewport.h"

namespace tilevk::cts {
namespace {

namespace geo = rast::geometry;

// Accumulates the union of every primitive's sample coverage. Tiles are disjoint, so no locking is needed.
class MaskConsumer final : public rast::CoverageConsumer {
  public:
    explicit MaskConsumer(OracleCoverage& cov) : cov_(cov) {}
    void begin_tile(unsigned, const rast::TileInfo&) override {}
    void end_tile(unsigned, const rast::TileInfo&) override {}
    void primitive(unsigned, const rast::TileInfo&, const rast::PrimCoverage& c) override {
        front_ = c.front_facing;
        rast::for_each_block4(c, [&](int32_t x, int32_t y, const uint16_t* masks) {
            for (int s = 0; s < cov_.samples; ++s)
                for (int bit = 0; bit < 16; ++bit)
                    if (masks[s] >> bit & 1) set(x + bit % 4, y + bit / 4, uint8_t(1u << s));
        });
        for (size_t i = 0; i < c.num_full; ++i) {
            const rast::FullBlock& f = c.full[i];
            for (int y = f.y; y < f.y + f.size; ++y)
                for (int x = f.x; x < f.x + f.size; ++x) set(x, y, uint8_t(c.sample_mask));
        }
    }

  private:
    void set(int x, int y, uint8_t bits) {
        if (x >= 0 && y >= 0 && uint32_t(x) < cov_.width && uint32_t(y) < cov_.height) {
            const size_t i = size_t(y) * cov_.width + x;
            cov_.mask[i] |= bits;
            if (cov_.counting != Frag::kColor && bits) ++(front_ ? cov_.front : cov_.back)[i];
        }
    }
    bool front_ = true;
    OracleCoverage& cov_;
};

// A colour as an RGBA8 word, only when every component converts exactly (0 or 1 for vertex colours, so that
// interpolating three equal values cannot round differently; no .5 ties for the clear colour).
bool exact_rgba8(const float c[4], bool only_0_1, uint32_t& out) {
    out = 0;
    for (int i = 0; i < 4; ++i) {
        if (!(c[i] >= 0.0f && c[i] <= 1.0f)) return false;
        if (only_0_1 && c[i] != 0.0f && c[i] != 1.0f) return false;
        const double v = double(c[i]) * 255.0;
        if (v - std::floor(v) == 0.5) return false;
        out |= uint32_t(std::lround(v)) << (8 * i);
    }
    return true;
}

bool additive(const VkPipelineColorBlendAttachmentState& b) {
    return b.blendEnable && b.srcColorBlendFactor == VK_BLEND_FACTOR_ONE &&
           b.dstColorBlendFactor == VK_BLEND_FACTOR_ONE && b.colorBlendOp == VK_BLEND_OP_ADD &&
           b.srcAlphaBlendFactor == VK_BLEND_FACTOR_ONE && b.dstAlphaBlendFactor == VK_BLEND_FACTOR_ONE &&
           b.alphaBlendOp == VK_BLEND_OP_ADD && b.colorWriteMask == 0xF;
}

std::string draw_domain(const Draw& d, Frag counting) {
    if (d.topology != VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST && d.topology != VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP &&
        d.topology != VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN)
        return "not a triangle topology";
    if (d.polygon_mode != VK_POLYGON_MODE_FILL) return "polygon mode not FILL";
    if (!d.vertex_glsl.empty() || !d.fragment_glsl.empty()) return "free-form shaders";
    if (!d.indices.empty() || d.instances != 1) return "indexed or instanced draw";
    if (d.color_format != VK_FORMAT_R32G32B32A32_SFLOAT) return "packed colour attribute";
    if (d.texture || d.frag != counting) return "shading is not a plain colour (or mixed counting modes)";
    if (counting == Frag::kColor && (d.blend.blendEnable || d.blend.colorWriteMask != 0xF))
        return "blending or a partial write mask";
    if (counting != Frag::kColor && !additive(d.blend)) return "counting without ONE,ONE additive blending";
    if (d.depth_test || d.stencil_test) return "depth or stencil test";
    if (d.alpha_to_coverage) return "alpha to coverage";
    return {};
}

// Vertex indices of triangle `t` in the spec's order (the winding is what matters for culling).
void triangle_indices(VkPrimitiveTopology topo, size_t t, size_t idx[3]) {
    if (topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST) {
        idx[0] = 3 * t, idx[1] = 3 * t + 1, idx[2] = 3 * t + 2;
    } else if (topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP) {
        // Vulkan: {i, i + (1 + i%2), i + (2 - i%2)}.
        idx[0] = t, idx[1] = t + 1 + t % 2, idx[2] = t + 2 - t % 2;
    } else {  // fan: {i + 1, i + 2, 0}
        idx[0] = t + 1, idx[1] = t + 2, idx[2] = 0;
    }
}

size_t triangle_count(VkPrimitiveTopology topo, size_t n) {
    if (topo == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST) return n / 3;
    return n >= 3 ? n - 2 : 0;
}

}  // namespace

std::string oracle_coverage(const Scene& scene, OracleCoverage& out) {
    const Target& t = scene.target;
    if (t.color != VK_FORMAT_R8G8B8A8_UNORM) return "colour format is not RGBA8 UNORM";
    if (t.samples != VK_SAMPLE_COUNT_1_BIT && t.samples != VK_SAMPLE_COUNT_4_BIT) return "not 1x or 4x";
    if (scene.draws.empty()) return "no draws";
    out = OracleCoverage{};
    out.width = t.width;
    out.height = t.height;
    out.samples = t.samples == VK_SAMPLE_COUNT_4_BIT ? 4 : 1;
    if (!exact_rgba8(t.clear_color, false, out.clear_rgba)) return "clear colour has no exact RGBA8 value";
    bool have_colour = false;
    out.counting = scene.draws[0].frag == Frag::kCount || scene.draws[0].frag == Frag::kFacing ? scene.draws[0].frag
                                                                                               : Frag::kColor;
    if (out.counting != Frag::kColor && out.samples != 1) return "counting at 4x (a resolved mix)";
    for (const Draw& d : scene.draws) {
        if (std::string e = draw_domain(d, out.counting); !e.empty()) return e;
        if (out.counting != Frag::kColor) {
            have_colour = true;  // the shader's constant, not the vertex colour
            continue;
        }
        for (const Vertex& v : d.vertices) {
            uint32_t c;
            if (!exact_rgba8(v.color, true, c)) return "a vertex colour is not 0/1 per component";
            if (have_colour && c != out.draw_rgba) return "vertices of different colours";
            out.draw_rgba = c;
            have_colour = true;
        }
    }
    if (!have_colour) return "no vertices";
    out.mask.assign(size_t(t.width) * t.height, 0);
    if (out.counting != Frag::kColor) {
        out.front.assign(out.mask.size(), 0);
        out.back.assign(out.mask.size(), 0);
    }

    rast::Scene rs({.width = int32_t(t.width),
                    .height = int32_t(t.height),
                    .samples = out.samples,
                    .method = rast::Method::kReference});
    const bool fused = host::has_fma();
    for (const Draw& d : scene.draws) {
        const VkViewport vkvp = d.viewport.value_or(VkViewport{0, 0, float(t.width), float(t.height), 0, 1});
        const VkRect2D sc = d.scissor.value_or(VkRect2D{{0, 0}, {t.width, t.height}});
        geo::ViewportConfig vcfg;
        vcfg.vp = geo::make_viewport(vkvp.x, vkvp.y, vkvp.width, vkvp.height, vkvp.minDepth, vkvp.maxDepth);
        vcfg.fused = fused;
        vcfg.bypass = geo::is_identity_viewport(vcfg.vp);
        geo::ClipMaskConfig mcfg;
        mcfg.clip_z = !d.depth_clamp;
        // Framebuffer ∩ scissor ∩ the viewport's whole-pixel rectangle.
        const geo::PixelRect vr = geo::viewport_pixel_rect(vcfg.vp);
        rast::ClipRect clip;
        clip.x0 = std::max({0, sc.offset.x, vr.x0});
        clip.y0 = std::max({0, sc.offset.y, vr.y0});
        clip.x1 = int32_t(std::min<int64_t>({int64_t(t.width), int64_t(sc.offset.x) + sc.extent.width, vr.x1}));
        clip.y1 = int32_t(std::min<int64_t>({int64_t(t.height), int64_t(sc.offset.y) + sc.extent.height, vr.y1}));

        std::vector<std::array<float, 2>> win(d.vertices.size());
        std::vector<uint32_t> mask(d.vertices.size());
        for (size_t i = 0; i < d.vertices.size(); ++i) {
            float w4[4];
            mask[i] = geo::compute_clipmask(mcfg, d.vertices[i].pos);
            geo::viewport_transform(vcfg, d.vertices[i].pos, w4);
            win[i] = {w4[0], w4[1]};
        }
        const size_t n = triangle_count(d.topology, d.vertices.size());
        for (size_t tri = 0; tri < n; ++tri) {
            size_t idx[3];
            triangle_indices(d.topology, tri, idx);
            if (mask[idx[0]] | mask[idx[1]] | mask[idx[2]])
                return "a vertex needs clipping (the clipper's new vertices are not modelled)";
            rast::TriangleInput in;
            for (int k = 0; k < 3; ++k) in.x[k] = win[idx[k]][0], in.y[k] = win[idx[k]][1];
            in.common.clip = clip;
            in.common.sample_mask = uint16_t(d.sample_mask & (out.samples == 4 ? 0xFu : 0x1u));
            in.cull = static_cast<rast::CullMode>(d.cull & 3);
            in.front_ccw = d.front_face == VK_FRONT_FACE_COUNTER_CLOCKWISE;
            const rast::SetupStatus st = rs.add_triangle(in);
            if (st == rast::SetupStatus::kOutOfRange || st == rast::SetupStatus::kInvalid)
                return std::string("rast rejects a triangle: ") + rast::to_string(st);
            ++out.triangles;
        }
    }
    rast::ThreadPool pool(1);
    MaskConsumer consumer(out);
    rs.rasterize(consumer, pool);
    return {};
}

std::string oracle_judge(const OracleCoverage& cov, const std::vector<Plane>& planes) {
    const Plane* p = nullptr;
    for (const Plane& q : planes)
        if (q.name == "color" && q.texel_bytes == 4) p = &q;
    if (!p) return "no RGBA8 colour plane";
    if (p->width != cov.width || p->height != cov.height) return "colour plane size differs from the scene";
    const uint8_t all = uint8_t((1u << cov.samples) - 1);
    uint64_t bad = 0, judged = 0;
    std::string first;
    for (uint32_t y = 0; y < cov.height; ++y)
        for (uint32_t x = 0; x < cov.width; ++x) {
            const uint8_t m = cov.mask[size_t(y) * cov.width + x];
            if (m != 0 && m != all) continue;  // partly covered 4x pixel: a resolved mix
            ++judged;
            uint32_t want = m ? cov.draw_rgba : cov.clear_rgba;
            if (cov.counting != Frag::kColor) {
                // kCount adds 1/255 per covering triangle to every channel; kFacing to red (front) or green
                // (back) and to alpha (both); unorm8 saturates at 255.
                const uint32_t f = cov.front[size_t(y) * cov.width + x], b = cov.back[size_t(y) * cov.width + x];
                const uint32_t add[4] = {cov.counting == Frag::kCount ? f + b : f,
                                         cov.counting == Frag::kCount ? f + b : b,
                                         cov.counting == Frag::kCount ? f + b : 0, f + b};
                want = 0;
                for (int ch = 0; ch < 4; ++ch)
                    want |= std::min<uint32_t>(255, (cov.clear_rgba >> (8 * ch) & 0xFF) + add[ch]) << (8 * ch);
            }
            uint32_t v;
            std::memcpy(&v, &p->data[(size_t(y) * p->width + x) * 4], 4);
            if (v == want) continue;
            if (bad++ == 0) {
                char buf[160];
                std::snprintf(buf, sizeof buf, "first (%u,%u) is 0x%08x, %s 0x%08x (ABGR)", x, y, v,
                              m ? "covered, expected" : "uncovered, expected the clear", want);
                first = buf;
            }
        }
    if (!bad) return {};
    return std::to_string(bad) + " of " + std::to_string(judged) +
           " judged pixels disagree with rast's reference "
           "coverage; " +
           first;
}

OracleVerdict rast_reference_oracle(const Scene& scene, const std::vector<Plane>& planes) {
    OracleVerdict v;
    OracleCoverage cov;
    if (std::string why = oracle_coverage(scene, cov); !why.empty()) {
        v.note = why;
        return v;
    }
    v.applies = true;
    v.note = std::to_string(cov.triangles) + " triangles, " + std::to_string(cov.samples) + "x" +
             (cov.counting == Frag::kCount    ? ", counted"
              : cov.counting == Frag::kFacing ? ", counted by facing"
                                              : "");
    v.error = oracle_judge(cov, planes);
    return v;
}

}  // namespace tilevk::cts
