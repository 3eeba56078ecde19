// Control flow (masks), discard/demote, derivatives and helper lanes on 4x4 fragment blocks; the colour outputs.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "glsl.h"

using namespace tilevk::shader;
using tilevk::shader::test::f;
using tilevk::shader::test::make_program;
using tilevk::shader::test::u;

namespace {

// Fragment shader with `in vec4 v` at location 0 and `out vec4 color` at location 0.
struct FsRun {
    std::shared_ptr<const Program> prog;
    FragmentBlock block;
    Scratch scratch;
    Bindings bindings;
    explicit FsRun(const std::string& body, const std::string& decls = "") {
        prog = make_program(Stage::Fragment,
                            "#version 450\n"
                            "layout(location=0) in vec4 v;\n"
                            "layout(location=0) out vec4 color;\n" +
                                decls + "void main() {\n" + body + "\n}\n");
    }
    void set_v(int lane, int c, float x) { block.inputs[0][c][lane] = u(x); }
    void run() {
        ASSERT_TRUE(prog);
        prog->run_fragment(bindings, block, scratch);
    }
    float out(int lane, int c) const { return f(block.outputs[0][c][lane]); }
};

}  // namespace

TEST(ShaderControl, LaneLayoutHelpers) {
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            int l = lane_of(x, y);
            EXPECT_EQ(lane_x(l), x);
            EXPECT_EQ(lane_y(l), y);
            EXPECT_EQ(l, ((y >> 1) * 2 + (x >> 1)) * 4 + (y & 1) * 2 + (x & 1));
        }
}

TEST(ShaderControl, IfElseDivergent) {
    FsRun r(R"(
        float x = v.x;
        if (x > 0.5) { color = vec4(1.0, x * 2.0, 0.0, 1.0); }
        else if (x > 0.25) { color = vec4(2.0, x + 1.0, 0.0, 1.0); }
        else { color = vec4(3.0, -x, 0.0, 1.0); }
    )");
    for (int l = 0; l < kLanes; ++l) r.set_v(l, 0, float(l) / 16.0f);
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float x = float(l) / 16.0f;
        float e0 = x > 0.5f ? 1.0f : x > 0.25f ? 2.0f : 3.0f;
        float e1 = x > 0.5f ? x * 2.0f : x > 0.25f ? x + 1.0f : -x;
        EXPECT_EQ(r.out(l, 0), e0) << l;
        EXPECT_EQ(r.out(l, 1), e1) << l;
    }
    EXPECT_EQ(r.block.live_mask, kAllLanes);
}

TEST(ShaderControl, LoopsWithBreakAndContinue) {
    FsRun r(R"(
        int n = int(v.x);
        float sum = 0.0;
        int iters = 0;
        for (int i = 0; i < 100; ++i) {
            iters++;
            if (i >= n) break;
            if ((i & 1) == 1) continue;
            sum += float(i) * v.y;
        }
        int j = 0;
        while (j * j < n) { j++; }
        color = vec4(sum, float(iters), float(j), 0.0);
    )");
    for (int l = 0; l < kLanes; ++l) {
        r.set_v(l, 0, float((l * 7) % 23));
        r.set_v(l, 1, 0.5f + float(l));
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int n = (l * 7) % 23;
        float y = 0.5f + float(l);
        float sum = 0.0f;
        int iters = 0;
        for (int i = 0; i < 100; ++i) {
            iters++;
            if (i >= n) break;
            if (i & 1) continue;
            sum += float(i) * y;
        }
        int j = 0;
        while (j * j < n) j++;
        EXPECT_EQ(r.out(l, 0), sum) << l;
        EXPECT_EQ(r.out(l, 1), float(iters)) << l;
        EXPECT_EQ(r.out(l, 2), float(j)) << l;
    }
}

TEST(ShaderControl, NestedLoopsAndSwitch) {
    FsRun r(R"(
        int n = int(v.x);
        int acc = 0;
        for (int i = 0; i < n; ++i) {
            for (int k = 0; k < 4; ++k) {
                if (k == i) break;
                switch ((i + k) % 3) {
                    case 0: acc += 1; break;
                    case 1: acc += 10;
                    case 2: acc += 100; break;
                }
            }
        }
        color = vec4(float(acc), 0.0, 0.0, 1.0);
    )");
    for (int l = 0; l < kLanes; ++l) r.set_v(l, 0, float(l % 7));
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int n = l % 7, acc = 0;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 4; ++k) {
                if (k == i) break;
                switch ((i + k) % 3) {
                    case 0:
                        acc += 1;
                        break;
                    case 1:
                        acc += 10;
                        [[fallthrough]];
                    case 2:
                        acc += 100;
                        break;
                }
            }
        EXPECT_EQ(r.out(l, 0), float(acc)) << l;
    }
}

TEST(ShaderControl, EarlyReturn) {
    FsRun r(R"(
        color = vec4(9.0);
        if (v.x < 3.0) { color = vec4(v.x); return; }
        color.y = 5.0;
    )");
    for (int l = 0; l < kLanes; ++l) r.set_v(l, 0, float(l));
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        EXPECT_EQ(r.out(l, 0), l < 3 ? float(l) : 9.0f);
        EXPECT_EQ(r.out(l, 1), l < 3 ? float(l) : 5.0f);
    }
}

TEST(ShaderControl, DiscardClearsLanes) {
    FsRun r(R"(
        if (v.x > 7.5) discard;
        color = vec4(v.x);
    )");
    for (int l = 0; l < kLanes; ++l) r.set_v(l, 0, float(l));
    r.block.cover_mask = 0x0FFF;  // lanes 12..15 are helpers
    r.run();
    EXPECT_EQ(r.block.live_mask, 0x00FFu);
    EXPECT_TRUE(r.prog->interface().uses_discard);
    for (int l = 0; l < 8; ++l) EXPECT_EQ(r.out(l, 0), float(l));
}

TEST(ShaderControl, DiscardInsideLoop) {
    FsRun r(R"(
        float s = 0.0;
        for (int i = 0; i < 8; ++i) {
            s += v.x;
            if (s > 20.0) discard;
        }
        color = vec4(s);
    )");
    for (int l = 0; l < kLanes; ++l) r.set_v(l, 0, float(l));
    r.run();
    uint32_t expect = 0;
    for (int l = 0; l < kLanes; ++l)
        if (8.0f * float(l) <= 20.0f) expect |= 1u << l;
    EXPECT_EQ(r.block.live_mask, expect);
    for (int l = 0; l < kLanes; ++l)
        if (expect >> l & 1) {
            EXPECT_EQ(r.out(l, 0), 8.0f * float(l));
        }
}

TEST(ShaderControl, DerivativesFineAndCoarse) {
    FsRun r(R"(
        float q = v.x * v.x + 3.0 * v.y;
        color = vec4(dFdx(q), dFdy(q), dFdxCoarse(q) + 100.0 * dFdyCoarse(q), fwidth(q));
    )");
    auto val = [](int l) {
        float x = float(lane_x(l)) + 0.5f, y = float(lane_y(l)) * 2.0f;
        return std::pair{x, y};
    };
    for (int l = 0; l < kLanes; ++l) {
        r.set_v(l, 0, val(l).first);
        r.set_v(l, 1, val(l).second);
    }
    r.block.cover_mask = 0x1;  // only one covered pixel: the rest are helpers but still feed derivatives
    r.run();
    EXPECT_TRUE(r.prog->interface().uses_derivatives);
    auto q = [&](int x, int y) {
        int l = lane_of(x, y);
        float a = val(l).first, b = val(l).second;
        return a * a + 3.0f * b;
    };
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            int l = lane_of(x, y);
            int x0 = x & ~1, y0 = y & ~1;
            float dx = q(x0 + 1, y) - q(x0, y);
            float dy = q(x, y0 + 1) - q(x, y0);
            float cdx = q(x0 + 1, y0) - q(x0, y0), cdy = q(x0, y0 + 1) - q(x0, y0);
            EXPECT_EQ(r.out(l, 0), dx);
            EXPECT_EQ(r.out(l, 1), dy);
            EXPECT_EQ(r.out(l, 2), cdx + 100.0f * cdy);
            EXPECT_EQ(r.out(l, 3), std::fabs(dx) + std::fabs(dy));
        }
}

TEST(ShaderControl, FragCoordFrontFacingFragDepth) {
    FsRun r(R"(
        color = vec4(gl_FragCoord.xy, gl_FrontFacing ? 1.0 : -1.0, gl_FragCoord.z);
        gl_FragDepth = gl_FragCoord.z * 0.5;
    )");
    for (int l = 0; l < kLanes; ++l) {
        r.block.frag_coord[0][l] = u(10.5f + float(lane_x(l)));
        r.block.frag_coord[1][l] = u(20.5f + float(lane_y(l)));
        r.block.frag_coord[2][l] = u(0.25f * float(l));
    }
    r.block.front_facing = 0;
    r.run();
    EXPECT_TRUE(r.prog->interface().writes_frag_depth);
    for (int l = 0; l < kLanes; ++l) {
        EXPECT_EQ(r.out(l, 0), 10.5f + float(lane_x(l)));
        EXPECT_EQ(r.out(l, 1), 20.5f + float(lane_y(l)));
        EXPECT_EQ(r.out(l, 2), -1.0f);
        EXPECT_EQ(f(r.block.frag_depth[l]), 0.25f * float(l) * 0.5f);
    }
}

TEST(ShaderControl, FunctionsAreInlined) {
    FsRun r(R"(
        color = vec4(helper(v.x), helper(v.y), 0.0, 1.0);
    )",
            "float helper(float t) { if (t < 0.0) return -t; float s = 0.0; for (int i = 0; i < 3; ++i) s += t; "
            "return s; }\n");
    for (int l = 0; l < kLanes; ++l) r.set_v(l, 0, float(l) - 8.0f), r.set_v(l, 1, float(l) * 0.5f);
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        float a = float(l) - 8.0f, b = float(l) * 0.5f;
        EXPECT_EQ(r.out(l, 0), a < 0 ? -a : a + a + a);
        EXPECT_EQ(r.out(l, 1), b + b + b);
    }
}

TEST(ShaderControl, DoWhileComplexContinueAndInfiniteLoopBreak) {
    FsRun r(R"(
        int n = int(v.x);
        int a = 0;
        do { a += 3; } while (a < n);
        int b = 0;
        for (int i = 0; i < n; i += (((i & 1) == 0) ? 1 : 2)) {
            if (i > 5 && v.y > 0.0) { b += 100; continue; }
            b += i;
        }
        int c = 0;
        while (true) {
            c++;
            if (c * 2 > n) {
                if (v.y > 0.0) break;
                c += 1000;
                break;
            }
        }
        color = vec4(float(a), float(b), float(c), 0.0);
    )");
    for (int l = 0; l < kLanes; ++l) {
        r.set_v(l, 0, float(l * 2));
        r.set_v(l, 1, l % 3 == 0 ? -1.0f : 1.0f);
    }
    r.run();
    for (int l = 0; l < kLanes; ++l) {
        int n = l * 2;
        float y = l % 3 == 0 ? -1.0f : 1.0f;
        int a = 0;
        do {
            a += 3;
        } while (a < n);
        int b = 0;
        for (int i = 0; i < n; i += ((i & 1) == 0 ? 1 : 2)) {
            if (i > 5 && y > 0.0f) {
                b += 100;
                continue;
            }
            b += i;
        }
        int c = 0;
        while (true) {
            c++;
            if (c * 2 > n) {
                if (y > 0.0f) break;
                c += 1000;
                break;
            }
        }
        EXPECT_EQ(r.out(l, 0), float(a)) << l;
        EXPECT_EQ(r.out(l, 1), float(b)) << l;
        EXPECT_EQ(r.out(l, 2), float(c)) << l;
    }
}

TEST(ShaderControl, DemoteKeepsHelperRunning) {
    auto spirv = tilevk::shader::test::compile_glsl(Stage::Fragment, R"(#version 450
        #extension GL_EXT_demote_to_helper_invocation : require
        layout(location=0) in vec4 v;
        layout(location=0) out vec4 color;
        void main() {
            if (v.x > 1.5) demote;
            color = vec4(dFdx(v.x), helperInvocationEXT() ? 1.0 : 0.0, 0.0, 1.0);
        })",
                                                    true);
    Result res = Program::create(spirv, Stage::Fragment);
    ASSERT_TRUE(res) << res.error;
    FragmentBlock fb;
    for (int l = 0; l < kLanes; ++l) fb.inputs[0][0][l] = u(float(lane_x(l)));
    Scratch s;
    res.program->run_fragment(Bindings{}, fb, s);
    uint32_t live = 0;
    for (int l = 0; l < kLanes; ++l) {
        if (lane_x(l) <= 1) live |= 1u << l;
        EXPECT_EQ(f(fb.outputs[0][0][l]), 1.0f) << l;  // derivative still from the demoted neighbour
        EXPECT_EQ(f(fb.outputs[0][1][l]), lane_x(l) > 1 ? 1.0f : 0.0f) << l;
    }
    EXPECT_EQ(fb.live_mask, live);
}

// Location 0, Index 1 (dual-source blending's second source) lands in its own slot, not on location 0; Index 1 is
// refused on any other location.
TEST(ShaderOutputs, SecondColorOutputHasItsOwnSlot) {
    FsRun r("color = v * 2.0; second = v + vec4(1.0);", "layout(location=0, index=1) out vec4 second;\n");
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) r.set_v(l, c, float(l) + 0.25f * float(c));
    r.run();
    for (int l = 0; l < kLanes; ++l)
        for (int c = 0; c < 4; ++c) {
            const float v = float(l) + 0.25f * float(c);
            EXPECT_EQ(r.out(l, c), v * 2.0f);
            EXPECT_EQ(f(r.block.outputs[kSecondColorOutput][c][l]), v + 1.0f);
        }
    const std::vector<uint32_t> spirv = tilevk::shader::test::compile_glsl(Stage::Fragment,
                                                                           "#version 450\n"
                                                                           "layout(location=1, index=1) out vec4 c1;\n"
                                                                           "void main() { c1 = vec4(1.0); }\n");
    ASSERT_FALSE(spirv.empty());
    const Result bad = Program::create(spirv, Stage::Fragment);
    EXPECT_FALSE(bad.program);
    EXPECT_NE(bad.error.find("Index 1"), std::string::npos) << bad.error;
}
