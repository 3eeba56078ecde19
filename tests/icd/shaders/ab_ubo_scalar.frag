#version 450
// VK_EXT_scalar_block_layout: a uniform block laid out by scalar rules (every member aligned to its component size):
// b at 4, the vec3 array c at 16 with stride 12, the mat3 m at 52 with column stride 12, d at 88 — where std430
// would put b at 16, c at 32 (stride 16), m at 80, d at 128.
#extension GL_EXT_scalar_block_layout : require
layout(scalar, set = 0, binding = 0) uniform U {
    float a;
    vec3 b;
    vec3 c[3];
    mat3 m;
    vec2 d;
} u;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed (adds 0)
layout(location = 0) out vec4 o;
void main() {
    int i = int(gl_FragCoord.x) % 3;
    o = vec4(u.a + u.b.y, u.c[i].z, u.m[i].y, u.d.y) + v_color * 0.0;
}
