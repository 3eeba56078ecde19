// Vertex fetch conversions and primitive assembly orders, against values derived independently here.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "rast/geometry/draw_module.h"
#include "rast/geometry/primitive_assembly.h"
#include "rast/geometry/vertex_fetch.h"

using namespace tilevk::rast::geometry;

namespace {

float as_f(uint32_t w) {
    return std::bit_cast<float>(w);
}
uint32_t bits(float f) {
    return std::bit_cast<uint32_t>(f);
}

// fl(c * fl(s)) evaluated in double: the product of two floats is exact in double, one rounding to float.
float mul_round(double c, double s) {
    return static_cast<float>(c * static_cast<double>(static_cast<float>(s)));
}

}  // namespace

TEST(VertexFetch, Unorm8IsMultiplyByRoundedReciprocalForAll256) {
    int differs_from_divide = 0;
    for (int c = 0; c < 256; ++c) {
        const uint8_t byte = static_cast<uint8_t>(c);
        const FetchedAttrib a = convert_element(VertexFormat::R8_UNORM, &byte);
        const float expect = mul_round(c, 1.0 / 255.0);
        EXPECT_EQ(a.w[0], bits(expect)) << c;
        if (expect != static_cast<float>(c / 255.0)) ++differs_from_divide;
        EXPECT_EQ(a.w[1], 0u);
        EXPECT_EQ(a.w[2], 0u);
        EXPECT_EQ(a.w[3], bits(1.0f));
    }
    EXPECT_GT(differs_from_divide, 0);  // the rule is observable: a divide would give other values
    const uint8_t max = 255;
    EXPECT_EQ(as_f(convert_element(VertexFormat::R8_UNORM, &max).w[0]), 1.0f);
}

TEST(VertexFetch, Unorm16AndSnorm) {
    for (uint32_t c : {0u, 1u, 257u, 32767u, 65534u, 65535u}) {
        uint8_t b[2] = {static_cast<uint8_t>(c), static_cast<uint8_t>(c >> 8)};
        EXPECT_EQ(convert_element(VertexFormat::R16_UNORM, b).w[0], bits(mul_round(c, 1.0 / 65535.0))) << c;
    }
    for (int c : {-128, -127, -1, 0, 1, 64, 127}) {
        const uint8_t b = static_cast<uint8_t>(static_cast<int8_t>(c));
        float expect = mul_round(c, 1.0 / 127.0);
        if (expect < -1.0f) expect = -1.0f;
        EXPECT_EQ(convert_element(VertexFormat::R8_SNORM, &b).w[0], bits(expect)) << c;
    }
    const uint8_t m128 = 0x80;
    EXPECT_EQ(as_f(convert_element(VertexFormat::R8_SNORM, &m128).w[0]), -1.0f);
    for (int c : {-32768, -32767, -2, 0, 5, 32767}) {
        const uint16_t u = static_cast<uint16_t>(static_cast<int16_t>(c));
        uint8_t b[2] = {static_cast<uint8_t>(u), static_cast<uint8_t>(u >> 8)};
        float expect = mul_round(c, 1.0 / 32767.0);
        if (expect < -1.0f) expect = -1.0f;
        EXPECT_EQ(convert_element(VertexFormat::R16_SNORM, b).w[0], bits(expect)) << c;
    }
}

// A2B10G10R10: R in bits 0-9, G 10-19, B 20-29, A 30-31 of one little-endian word; each channel converted with
// its own width (unorm 10: c * fl(1/1023), snorm 2-bit alpha: max(c * 1, -1)).
TEST(VertexFetch, Packed2101010) {
    const uint32_t word = 1023u | (512u << 10) | (1u << 20) | (2u << 30);  // R max, G 512, B 1, A 0b10
    uint8_t b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<uint8_t>(word >> (8 * i));
    EXPECT_EQ(format_info(VertexFormat::A2B10G10R10_UNORM_PACK32).bytes, 4u);
    const FetchedAttrib un = convert_element(VertexFormat::A2B10G10R10_UNORM_PACK32, b);
    EXPECT_EQ(as_f(un.w[0]), 1.0f);
    EXPECT_EQ(un.w[1], bits(mul_round(512, 1.0 / 1023.0)));
    EXPECT_EQ(un.w[2], bits(mul_round(1, 1.0 / 1023.0)));
    EXPECT_EQ(un.w[3], bits(mul_round(2, 1.0 / 3.0)));
    const FetchedAttrib sn = convert_element(VertexFormat::A2B10G10R10_SNORM_PACK32, b);
    EXPECT_EQ(as_f(sn.w[0]), -mul_round(1, 1.0 / 511.0));  // 1023 = -1 in 10-bit two's complement
    EXPECT_EQ(as_f(sn.w[1]), -1.0f);                       // -512 * (1/511) < -1: clamped
    EXPECT_EQ(as_f(sn.w[3]), -1.0f);                       // 2-bit 0b10 = -2, times 1, clamped
    const FetchedAttrib ui = convert_element(VertexFormat::A2B10G10R10_UINT_PACK32, b);
    EXPECT_EQ(ui.w[0], 1023u);
    EXPECT_EQ(ui.w[1], 512u);
    EXPECT_EQ(ui.w[2], 1u);
    EXPECT_EQ(ui.w[3], 2u);
    const FetchedAttrib si = convert_element(VertexFormat::A2B10G10R10_SINT_PACK32, b);
    EXPECT_EQ(static_cast<int32_t>(si.w[0]), -1);
    EXPECT_EQ(static_cast<int32_t>(si.w[1]), -512);
    EXPECT_EQ(static_cast<int32_t>(si.w[3]), -2);
}

TEST(VertexFetch, IntegersHalfFloatsBgraAndFill) {
    const uint8_t s8[4] = {0x80, 0x7F, 0xFF, 0x00};
    const FetchedAttrib a = convert_element(VertexFormat::R8G8B8A8_SINT, s8);
    EXPECT_EQ(static_cast<int32_t>(a.w[0]), -128);
    EXPECT_EQ(static_cast<int32_t>(a.w[1]), 127);
    EXPECT_EQ(static_cast<int32_t>(a.w[2]), -1);
    EXPECT_EQ(a.w[3], 0u);
    const FetchedAttrib u = convert_element(VertexFormat::R8G8B8A8_UINT, s8);
    EXPECT_EQ(u.w[0], 128u);
    EXPECT_EQ(u.w[2], 255u);
    const uint8_t s16[2] = {0x00, 0x80};
    const FetchedAttrib b = convert_element(VertexFormat::R16_SINT, s16);
    EXPECT_EQ(static_cast<int32_t>(b.w[0]), -32768);
    EXPECT_EQ(b.w[1], 0u);
    EXPECT_EQ(b.w[3], 1u);  // integer formats fill w with integer 1
    const uint8_t u32[8] = {0xFF, 0xFF, 0xFF, 0xFF, 1, 0, 0, 0};
    const FetchedAttrib c = convert_element(VertexFormat::R32G32_UINT, u32);
    EXPECT_EQ(c.w[0], 0xFFFFFFFFu);
    EXPECT_EQ(c.w[1], 1u);
    EXPECT_EQ(c.w[2], 0u);
    EXPECT_EQ(c.w[3], 1u);
    // halves: 1.0, -2.0, smallest subnormal 2^-24, +Inf
    const uint16_t h[4] = {0x3C00, 0xC000, 0x0001, 0x7C00};
    uint8_t hb[8];
    std::memcpy(hb, h, 8);
    const FetchedAttrib d = convert_element(VertexFormat::R16G16B16A16_SFLOAT, hb);
    EXPECT_EQ(as_f(d.w[0]), 1.0f);
    EXPECT_EQ(as_f(d.w[1]), -2.0f);
    EXPECT_EQ(as_f(d.w[2]), std::ldexp(1.0f, -24));
    EXPECT_TRUE(std::isinf(as_f(d.w[3])));
    // BGRA: memory B,G,R,A -> (R,G,B,A)
    const uint8_t bgra[4] = {10, 20, 30, 40};
    const FetchedAttrib e = convert_element(VertexFormat::B8G8R8A8_UNORM, bgra);
    EXPECT_EQ(e.w[0], bits(mul_round(30, 1.0 / 255)));
    EXPECT_EQ(e.w[1], bits(mul_round(20, 1.0 / 255)));
    EXPECT_EQ(e.w[2], bits(mul_round(10, 1.0 / 255)));
    EXPECT_EQ(e.w[3], bits(mul_round(40, 1.0 / 255)));
    // float3: w filled with 1.0f
    const float f3[3] = {1.5f, -0.0f, 3.0f};
    uint8_t fb[12];
    std::memcpy(fb, f3, 12);
    const FetchedAttrib f = convert_element(VertexFormat::R32G32B32_SFLOAT, fb);
    EXPECT_EQ(f.w[1], 0x80000000u);
    EXPECT_EQ(as_f(f.w[3]), 1.0f);
}

TEST(VertexFetch, BoundsStrideZeroAndInstanceRate) {
    std::vector<float> data = {1, 2, 3, 4, 5, 6, 7};  // 28 bytes
    VertexBufferView vb;
    vb.data = reinterpret_cast<const uint8_t*>(data.data());
    vb.size = 28;
    vb.stride = 8;
    VertexAttribDesc at{VertexFormat::R32G32B32_SFLOAT, 0, 4};  // reads floats [2i+1, 2i+4)
    // element i in bounds iff 8i + 4 + 12 <= 28 -> i <= 1
    FetchedAttrib a = fetch_attribute(at, vb, {1, true});
    EXPECT_EQ(as_f(a.w[0]), 4.0f);
    EXPECT_EQ(as_f(a.w[2]), 6.0f);
    a = fetch_attribute(at, vb, {2, true});  // out of bounds, per-vertex: own components 0, w = 1
    EXPECT_EQ(a.w[0], 0u);
    EXPECT_EQ(a.w[2], 0u);
    EXPECT_EQ(as_f(a.w[3]), 1.0f);
    a = fetch_attribute(at, vb, {0xFFFFFFFFu, true});  // huge index never reads out of bounds
    EXPECT_EQ(a.w[0], 0u);
    // per-instance out of bounds: everything 0, including the filled w
    VertexBufferView vi = vb;
    vi.rate = InputRate::kInstance;
    a = fetch_attribute(at, vi, element_index(vi, 0, 5, 0));
    EXPECT_EQ(a.w[3], 0u);
    // instance index = first_instance + instance_id / divisor
    vi.divisor = 2;
    EXPECT_EQ(element_index(vi, 99, 3, 0).index, 1u);
    EXPECT_FALSE(element_index(vi, 0, 4, 0xFFFFFFFFu).valid);
    // stride 0: every vertex reads element 0
    vb.stride = 0;
    a = fetch_attribute(at, vb, {1000, true});
    EXPECT_EQ(as_f(a.w[0]), 2.0f);
    // attribute offset past the buffer, and a null buffer
    VertexAttribDesc far{VertexFormat::R32_SFLOAT, 0, 100};
    EXPECT_EQ(fetch_attribute(far, vb, {0, true}).w[0], 0u);
    VertexBufferView empty;
    EXPECT_EQ(as_f(fetch_attribute(at, empty, {0, true}).w[3]), 1.0f);
}

namespace {

std::vector<uint32_t> assemble(Topology t, const std::vector<uint32_t>& idx, bool restart, bool first = true,
                               uint32_t size = 4) {
    std::vector<uint8_t> bytes;
    for (uint32_t v : idx) {
        for (uint32_t b = 0; b < size; ++b) bytes.push_back(static_cast<uint8_t>(v >> (8 * b)));
    }
    IndexSource src;
    src.indices = bytes.data();
    src.index_size = size;
    src.index_count_total = static_cast<uint32_t>(idx.size());
    src.count = static_cast<uint32_t>(idx.size());
    src.primitive_restart = restart;
    std::vector<uint32_t> out(assembled_index_capacity(t, src.count));
    const uint32_t prims = assemble_primitives(src, t, first, out.data(), out.size());
    out.resize(prims * vertices_per_primitive(t));
    return out;
}

std::vector<uint32_t> seq(uint32_t n) {
    std::vector<uint32_t> v(n);
    for (uint32_t i = 0; i < n; ++i) v[i] = i;
    return v;
}

}  // namespace

// The per-draw lane fetch (16 vertices, hoisted bounds, per-format conversions) is fetch_attribute lane by lane:
// every format, both rates, random bytes, strides and offsets, indices in and out of bounds, invalid elements.
TEST(VertexFetch, LaneFetchIsFetchAttributeForEveryFormat) {
    uint64_t state = 12345;
    auto rnd = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return uint32_t(state >> 33);
    };
    std::vector<uint8_t> bytes(512);
    for (uint8_t& b : bytes) b = uint8_t(rnd());
    int checked = 0;
    for (int f = 0; f < int(VertexFormat::kCount); ++f)
        for (int trial = 0; trial < 24; ++trial) {
            VertexAttribDesc a;
            a.format = VertexFormat(f);
            a.binding = 0;
            a.offset = rnd() % 24;
            VertexBufferView vb;
            vb.data = trial == 5 ? nullptr : bytes.data();
            vb.size = rnd() % 400;
            vb.offset = trial == 7 ? 0xFFFFFFF0u : rnd() % 32;
            vb.stride = trial == 3 ? 0 : rnd() % 40;
            vb.rate = trial % 2 ? InputRate::kInstance : InputRate::kVertex;
            const AttribFetchPlan plan = make_attrib_fetch_plan(a, vb);
            uint32_t element[16];
            bool valid[16];
            for (int l = 0; l < 16; ++l) {
                element[l] = trial == 9 ? 0xFFFFFFFFu - uint32_t(l) : rnd() % 20;
                valid[l] = trial != 11 || l % 3 != 0;
            }
            const uint32_t n = 1 + rnd() % 16;
            uint32_t out[4][16];
            std::memset(out, 0xAB, sizeof out);
            fetch_lanes(plan, element, valid, n, out);
            for (uint32_t l = 0; l < n; ++l) {
                const FetchedAttrib want = fetch_attribute(a, vb, ElementIndex{element[l], valid[l]});
                for (int c = 0; c < 4; ++c) {
                    ASSERT_EQ(out[c][l], want.w[c]) << "format " << f << " trial " << trial << " lane " << l;
                    ++checked;
                }
            }
        }
    EXPECT_GT(checked, 10000);
}

TEST(PrimitiveAssembly, OrdersForEveryTopology) {
    using V = std::vector<uint32_t>;
    EXPECT_EQ(assemble(Topology::kPointList, seq(3), false), (V{0, 1, 2}));
    EXPECT_EQ(assemble(Topology::kLineList, seq(5), false), (V{0, 1, 2, 3}));
    EXPECT_EQ(assemble(Topology::kLineStrip, seq(4), false), (V{0, 1, 1, 2, 2, 3}));
    EXPECT_EQ(assemble(Topology::kTriangleList, seq(7), false), (V{0, 1, 2, 3, 4, 5}));
    // Vulkan first-vertex provoking: triangle k's provoking vertex (k for strips, k+1 for fans) comes first.
    EXPECT_EQ(assemble(Topology::kTriangleStrip, seq(6), false), (V{0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4}));
    EXPECT_EQ(assemble(Topology::kTriangleFan, seq(5), false), (V{1, 2, 0, 2, 3, 0, 3, 4, 0}));
    // last-vertex provoking (VK_EXT_provoking_vertex): provoking vertex (k+2) last
    EXPECT_EQ(assemble(Topology::kTriangleStrip, seq(5), false, false), (V{0, 1, 2, 2, 1, 3, 2, 3, 4}));
    EXPECT_EQ(assemble(Topology::kTriangleFan, seq(4), false, false), (V{0, 1, 2, 0, 2, 3}));
}

TEST(PrimitiveAssembly, RestartSplitsRunsAndResetsParity) {
    using V = std::vector<uint32_t>;
    const uint32_t r16 = 0xFFFF;
    EXPECT_EQ(assemble(Topology::kTriangleStrip, {0, 1, 2, 3, r16, 4, 5, 6, 7}, true, true, 2),
              (V{0, 1, 2, 1, 3, 2, 4, 5, 6, 5, 7, 6}));
    EXPECT_EQ(assemble(Topology::kTriangleFan, {9, 1, 2, 3, 0xFFFFFFFFu, 8, 4, 5}, true),
              (V{1, 2, 9, 2, 3, 9, 4, 5, 8}));
    EXPECT_EQ(assemble(Topology::kLineStrip, {0, 1, r16, 2, 3, 4}, true, true, 2), (V{0, 1, 2, 3, 3, 4}));
    // restart drops the incomplete triangle of a list and restarts the grouping
    EXPECT_EQ(assemble(Topology::kTriangleList, {0, 1, r16, 2, 3, 4}, true, true, 2), (V{2, 3, 4}));
    // without restart 0xFFFF is an ordinary index
    EXPECT_EQ(assemble(Topology::kTriangleList, {0, 1, r16}, false, true, 2), (V{0, 1, 0xFFFF}));
    // 32-bit restart value is not a restart for 16-bit-sized comparisons and vice versa
    EXPECT_EQ(assemble(Topology::kPointList, {0xFFFF, 1}, true, true, 4), (V{0xFFFF, 1}));
}

TEST(PrimitiveAssembly, IndexFetchRules) {
    std::vector<uint16_t> idx = {5, 6, 7};
    IndexSource src;
    src.indices = reinterpret_cast<const uint8_t*>(idx.data());
    src.index_size = 2;
    src.index_count_total = 3;
    src.first = 1;
    src.count = 4;  // positions 1..4; 3 and 4 lie past the buffer and read as 0
    src.vertex_offset = -10;
    std::vector<uint32_t> out(4);
    ASSERT_EQ(assemble_primitives(src, Topology::kPointList, true, out.data(), out.size()), 4u);
    EXPECT_EQ(out[0], static_cast<uint32_t>(6 - 10));  // wraps to 0xFFFFFFFC: fetch then treats it as OOB
    EXPECT_EQ(out[1], static_cast<uint32_t>(7 - 10));
    EXPECT_EQ(out[2], static_cast<uint32_t>(-10));
    EXPECT_EQ(out[3], static_cast<uint32_t>(-10));
    // non-indexed
    IndexSource na;
    na.first = 7;
    na.count = 3;
    ASSERT_EQ(assemble_primitives(na, Topology::kTriangleList, true, out.data(), out.size()), 1u);
    EXPECT_EQ(out[0], 7u);
    EXPECT_EQ(out[2], 9u);
    // too-small output buffer: no overflow, fewer primitives
    EXPECT_EQ(assemble_primitives(na, Topology::kTriangleList, true, out.data(), 2), 0u);
}

// Non-indexed lists (a path of their own, written in one pass): vertex first + i for every vertex of a whole
// primitive, the incomplete last one dropped, the 32-bit position wrapping as fetch_index's does, never more
// primitives than the output holds; each checked against the strip/fan-free rule spelled out here.
TEST(PrimitiveAssembly, NonIndexedListsAreConsecutiveVertices) {
    std::vector<uint32_t> out(64, 0xDEADBEEFu);
    for (const Topology t : {Topology::kPointList, Topology::kLineList, Topology::kTriangleList}) {
        const uint32_t per = vertices_per_primitive(t);
        for (const uint32_t first : {0u, 5u, 0xFFFFFFFEu}) {
            IndexSource na;
            na.first = first;
            na.count = 20;  // 20, 10 and 6 whole primitives (two vertices of a triangle left over)
            std::fill(out.begin(), out.end(), 0xDEADBEEFu);
            const uint32_t prims = assemble_primitives(na, t, true, out.data(), out.size());
            ASSERT_EQ(prims, 20 / per);
            for (uint32_t i = 0; i < prims * per; ++i) EXPECT_EQ(out[i], uint32_t(first + i)) << i;
            EXPECT_EQ(out[prims * per], 0xDEADBEEFu) << "past the last whole primitive";
            // an output of 7 indices holds 7 / per whole primitives
            EXPECT_EQ(assemble_primitives(na, t, true, out.data(), 7), 7 / per);
        }
    }
}

TEST(LavapipeQuirks, NineVertexTriangleList) {
    // first six vertices: the aero rectangle (X0,Y0) (X0,Y1) (X1,Y1) | (X1,Y0) (X1,Y1) (X0,Y0); last three on y = 7
    const float aero[9][2] = {{1, 2}, {1, 5}, {4, 5}, {4, 2}, {4, 5}, {1, 2}, {0, 7}, {3, 7}, {9, 7}};
    TriangleListBatch b;
    b.vertex_count = 9;
    EXPECT_EQ(nine_vertex_quirk(b, aero), NineVertexQuirk::kAeroRect);
    float other[9][2];
    std::memcpy(other, aero, sizeof(other));
    other[3][0] = 4.5f;  // breaks the pattern: swallowed
    EXPECT_EQ(nine_vertex_quirk(b, other), NineVertexQuirk::kSwallowed);
    other[8][1] = 7.5f;  // last triangle not flat in y: normal draw
    EXPECT_EQ(nine_vertex_quirk(b, other), NineVertexQuirk::kNone);
    b.vertex_count = 11;  // trimmed to 9
    EXPECT_EQ(nine_vertex_quirk(b, aero), NineVertexQuirk::kAeroRect);
    b.vertex_count = 12;
    EXPECT_EQ(nine_vertex_quirk(b, aero), NineVertexQuirk::kNone);
    b.vertex_count = 9;
    b.fs_has_flat_input = true;
    EXPECT_EQ(nine_vertex_quirk(b, aero), NineVertexQuirk::kNone);
    b.fs_has_flat_input = false;
    b.indexed = true;
    EXPECT_EQ(nine_vertex_quirk(b, aero), NineVertexQuirk::kNone);
    b.indexed = false;
    b.any_vertex_clipped = true;
    EXPECT_EQ(nine_vertex_quirk(b, aero), NineVertexQuirk::kNone);
    b.any_vertex_clipped = false;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    float nans[9][2];
    std::memcpy(nans, aero, sizeof(nans));
    nans[6][1] = nans[7][1] = nans[8][1] = nan;
    EXPECT_EQ(nine_vertex_quirk(b, nans), NineVertexQuirk::kNone);
}
