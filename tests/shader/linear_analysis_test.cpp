// Program::linear_copy_input: the copy class of llvmpipe's linear shaders, recognised on tilevk's program.
#include <gtest/gtest.h>

#include <string>

#include "glsl.h"

using tilevk::shader::Stage;
using tilevk::shader::test::make_program;

namespace {

int analyse(const std::string& body, const std::string& decls = "") {
    const std::string src =
        "#version 450\n"
        "layout(location=0) in vec4 v_color;\n"
        "layout(location=1) in vec2 v_uv;\n"
        "layout(location=2) in vec4 v_other;\n"
        "layout(location=0) out vec4 o_color;\n" +
        decls + "void main() { " + body + " }\n";
    auto p = make_program(Stage::Fragment, src);
    return p ? p->linear_copy_input() : -2;
}

}  // namespace

TEST(LinearAnalysis, PlainCopies) {
    EXPECT_EQ(analyse("o_color = v_color;"), 0);
    EXPECT_EQ(analyse("o_color = v_other;"), 2);
}

TEST(LinearAnalysis, EverythingElseIsRefused) {
    // arithmetic (fadd; lavapipe refuses it too), multiplies and constants (lavapipe accepts them when the
    // constants are in [0,1]; tilevk does not model the 8-bit arithmetic: refused, a named difference)
    EXPECT_EQ(analyse("o_color = v_color + v_color;"), -1);
    EXPECT_EQ(analyse("o_color = v_color * v_other;"), -1);
    EXPECT_EQ(analyse("o_color = vec4(0.5);"), -1);  // not a plain copy (see ConstantsAndPartialCopies)
    EXPECT_EQ(analyse("o_color = vec4(v_color.rgb, 1.0);"), -1);
    // swizzles and mixes of inputs
    EXPECT_EQ(analyse("o_color = v_color.bgra;"), -1);
    EXPECT_EQ(analyse("o_color = vec4(v_color.xy, v_other.zw);"), -1);
    // textures, built-ins, discard, control flow, a second output
    EXPECT_EQ(analyse("o_color = texture(tex, v_uv);", "layout(set=0, binding=0) uniform sampler2D tex;\n"), -1);
    EXPECT_EQ(analyse("o_color = gl_FragCoord;"), -1);
    EXPECT_EQ(analyse("if (v_color.x > 0.5) discard; o_color = v_color;"), -1);
    EXPECT_EQ(analyse("o_color = v_color.x > 0.5 ? v_color : v_other;"), -1);
    EXPECT_EQ(analyse("o_color = v_color; o2 = v_other;", "layout(location=1) out vec4 o2;\n"), -1);
    EXPECT_EQ(analyse("o_color = v_color; gl_FragDepth = 0.5;"), -1);
}

TEST(LinearAnalysis, IntegerInputsAreNotColours) {
    auto p = make_program(Stage::Fragment,
                          "#version 450\n"
                          "layout(location=0) flat in uvec4 v;\n"
                          "layout(location=0) out uvec4 o;\n"
                          "void main() { o = v; }\n");
    ASSERT_TRUE(p);
    EXPECT_EQ(p->linear_copy_input(), -1);
}

TEST(LinearAnalysis, ConstantsAndPartialCopies) {
    auto make = [](const std::string& body) {
        return make_program(Stage::Fragment,
                            "#version 450\n"
                            "layout(location=0) in vec4 v_color;\n"
                            "layout(location=3) in vec4 v_other;\n"
                            "layout(location=0) out vec4 o_color;\n"
                            "void main() { " +
                                body + " }\n");
    };
    auto c = make("o_color = vec4(0.5, 0.25, 1.0, 0.0);");
    ASSERT_TRUE(c);
    auto l = c->linear_shader();
    ASSERT_TRUE(l.ok);
    EXPECT_EQ(l.location, -1);
    EXPECT_EQ(l.usage, 0);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(l.source[k], -1);
    EXPECT_EQ(l.constant[0], 0.5f);
    EXPECT_EQ(l.constant[2], 1.0f);
    auto rgb1 = make("o_color = vec4(v_other.rgb, 1.0);");
    ASSERT_TRUE(rgb1);
    l = rgb1->linear_shader();
    ASSERT_TRUE(l.ok);
    EXPECT_EQ(l.location, 3);
    EXPECT_EQ(l.usage, 0x7);
    EXPECT_EQ(l.source[0], 0);
    EXPECT_EQ(l.source[2], 2);
    EXPECT_EQ(l.source[3], -1);
    EXPECT_EQ(l.constant[3], 1.0f);
    // constants outside [0, 1] (lavapipe's analysis refuses them too), swizzles, two inputs
    EXPECT_FALSE(make("o_color = vec4(1.5, 0.0, 0.0, 1.0);")->linear_shader().ok);
    EXPECT_FALSE(make("o_color = vec4(-0.25, 0.0, 0.0, 1.0);")->linear_shader().ok);
    EXPECT_FALSE(make("o_color = v_color.bgra;")->linear_shader().ok);
    EXPECT_FALSE(make("o_color = vec4(v_color.rg, v_other.ba);")->linear_shader().ok);
}
