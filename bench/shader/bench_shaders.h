// The shaders bench/shader measures (GLSL 450). tests/shader/jit_diff_test.cpp runs them through both tiers too.
#pragma once

namespace tilevk::bench_shaders {

inline const char* kPassVs = R"(#version 450
layout(location=0) in vec4 pos; layout(location=1) in vec4 col;
layout(location=0) out vec4 ocol;
void main() { gl_Position = pos; ocol = col; })";

inline const char* kPassFs = R"(#version 450
layout(location=0) in vec4 col; layout(location=0) out vec4 color;
void main() { color = col; })";

inline const char* kPhongFs = R"(#version 450
layout(location=0) in vec3 n; layout(location=1) in vec3 wpos; layout(location=0) out vec4 color;
layout(set=0, binding=0) uniform L { vec4 light_pos; vec4 eye; vec4 diffuse; vec4 spec; } l;
void main() {
    vec3 N = normalize(n);
    vec3 Ld = normalize(l.light_pos.xyz - wpos);
    vec3 V = normalize(l.eye.xyz - wpos);
    vec3 R = reflect(-Ld, N);
    float d = max(dot(N, Ld), 0.0);
    float s = pow(max(dot(R, V), 0.0), l.spec.w);
    color = vec4(l.diffuse.rgb * d + l.spec.rgb * s + vec3(0.05), 1.0);
})";

inline const char* kTexFs = R"(#version 450
layout(location=0) in vec2 uv; layout(location=0) out vec4 color;
layout(set=0, binding=1) uniform sampler2D tex;
void main() { color = texture(tex, uv) * vec4(0.9, 0.9, 0.9, 1.0); })";

// A lit mesh's vertex shader: model-view-projection, normal matrix, one directional light.
inline const char* kMeshVs = R"(#version 450
layout(set=0, binding=0, std140) uniform U { mat4 mvp; mat4 model; vec4 light; } u;
layout(location=0) in vec3 pos; layout(location=1) in vec3 normal; layout(location=2) in vec2 uv;
layout(location=0) out vec3 n; layout(location=1) out vec2 ouv; layout(location=2) out float lit;
void main() {
    gl_Position = u.mvp * vec4(pos, 1.0);
    n = normalize(mat3(u.model) * normal);
    ouv = uv;
    lit = max(dot(n, normalize(u.light.xyz)), 0.0);
})";

// Arithmetic in a loop with a lane-dependent trip count (procedural pattern): the interpreter's dispatch cost.
inline const char* kLoopFs = R"(#version 450
layout(location=0) in vec2 p; layout(location=0) out vec4 color;
void main() {
    vec2 z = p;
    int k = 0;
    for (; k < 24; ++k) {
        z = vec2(z.x * z.x - z.y * z.y, 2.0 * z.x * z.y) + p;
        if (dot(z, z) > 4.0) break;
    }
    float t = float(k) / 24.0;
    color = vec4(t, t * t, fract(z.x), 1.0);
})";

}  // namespace tilevk::bench_shaders
