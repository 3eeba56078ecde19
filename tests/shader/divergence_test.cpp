// Divergent control flow under the lane/mask model: every lane must see what a scalar (one invocation at a
// time) execution computes. Each case's expectation comes from a plain C++ model of the same shader run one
// invocation after another.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::f;
using tilevk::shader::test::make_program;
using tilevk::shader::test::u;

namespace {


}  // namespace

// Issue #4's known case: a value loaded inside a loop from a buffer that other lanes write in the same loop.
// Lane L loops until the shared counter reaches L, each iteration writing counter+1. Run one invocation after
// another (and equally in lock-step), lane L leaves the loop with v == L after counting L increments of its own
// or others. A lane that left early must keep the value it loaded, not the counter's final value.
TEST(ShaderDivergence, LoadInLoopFromBufferOtherLanesWrite) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(set=0, binding=0, std430) buffer C { uint counter; } c;
        layout(location=0) flat out uvec4 o;
        void main() {
            uint lane = uint(gl_VertexIndex);
            uint v;
            uint twice;
            for (;;) {
                v = c.counter;
                twice = v * 2u;
                if (v >= lane) break;
                c.counter = v + 1u;
            }
            o = uvec4(v, twice, lane, 0u);
            gl_Position = vec4(0.0);
        })");
    ASSERT_TRUE(prog);
    uint32_t counter = 0;
    Bindings b;
    b.set(0, 0, 0, Descriptor{BufferView{&counter, &counter, 4}});
    VertexBatch vb;
    for (int l = 0; l < kLanes; ++l) vb.vertex_index[l] = uint32_t(l);
    Scratch s;
    prog->run_vertex(b, vb, s);
    // scalar model: invocations in order; each reads the counter until it reaches its index
    uint32_t model = 0;
    for (uint32_t l = 0; l < uint32_t(kLanes); ++l) {
        uint32_t v;
        for (;;) {
            v = model;
            if (v >= l) break;
            model = v + 1;
        }
        EXPECT_EQ(vb.outputs[0][0][l], v) << "lane " << l;
        EXPECT_EQ(vb.outputs[0][1][l], v * 2) << "lane " << l;
    }
    EXPECT_EQ(counter, model);
}

namespace {

// A fragment shader over one 4x4 block with `flat in int idx` (= lane), `in vec4 v`, `out vec4 color` and a
// 64-word storage buffer at set 0 binding 0.
struct Frag {
    std::shared_ptr<const Program> prog;
    FragmentBlock block;
    Scratch scratch;
    Bindings bindings;
    std::vector<uint32_t> data = std::vector<uint32_t>(64, 0);
    Frag(const std::string& body, bool demote = false) {
        std::string src = std::string("#version 450\n") +
                          (demote ? "#extension GL_EXT_demote_to_helper_invocation : require\n" : "") +
                          "layout(location=0) flat in int idx;\n"
                          "layout(location=1) in vec4 v;\n"
                          "layout(location=0) out vec4 color;\n"
                          "layout(set=0, binding=0, std430) buffer S { uint data[64]; } s;\n"
                          "void main() {\n" +
                          body + "\n}\n";
        auto spirv = tilevk::shader::test::compile_glsl(Stage::Fragment, src, demote);
        Result r = Program::create(spirv, Stage::Fragment);
        EXPECT_TRUE(r) << r.error;
        prog = r.program;
        for (int l = 0; l < kLanes; ++l) block.inputs[0][0][l] = uint32_t(l);
    }
    void run() {
        ASSERT_TRUE(prog);
        bindings.set(0, 0, 0, Descriptor{BufferView{data.data(), data.data(), data.size() * 4}});
        prog->run_fragment(bindings, block, scratch);
    }
    float out(int lane, int c) const { return f(block.outputs[0][c][lane]); }
};

}  // namespace

// Buffer stores in if/else chains, switch fallthrough and loops with lane-dependent trip counts land exactly for
// the lanes (and iterations) that execute them; helper lanes never store.
TEST(ShaderDivergence, StoresUnderDivergentControlFlow) {
    Frag r(R"(
        int l = idx;
        if (l % 3 == 0) { s.data[l] = 1u; }
        else if (l % 3 == 1) { for (int i = 0; i < l; ++i) s.data[l] += uint(i); }
        else {
            switch (l % 4) {
                case 0: s.data[l] = 7u;
                case 1: s.data[l] += 100u; break;
                default: s.data[l] = 9u; break;
            }
        }
        for (int i = 0; i < l; ++i) { if (i == 5) continue; if (i > 9) break; s.data[16 + l] = uint(i * 3 + l); }
        color = vec4(1.0);
    )");
    r.block.cover_mask = kAllLanes & ~((1u << 5) | (1u << 14));  // lanes 5 and 14 are helpers
    r.run();
    std::vector<uint32_t> e(64, 0);
    for (int l = 0; l < kLanes; ++l) {
        if (l == 5 || l == 14) continue;
        if (l % 3 == 0) {
            e[size_t(l)] = 1;
        } else if (l % 3 == 1) {
            for (int i = 0; i < l; ++i) e[size_t(l)] += uint32_t(i);
        } else {
            switch (l % 4) {
                case 0:
                    e[size_t(l)] = 7;
                    [[fallthrough]];
                case 1:
                    e[size_t(l)] += 100;
                    break;
                default:
                    e[size_t(l)] = 9;
                    break;
            }
        }
        for (int i = 0; i < l; ++i) {
            if (i == 5) continue;
            if (i > 9) break;
            e[size_t(16 + l)] = uint32_t(i * 3 + l);
        }
    }
    for (size_t i = 0; i < 64; ++i) EXPECT_EQ(r.data[i], e[i]) << "word " << i;
}

// Lane-dependent trip counts: values defined inside the loop (from buffer loads, including this lane's own
// earlier stores, and from a nested loop) and used after it are the ones of the lane's own last iteration.
TEST(ShaderDivergence, LaneDependentTripCountsValuesUsedAfterLoop) {
    Frag r(R"(
        int l = idx;
        uint last = 0u, seen = 0u, inner = 0u;
        int i = 0;
        for (;; ++i) {
            last = s.data[32 + i] + uint(l);        // read-only table, loaded in the loop
            s.data[l] = uint(i) * 10u;              // own slot...
            seen = s.data[l] + 1u;                  // ...read back in the same iteration
            int k = 0;
            while (k * k < i) k++;
            inner = uint(k);
            if (i >= l / 2) break;
        }
        color = vec4(float(last), float(seen), float(inner), float(i));
    )");
    for (size_t i = 0; i < 32; ++i) r.data[32 + i] = uint32_t(i * i + 1000);
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        uint32_t last = 0, seen = 0, inner = 0;
        int i = 0;
        for (;; ++i) {
            last = uint32_t(i * i + 1000) + uint32_t(l);
            seen = uint32_t(i) * 10 + 1;
            int k = 0;
            while (k * k < i) k++;
            inner = uint32_t(k);
            if (i >= l / 2) break;
        }
        EXPECT_EQ(r.out(l, 0), float(last)) << l;
        EXPECT_EQ(r.out(l, 1), float(seen)) << l;
        EXPECT_EQ(r.out(l, 2), float(inner)) << l;
        EXPECT_EQ(r.out(l, 3), float(i)) << l;
    }
}

// return inside a loop ends the invocation: nothing after it runs for that lane, earlier writes stay.
TEST(ShaderDivergence, EarlyReturnInsideLoop) {
    Frag r(R"(
        int l = idx;
        color = vec4(-1.0);
        for (int i = 0; i < 8; ++i) {
            s.data[l] = uint(i);
            if (i * 2 >= l) { color = vec4(float(i)); return; }
        }
        s.data[16 + l] = 77u;
        color = vec4(100.0);
    )");
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int ret = -1, last = 0;
        for (int i = 0; i < 8; ++i) {
            last = i;
            if (i * 2 >= l) {
                ret = i;
                break;
            }
        }
        EXPECT_EQ(r.data[size_t(l)], uint32_t(last)) << l;
        EXPECT_EQ(r.data[size_t(16 + l)], ret < 0 ? 77u : 0u) << l;
        EXPECT_EQ(r.out(l, 0), ret < 0 ? 100.0f : float(ret)) << l;
    }
}

// discard inside a loop: the lane stops, its later stores never land, the others run on.
TEST(ShaderDivergence, DiscardInsideLoopStopsLaterStores) {
    Frag r(R"(
        int l = idx;
        for (int i = 0; i < 6; ++i) {
            s.data[l] += 1u;
            if (l % 4 == 1 && i == l / 4) discard;
        }
        s.data[16 + l] = 5u;
        color = vec4(float(l));
    )");
    r.run();
    uint32_t live = 0;
    for (int l = 0; l < kLanes; ++l) {
        bool killed = l % 4 == 1;
        uint32_t count = killed ? uint32_t(l / 4 + 1) : 6u;
        if (!killed) live |= 1u << l;
        EXPECT_EQ(r.data[size_t(l)], count) << l;
        EXPECT_EQ(r.data[size_t(16 + l)], killed ? 0u : 5u) << l;
        if (!killed) {
            EXPECT_EQ(r.out(l, 0), float(l));
        }
    }
    EXPECT_EQ(r.block.live_mask, live);
}

// demote inside a loop: the lane keeps running as a helper (its stores stop landing) and sees itself as one.
TEST(ShaderDivergence, DemoteInsideLoop) {
    Frag r(R"(
        int l = idx;
        int i = 0;
        for (; i < 4; ++i) {
            s.data[l] += 1u;
            if (l % 2 == 1 && i == 1) demote;
        }
        color = vec4(float(i), helperInvocationEXT() ? 1.0 : 0.0, 0.0, 0.0);
    )",
           true);
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        bool demoted = l % 2 == 1;
        EXPECT_EQ(r.data[size_t(l)], demoted ? 2u : 4u) << l;
        EXPECT_EQ(r.out(l, 0), 4.0f) << l;
        EXPECT_EQ(r.out(l, 1), demoted ? 1.0f : 0.0f) << l;
    }
    EXPECT_EQ(r.block.live_mask, 0x5555u);
}

// Derivatives in quad-uniform control flow are defined (and exact); in non-uniform control flow (an if, a loop
// with a lane-dependent trip count) they are undefined in GLSL but must not crash and must not depend on what
// the scratch held before.
TEST(ShaderDivergence, DerivativesInNonUniformControlFlow) {
    const std::string body = R"(
        int l = idx;
        float q = v.x * v.x + 2.0 * v.y;
        float a = 0.0, b = 0.0, c = 0.0;
        if ((l >> 2) % 2 == 0) a = dFdx(q) + 10.0 * dFdy(q);   // uniform per quad (lane >> 2 is the quad)
        if (l % 3 == 0) {                                       // non-uniform inside quads
            float t;
            if (v.z > 9.0) { t = v.z * 2.0; } else { t = v.w + 1.0; }
            b = dFdx(t) + dFdy(q);
        }
        float p = q;
        for (int i = 0; i < l % 5; ++i) { p = p * 0.5 + 1.0; c += fwidth(p); }
        color = vec4(a, b, c, p);
    )";
    Frag r(body);
    for (int l = 0; l < kLanes; ++l)
        for (int k = 0; k < 4; ++k) r.block.inputs[1][k][l] = u(float(lane_x(l) * 3 + lane_y(l) * 5 + k));
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        if ((l >> 2) % 2) continue;
        auto q = [](int x, int y) {
            return float(x * 3 + y * 5) * float(x * 3 + y * 5) + 2.0f * float(x * 3 + y * 5 + 1);
        };
        int x0 = lane_x(l) & ~1, y0 = lane_y(l) & ~1;
        float ddx = q(x0 + 1, lane_y(l)) - q(x0, lane_y(l));
        float ddy = q(lane_x(l), y0 + 1) - q(lane_x(l), y0);
        EXPECT_EQ(r.out(l, 0), ddx + 10.0f * ddy) << l;
    }
    // Same block on a scratch that first ran other inputs, and on a fresh scratch: identical bits.
    Frag other(body);
    for (int l = 0; l < kLanes; ++l) {
        other.block.inputs[0][0][l] = uint32_t(l + 1);  // other lanes take the branches first
        for (int k = 0; k < 4; ++k) other.block.inputs[1][k][l] = u(1000.0f - float(l * 7 + k));
    }
    other.run();
    std::memcpy(other.block.inputs, r.block.inputs, sizeof(r.block.inputs));
    other.run();
    Frag fresh(body);
    std::memcpy(fresh.block.inputs, r.block.inputs, sizeof(r.block.inputs));
    fresh.run();
    for (int l = 0; l < kLanes; ++l)
        for (int k = 0; k < 4; ++k) {
            EXPECT_EQ(other.block.outputs[0][k][l], r.block.outputs[0][k][l]) << l << " " << k;
            EXPECT_EQ(fresh.block.outputs[0][k][l], r.block.outputs[0][k][l]) << l << " " << k;
        }
}

// A partial vertex batch: lanes at or past `count` execute nothing visible, buffer stores included.
TEST(ShaderDivergence, PartialVertexBatchDoesNotStore) {
    auto prog = make_program(Stage::Vertex, R"(#version 450
        layout(set=0, binding=0, std430) buffer S { uint data[16]; } s;
        void main() {
            for (int i = 0; i <= gl_VertexIndex; ++i) s.data[gl_VertexIndex] += 1u;
            gl_Position = vec4(float(gl_VertexIndex));
        })");
    ASSERT_TRUE(prog);
    std::vector<uint32_t> data(16, 0);
    Bindings b;
    b.set(0, 0, 0, Descriptor{BufferView{data.data(), data.data(), 64}});
    VertexBatch vb;
    vb.count = 5;
    for (int l = 0; l < kLanes; ++l) vb.vertex_index[l] = uint32_t(l);
    Scratch s;
    prog->run_vertex(b, vb, s);
    for (uint32_t l = 0; l < 16; ++l) EXPECT_EQ(data[l], l < 5 ? l + 1 : 0u) << l;
}
