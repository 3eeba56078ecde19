// extreme.*: triangles with extreme clip-space vertices, decided class by class (rast/geometry/README.md,
// "Extreme coordinates"): huge |x| or |y| up to FLT_MAX, tiny or huge w, w = +-Inf, NaN, denormal z. Every case is
// compared byte for byte with lavapipe; where the exact pixel-centre answer exists (finite inputs), it is also
// checked independently with exact integer arithmetic (exact_coverage.hpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "case.hpp"
#include "exact_coverage.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

float bits(uint32_t b) {
    return std::bit_cast<float>(b);
}

Vertex raw(float x, float y, float z, float w, std::array<float, 4> c) {
    Vertex v;
    v.pos[0] = x;
    v.pos[1] = y;
    v.pos[2] = z;
    v.pos[3] = w;
    for (int i = 0; i < 4; ++i) v.color[i] = c[i];
    return v;
}

const std::array<float, 4> kRed = {1, 0, 0, 1}, kGreen = {0, 1, 0, 1}, kBlue = {0, 0, 1, 1};

// One smooth-coloured triangle on a 256x256 target with a D32 LESS depth test (cleared to 1).
Scene depth_tested(std::vector<Vertex> v) {
    Scene s;
    s.target.width = s.target.height = 256;
    s.target.depth = VK_FORMAT_D32_SFLOAT;
    Draw d;
    d.vertices = std::move(v);
    d.depth_test = d.depth_write = true;
    d.depth_op = VK_COMPARE_OP_LESS;
    s.draws.push_back(std::move(d));
    return s;
}

// The issue's triangle: a huge-y vertex with tiny w (y = -1e10, w = 1e-7) and one with y = +1e10, all w > 0 and
// z/w in [0, 1) where visible. 14 080 pixel centres are inside.
Scene huge_y_tiny_w() {
    return depth_tested({raw(bits(0xbeb69e15), bits(0x3f265ecf), bits(0x3b6d059e), bits(0x3f6a91ca), kRed),
                         raw(bits(0xbf2f9c14), bits(0xd01502f9), bits(0x3d8c1320), bits(0x33d6bf95), kGreen),
                         raw(bits(0xbf046fad), bits(0x501502f9), bits(0x3ddcca1b), bits(0x3fbb898d), kBlue)});
}

// --- the random group: extreme vertices mixed into ordinary ones ------------------------------------------------

// The vertex classes of the random group (rast/geometry/README.md, "Extreme coordinates").
enum class VertexClass { kOrdinary, kHugeXY, kTinyW, kHugeW, kInfW, kInfXY, kNaN, kDenormZ, kNegativeW, kZeroW };
constexpr const char* kClassNames[] = {"ordinary", "huge_xy", "tiny_w",   "huge_w",     "inf_w",
                                       "inf_xy",   "nan",     "denorm_z", "negative_w", "zero_w"};
constexpr uint32_t kClasses = 10;

Vertex random_vertex(Rng& r, VertexClass c) {
    const float inf = std::numeric_limits<float>::infinity();
    // NDC position and depth, then scaled by w as a vertex shader would.
    float w = r.range(0.5f, 2.0f);
    float x = r.range(-1.5f, 1.5f) * w, y = r.range(-1.5f, 1.5f) * w, z = r.range(0.0f, 1.0f) * w;
    static const float kHuge[] = {1e5f, 1e10f, 1e20f, 1e30f, 1e37f, 1e38f, 3e38f, std::numeric_limits<float>::max()};
    static const float kTiny[] = {1e-7f, 1e-20f, 1e-30f, 1.17549435e-38f, 1e-40f, 1e-45f};
    static const float kDenorm[] = {1e-40f, 1e-45f, 5e-39f};
    switch (c) {
        case VertexClass::kOrdinary:
            break;
        case VertexClass::kHugeXY:
            if (r.below(3) != 1) x = r.sign() * r.pick(kHuge);
            if (r.below(3) != 0) y = r.sign() * r.pick(kHuge);
            break;
        case VertexClass::kTinyW:
            w = r.sign() * r.pick(kTiny);
            x = r.range(-1.5f, 1.5f), y = r.range(-1.5f, 1.5f), z = r.range(0.0f, 1.0f);
            break;
        case VertexClass::kHugeW:
            w = r.pick(kHuge) * (r.below(4) == 0 ? -1.0f : 1.0f);
            if (r.below(2)) x *= w, y *= w, z *= w;  // else the NDC values stay tiny next to w
            break;
        case VertexClass::kInfW:
            w = r.sign() * inf;
            break;
        case VertexClass::kInfXY:
            (r.below(2) ? x : y) = r.sign() * inf;
            break;
        case VertexClass::kNaN: {
            float* comp[4] = {&x, &y, &z, &w};
            *comp[r.below(4)] = std::numeric_limits<float>::quiet_NaN();
            break;
        }
        case VertexClass::kDenormZ:
            z = r.sign() * r.pick(kDenorm);
            break;
        case VertexClass::kNegativeW:
            w = -w;
            break;
        case VertexClass::kZeroW:
            w = r.sign() * 0.0f;
            break;
    }
    Vertex v = raw(x, y, z, w, {r.unit(), r.unit(), r.unit(), 1.0f});
    return v;
}

// One random scene on a 64x64 (or 256x256) target with a D32 LESS depth test: up to two ordinary triangles inside
// the viewport, then one triangle with one to three vertices of a random extreme class (the others ordinary).
Scene random_scene(uint32_t seed) {
    Rng r(seed);
    std::vector<Vertex> v;
    const uint32_t ordinary = r.below(3);
    for (uint32_t t = 0; t < 3 * ordinary; ++t) {
        const float w = r.range(0.5f, 2.0f);
        v.push_back(raw(r.range(-0.9f, 0.9f) * w, r.range(-0.9f, 0.9f) * w, r.range(0.05f, 0.95f) * w, w,
                        {r.unit(), r.unit(), r.unit(), 1.0f}));
    }
    const uint32_t extreme = 1 + r.below(3);
    const VertexClass c = VertexClass(1 + r.below(kClasses - 1));
    for (uint32_t k = 0; k < 3; ++k)
        v.push_back(random_vertex(
            r, k < extreme ? (r.below(4) == 0 ? VertexClass(1 + r.below(kClasses - 1)) : c) : VertexClass::kOrdinary));
    std::rotate(v.end() - 3, v.end() - 3 + r.below(3), v.end());  // the extreme vertices are not always first
    // Minimisation: TILEVK_CTS_EXTREME_KEEP=MASK keeps the triangles whose bit is set.
    if (const char* keep = std::getenv("TILEVK_CTS_EXTREME_KEEP")) {
        const unsigned long mask = std::strtoul(keep, nullptr, 0);
        std::vector<Vertex> kept;
        for (size_t t = 0; t < v.size() / 3; ++t)
            if (mask >> t & 1) kept.insert(kept.end(), v.begin() + 3 * t, v.begin() + 3 * t + 3);
        v = std::move(kept);
    }
    const uint32_t size = r.below(4) == 0 ? 256 : 64;
    Scene s = depth_tested(std::move(v));
    s.target.width = s.target.height = size;
    if (std::getenv("TILEVK_CTS_EXTREME_DUMP")) {
        std::printf("extreme.random.seed_%u: %ux%u\n", seed, s.target.width, s.target.height);
        for (const Vertex& vx : s.draws[0].vertices)
            std::printf("  (%.9g, %.9g, %.9g, %.9g) = {0x%08x, 0x%08x, 0x%08x, 0x%08x}, colour {%.9g, %.9g, %.9g}\n",
                        double(vx.pos[0]), double(vx.pos[1]), double(vx.pos[2]), double(vx.pos[3]),
                        std::bit_cast<uint32_t>(vx.pos[0]), std::bit_cast<uint32_t>(vx.pos[1]),
                        std::bit_cast<uint32_t>(vx.pos[2]), std::bit_cast<uint32_t>(vx.pos[3]), double(vx.color[0]),
                        double(vx.color[1]), double(vx.color[2]));
    }
    return s;
}

// One class each: an ordinary triangle with one vertex (the middle one) replaced. The hand-checked expectations are
// in tests/rast/geometry/extreme_test.cpp; here both drivers draw them through Vulkan.
Scene one_extreme(float x, float y, float z, float w) {
    return depth_tested(
        {raw(-0.6f, -0.5f, 0.3f, 1.0f, kRed), raw(x, y, z, w, kGreen), raw(0.1f, 0.7f, 0.6f, 1.0f, kBlue)});
}

struct HandCase {
    const char* name;
    float x, y, z, w;
};
const float kInf = std::numeric_limits<float>::infinity(), kNan = std::numeric_limits<float>::quiet_NaN(),
            kMax = std::numeric_limits<float>::max();
const HandCase kHandCases[] = {
    {"w_pos_inf", 0.5f, -0.4f, 0.5f, kInf},
    {"w_neg_inf", 0.5f, -0.4f, 0.5f, -kInf},
    {"x_pos_inf", kInf, -0.4f, 0.5f, 1.0f},
    {"y_neg_inf", 0.5f, -kInf, 0.5f, 1.0f},
    {"x_nan", kNan, -0.4f, 0.5f, 1.0f},
    {"w_nan", 0.5f, -0.4f, 0.5f, kNan},
    {"z_nan", 0.5f, -0.4f, kNan, 1.0f},
    {"z_negative_denormal", 0.5f, -0.4f, -1e-40f, 1.0f},
    {"z_positive_denormal", 0.5f, -0.4f, 1e-40f, 1.0f},
    {"x_3e38", 3e38f, -0.4f, 0.5f, 1.0f},
    {"x_flt_max", kMax, -0.4f, 0.5f, 1.0f},
    {"xy_flt_max", kMax, -kMax, 0.5f, 1.0f},
    {"w_flt_max", 0.5f, -0.4f, 0.5f, kMax},
    {"w_tiny", 0.5f, -0.4f, 0.5f, 1e-30f},
    {"w_denormal", 0.5f, -0.4f, 0.5f, 1e-40f},
    {"w_negative_tiny", 0.5f, -0.4f, 0.5f, -1e-30f},
    {"w_zero", 0.5f, -0.4f, 0.5f, 0.0f},
    {"w_negative_zero", 0.5f, -0.4f, 0.5f, -0.0f},
    {"x_flt_max_w_flt_max", kMax, -0.4f, 0.5f, kMax},
};

// Frozen scenes the fuzzer found (the reproduction tilevk-cts --fuzz prints for a minimised failure dumps its
// vertices in this form, TILEVK_CTS_EXTREME_DUMP): each broke tilevk or showed a new class before its fix. Seeds
// alone would not do: the generator may change.
struct Regression {
    const char* name;
    uint32_t size;                                  // square target
    std::vector<std::array<uint32_t, 4>> vertices;  // clip-space position bits, three per triangle
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPolygonMode polygon_mode = VK_POLYGON_MODE_FILL;
    std::vector<std::array<float, 3>> colours = {};  // per vertex; empty: red, green, blue in turn
};
const Regression kRegressions[] = {
    // (-1e38, 1e38) at w = 1.5: lavapipe's clip of the edges to it cancels; lavapipe misses 19 of its pixel
    // centres, tilevk (precise fallback) draws them (extreme.random.seed_2 of the first generator).
    {"huge_xy_cancellation",
     64,
     {{0xbecf6d0e, 0x3ebcbb30, 0x3ea44ce8, 0x3f9f702e},
      {0xbfc607a9, 0x3fbc6c60, 0x3fb82e04, 0x3fb8b512},
      {0xfe967699, 0x7e967699, 0x3f0ba4e3, 0x3fc33e88}}},
    // y = 3e38 with x = 1e5 beside a vertex at x = -1e37: the intersection parameter flushes (FTZ); lavapipe draws
    // about half the exact pixels (extreme.random.seed_3, its extreme triangle).
    {"flushed_t_y_3e38",
     64,
     {{0xfcf0bdc2, 0x3fa14020, 0x3eb2ad94, 0x3fa08fc2},
      {0x47c35000, 0x7f61b1e6, 0x3ec61d3e, 0x3f4ff24c},
      {0x4008fa7c, 0xf149f2ca, 0x3f914982, 0x3fdcdf28}}},
    // y = -1e38 at w = 0.65: lavapipe's clip cancels into a polygon that misses a corner sliver of the viewport
    // (0.4 px high at x = 0) but no pixel centre, so its result is kept at 1x although the precise polygon differs by
    // more than 1/512 px; the precise one drew the same pixels with depths 1 ulp off on 1901 of them
    // (extreme.random.seed_2121, its second triangle).
    {"huge_y_same_centres",
     64,
     {{0xbefc25f8, 0xfe967699, 0x3f1dbcd1, 0x3f25e690},
      {0x3f920978, 0x3fa1d496, 0x3d65fa7f, 0x3fa50aa9},
      {0xbf927dd1, 0xbf9318e4, 0x3f1224e6, 0x3f4fcbb1}}},
    // w = 1e37 beside w = 0 (extreme.random.seed_2903): draw's intersection with the far plane, 4e-39 from the
    // w = 1e37 vertex, flushes to t = 0 and keeps a vertex past that plane, 10 px from the precise one; but with D32
    // LESS what it adds there is at depth >= 1 and never drawn, so draw's polygon draws the exact pixels and its
    // roundings are kept (ClipConfig::hidden_depth; the precise polygon gave 1 pixel and 2 colours otherwise).
    {"w_zero_far_plane",
     256,
     {{0xbf7769a1, 0x3f2860da, 0x3f75b2c8, 0x7cf0bdc2},
      {0x3fb8ea4b, 0xbf65f060, 0x3f173249, 0x3f90119c},
      {0xbeeeb050, 0xbe0c790f, 0x3f0211b2, 0x00000000}}},
    // Lines with w = 2.5e37..5e37 and small colours: the 1/w-premultiplied colours and their differences along a
    // line meet subnormals in llvmpipe's line setup (lp_setup_line.c, plain C). Clipped lines wait in draw's vbuf
    // like triangles and are set up after draw_vbo, denormals kept; tilevk set them up at once with denormals
    // flushed (124 pixels differed).
    {"lines_w_3e37_setup_after_draw",
     64,
     {{0x7dd01240, 0xfcae4616, 0x7c47109e, 0x7e167699},
      {0xfdc6e0ad, 0x7d4a92da, 0x7da38edb, 0x7db48e52},
      {0xfcf0469e, 0x7d55c3fa, 0x7d2630a2, 0x7db48e52},
      {0xfd076f00, 0xfd41af7c, 0x7db1628c, 0x7db48e52},
      {0xfbd70eed, 0xfd27382f, 0x7d814dec, 0x7db48e52},
      {0x7d88e47b, 0xfda94405, 0x7d537418, 0x7db48e52}},
     VK_PRIMITIVE_TOPOLOGY_LINE_LIST,
     VK_POLYGON_MODE_FILL,
     {{0.567100704f, 0.0215862151f, 0.418073058f},
      {0.909990907f, 0.705541015f, 0.224205479f},
      {0.91857636f, 0.352847993f, 2.66411075e-06f},
      {0.0477041863f, 0.000267092022f, 0.474410772f},
      {0.632494926f, 0.597110689f, 0.0344341211f},
      {0.385582685f, 0.0126472199f, 0.189255178f}}},
    // The same through polygonMode LINE: the unfilled stage's edges reach the vbuf as lines.
    {"polygon_line_w_3e37_setup_after_draw",
     64,
     {{0x7d8feda5, 0x7d8a72cc, 0x7c1ccaf0, 0x7db48e52},
      {0x7b20bb3a, 0x7a7fe36e, 0x787e8f56, 0x7b4097ce},
      {0x7d885361, 0xfe5318fb, 0x7e8e37bc, 0x7e967699},
      {0x7d367a6e, 0x7d1c6392, 0x7d8beb60, 0x7db48e52},
      {0xfd503d0c, 0xfda36114, 0x7c003f29, 0x7db48e52},
      {0x7c34e22a, 0xfbb19292, 0x7d3c78eb, 0x7db48e52}},
     VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
     VK_POLYGON_MODE_LINE,
     {{4.49179197e-06f, 0.08767014f, 0.000100857833f},
      {0.0181117151f, 0.516004622f, 0.151030898f},
      {0.222569466f, 0.167743996f, 0.27937752f},
      {0.00632749684f, 2.24866853e-05f, 0.00916628446f},
      {0.172597408f, 0.0829013735f, 0.0062905862f},
      {0.42352134f, 0.0383573174f, 0.562924445f}}},
    // w = FLT_MAX beside a vertex at w = 1e-20 past the right, bottom and far planes (extreme.random.seed_6638): draw's
    // cut of the edge back to the w = FLT_MAX vertex has t = 0.986 / FLT_MAX, flushed to 0 (FTZ), so it keeps the
    // w = 1e-20 vertex, 1e20 px away; lavapipe snaps it to INT_MIN and draws 1721 wrong pixels, tilevk's precise clip
    // the exact ones. With x, y, z at most 2^-64 w, FTZ's centre is the exact projection, so the exact answer holds.
    {"w_flt_max_flushed_t",
     64,
     {{0x402cf557, 0x3fa4d831, 0x3eb47ea0, 0x7f7fffff},
      {0xbe80f722, 0x3ff0f6fc, 0x3f4c3489, 0x3fa7a738},
      {0x3f7c5710, 0x3f9132d0, 0x3e8e5d60, 0x1e3ce508}}},
    // y = 3e38 at w = 0.89 beside w = FLT_MAX (extreme.random.seed_2215): a plane distance FLT_MAX + 3e38 overflows,
    // t = 0 keeps a vertex at y = 9.6e19 px; lavapipe draws half the target from INT_MIN, tilevk the exact 555 centres.
    {"w_flt_max_overflow",
     64,
     {{0x60ad78ec, 0x7f61b1e6, 0x3f10765d, 0x3f634504},
      {0xbf3df3c8, 0x3fbb5899, 0x3eeb4e42, 0x7f7fffff},
      {0x3f3bc6bf, 0x3f005b5c, 0x3b6713ad, 0x3f84c1c9}}},
    // w = 1e38 and 1e37 (extreme.random.seed_2403, its third triangle): the colour and 1/w planes' setup meets
    // subnormals. The clipped triangle waits in draw's vbuf until llvmpipe_draw_vbo's final draw_flush, after draw_vbo
    // has restored the float state, so lavapipe sets it up with denormals kept (rast/geometry/README.md).
    {"w_1e37_setup_after_draw",
     64,
     {{0xbf7609ea, 0x3ec6dd5f, 0x3f727cb6, 0x7e967699},
      {0x7cb2d340, 0x7c84eb17, 0x7b0c2a59, 0x7cf0bdc2},
      {0x7d236e58, 0x7d40c316, 0x7b7a3b9d, 0x7cf0bdc2}}},
};

Scene regression_scene(const Regression& g);

// `count` small ordinary triangles (ids from `first`), inside the viewport.
std::vector<Vertex> small_triangles(int first, int count) {
    std::vector<Vertex> small;
    for (int i = first; i < first + count; ++i) {
        const float x = -0.95f + 0.009f * float(i % 100), y = -0.95f + 0.015f * float(i / 100 % 20);
        small.push_back(raw(x, y, 0.5f, 1.0f, kRed));
        small.push_back(raw(x + 0.02f, y, 0.5f, 1.0f, kGreen));
        small.push_back(raw(x, y + 0.03f, 0.5f, 1.0f, kBlue));
    }
    return small;
}

// The same triangle with `count` small ordinary ones after it (extreme_last: before it), all in one draw. After it,
// in the same batch (so through draw's pipeline), they fill draw's vbuf: the extreme triangle reaches setup inside
// draw_vbo, with denormals flushed. Before it, in a draw large enough for tilevk's parallel triangle path, it is
// still in the vbuf at the end of the draw.
Scene with_small_triangles(const Regression& g, int count, bool extreme_last) {
    Scene s = regression_scene(g);
    std::vector<Vertex>& v = s.draws[0].vertices;
    const std::vector<Vertex> small = small_triangles(0, count);
    v.insert(extreme_last ? v.begin() : v.end(), small.begin(), small.end());
    return s;
}

// The same triangle twice in a large draw: mirrored in x in the middle (`before` small ones, it, `after` small ones;
// mirrored so that both stay visible under the depth test) and as it is last. The middle one's batch goes through
// draw's pipeline and is flushed by the next direct batch, inside draw_vbo (denormals flushed); the last one waits
// in the vbuf until after draw_vbo (denormals kept). tilevk sets the draw up to its last direct batch on the
// parallel path and the rest in order.
Scene mid_and_end_of_large_draw(const Regression& g, int before, int after) {
    Scene s = regression_scene(g);
    std::vector<Vertex>& v = s.draws[0].vertices;
    const std::vector<Vertex> extreme = v;
    for (Vertex& m : v) m.pos[0] = -m.pos[0];
    const std::vector<Vertex> head = small_triangles(0, before), tail = small_triangles(before, after);
    v.insert(v.begin(), head.begin(), head.end());
    v.insert(v.end(), tail.begin(), tail.end());
    v.insert(v.end(), extreme.begin(), extreme.end());
    return s;
}

// The same triangle at the start of draw's vbuf's last filling, in a draw large enough for tilevk's parallel triangle
// path whose every batch goes through draw's pipeline (each has a triangle wholly right of the viewport, which the
// clipper drops), so the draw has no direct batch. A vbuf vertex is 3 slots here (tilevk's count: position, v_color
// and the vertex shader's point size; lavapipe's boundaries agree on this scene), a buffer 85 vertices: 28
// unclipped small triangles. After 73 full buffers of small ones (flushed inside draw_vbo, denormals flushed), the
// triangle starts the last buffer, with 3 small ones after it, set up after draw_vbo (denormals kept). tilevk sets
// the draw up in parallel up to that last filling: a boundary one filling (or one triangle) late sets the triangle
// up with denormals flushed.
Scene at_last_vbuf_filling(const Regression& g) {
    Scene s = regression_scene(g);
    std::vector<Vertex>& v = s.draws[0].vertices;
    const std::vector<Vertex> extreme = v;
    const std::vector<Vertex> off = {raw(3.0f, 0.0f, 0.5f, 1.0f, kRed), raw(3.5f, 0.0f, 0.5f, 1.0f, kGreen),
                                     raw(3.0f, 0.5f, 0.5f, 1.0f, kBlue)};
    constexpr int kHead = 73 * 28, kBatchTriangles = 1365;  // non-indexed list batches: 4095 vertices
    v = off;                                                // batch 0 starts with one
    const std::vector<Vertex> head = small_triangles(0, kHead), tail = small_triangles(kHead, 3);
    for (int i = 0; i < kHead; ++i) {
        if (v.size() / 3 == kBatchTriangles) v.insert(v.end(), off.begin(), off.end());  // and batch 1
        v.insert(v.end(), head.begin() + 3 * i, head.begin() + 3 * i + 3);
    }
    v.insert(v.end(), extreme.begin(), extreme.end());
    v.insert(v.end(), tail.begin(), tail.end());
    return s;
}

// The same triangle at the end of a full vbuf whose limit is its 1020 indices (LP_MAX_VBUF_INDEXES), not its
// vertices: an indexed list cycling through 8 small triangles (24 vertices, each emitted once per buffer) fills the
// indices long before the 85 vertices. Indexed batches are 341 triangles (draw's vsplit segments of 1023 indices);
// each batch starts with a triangle wholly right of the viewport, so both go through draw's pipeline and nothing
// flushes the vbuf but its limit and the end of the draw. Batch 0 is that triangle, the extreme triangle (first, so
// that none of its pieces is near a buffer boundary: rast/geometry/README.md "Serial tails" names a difference
// there) and 339 small ones: at least 340 triangles reach the vbuf, which is full before batch 1's small ones, so
// the extreme triangle is set up inside draw_vbo (denormals flushed). With a limit larger by a dozen triangles it
// would still wait in the vbuf after draw_vbo (denormals kept): the output depends on where the full vbuf is
// flushed.
Scene at_vbuf_index_limit(const Regression& g) {
    Scene s = regression_scene(g);
    Draw& d = s.draws[0];
    const std::vector<Vertex> extreme = d.vertices;
    d.vertices = {raw(3.0f, 0.0f, 0.5f, 1.0f, kRed), raw(3.5f, 0.0f, 0.5f, 1.0f, kGreen),
                  raw(3.0f, 0.5f, 0.5f, 1.0f, kBlue)};
    d.vertices.insert(d.vertices.end(), extreme.begin(), extreme.end());
    const std::vector<Vertex> small = small_triangles(0, 8);
    d.vertices.insert(d.vertices.end(), small.begin(), small.end());
    uint32_t next_small = 0;
    auto add = [&d](uint32_t first) { d.indices.insert(d.indices.end(), {first, first + 1, first + 2}); };
    auto add_small = [&] { add(6 + 3 * (next_small++ % 8)); };
    add(0);  // batch 0
    add(3);
    for (int i = 0; i < 339; ++i) add_small();
    add(0);  // batch 1
    for (int i = 0; i < 5; ++i) add_small();
    return s;
}

Scene regression_scene(const Regression& g) {
    std::vector<Vertex> v;
    const std::array<float, 4> colours[3] = {kRed, kGreen, kBlue};
    for (size_t i = 0; i < g.vertices.size(); ++i) {
        const auto& b = g.vertices[i];
        const std::array<float, 4> c = g.colours.empty()
                                           ? colours[i % 3]
                                           : std::array<float, 4>{g.colours[i][0], g.colours[i][1], g.colours[i][2], 1};
        v.push_back(raw(bits(b[0]), bits(b[1]), bits(b[2]), bits(b[3]), c));
    }
    Scene s = depth_tested(std::move(v));
    s.target.width = s.target.height = g.size;
    s.draws[0].topology = g.topology;
    s.draws[0].polygon_mode = g.polygon_mode;
    return s;
}

// The named difference of this group (rast/geometry/README.md, "Extreme coordinates").
constexpr const char* kReferenceWrong =
    "lavapipe's float clipper or viewport overflows, flushes or cancels on extreme finite inputs; tilevk draws the "
    "exact pixel centres";

// A case on `make`'s scene: byte-equal to lavapipe, or, with finite vertices, the exact coverage on tilevk and
// either byte equality or a lavapipe frame that fails the same exact check.
Case extreme_case(std::string name, std::function<Scene()> make) {
    const Scene s = make();
    const bool finite = exact_applies(s).empty();
    return {
        std::move(name), std::move(make), finite ? exact_coverage(s) : Check(), "", {}, finite ? kReferenceWrong : ""};
}

}  // namespace

void add_extreme_cases(CaseList& out) {
    Case issue = extreme_case("extreme.huge_y_tiny_w", huge_y_tiny_w);
    issue.check = exact_coverage(huge_y_tiny_w(), 14080);
    out.push_back(std::move(issue));
    for (const Regression& g : kRegressions)
        out.push_back(extreme_case(std::string("extreme.regression.") + g.name, [&g] { return regression_scene(g); }));
    const Regression& late_setup = kRegressions[std::size(kRegressions) - 1];
    out.push_back(extreme_case("extreme.regression.w_1e37_setup_in_draw",
                               [&late_setup] { return with_small_triangles(late_setup, 200, false); }));
    out.push_back(extreme_case("extreme.regression.w_1e37_setup_after_large_draw",
                               [&late_setup] { return with_small_triangles(late_setup, 2100, true); }));
    out.push_back(extreme_case("extreme.regression.w_1e37_setup_mid_and_end_of_large_draw",
                               [&late_setup] { return mid_and_end_of_large_draw(late_setup, 1000, 1100); }));
    out.push_back(extreme_case("extreme.regression.w_1e37_setup_at_last_vbuf_filling",
                               [&late_setup] { return at_last_vbuf_filling(late_setup); }));
    out.push_back(extreme_case("extreme.regression.w_1e37_setup_before_vbuf_index_limit_flush",
                               [&late_setup] { return at_vbuf_index_limit(late_setup); }));
    for (const HandCase& h : kHandCases)
        out.push_back(
            extreme_case(std::string("extreme.class.") + h.name, [h] { return one_extreme(h.x, h.y, h.z, h.w); }));
    // The default list is fixed (seeds 1..200); TILEVK_CTS_EXTREME_SEEDS=FIRST:COUNT explores others (the main job's
    // fuzzing window, tools/run_main.sh).
    uint32_t first = 1, count = 200;
    if (const char* env = std::getenv("TILEVK_CTS_EXTREME_SEEDS")) {
        if (std::sscanf(env, "%u:%u", &first, &count) != 2)
            throw std::runtime_error("TILEVK_CTS_EXTREME_SEEDS: expected FIRST:COUNT, got " + std::string(env));
    }
    for (uint32_t seed = first; seed < first + count; ++seed) out.push_back(extreme_seed_case(seed));
}

Case extreme_seed_case(uint32_t seed) {
    return extreme_case("extreme.random.seed_" + std::to_string(seed), [seed] { return random_scene(seed); });
}

}  // namespace tilevk::cts
