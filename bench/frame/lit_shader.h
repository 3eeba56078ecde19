// The meshes_lit scene's fragment shader (frame_scenes.cpp): diffuse and specular light times a texture. One text
// for the benchmark and for the JIT differential test that runs it on both shader tiers (tests/shader/
// jit_diff_corpus.h).
#pragma once

namespace tilevk::bench {

inline constexpr const char* kLitFs = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D u_tex;
layout(push_constant) uniform Push { vec4 offset; vec4 tint; } pc;
layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec2 v_uv;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 n = normalize(v_normal);
    vec3 l = normalize(vec3(0.4, -0.6, -0.7));
    float diffuse = max(dot(n, -l), 0.0);
    vec3 h = normalize(-l + vec3(0.0, 0.0, -1.0));
    float spec = pow(max(dot(n, h), 0.0), 16.0);
    vec4 t = texture(u_tex, v_uv);
    o_color = vec4(t.rgb * (0.2 + 0.8 * diffuse) * pc.tint.rgb + vec3(0.3 * spec), 1.0);
}
)";

}  // namespace tilevk::bench
