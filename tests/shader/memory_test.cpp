// Uniform/storage buffers (std140/std430 layouts), push constants, local arrays, storage images; robust bounds
// checks.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <vector>

#include "compute_harness.h"
#include "glsl.h"
#include "shader/jit/jit.h"

using namespace tilevk::shader;
using tilevk::shader::test::f;
using tilevk::shader::test::make_program;
using tilevk::shader::test::u;

namespace {

template <typename T>
void put(std::vector<uint8_t>& buf, size_t off, T v) {
    std::memcpy(buf.data() + off, &v, sizeof(T));
}

// A w x h x layers R32_UINT image over `words` (rows packed), as icd/ hands a storage image over.
ImageView r32ui_view(std::vector<uint32_t>& words, uint32_t w, uint32_t h, uint32_t layers = 1) {
    ImageView v;
    v.base = reinterpret_cast<const uint8_t*>(words.data());
    v.format = Format::R32_UINT;
    v.width = w, v.height = h, v.layers = layers;
    v.level[0].row_pitch = uint64_t(w) * 4;
    v.level[0].layer_pitch = uint64_t(w) * h * 4;
    return v;
}
Descriptor storage_image(const ImageView& v, std::vector<uint32_t>& words, bool writable = true) {
    Descriptor d;
    d.image = &v;
    d.image_writable = writable ? reinterpret_cast<uint8_t*>(words.data()) : nullptr;
    return d;
}
}  // namespace

TEST(ShaderMemory, UniformBufferStd140) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(set=0, binding=1, std140) uniform U {
            mat4 mvp;          // offset 0, column stride 16
            float scale[3];    // offset 64, array stride 16
            vec3 tint;         // offset 112
            layout(row_major) mat2 rm;  // offset 128, row stride 16
        } u;
        layout(location=0) in vec4 pos;
        layout(location=0) out vec4 o;
        void main() {
            gl_Position = u.mvp * pos;
            int i = gl_VertexIndex % 3;
            o = vec4(u.scale[i], u.tint.z, (u.rm * vec2(1.0, 2.0)));
        })");
    ASSERT_TRUE(prog);
    std::vector<uint8_t> ubo(160, 0);
    float m[16];
    for (int i = 0; i < 16; ++i) m[i] = float(i) * 0.5f - 3.0f;
    for (int i = 0; i < 16; ++i) put(ubo, size_t(i) * 4, m[i]);
    for (int i = 0; i < 3; ++i) put(ubo, 64 + size_t(i) * 16, 10.0f + float(i));
    put(ubo, 112 + 8, 0.75f);
    // row-major mat2: row 0 at 128 = (m00, m01), row 1 at 144 = (m10, m11)
    float rm[2][2] = {{1.0f, 3.0f}, {5.0f, 7.0f}};  // rm[row][col]
    put(ubo, 128, rm[0][0]), put(ubo, 132, rm[0][1]), put(ubo, 144, rm[1][0]), put(ubo, 148, rm[1][1]);
    Bindings b;
    b.set(0, 1, 0, Descriptor{BufferView{ubo.data(), nullptr, ubo.size()}});
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l) {
        vb.vertex_index[l] = uint32_t(l);
        for (int c = 0; c < 4; ++c) vb.inputs[0][c][l] = u(float(l + c) * 0.25f);
    }
    Scratch s;
    prog->run_vertex(b, vb, s);
    for (int l = 0; l < kLanes; ++l) {
        float p[4];
        for (int c = 0; c < 4; ++c) p[c] = float(l + c) * 0.25f;
        for (int row = 0; row < 4; ++row) {
            float acc = m[row] * p[0];
            for (int c = 1; c < 4; ++c) acc = acc + m[c * 4 + row] * p[c];
            EXPECT_EQ(f(vb.position[row][l]), acc);
        }
        EXPECT_EQ(f(vb.outputs[0][0][l]), 10.0f + float(l % 3));
        EXPECT_EQ(f(vb.outputs[0][1][l]), 0.75f);
        EXPECT_EQ(f(vb.outputs[0][2][l]), rm[0][0] * 1.0f + rm[0][1] * 2.0f);
        EXPECT_EQ(f(vb.outputs[0][3][l]), rm[1][0] * 1.0f + rm[1][1] * 2.0f);
    }
    const auto& io = prog->interface();
    ASSERT_EQ(io.descriptors.size(), 1u);
    EXPECT_EQ(io.descriptors[0].binding, 1u);
    EXPECT_EQ(io.descriptors[0].kind, DescriptorKind::UniformBuffer);
}

TEST(ShaderMemory, StorageBufferReadWriteAndBounds) {
    auto prog = make_program(Stage::Fragment, R"(#version 450
        layout(set=0, binding=0, std430) buffer S { uint count; float data[]; } s;
        layout(set=1, binding=2, std430) readonly buffer R { vec2 v[]; } r;
        layout(location=0) flat in int idx;
        layout(location=0) out vec4 color;
        void main() {
            s.data[idx] = float(idx) * 2.0;     // out-of-bounds stores are dropped
            color = vec4(r.v[idx], s.data[idx + 1000000], 1.0);  // out-of-bounds loads give 0
        })");
    ASSERT_TRUE(prog);
    std::vector<uint8_t> ssbo(4 + 4 * 10, 0xAB);
    std::vector<float> rv(2 * 8);
    for (size_t i = 0; i < rv.size(); ++i) rv[i] = float(i) + 0.5f;
    Bindings b;
    b.set(0, 0, 0, Descriptor{BufferView{ssbo.data(), ssbo.data(), ssbo.size()}});
    b.set(1, 2, 0, Descriptor{BufferView{rv.data(), nullptr, rv.size() * 4}});
    FragmentBlock fb;
    fb.cover_mask = 0xFFFF & ~(1u << 3);  // lane 3 is a helper: its store must not land
    for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = uint32_t(l);
    Scratch sc;
    prog->run_fragment(b, fb, sc);
    for (int l = 0; l < kLanes; ++l) {
        if (l < 10) {
            float got;
            std::memcpy(&got, ssbo.data() + 4 + 4 * l, 4);
            if (l == 3) {
                uint32_t raw;
                std::memcpy(&raw, ssbo.data() + 4 + 4 * l, 4);
                EXPECT_EQ(raw, 0xABABABABu);
            } else {
                EXPECT_EQ(got, float(l) * 2.0f);
            }
        }
        EXPECT_EQ(f(fb.outputs[0][0][l]), l < 8 ? float(2 * l) + 0.5f : 0.0f);
        EXPECT_EQ(f(fb.outputs[0][1][l]), l < 8 ? float(2 * l + 1) + 0.5f : 0.0f);
        EXPECT_EQ(f(fb.outputs[0][2][l]), 0.0f);
    }
    uint32_t count;
    std::memcpy(&count, ssbo.data(), 4);
    EXPECT_EQ(count, 0xABABABABu);
    const auto& io = prog->interface();
    ASSERT_EQ(io.descriptors.size(), 2u);
    EXPECT_EQ(io.descriptors[0].kind, DescriptorKind::StorageBuffer);
    EXPECT_TRUE(io.descriptors[0].written);
}

TEST(ShaderMemory, MissingDescriptorReadsZero) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(set=0, binding=0) uniform U { vec4 x; } u;
        void main() { gl_Position = u.x + vec4(1.0); })");
    ASSERT_TRUE(prog);
    VertexBatch vb;
    Scratch s;
    prog->run_vertex(Bindings{}, vb, s);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(f(vb.position[c][0]), 1.0f);
}

TEST(ShaderMemory, PushConstants) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(push_constant) uniform P { vec4 offset; int mode; } pc;
        void main() { gl_Position = pc.offset * float(pc.mode); })");
    ASSERT_TRUE(prog);
    EXPECT_EQ(prog->interface().push_constant_size, 20u);
    std::vector<std::byte> bytes(20);
    float off[4] = {1.5f, -2.0f, 3.25f, 4.0f};
    int32_t mode = 3;
    std::memcpy(bytes.data(), off, 16);
    std::memcpy(bytes.data() + 16, &mode, 4);
    Bindings b;
    b.push_constants = bytes;
    VertexBatch vb;
    Scratch s;
    prog->run_vertex(b, vb, s);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(f(vb.position[c][5]), off[c] * 3.0f);
    // short push-constant range: the int reads as 0
    b.push_constants = std::span<const std::byte>(bytes.data(), 16);
    prog->run_vertex(b, vb, s);
    EXPECT_EQ(f(vb.position[0][5]), 0.0f);
}

TEST(ShaderMemory, LocalArraysDynamicIndexing) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(location=0) in ivec2 k;
        layout(location=0) out vec4 o;
        float table[5] = float[5](1.0, 2.0, 4.0, 8.0, 16.0);
        struct S { vec2 a; float b[3]; };
        void main() {
            float arr[8];
            for (int i = 0; i < 8; ++i) arr[i] = float(i * i);
            arr[k.y] = -1.0;
            S s;
            s.a = vec2(k);
            s.b[k.x % 3] = 5.0;
            s.b[(k.x + 1) % 3] = 6.0;
            s.b[(k.x + 2) % 3] = 7.0;
            o = vec4(arr[k.x], table[k.x % 5], s.b[1], s.a.y);
        })");
    ASSERT_TRUE(prog);
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l) vb.inputs[0][0][l] = uint32_t(l % 8), vb.inputs[0][1][l] = uint32_t((l * 3) % 8);
    Scratch s;
    prog->run_vertex(Bindings{}, vb, s);
    const float table[5] = {1, 2, 4, 8, 16};
    for (int l = 0; l < kLanes; ++l) {
        int kx = l % 8, ky = (l * 3) % 8;
        float arr[8];
        for (int i = 0; i < 8; ++i) arr[i] = float(i * i);
        arr[ky] = -1.0f;
        float b[3];
        b[kx % 3] = 5, b[(kx + 1) % 3] = 6, b[(kx + 2) % 3] = 7;
        EXPECT_EQ(f(vb.outputs[0][0][l]), arr[kx]);
        EXPECT_EQ(f(vb.outputs[0][1][l]), table[kx % 5]);
        EXPECT_EQ(f(vb.outputs[0][2][l]), b[1]);
        EXPECT_EQ(f(vb.outputs[0][3][l]), float(ky));
    }
}

TEST(ShaderMemory, LocalArrayOutOfBoundsIndexDoesNotCrash) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(location=0) in int k;
        layout(location=0) out vec4 o;
        void main() {
            float arr[4] = float[4](1.0, 2.0, 3.0, 4.0);
            arr[k] = 9.0;
            o = vec4(arr[k], arr[-k], 0.0, 0.0);
        })");
    ASSERT_TRUE(prog);
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l) vb.inputs[0][0][l] = uint32_t(l * 100000000);
    Scratch s;
    prog->run_vertex(Bindings{}, vb, s);  // must not crash; values are unspecified past the array
    SUCCEED();
}

// imageStore / imageLoad / imageSize in compute: every invocation of an 8x4 workgroup stores at its id into a 6x3
// array layer 1 (the lanes past x = 5 or y = 2 are outside: dropped), loads the texel one to the left (outside at
// x = 0: (0, 0, 0, 1), R32_UINT has no alpha) into a buffer.
TEST(ShaderMemory, StorageImageComputeStoresLoadsAndBounds) {
    auto p = tilevk::shader::test::compute(R"(#version 450
        layout(local_size_x = 8, local_size_y = 4) in;
        layout(r32ui, set = 0, binding = 0) uniform uimage2DArray img;
        layout(std430, set = 0, binding = 1) buffer Out { uvec4 o[32]; ivec4 size; };
        void main() {
            ivec2 p = ivec2(gl_LocalInvocationID.xy);
            imageStore(img, ivec3(p, 1), uvec4(uint(p.x * 10 + p.y + 1)));
            memoryBarrierImage();
            barrier();
            o[gl_LocalInvocationIndex] = imageLoad(img, ivec3(p.x - 1, p.y, 1));
            size = ivec4(imageSize(img), 0);
        })");
    ASSERT_TRUE(p);
    EXPECT_EQ(p->compiled(), jit::enabled() && jit::host_supported());  // compiled unless TILEVK_JIT=0
    ASSERT_EQ(p->interface().descriptors.size(), 2u);
    EXPECT_EQ(p->interface().descriptors[0].kind, DescriptorKind::StorageImage);
    EXPECT_TRUE(p->interface().descriptors[0].written);
    std::vector<uint32_t> texels(6 * 3 * 2, 0xEEu), out(32 * 4 + 4, 0xDDu);
    const ImageView v = r32ui_view(texels, 6, 3, 2);
    Bindings b;
    b.set(0, 0, 0, storage_image(v, texels));
    b.set(0, 1, 0, tilevk::shader::test::storage(out));
    Scratch s;
    tilevk::shader::test::dispatch(*p, b, 0, 1, 1, s);
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 0; x < 6; ++x) {
            EXPECT_EQ(texels[y * 6 + x], 0xEEu) << "layer 0 untouched";
            EXPECT_EQ(texels[18 + y * 6 + x], x * 10 + y + 1) << x << "," << y;
        }
    for (uint32_t i = 0; i < 32; ++i) {
        const uint32_t x = i % 8, y = i / 8;
        const bool inside = x >= 1 && x - 1 < 6 && y < 3;
        EXPECT_EQ(out[i * 4], inside ? (x - 1) * 10 + y + 1 : 0u) << i;
        EXPECT_EQ(out[i * 4 + 1], 0u) << i;
        EXPECT_EQ(out[i * 4 + 3], 1u) << i;  // alpha: the integer 1 inside and outside
    }
    EXPECT_EQ(out[128], 6u);
    EXPECT_EQ(out[129], 3u);
    EXPECT_EQ(out[130], 2u);
    // Without a writable descriptor (not a storage image binding) nothing is stored.
    std::vector<uint32_t> ro(6 * 3 * 2, 0x77u);
    const ImageView rv = r32ui_view(ro, 6, 3, 2);
    Bindings b2;
    b2.set(0, 0, 0, storage_image(rv, ro, false));
    b2.set(0, 1, 0, tilevk::shader::test::storage(out));
    tilevk::shader::test::dispatch(*p, b2, 0, 1, 1, s);
    for (uint32_t t : ro) EXPECT_EQ(t, 0x77u);
}

// Fragment imageStore: helper lanes (not covered) and discarded lanes write nothing; all the others store at one
// texel in lane order, so the last such lane's value stays.
TEST(ShaderMemory, StorageImageFragmentStoresOnlyLiveCoveredLanes) {
    auto prog = make_program(Stage::Fragment, R"(#version 450
        layout(r32ui, set = 0, binding = 0) uniform uimage2D img;
        layout(location = 0) flat in int lane;
        layout(location = 0) out vec4 color;
        void main() {
            if (lane == 6) discard;
            imageStore(img, ivec2(lane, 0), uvec4(uint(lane + 100)));
            imageStore(img, ivec2(0, 1), uvec4(uint(lane)));
            color = vec4(1.0);
        })");
    ASSERT_TRUE(prog);
    std::vector<uint32_t> texels(16 * 2, 0xEEu);
    const ImageView v = r32ui_view(texels, 16, 2);
    Bindings b;
    b.set(0, 0, 0, storage_image(v, texels));
    FragmentBlock fb;
    fb.cover_mask = 0xFFFF & ~(1u << 3) & ~(1u << 15);  // lanes 3 and 15: helpers
    for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = uint32_t(l);
    Scratch sc;
    prog->run_fragment(b, fb, sc);
    for (uint32_t l = 0; l < 16; ++l)
        EXPECT_EQ(texels[l], l == 3 || l == 6 || l == 15 ? 0xEEu : l + 100) << "lane " << l;
    EXPECT_EQ(texels[16], 14u);  // the last live lane
}
