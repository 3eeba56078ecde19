#include "exact_coverage.hpp"

#include <bit>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <cstring>

namespace tilevk::cts {
namespace {

namespace mp = boost::multiprecision;
// Floats scaled by 2^149 are integers below 2^278; a cross product below 2^557, an edge function (times pixel
// coordinates below 2^31) below 2^590, a depth form (times z) below 2^869 and its square below 2^1750: 2048 bits
// hold every value.
using Int = mp::number<mp::cpp_int_backend<2048, 2048, mp::signed_magnitude, mp::unchecked, void>>;

// f * 2^149, exactly (f finite), with subnormal inputs read as zero: lavapipe's draw runs with DAZ, so a subnormal
// coordinate is 0 there, and that defines the input (computations after it are exact here).
Int scaled(float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    const uint32_t e = (bits >> 23) & 0xff, m = bits & 0x7fffff;
    Int v = e == 0 ? Int(0) : Int(m | 0x800000u) << (e - 1);
    return bits >> 31 ? Int(-v) : v;
}

int sign(const Int& v) {
    return v > 0 ? 1 : v < 0 ? -1 : 0;
}

struct Vec3 {
    Int x, y, w;
};
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.w - a.w * b.y, a.w * b.x - a.x * b.w, a.x * b.y - a.y * b.x};
}

uint32_t rgba_at(const Plane& p, uint32_t x, uint32_t y) {
    uint32_t v;
    std::memcpy(&v, &p.data[(size_t(y) * p.width + x) * 4], 4);
    return v;
}

bool triangle_lists_only(const Scene& s, std::string* why) {
    for (const Draw& d : s.draws) {
        if (d.topology != VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST || !d.indices.empty() || d.instances != 1) {
            *why = "not a non-indexed triangle list";
            return false;
        }
        if (d.cull != VK_CULL_MODE_NONE || d.polygon_mode != VK_POLYGON_MODE_FILL || d.viewport || d.scissor ||
            d.stencil_test || d.depth_bias || d.sample_mask != 0xFFFFFFFFu || d.alpha_to_coverage ||
            !d.vertex_glsl.empty()) {
            *why = "state beyond filled, unculled triangles on the full viewport";
            return false;
        }
        if (d.depth_test && !(d.depth_op == VK_COMPARE_OP_LESS && s.target.clear_depth == 1.0f)) {
            *why = "a depth test that could reject covered pixels";
            return false;
        }
        if (d.frag != Frag::kColor || d.blend.blendEnable) {
            *why = "a fragment stage that could write the clear colour";
            return false;
        }
    }
    if (s.target.samples != VK_SAMPLE_COUNT_1_BIT || s.target.color != VK_FORMAT_R8G8B8A8_UNORM) {
        *why = "not a 1x RGBA8 target";
        return false;
    }
    return true;
}

}  // namespace

bool finite_position(const float v[4]) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

std::vector<ExactCover> exact_triangle_coverage(const float v0[4], const float v1[4], const float v2[4], uint32_t width,
                                                uint32_t height, bool clip_z) {
    std::vector<ExactCover> out(size_t(width) * height, ExactCover::kOutside);
    const float* v[3] = {v0, v1, v2};
    Vec3 p[3];
    Int z[3];
    for (int i = 0; i < 3; ++i) {
        p[i] = {scaled(v[i][0]), scaled(v[i][1]), scaled(v[i][3])};
        z[i] = scaled(v[i][2]);
    }
    // E_i(P) = P . (V_j x V_k); D = V0 . (V1 x V2).
    const Vec3 c[3] = {cross(p[1], p[2]), cross(p[2], p[0]), cross(p[0], p[1])};
    const int d_sign = sign(p[0].x * c[0].x + p[0].y * c[0].y + p[0].w * c[0].w);
    if (d_sign == 0) return out;  // the triangle's plane contains the eye: nothing is visible
    // The constraints as linear forms F(P) = P . f that must be positive: the three edges (times sign(D)) and,
    // with clip_z, the depth range: z/w = N/M with N = sum(z_i E_i), M = sum(w_i E_i), 0 <= N/M <= 1, i.e.
    // sign(M) N >= 0 and sign(M) (M - N) >= 0 (M has one sign inside the triangle: it is a multiple of D).
    std::vector<Vec3> forms;
    for (const Vec3& e : c) forms.push_back(d_sign > 0 ? e : Vec3{-e.x, -e.y, -e.w});
    Vec3 n{0, 0, 0}, m{0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        n = {n.x + z[i] * c[i].x, n.y + z[i] * c[i].y, n.w + z[i] * c[i].w};
        m = {m.x + p[i].w * c[i].x, m.y + p[i].w * c[i].y, m.w + p[i].w * c[i].w};
    }
    const size_t edge_forms = forms.size();
    if (clip_z) {
        forms.push_back(n);
        forms.push_back({m.x - n.x, m.y - n.y, m.w - n.w});
    }
    // A pixel centre within kMargin px of a constraint's line is undecided: both drivers snap vertices to 1/256 px,
    // which moves edges by up to about that much. In window pixels F's gradient is (2 fx / W, 2 fy / H) (in units
    // of W H, the scale of P below), so the test is F(P)^2 kMargin^-2 <= 4 (fx^2 H^2 + fy^2 W^2).
    constexpr int64_t kInvMargin = 128;
    const int64_t W = width, H = height;
    std::vector<Int> grad2;
    grad2.reserve(forms.size());
    for (const Vec3& f : forms) grad2.push_back(4 * (f.x * f.x * Int(H * H) + f.y * f.y * Int(W * W)));
    for (uint32_t py = 0; py < height; ++py) {
        const Int Y((2 * int64_t(py) + 1 - H) * W);
        for (uint32_t px = 0; px < width; ++px) {
            // Pixel centre (px + 1/2, py + 1/2) in NDC, times W H: ((2px + 1 - W) H, (2py + 1 - H) W, W H).
            const Int X((2 * int64_t(px) + 1 - W) * H), S(W * H);
            const int m_sign = clip_z ? sign(X * m.x + Y * m.y + S * m.w) : 1;
            bool outside = false, near = false;
            for (size_t k = 0; k < forms.size(); ++k) {
                Int f = X * forms[k].x + Y * forms[k].y + S * forms[k].w;
                if (k >= edge_forms && m_sign < 0) f = -f;
                if (f * f * (kInvMargin * kInvMargin) <= grad2[k])
                    near = true;
                else if (f < 0)
                    outside = true;
            }
            ExactCover& o = out[size_t(py) * width + px];
            o = outside ? ExactCover::kOutside : near ? ExactCover::kOnEdge : ExactCover::kInside;
        }
    }
    return out;
}

std::string exact_applies(const Scene& s) {
    std::string why;
    if (!triangle_lists_only(s, &why)) return why;
    for (const Draw& d : s.draws)
        for (const Vertex& v : d.vertices) {
            if (!finite_position(v.pos)) return "a vertex with an infinite or NaN coordinate has no exact answer";
            // 1/w below FLT_MIN is flushed to 0 by lavapipe's FTZ, which puts the vertex on the viewport's centre:
            // its float environment defines that projection, tilevk follows it, and no exact answer applies.
            // Unless x, y and z are at most 2^-64 |w|: then the centre is the exact projection too (to 2^-49 px).
            const float w = std::fabs(v.pos[3]), centred = w * 0x1p-64f;
            if (w >= 0x1p126f &&
                !(std::fabs(v.pos[0]) <= centred && std::fabs(v.pos[1]) <= centred && std::fabs(v.pos[2]) <= centred))
                return "a vertex with |w| >= 2^126 (1/w flushed by FTZ) and x, y or z above 2^-64 |w|";
        }
    return {};
}

std::vector<ExactCover> exact_scene_coverage(const Scene& s) {
    const uint32_t w = s.target.width, h = s.target.height;
    std::vector<ExactCover> out(size_t(w) * h, ExactCover::kOutside);
    for (const Draw& d : s.draws)
        for (size_t t = 0; t + 2 < d.vertices.size(); t += 3) {
            const std::vector<ExactCover> one = exact_triangle_coverage(d.vertices[t].pos, d.vertices[t + 1].pos,
                                                                        d.vertices[t + 2].pos, w, h, !d.depth_clamp);
            for (size_t i = 0; i < out.size(); ++i)
                if (one[i] == ExactCover::kOnEdge || out[i] == ExactCover::kOnEdge)
                    out[i] = ExactCover::kOnEdge;
                else if (one[i] == ExactCover::kInside)
                    out[i] = ExactCover::kInside;
        }
    return out;
}

Check exact_coverage(const Scene& scene, int64_t expected_inside) {
    // The exact answer is computed when the check runs, not when the case list is built: it takes seconds per
    // extreme scene, and every run of the runner builds the whole list whatever its filter selects.
    const std::string why = exact_applies(scene);
    const uint32_t clear = uint32_t(std::lround(scene.target.clear_color[0] * 255)) |
                           uint32_t(std::lround(scene.target.clear_color[1] * 255)) << 8 |
                           uint32_t(std::lround(scene.target.clear_color[2] * 255)) << 16 |
                           uint32_t(std::lround(scene.target.clear_color[3] * 255)) << 24;
    const uint32_t clear_depth = std::bit_cast<uint32_t>(scene.target.clear_depth);
    return [=](const std::vector<Plane>& planes) -> std::string {
        if (!why.empty()) return "exact_coverage: " + why;
        const Plane* p = nullptr;
        for (const Plane& q : planes)
            if (q.name == "color" && q.texel_bytes == 4) p = &q;
        if (p == nullptr) return "exact_coverage: no RGBA8 colour plane";
        // A D32 depth plane tells drawn pixels apart too: a fragment that passed the depth test wrote its depth even
        // where its colour came out as the clear colour (every attribute flushed to 0 beside a vertex whose 1/w is
        // subnormal: extreme.regression.w_1e37_setup_in_draw).
        const Plane* depth = nullptr;
        for (const Plane& q : planes)
            if (q.name == "depth" && q.format == VK_FORMAT_D32_SFLOAT) depth = &q;
        const std::vector<ExactCover> exact = exact_scene_coverage(scene);
        int64_t inside = 0, wrong = 0;
        std::string first;
        for (uint32_t y = 0; y < p->height; ++y)
            for (uint32_t x = 0; x < p->width; ++x) {
                const ExactCover e = exact[size_t(y) * p->width + x];
                inside += e == ExactCover::kInside;
                if (e == ExactCover::kOnEdge) continue;
                const bool drawn =
                    rgba_at(*p, x, y) != clear || (depth != nullptr && rgba_at(*depth, x, y) != clear_depth);
                if (drawn != (e == ExactCover::kInside) && wrong++ == 0)
                    first = "(" + std::to_string(x) + "," + std::to_string(y) + ") is " +
                            (drawn ? "drawn outside" : "not drawn inside");
            }
        if (expected_inside >= 0 && inside != expected_inside)
            return "the exact answer covers " + std::to_string(inside) + " pixel centres, the case expects " +
                   std::to_string(expected_inside);
        if (wrong != 0)
            return std::to_string(wrong) + " pixels disagree with the exact coverage (" + std::to_string(inside) +
                   " centres inside); first: " + first;
        return {};
    };
}

}  // namespace tilevk::cts
