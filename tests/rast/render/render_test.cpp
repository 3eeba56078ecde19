// End-to-end tests of the render orchestrator: GLSL shaders -> Renderer -> memory, checked against coverage and
// colours computed independently here (the top-left rule on snapped coordinates, exact UNORM8 conversions).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "bench/shader/bench_shaders.h"
#include "rast/core/thread_pool.h"
#include "rast/render/renderer.h"
#include "tests/shader/glsl.h"

namespace tilevk::rast::render {
namespace {

using shader::Stage;

struct Vertex {
    float pos[4];
    float color[4];
};

struct Image {
    int w, h;
    std::vector<uint8_t> rgba;
    std::vector<float> depth;
};

PipelineState make_pipeline(const shader::Program* vs, const shader::Program* fs, int w, int h) {
    PipelineState p;
    p.vertex = vs;
    p.fragment = fs;
    p.attribs = {{geometry::VertexFormat::R32G32B32A32_SFLOAT, 0, 0},
                 {geometry::VertexFormat::R32G32B32A32_SFLOAT, 0, 16}};
    p.attrib_locations = {0, 1};
    p.bindings = {{sizeof(Vertex), geometry::InputRate::kVertex}};
    p.viewport = {0, 0, float(w), float(h), 0, 1};
    return p;
}

Framebuffer make_fb(Image& img, bool with_depth) {
    Framebuffer fb;
    fb.width = img.w;
    fb.height = img.h;
    fb.num_color = 1;
    fb.color[0] = {img.rgba.data(), fragment::ColorFormat::R8G8B8A8_UNORM, size_t(img.w) * 4, 0};
    if (with_depth) {
        fb.depth_stencil.depth = reinterpret_cast<uint8_t*>(img.depth.data());
        fb.depth_stencil.format = fragment::DepthFormat::D32F;
        fb.depth_stencil.depth_row_pitch = size_t(img.w) * 4;
    }
    return fb;
}

void draw(Renderer& r, const PipelineState& p, const std::vector<Vertex>& verts) {
    DrawCall call;
    call.count = static_cast<uint32_t>(verts.size());
    call.vertex_buffers = {{reinterpret_cast<const uint8_t*>(verts.data()), uint32_t(verts.size() * sizeof(Vertex))}};
    shader::Bindings bindings;
    ASSERT_EQ(r.draw(p, call, bindings), "");
}

// Independent coverage: the top-left rule at 1x on coordinates snapped as rne(fl(x - 0.5) * 256).
bool covered(const float wx[3], const float wy[3], int px, int py) {
    int64_t x[3], y[3];
    for (int i = 0; i < 3; ++i) {
        x[i] = std::llrint((wx[i] - 0.5f) * 256.0f);
        y[i] = std::llrint((wy[i] - 0.5f) * 256.0f);
    }
    const int64_t area = (x[0] - x[1]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[0] - y[1]);
    if (area == 0) return false;
    if (area < 0) std::swap(x[1], x[2]), std::swap(y[1], y[2]);
    const int64_t sx = int64_t(px) * 256, sy = int64_t(py) * 256;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const int64_t dy = y[i] - y[j], dx = x[i] - x[j];
        const int64_t bias = (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;
        if (dy * (x[i] - sx) - dx * (y[i] - sy) + bias <= 0) return false;
    }
    return true;
}

class RenderTest : public ::testing::Test {
  protected:
    std::shared_ptr<const shader::Program> vs = shader::test::make_program(Stage::Vertex, bench_shaders::kPassVs);
    std::shared_ptr<const shader::Program> fs = shader::test::make_program(Stage::Fragment, bench_shaders::kPassFs);
};

TEST_F(RenderTest, FlatTriangleCoverageMatchesTopLeftRule) {
    const int w = 67, h = 45;  // not a multiple of the tile or block size
    Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0), {}};
    ThreadPool pool(2);
    Renderer r(pool, Method::kHier);
    PipelineState p = make_pipeline(vs.get(), fs.get(), w, h);
    // Clip-space vertices chosen so window coordinates are exact in float.
    std::vector<Vertex> v = {{{-0.9f, -0.8f, 0.5f, 1}, {1, 0, 0, 1}},
                             {{0.8f, -0.3f, 0.5f, 1}, {1, 0, 0, 1}},
                             {{-0.2f, 0.95f, 0.5f, 1}, {1, 0, 0, 1}}};
    r.begin(make_fb(img, false));
    draw(r, p, v);
    r.end();
    float wx[3], wy[3];
    for (int i = 0; i < 3; ++i) {
        // The viewport transform with FMA when the host fuses; both forms agree on these inputs to within the
        // float rounding the snap absorbs, so compute as lavapipe does.
        const float sx = 0.5f * w, sy = 0.5f * h;
        wx[i] = Renderer::fused() ? std::fma(v[i].pos[0], sx, sx) : v[i].pos[0] * sx + sx;
        wy[i] = Renderer::fused() ? std::fma(v[i].pos[1], sy, sy) : v[i].pos[1] * sy + sy;
    }
    int mismatches = 0, count = 0;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            const uint8_t* c = &img.rgba[(size_t(py) * w + px) * 4];
            const bool expect = covered(wx, wy, px, py);
            count += expect;
            if (expect) {
                mismatches += !(c[0] == 255 && c[1] == 0 && c[2] == 0 && c[3] == 255);
            } else {
                mismatches += !(c[0] == 0 && c[1] == 0 && c[2] == 0 && c[3] == 0);
            }
        }
    EXPECT_GT(count, 500);
    EXPECT_EQ(mismatches, 0);
}

// Pipeline statistics (DrawCall::statistics, docs/lavapipe-rules.md §13): every triangle reaching setup is one
// clipping primitive, and llvmpipe calls its fragment function once per 4x4 block in which the triangle covers a
// pixel (whole 64x64 tiles and 16x16 blocks included), counted here from the top-left rule; cull FRONT_AND_BACK
// counts nothing. The same for any thread count and method, and nothing without a statistics sink.
TEST_F(RenderTest, StatisticsCountSetupTrianglesAndCoveredBlocks) {
    const int w = 141, h = 99;  // a whole tile at (0, 0), partial tiles and blocks at the edges
    const std::vector<Vertex> v = {{{-1, -1, 0.5f, 1}, {1, 0, 0, 1}},      {{1, -1, 0.5f, 1}, {1, 0, 0, 1}},
                                   {{-1, 1, 0.5f, 1}, {1, 0, 0, 1}},       {{-0.9f, -0.8f, 0.5f, 1}, {0, 1, 0, 1}},
                                   {{0.8f, -0.3f, 0.5f, 1}, {0, 1, 0, 1}}, {{-0.2f, 0.95f, 0.5f, 1}, {0, 1, 0, 1}},
                                   {{0.31f, 0.3f, 0.5f, 1}, {0, 0, 1, 1}}, {{0.37f, 0.33f, 0.5f, 1}, {0, 0, 1, 1}},
                                   {{0.32f, 0.41f, 0.5f, 1}, {0, 0, 1, 1}}};
    uint64_t blocks = 0, pixels = 0;
    for (size_t t = 0; t < v.size(); t += 3) {
        float wx[3], wy[3];
        for (int i = 0; i < 3; ++i) {
            const float sx = 0.5f * w, sy = 0.5f * h;
            wx[i] = Renderer::fused() ? std::fma(v[t + i].pos[0], sx, sx) : v[t + i].pos[0] * sx + sx;
            wy[i] = Renderer::fused() ? std::fma(v[t + i].pos[1], sy, sy) : v[t + i].pos[1] * sy + sy;
        }
        for (int by = 0; by < h; by += 4)
            for (int bx = 0; bx < w; bx += 4) {
                int n = 0;
                for (int py = by; py < std::min(by + 4, h); ++py)
                    for (int px = bx; px < std::min(bx + 4, w); ++px) n += covered(wx, wy, px, py);
                blocks += n != 0;
                pixels += uint64_t(n);
            }
    }
    EXPECT_GT(blocks, 64u * 64u / 16u);  // more than the whole tile
    EXPECT_NE(blocks * 16, pixels);      // a count per pixel would differ
    for (const unsigned threads : {1u, 2u})
        for (const Method m : {Method::kHier, Method::kReference}) {
            Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0), {}};
            ThreadPool pool(threads);
            Renderer r(pool, m);
            PipelineState p = make_pipeline(vs.get(), fs.get(), w, h);
            PipelineState culled = p;
            culled.cull = CullMode::kBoth;
            RasterStatistics counted, none;
            r.begin(make_fb(img, false));
            for (const auto& [pipe, sink] : {std::pair{&p, &counted}, std::pair{&culled, &none},
                                             std::pair<PipelineState*, RasterStatistics*>{&p, nullptr}}) {
                DrawCall call;
                call.count = uint32_t(v.size());
                call.vertex_buffers = {
                    {reinterpret_cast<const uint8_t*>(v.data()), uint32_t(v.size() * sizeof(Vertex))}};
                call.statistics = sink;
                shader::Bindings bindings;
                ASSERT_EQ(r.draw(*pipe, call, bindings), "");
            }
            r.end();
            EXPECT_EQ(counted.clipping_primitives, 3u) << threads << " threads";
            EXPECT_EQ(counted.fragment_blocks, blocks) << threads << " threads";
            EXPECT_EQ(none.clipping_primitives, 0u);
            EXPECT_EQ(none.fragment_blocks, 0u);
        }
}

TEST_F(RenderTest, DepthTestKeepsNearerTriangleAndIsThreadCountIndependent) {
    const int w = 130, h = 70;
    auto render = [&](unsigned threads) {
        Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0), std::vector<float>(size_t(w) * h, 1.0f)};
        ThreadPool pool(threads);
        Renderer r(pool, Method::kHier);
        PipelineState p = make_pipeline(vs.get(), fs.get(), w, h);
        p.depth_stencil.depth_test = true;
        p.depth_stencil.depth_write = true;
        p.depth_stencil.depth_compare = fragment::CompareOp::Less;
        // Full-screen pair at z=0.25 (green) drawn after a full-screen pair at z=0.75 (red), then a far blue one.
        auto quad = [](float z, const float c[4]) {
            std::vector<Vertex> q;
            const float xy[6][2] = {{-1, -1}, {1, -1}, {-1, 1}, {-1, 1}, {1, -1}, {1, 1}};
            for (auto& p2 : xy) q.push_back({{p2[0], p2[1], z, 1}, {c[0], c[1], c[2], c[3]}});
            return q;
        };
        const float red[4] = {1, 0, 0, 1}, green[4] = {0, 1, 0, 1}, blue[4] = {0, 0, 1, 1};
        r.begin(make_fb(img, true));
        draw(r, p, quad(0.75f, red));
        draw(r, p, quad(0.25f, green));
        draw(r, p, quad(0.5f, blue));
        r.end();
        return img;
    };
    Image a = render(1), b = render(3);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_EQ(a.depth, b.depth);
    for (int i = 0; i < w * h; ++i) {
        ASSERT_EQ(a.rgba[i * 4 + 0], 0) << i;
        ASSERT_EQ(a.rgba[i * 4 + 1], 255) << i;
        ASSERT_EQ(a.depth[i], 0.25f) << i;
    }
}

TEST_F(RenderTest, SmoothColourIsInterpolatedAndConverted) {
    // A full-screen triangle pair whose colour is x-linear: pixel centres sample exact values in float.
    const int w = 8, h = 4;
    Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0), {}};
    ThreadPool pool(1);
    Renderer r(pool, Method::kHier);
    PipelineState p = make_pipeline(vs.get(), fs.get(), w, h);
    std::vector<Vertex> v = {{{-1, -1, 0, 1}, {0, 0, 0, 1}}, {{1, -1, 0, 1}, {1, 0, 0, 1}},
                             {{-1, 1, 0, 1}, {0, 0, 0, 1}},  {{-1, 1, 0, 1}, {0, 0, 0, 1}},
                             {{1, -1, 0, 1}, {1, 0, 0, 1}},  {{1, 1, 0, 1}, {1, 0, 0, 1}}};
    r.begin(make_fb(img, false));
    draw(r, p, v);
    r.end();
    for (int px = 0; px < w; ++px) {
        const float red = (px + 0.5f) / w;                                  // exact: w is a power of two
        const int expect = static_cast<int>(std::nearbyint(red * 255.0f));  // rne(x*255)
        for (int py = 0; py < h; ++py) EXPECT_EQ(img.rgba[(size_t(py) * w + px) * 4], expect) << px << "," << py;
    }
}

// Lines and points through the scene. Window coordinates are exact in float (32x16 target: wx = (x+1)*16,
// wy = (y+1)*8). Independent expectations: a 1-wide horizontal rectangular line from (2.5, 4.5) to (10.5, 4.5)
// covers the pixel centres inside [2.5, 10.5) x (4, 5) (top-left rule: the left end is in, the right end out);
// a size-1 point at (20.5, 10.5) covers exactly pixel (20, 10).
TEST_F(RenderTest, LineAndPointCoverage) {
    const int w = 32, h = 16;
    Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0), {}};
    ThreadPool pool(2);
    Renderer r(pool, Method::kHier);
    auto clip_x = [](float wx) { return wx / 16.0f - 1.0f; };
    auto clip_y = [](float wy) { return wy / 8.0f - 1.0f; };
    PipelineState lines = make_pipeline(vs.get(), fs.get(), w, h);
    lines.topology = geometry::Topology::kLineList;
    PipelineState points = make_pipeline(vs.get(), fs.get(), w, h);
    points.topology = geometry::Topology::kPointList;
    r.begin(make_fb(img, false));
    draw(r, lines,
         {{{clip_x(2.5f), clip_y(4.5f), 0.5f, 1}, {0, 1, 0, 1}},
          {{clip_x(10.5f), clip_y(4.5f), 0.5f, 1}, {0, 1, 0, 1}}});
    draw(r, points, {{{clip_x(20.5f), clip_y(10.5f), 0.5f, 1}, {0, 0, 1, 1}}});
    r.end();
    int mismatches = 0;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            const uint8_t* c = &img.rgba[(size_t(py) * w + px) * 4];
            const bool on_line = py == 4 && px >= 2 && px <= 9;
            const bool on_point = py == 10 && px == 20;
            const uint8_t want[4] = {0, uint8_t(on_line ? 255 : 0), uint8_t(on_point ? 255 : 0),
                                     uint8_t(on_line || on_point ? 255 : 0)};
            if (std::memcmp(c, want, 4) != 0) {
                ++mismatches;
                ADD_FAILURE() << "pixel " << px << "," << py << " = " << int(c[0]) << " " << int(c[1]) << " "
                              << int(c[2]) << " " << int(c[3]);
            }
        }
    EXPECT_EQ(mismatches, 0);
}

// Large draws set up and bin on the workers (Renderer::add_triangles_parallel, Scene::bin_reserved); a pool of one
// runs them one triangle after the other. Every thread count must give the same bytes: random triangles from
// sub-pixel to larger than the target (degenerate ones, back faces culled in one draw), overlapping depth-tested
// and blended draws whose order shows, small draws between the large ones, an indexed instanced draw, a draw with
// clipped vertices (x, y and z: the clipper's pieces, with and without the float cull), at 1x and 4x.
TEST_F(RenderTest, LargeDrawsGiveTheSameBytesForEveryThreadCount) {
    const int w = 300, h = 200;
    uint64_t state = 99;
    auto rnd = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(uint32_t(state >> 40)) / float(1u << 24);
    };
    auto triangles = [&](int n, float size, float reach, float z_lo = 0, float z_hi = 1) {
        std::vector<Vertex> v;
        for (int t = 0; t < n; ++t) {
            const float cx = rnd() * 2 - 1, cy = rnd() * 2 - 1, z = z_lo + (z_hi - z_lo) * rnd();
            const float s = size * (0.2f + rnd());
            const float c[4] = {rnd(), rnd(), rnd(), 0.6f};
            for (int k = 0; k < 3; ++k) {
                // inside the view (no clipping) unless reach > 1; every 97th triangle is degenerate
                const float px = std::clamp(t % 97 == 0 ? cx : cx + (rnd() - 0.5f) * s, -0.999f, 0.999f);
                const float py = std::clamp(cy + (rnd() - 0.5f) * s, -0.999f, 0.999f);
                v.push_back({{px * reach, py * reach, z, 1}, {c[0], c[1], c[2], c[3]}});
            }
        }
        return v;
    };
    const std::vector<Vertex> small = triangles(6000, 0.04f, 1.0f), mixed = triangles(3000, 0.6f, 1.0f),
                              tiny = triangles(40, 0.1f, 1.0f), clipped = triangles(3000, 0.3f, 1.3f, -0.3f, 1.3f),
                              layered = triangles(4000, 0.15f, 1.0f);
    // Slivers whose float and snapped orientations disagree (as in
    // LavapipeCrossCheck.FloatCullOnlyOnDrawsPipelinePath): in a batch with clipped vertices the float cull decides
    // them, elsewhere the integer area does.
    std::vector<Vertex> clipped_slivers;
    for (int k = 0; k < 40; ++k) {
        const float ox = float(k % 5) * 55, oy = float(k / 5) * 23;
        auto at = [&](float wx, float wy) {
            return Vertex{{(wx + ox) / 150.0f - 1.0f, (wy + oy) / 100.0f - 1.0f, 0.01f, 1}, {1, 1, 1, 1}};
        };
        const Vertex a = at(10.5f, 10.5f), b = at(30.5f, 10.5017f), c = at(50.5f, 10.503f);
        for (const Vertex& v : k % 2 ? std::vector<Vertex>{a, b, c} : std::vector<Vertex>{a, c, b})
            clipped_slivers.push_back(v);
    }
    clipped_slivers.insert(clipped_slivers.end(), clipped.begin(), clipped.end());
    std::vector<Vertex> strip = triangles(1500, 0.05f, 1.0f);
    std::vector<uint32_t> indices;
    for (uint32_t i = 0; i < strip.size(); ++i) indices.push_back(uint32_t((i * 7919) % strip.size()));
    auto render = [&](unsigned threads, int samples) {
        const size_t planes = size_t(samples);
        Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4 * planes, 0),
                  std::vector<float>(size_t(w) * h * planes, 1.0f)};
        ThreadPool pool(threads);
        Renderer r(pool, Method::kHier);
        PipelineState depth = make_pipeline(vs.get(), fs.get(), w, h);
        depth.samples = samples;
        depth.depth_stencil.depth_test = depth.depth_stencil.depth_write = true;
        depth.depth_stencil.depth_compare = fragment::CompareOp::Less;
        PipelineState blend = depth;  // no depth test: the order of overlapping triangles shows in the colours
        blend.depth_stencil.depth_test = blend.depth_stencil.depth_write = false;
        blend.blend[0].blend_enable = true;
        blend.blend[0].src_color = blend.blend[0].src_alpha = fragment::BlendFactor::SrcAlpha;
        blend.blend[0].dst_color = blend.blend[0].dst_alpha = fragment::BlendFactor::OneMinusSrcAlpha;
        PipelineState culled = depth;
        culled.cull = CullMode::kBack;
        Framebuffer fb = make_fb(img, true);
        fb.samples = samples;
        fb.color[0].sample_stride = size_t(w) * h * 4;
        fb.depth_stencil.depth_sample_stride = size_t(w) * h * 4;
        r.begin(fb);
        draw(r, depth, small);
        draw(r, blend, tiny);
        draw(r, culled, mixed);
        draw(r, blend, layered);
        draw(r, depth, clipped);
        draw(r, culled, clipped_slivers);
        DrawCall call;
        call.indexed = true;
        call.count = uint32_t(indices.size());
        call.instance_count = 2;
        call.index_data = reinterpret_cast<const uint8_t*>(indices.data());
        call.index_bytes = uint32_t(indices.size() * 4);
        call.index_size = 4;
        call.vertex_buffers = {
            {reinterpret_cast<const uint8_t*>(strip.data()), uint32_t(strip.size() * sizeof(Vertex))}};
        EXPECT_EQ(r.draw(blend, call, shader::Bindings{}), "");
        r.end();
        return img;
    };
    for (int samples : {1, 4}) {
        const Image one = render(1, samples);
        size_t lit = 0;
        for (size_t i = 0; i < one.rgba.size(); i += 4) lit += one.rgba[i + 3] != 0;
        EXPECT_GT(lit, one.rgba.size() / 4 / 2) << "the scene should cover most of the target";
        for (unsigned threads : {2u, 5u}) {
            const Image many = render(threads, samples);
            EXPECT_EQ(one.rgba, many.rgba) << threads << " threads, " << samples << "x";
            EXPECT_EQ(one.depth, many.depth) << threads << " threads, " << samples << "x";
        }
    }
}

// One blended draw large enough that Scene::bin_reserved sorts its slots in several chunks into several tile bands
// (and triangles that cross band boundaries), overlapping so that every pixel blends many triangles: the colours
// show the order in which each tile received them. A pool of one bins them one after the other (add_triangle), the
// reference; 2, 3 and 8 threads split the setup and the bands differently and must give the same bytes.
TEST_F(RenderTest, LargeBlendedDrawKeepsApiOrderAcrossChunksAndBands) {
    const int w = 256, h = 320;  // 5 tile rows: several bands at every thread count above one
    uint64_t state = 7;
    auto rnd = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(uint32_t(state >> 40)) / float(1u << 24);
    };
    std::vector<Vertex> v;
    for (int t = 0; t < 20000; ++t) {  // ~5 chunks of bin_reserved
        const float cx = rnd() * 2 - 1, cy = rnd() * 2 - 1;
        const float s = t % 13 == 0 ? 0.9f : 0.12f;  // some span several tiles and bands
        const float c[4] = {rnd(), rnd(), rnd(), 0.5f};
        for (int k = 0; k < 3; ++k)
            v.push_back({{std::clamp(cx + (rnd() - 0.5f) * s, -0.999f, 0.999f),
                          std::clamp(cy + (rnd() - 0.5f) * s, -0.999f, 0.999f), 0.5f, 1},
                         {c[0], c[1], c[2], c[3]}});
    }
    auto render = [&](unsigned threads) {
        Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0), {}};
        ThreadPool pool(threads);
        Renderer r(pool, Method::kHier);
        PipelineState blend = make_pipeline(vs.get(), fs.get(), w, h);
        blend.blend[0].blend_enable = true;
        blend.blend[0].src_color = blend.blend[0].src_alpha = fragment::BlendFactor::SrcAlpha;
        blend.blend[0].dst_color = blend.blend[0].dst_alpha = fragment::BlendFactor::OneMinusSrcAlpha;
        r.begin(make_fb(img, false));
        draw(r, blend, v);
        r.end();
        return img;
    };
    const Image one = render(1);
    size_t lit = 0;
    for (size_t i = 0; i < one.rgba.size(); i += 4) lit += one.rgba[i + 3] != 0;
    EXPECT_GT(lit, one.rgba.size() / 4 * 9 / 10) << "the draw should cover the target";
    for (unsigned threads : {2u, 3u, 8u}) EXPECT_EQ(one.rgba, render(threads).rgba) << threads << " threads";
}

// Primitive records of every kind and size in one scene: a large draw with one varying and one with three (records
// of 28 and 52 floats, set up on the workers at every thread count above one), scissored (box planes; at 4x
// lavapipe's sample scissor planes), lines, points and small draws between them. The hier method reads the compact
// pixel planes (at 4x their per-sample offsets), the reference method the 64-bit planes a scene keeps only for it:
// both must give the same bytes, at every thread count (a pool of one sets every record up one after the other).
TEST_F(RenderTest, RecordsOfEveryKindAndSizeAgreeAcrossMethodsAndThreads) {
    const auto vs3 = shader::test::make_program(Stage::Vertex, R"(#version 450
layout(location=0) in vec4 pos; layout(location=1) in vec4 col;
layout(location=0) out vec4 a; layout(location=1) out vec4 b; layout(location=2) out vec4 c;
void main() { gl_Position = pos; a = col; b = col.zxyw * 0.5; c = vec4(pos.xy * 0.5 + 0.5, col.x, 1.0); })");
    const auto fs3 = shader::test::make_program(Stage::Fragment, R"(#version 450
layout(location=0) in vec4 a; layout(location=1) in vec4 b; layout(location=2) in vec4 c;
layout(location=0) out vec4 color;
void main() { color = vec4(a.x * 0.3 + b.y * 0.4 + c.x * 0.3, a.y * 0.5 + c.y * 0.5, b.z + c.z * 0.25, a.w); })");
    const int w = 200, h = 140;
    uint64_t state = 5;
    auto rnd = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(uint32_t(state >> 40)) / float(1u << 24);
    };
    auto triangles = [&](int n, float size) {
        std::vector<Vertex> v;
        for (int t = 0; t < n; ++t) {
            const float cx = rnd() * 2 - 1, cy = rnd() * 2 - 1, z = rnd();
            const float c[4] = {rnd(), rnd(), rnd(), 1.0f};
            for (int k = 0; k < 3; ++k)
                v.push_back({{std::clamp(cx + (rnd() - 0.5f) * size, -0.999f, 0.999f),
                              std::clamp(cy + (rnd() - 0.5f) * size, -0.999f, 0.999f), z, 1},
                             {c[0], c[1], c[2], c[3]}});
        }
        return v;
    };
    const std::vector<Vertex> one = triangles(2500, 0.08f), three = triangles(2500, 0.1f), few = triangles(9, 0.5f);
    const std::vector<Vertex> segs = triangles(60, 0.3f);  // pairs of its vertices as lines, its vertices as points
    auto render = [&](unsigned threads, int samples, Method method) {
        const size_t planes = size_t(samples);
        Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4 * planes, 0),
                  std::vector<float>(size_t(w) * h * planes, 1.0f)};
        ThreadPool pool(threads);
        Renderer r(pool, method);
        PipelineState p1 = make_pipeline(vs.get(), fs.get(), w, h);
        p1.samples = samples;
        p1.depth_stencil.depth_test = p1.depth_stencil.depth_write = true;
        p1.depth_stencil.depth_compare = fragment::CompareOp::Less;
        PipelineState p3 = p1;
        p3.vertex = vs3.get();
        p3.fragment = fs3.get();
        p3.scissor = {13, 9, 171, 122};  // box planes on every side; at 4x the sample scissor planes
        PipelineState lines = p3, points = p1;
        lines.topology = geometry::Topology::kLineList;
        points.topology = geometry::Topology::kPointList;
        Framebuffer fb = make_fb(img, true);
        fb.samples = samples;
        fb.color[0].sample_stride = size_t(w) * h * 4;
        fb.depth_stencil.depth_sample_stride = size_t(w) * h * 4;
        r.begin(fb);
        draw(r, p1, one);
        draw(r, p3, few);
        draw(r, p3, three);
        draw(r, lines, segs);
        draw(r, p1, few);
        draw(r, points, segs);
        r.end();
        return img;
    };
    for (int samples : {1, 4}) {
        const Image want = render(1, samples, Method::kHier);
        size_t lit = 0;
        for (size_t i = 0; i < want.rgba.size(); i += 4) lit += want.rgba[i + 3] != 0;
        EXPECT_GT(lit, want.rgba.size() / 4 / 2) << "the scene should cover most of the target";
        for (const auto& [threads, method] : {std::pair{3u, Method::kHier}, std::pair{1u, Method::kReference},
                                              std::pair{2u, Method::kReference}, std::pair{2u, Method::kBBox}}) {
            const Image got = render(threads, samples, method);
            EXPECT_EQ(want.rgba, got.rgba) << threads << " threads, " << samples << "x, " << to_string(method);
            EXPECT_EQ(want.depth, got.depth) << threads << " threads, " << samples << "x, " << to_string(method);
        }
    }
}

// Sample shading (PipelineState::per_sample): one shader run per sample, at that sample's position. The expected
// bytes are the 4x positions (0.375, 0.125), (0.875, 0.375), (0.125, 0.625), (0.625, 0.875) and SampleId / 3 as
// UNORM8 by hand (rne(v * 255)); per pixel, SamplePosition is sample 0's and FragCoord the centre (0.5 -> 128).
TEST_F(RenderTest, SampleShadingRunsOncePerSampleAtItsPosition) {
    const int w = 8, h = 8;
    auto fs_id = shader::test::make_program(Stage::Fragment, R"(#version 450
layout(location=0) in vec4 col; layout(location=0) out vec4 color;
void main() { color = vec4(gl_SamplePosition, float(gl_SampleID) / 3.0, 1.0); })");
    auto fs_coord = shader::test::make_program(Stage::Fragment, R"(#version 450
layout(location=0) in vec4 col; layout(location=0) out vec4 color;
void main() { color = vec4(fract(gl_FragCoord.xy), col.b, 1.0); })");
    const uint8_t per_sample_want[4][3] = {{96, 32, 0}, {223, 96, 85}, {32, 159, 170}, {159, 223, 255}};
    auto render = [&](const shader::Program* f, bool per_sample) {
        Image img{w, h, std::vector<uint8_t>(size_t(w) * h * 4 * 4, 0), {}};
        ThreadPool pool(1);
        Renderer r(pool, Method::kHier);
        PipelineState p = make_pipeline(vs.get(), f, w, h);
        p.samples = 4;
        p.per_sample = per_sample;
        Framebuffer fb = make_fb(img, false);
        fb.samples = 4;
        fb.color[0].sample_stride = size_t(w) * h * 4;
        r.begin(fb);
        draw(r, p, {{{-1, -1, 0, 1}, {0, 0, 0, 1}}, {{3, -1, 0, 1}, {0, 0, 0, 1}}, {{-1, 3, 0, 1}, {0, 0, 0, 1}}});
        r.end();
        return img;
    };
    const Image ids = render(fs_id.get(), true);
    const Image coords = render(fs_coord.get(), true);
    const Image centre = render(fs_coord.get(), false);
    for (int s = 0; s < 4; ++s)
        for (int i = 0; i < w * h; ++i) {
            const uint8_t* id = &ids.rgba[(size_t(s) * w * h + i) * 4];
            const uint8_t* at = &coords.rgba[(size_t(s) * w * h + i) * 4];
            const uint8_t* mid = &centre.rgba[(size_t(s) * w * h + i) * 4];
            ASSERT_EQ(id[0], per_sample_want[s][0]) << "sample " << s << " pixel " << i;
            ASSERT_EQ(id[1], per_sample_want[s][1]) << "sample " << s << " pixel " << i;
            ASSERT_EQ(id[2], per_sample_want[s][2]) << "sample " << s << " pixel " << i;
            ASSERT_EQ(at[0], per_sample_want[s][0]) << "sample " << s << " pixel " << i;
            ASSERT_EQ(at[1], per_sample_want[s][1]) << "sample " << s << " pixel " << i;
            ASSERT_EQ(mid[0], 128) << "sample " << s << " pixel " << i;
            ASSERT_EQ(mid[1], 128) << "sample " << s << " pixel " << i;
        }
}

}  // namespace
}  // namespace tilevk::rast::render
