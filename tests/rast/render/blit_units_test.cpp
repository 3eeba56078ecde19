// The blit's pieces (rast/render/blit.h, format/texel_codec.h), checked against expectations computed here: the
// blitter's quad covers every destination pixel of its box exactly once and nothing outside it; its interpolated
// coordinates stay within a small tolerance of the exact affine map (the exact lavapipe rounding is pinned by
// tests/icd/blit_test.cpp); the texel conversions a blit uses round-trip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "format/texel_codec.h"
#include "rast/core/thread_pool.h"
#include "rast/render/blit.h"

namespace tilevk::rast::render {
namespace {

using format::Format;
using format::format_info;
using Rgba = std::array<float, 4>;

// What rasterize_blit_quad hands over, per pixel of the surface: how often it was covered and its coordinates.
struct QuadPixels {
    uint32_t w;
    std::vector<int> count;
    std::vector<float> s, t;
    bool texcoord(int32_t x, int32_t y, float& so, float& to) const {
        const size_t i = size_t(y) * w + size_t(x);
        so = s[i], to = t[i];
        return count[i] > 0;
    }
};
QuadPixels rasterize(uint32_t w, uint32_t h, int32_t x1, int32_t y1, int32_t x2, int32_t y2, float s1, float t1,
                     float s2, float t2, bool fused, bool rect) {
    static ThreadPool pool(2);
    QuadPixels q{w, std::vector<int>(size_t(w) * h), std::vector<float>(size_t(w) * h),
                 std::vector<float>(size_t(w) * h)};
    BlitQuad quad;
    quad.surf_w = w, quad.surf_h = h, quad.x1 = x1, quad.y1 = y1, quad.x2 = x2, quad.y2 = y2;
    quad.s1 = s1, quad.t1 = t1, quad.s2 = s2, quad.t2 = t2, quad.fused = fused, quad.rect = rect;
    // each pixel belongs to one tile, so one worker writes it
    rasterize_blit_quad(quad, pool, [&q](int32_t px, int32_t py, float s, float t) {
        const size_t i = size_t(py) * q.w + size_t(px);
        ++q.count[i];
        q.s[i] = s, q.t[i] = t;
    });
    return q;
}

Rgba decode(const format::FormatInfo& f, const uint8_t* p, bool fused) {
    Rgba c;
    format::decode_color(f, p, c.data(), fused);
    return c;
}
void encode(const format::FormatInfo& f, const Rgba& c, uint8_t* p, bool fused) {
    format::encode_color(f, c.data(), p, fused);
}

struct Lcg {
    uint32_t s;
    uint32_t next(uint32_t n) {
        s = s * 1664525u + 1013904223u;
        return (s >> 8) % n;
    }
};

TEST(BlitQuad, CoversTheBoxExactlyOnce) {
    Lcg g{99};
    for (int iter = 0; iter < 300; ++iter) {
        const uint32_t w = 1 + g.next(300), h = 1 + g.next(300);
        const int32_t x1 = int32_t(g.next(w)), y1 = int32_t(g.next(h));
        const int32_t x2 = x1 + 1 + int32_t(g.next(w - uint32_t(x1))), y2 = y1 + 1 + int32_t(g.next(h - uint32_t(y1)));
        for (int mode = 0; mode < 3; ++mode) {  // triangles fused / unfused, the linear-mode rectangle
            const bool fused = mode != 1, rect = mode == 2;
            const QuadPixels q = rasterize(w, h, x1, y1, x2, y2, 0.0f, 0.0f, 1.0f, 1.0f, fused, rect);
            for (int32_t y = 0; y < int32_t(h); ++y) {
                for (int32_t x = 0; x < int32_t(w); ++x) {
                    const int n = q.count[size_t(y) * w + size_t(x)];
                    const bool inside = x >= x1 && x < x2 && y >= y1 && y < y2;
                    ASSERT_EQ(n, inside ? 1 : 0) << "surface " << w << "x" << h << " box (" << x1 << "," << y1 << ")-("
                                                 << x2 << "," << y2 << ") pixel " << x << "," << y;
                }
            }
        }
    }
}

TEST(BlitQuad, CoordinatesFollowTheAffineMap) {
    // s at pixel centre x: s1 + (x + 0.5 - x1) / (x2 - x1) * (s2 - s1), up to float rounding of the planes
    Lcg g{7};
    for (int iter = 0; iter < 200; ++iter) {
        const uint32_t w = 2 + g.next(500), h = 2 + g.next(500);
        const int32_t x1 = int32_t(g.next(w / 2)), y1 = int32_t(g.next(h / 2));
        const int32_t x2 = x1 + 1 + int32_t(g.next(w - uint32_t(x1))), y2 = y1 + 1 + int32_t(g.next(h - uint32_t(y1)));
        const float s1 = float(g.next(1000)) / 1000.0f, s2 = float(g.next(1000)) / 1000.0f;
        const float t1 = float(g.next(1000)) / 1000.0f, t2 = float(g.next(1000)) / 1000.0f;
        const QuadPixels q = rasterize(w, h, x1, y1, x2, y2, s1, t1, s2, t2, true, iter % 2 == 1);
        for (int32_t y = y1; y < y2; y += 1 + (y2 - y1) / 7) {
            for (int32_t x = x1; x < x2; x += 1 + (x2 - x1) / 7) {
                float s, t;
                ASSERT_TRUE(q.texcoord(x, y, s, t));
                const double es = s1 + (x + 0.5 - x1) / double(x2 - x1) * (double(s2) - s1);
                const double et = t1 + (y + 0.5 - y1) / double(y2 - y1) * (double(t2) - t1);
                EXPECT_NEAR(s, es, 1e-4) << x << "," << y;
                EXPECT_NEAR(t, et, 1e-4) << x << "," << y;
            }
        }
    }
}

TEST(BlitTexels, ConversionsRoundTrip) {
    // every UNORM8 byte decodes to u/255 (as u * fl(1/255)) and encodes back to itself; halves and floats are exact
    const format::FormatInfo& rgba8 = format_info(Format::R8G8B8A8_UNORM);
    for (int u = 0; u < 256; ++u) {
        const uint8_t in[4] = {uint8_t(u), uint8_t(255 - u), uint8_t(u / 2), uint8_t(u ^ 0x55)};
        const Rgba c = decode(rgba8, in, true);
        EXPECT_EQ(c[0], float(u) * (1.0f / 255.0f));
        uint8_t out[4];
        encode(rgba8, c, out, true);
        EXPECT_EQ(std::memcmp(in, out, 4), 0) << u;
    }
    const format::FormatInfo& bgra8 = format_info(Format::B8G8R8A8_UNORM);
    const uint8_t b[4] = {10, 20, 30, 40};  // B, G, R, A in memory
    const Rgba c = decode(bgra8, b, true);
    EXPECT_EQ(c[0], 30.0f * (1.0f / 255.0f));
    EXPECT_EQ(c[2], 10.0f * (1.0f / 255.0f));
    const format::FormatInfo& r8 = format_info(Format::R8_UNORM);
    const uint8_t one = 7;
    const Rgba rc = decode(r8, &one, true);
    EXPECT_EQ(rc[1], 0.0f);
    EXPECT_EQ(rc[3], 1.0f);
    const format::FormatInfo& half = format_info(Format::R16G16B16A16_SFLOAT);
    for (uint32_t h = 0; h < 0x7c00; h += 37) {  // finite non-negative halves
        const uint16_t in[4] = {uint16_t(h), uint16_t(h + 1), 0x3c00, 0};
        uint16_t out[4];
        encode(half, decode(half, reinterpret_cast<const uint8_t*>(in), true), reinterpret_cast<uint8_t*>(out), true);
        EXPECT_EQ(std::memcmp(in, out, 8), 0) << h;
    }
    // D16: every value survives decode -> encode (u * fl(1/65535), then the +128 store trick)
    const format::FormatInfo& d16 = format_info(Format::D16_UNORM);
    for (uint32_t d = 0; d < 65536; ++d) {
        const uint16_t in = uint16_t(d);
        uint16_t out;
        encode(d16, decode(d16, reinterpret_cast<const uint8_t*>(&in), true), reinterpret_cast<uint8_t*>(&out), true);
        ASSERT_EQ(in, out) << d;
    }
}

// The source z of each destination slice (u_blitter's per-slice coordinate): a 3D source is read at slice centres
// spread over its box, `z0 + (z + 0.5) * S / D` (exact here: every term is a small dyadic), flipped from the box's
// far end; array layers are read one for one without the half-slice offset.
TEST(BlitUnits, SourceZOfEachDestinationSlice) {
    for (int32_t z = 0; z < 4; ++z) {
        EXPECT_EQ(blit_source_z(0, 8, 4, z, true), float(2 * z + 1)) << z;  // 8 slices into 4: centres 1, 3, ..
        EXPECT_EQ(blit_source_z(2, 2, 8, z, true), 2.0f + 0.25f * z + 0.125f) << z;  // 2 into 8
        EXPECT_EQ(blit_source_z(8, -8, 4, z, true), float(7 - 2 * z)) << z;          // flipped: 7, 5, 3, 1
        EXPECT_EQ(blit_source_z(3, 4, 4, z, true), 3.5f + float(z)) << z;            // unscaled: the slice centre
        EXPECT_EQ(blit_source_z(3, 4, 4, z, false), 3.0f + float(z)) << z;           // array layers: the layer itself
    }
}

}  // namespace
}  // namespace tilevk::rast::render
