// 8- and 16-bit integers and 16-bit float storage (shader/translate_narrow.cpp, exec_narrow.h), and float -> uint
// conversions (exec_kernels.h f2u): results against models written from the rules (wrap-around at the width, shift
// counts masked, llvmpipe's division by zero, lavapipe's float -> uint, round-to-nearest-even halves), stores that
// write only their own bytes, element-sized bounds checks, and refusals by name. cts types.* compares the same
// operations with lavapipe.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "compute_harness.h"
#include "shader/jit/jit.h"

namespace tilevk::shader::test {
namespace {

const char* kHeader =
    "#version 450\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int16 : require\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int8 : require\n"
    "#extension GL_EXT_shader_16bit_storage : require\n"
    "#extension GL_EXT_shader_8bit_storage : require\n"
    "layout(local_size_x=16) in;\n";

int32_t sext16(uint32_t x) {
    return int32_t(x << 16) >> 16;
}

TEST(ShaderNarrow, Int16ArithmeticWrapsShiftsAndDividesAsLlvmpipe) {
    auto p = compute(std::string(kHeader) +
                     "layout(std430, binding=0) readonly buffer In { uint16_t a[]; } inp;\n"
                     "layout(std430, binding=1) buffer Out { uint r[]; } o;\n"
                     "void main() {\n"
                     "  uint i = gl_GlobalInvocationID.x;\n"
                     "  uint16_t x = inp.a[2u * i], y = inp.a[2u * i + 1u];\n"
                     "  int16_t sx = int16_t(x), sy = int16_t(y);\n"
                     "  o.r[8u * i] = uint(x * y); o.r[8u * i + 1u] = uint(int(sx / sy));\n"
                     "  o.r[8u * i + 2u] = uint(x / y); o.r[8u * i + 3u] = uint(int(sx >> y));\n"
                     "  o.r[8u * i + 4u] = uint(x << y); o.r[8u * i + 5u] = uint(sx < sy) | uint(x < y) << 1;\n"
                     "  o.r[8u * i + 6u] = uint(int(int8_t(sx))); o.r[8u * i + 7u] = uint(uint16_t(-sx));\n"
                     "}\n");
    ASSERT_TRUE(p);
    const uint32_t vals[] = {0, 1, 0xFFFF, 0x8000, 0x7FFF, 17, 0xFF80, 0x0080, 16, 31, 33, 5, 0xFFFE, 300, 0x1234, 2};
    std::vector<uint32_t> pairs;
    for (uint32_t x : vals)
        for (uint32_t y : vals) pairs.push_back(x | y << 16);
    std::vector<uint32_t> out(pairs.size() * 8, 0xDEADBEEFu);
    Bindings b;
    b.set(0, 0, 0, storage(pairs));
    b.set(0, 1, 0, storage(out));
    Scratch s;
    dispatch(*p, b, 0, uint32_t(pairs.size() / 16), uint32_t(pairs.size() / 16), s);
    for (size_t i = 0; i < pairs.size(); ++i) {
        const uint32_t x = pairs[i] & 0xFFFF, y = pairs[i] >> 16;
        const int32_t sx = sext16(x), sy = sext16(y);
        const uint32_t want[] = {(x * y) & 0xFFFF,
                                 uint32_t(sy == 0 ? 0 : sext16(uint32_t(sx / sy) & 0xFFFF)),
                                 y ? x / y : 0xFFFF,
                                 uint32_t(sx >> (y & 15)),
                                 (x << (y & 15)) & 0xFFFF,
                                 uint32_t(sx < sy) | uint32_t(x < y) << 1,
                                 uint32_t(int32_t(int8_t(x & 0xFF))),
                                 uint32_t(-sx) & 0xFFFF};
        for (uint32_t k = 0; k < 8; ++k) EXPECT_EQ(out[i * 8 + k], want[k]) << "x=" << x << " y=" << y << " k=" << k;
    }
}

// Neighbouring invocations store bytes and halves of one word: each writes its own bytes only; an element whose
// bytes are not all inside the range loads 0 and is not stored.
TEST(ShaderNarrow, StoresWriteOnlyTheirBytesAndBoundsAreElementSized) {
    auto p = compute(std::string(kHeader) +
                     "layout(std430, binding=0) buffer B { uint8_t b[]; } bb;\n"
                     "layout(std430, binding=1) buffer H { uint16_t h[]; } hb;\n"
                     "layout(std430, binding=2) buffer O { uint r[]; } o;\n"
                     "void main() {\n"
                     "  uint i = gl_GlobalInvocationID.x;\n"
                     "  if ((i & 1u) == 0u) bb.b[i] = uint8_t(i * 3u + 1u);\n"
                     "  hb.h[i] = uint16_t(i * 4099u);\n"
                     "  if (i == 0u) { hb.h[19] = uint16_t(0x7777); bb.b[21] = uint8_t(0x77); }\n"
                     "  o.r[i] = uint(hb.h[i + 16u]) | uint(bb.b[i + 16u]) << 16;\n"
                     "}\n");
    ASSERT_TRUE(p);
    std::vector<uint32_t> bytes(8, 0xA5A5A5A5u), halves(12, 0x5A5A5A5Au), out(16, 0);
    for (uint32_t k = 4; k < 8; ++k) bytes[k] = 0x04030201u * (k + 1);
    for (uint32_t k = 8; k < 12; ++k) halves[k] = 0x00020001u * (k + 1);
    Bindings b;
    b.set(0, 0, 0, Descriptor{BufferView{bytes.data(), bytes.data(), 16 + 5}});    // bytes 16..20 of the second 16
    b.set(0, 1, 0, Descriptor{BufferView{halves.data(), halves.data(), 32 + 7}});  // halves 16..18 (19 straddles)
    b.set(0, 2, 0, storage(out));
    Scratch s;
    dispatch(*p, b, 0, 1, 1, s);
    for (uint32_t i = 0; i < 16; ++i) {
        const uint8_t byte = uint8_t(bytes[i / 4] >> (i % 4 * 8));
        EXPECT_EQ(byte, i % 2 == 0 ? uint8_t(i * 3 + 1) : 0xA5) << i;
        EXPECT_EQ((halves[i / 2] >> (i % 2 * 16)) & 0xFFFF, (i * 4099) & 0xFFFF) << i;
        const uint32_t h = i < 3 ? ((halves[8 + i / 2] >> (i % 2 * 16)) & 0xFFFF) : 0;
        const uint32_t bt = i < 5 ? uint8_t(bytes[4 + i / 4] >> (i % 4 * 8)) : 0;
        EXPECT_EQ(out[i], h | bt << 16) << i;
    }
    EXPECT_EQ(halves[9] >> 16, 0x0014u);               // half 19 straddles the end: not stored
    EXPECT_EQ(uint8_t(bytes[5] >> 8), uint8_t(0x0C));  // byte 21 lies past it: not stored (0x18120C06)
}

uint32_t half_rne(float f) {  // finite floats: the nearest half, ties to even
    const uint32_t sign = std::signbit(f) ? 0x8000u : 0;
    const double a = std::fabs(double(f));
    if (a >= 65520.0) return sign | 0x7C00u;
    if (a == 0) return sign;
    const int e = std::max(int(std::floor(std::log2(a))), -14);
    const auto m = uint32_t(std::nearbyint(a / std::ldexp(1.0, e - 10)));
    return sign | (e == -14 && m < 1024 ? m : (uint32_t(e + 15) << 10) + (m - 1024));
}

TEST(ShaderNarrow, HalfStorageConvertsAsFpextAndFptrunc) {
    auto p = compute(std::string(kHeader) +
                     "layout(std430, binding=0) readonly buffer In { float f[64]; } inp;\n"
                     "layout(std430, binding=1) buffer Out { float16_t h[32]; float back[32]; } o;\n"
                     "void main() {\n"
                     "  uint i = gl_GlobalInvocationID.x;\n"
                     "  o.h[i] = float16_t(inp.f[i]);\n"
                     "  o.back[i] = float(o.h[i]);\n"
                     "}\n");
    ASSERT_TRUE(p);
    const float in[32] = {0.0f,
                          -0.0f,
                          1.0f,
                          0x1.004p0f,
                          0x1.006p0f,
                          0x1.002p0f,
                          65504.0f,
                          65519.0f,
                          65520.0f,
                          -1e6f,
                          0x1p-24f,
                          0x1p-25f,
                          0x1.8p-25f,
                          0x1.8p-24f,
                          0x1p-14f,
                          0x1.ffcp-15f,
                          1e-40f,
                          0.1f,
                          -3.14159f,
                          INFINITY,
                          -INFINITY,
                          std::bit_cast<float>(0x7FC12345u),
                          std::bit_cast<float>(0xFF812345u),
                          1.5f,
                          2.5f,
                          1000.3f,
                          -0.33333f,
                          7e-6f,
                          0x1.0p-20f,
                          12345.6f,
                          -0x1.ffep-15f,
                          3.0f};
    std::vector<uint32_t> words(64, 0);
    for (int i = 0; i < 32; ++i) words[size_t(i)] = std::bit_cast<uint32_t>(in[i]);
    std::vector<uint32_t> out(48, 0xDEADBEEFu);
    Bindings b;
    b.set(0, 0, 0, storage(words));
    b.set(0, 1, 0, storage(out));
    Scratch s;
    dispatch(*p, b, 0, 2, 2, s);
    for (uint32_t i = 0; i < 32; ++i) {
        const uint32_t h = (out[i / 2] >> (i % 2 * 16)) & 0xFFFF;
        const uint32_t x = std::bit_cast<uint32_t>(in[i]);
        // NaN: the quiet NaN 0x7E00 with its sign, the payload dropped (as lavapipe)
        const uint32_t want = std::isnan(in[i]) ? ((x >> 16) & 0x8000) | 0x7E00 : half_rne(in[i]);
        EXPECT_EQ(h, want) << "float16_t(" << in[i] << ")";
        if (std::isnan(in[i])) continue;
        const double v = (h & 0x7C00) == 0x7C00 ? INFINITY
                         : (h >> 10 & 31)       ? std::ldexp(1024 + (h & 1023), int(h >> 10 & 31) - 25)
                                                : std::ldexp(h & 1023, -24);
        EXPECT_EQ(out[16 + i], std::bit_cast<uint32_t>(float(h & 0x8000 ? -v : v))) << "float(half " << h << ")";
    }
}

// lavapipe's float -> uint (measured): trunc(x) in (-1, 2^32), all ones outside and for NaN.
TEST(ShaderNarrow, FloatToUintOutsideTheRangeIsAllOnes) {
    auto p = compute(
        "#version 450\nlayout(local_size_x=16) in;\n"
        "layout(std430, binding=0) buffer B { float f[16]; uint u[16]; } b;\n"
        "void main() { uint i = gl_GlobalInvocationID.x; b.u[i] = uint(b.f[i]); }\n");
    ASSERT_TRUE(p);
    const float in[16] = {-1.0f,         -0.5f,    std::numeric_limits<float>::quiet_NaN(),
                          0x1p32f,       3e9f,     -3e9f,
                          -100.0f,       -0x1p31f, 0x1p31f,
                          4294967040.0f, INFINITY, -INFINITY,
                          -1.5f,         0.75f,    7.0f,
                          -0.0f};
    const uint32_t want[16] = {~0u,         0,           ~0u, ~0u, 3000000000u, ~0u, ~0u, ~0u,
                               0x80000000u, 4294967040u, ~0u, ~0u, ~0u,         0,   7,   0};
    std::vector<uint32_t> words(32, 0);
    for (int i = 0; i < 16; ++i) words[size_t(i)] = std::bit_cast<uint32_t>(in[i]);
    Bindings b;
    b.set(0, 0, 0, storage(words));
    Scratch s;
    dispatch(*p, b, 0, 1, 1, s);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(words[size_t(16 + i)], want[i]) << "uint(" << in[i] << ")";
}

TEST(ShaderNarrow, BufferAccessStaysInTheInterpreterArithmeticCompiles) {
    auto with_buffer = compute(std::string(kHeader) +
                               "layout(std430, binding=0) buffer B { uint16_t h[]; } b;\n"
                               "void main() { b.h[gl_GlobalInvocationID.x] += uint16_t(3); }\n");
    ASSERT_TRUE(with_buffer);
    EXPECT_FALSE(with_buffer->compiled());
    auto arithmetic = compute(std::string(kHeader) +
                              "layout(std430, binding=0) buffer B { uint u[]; } b;\n"
                              "void main() { uint i = gl_GlobalInvocationID.x;\n"
                              "  int16_t x = int16_t(b.u[i]) * int16_t(-7); b.u[i] = uint(int(x >> int16_t(3))); }\n");
    ASSERT_TRUE(arithmetic);
    EXPECT_EQ(arithmetic->compiled(), jit::enabled() && jit::host_supported());
}

TEST(ShaderNarrow, HalfArithmeticAndPointerAccessAreRefusedByName) {
    const std::vector<uint32_t> f16 =
        compile_glsl(Stage::Compute,
                     "#version 450\n"
                     "#extension GL_EXT_shader_explicit_arithmetic_types_float16 : "
                     "require\n"
                     "layout(local_size_x=1) in;\n"
                     "layout(std430, binding=0) buffer B { float f; } b;\n"
                     "void main() { float16_t h = float16_t(b.f); b.f = float(h * h); }\n",
                     false);
    const Result r = Program::create(f16, Stage::Compute, "main", {});
    EXPECT_FALSE(r);
    EXPECT_NE(r.error.find("Float16"), std::string::npos) << r.error;
    // valid SPIR-V that shader/ refuses by name: a 16-bit load through a PhysicalStorageBuffer pointer
    const std::vector<uint32_t> ptr = compile_glsl(Stage::Compute,
                                                   std::string(kHeader) +
                                                       "#extension GL_EXT_buffer_reference : require\n"
                                                       "layout(buffer_reference, std430) buffer P { uint16_t v; };\n"
                                                       "layout(std430, binding=0) buffer B { P p; uint16_t h; } b;\n"
                                                       "void main() { b.h = b.p.v; }\n",
                                                   false);
    const Result r2 = Program::create(ptr, Stage::Compute, "main", {});
    EXPECT_FALSE(r2);
    EXPECT_NE(r2.error.find("8- or 16-bit load through a PhysicalStorageBuffer pointer"), std::string::npos)
        << r2.error;
}

}  // namespace
}  // namespace tilevk::shader::test
