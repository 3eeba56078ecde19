#version 450
// VK_KHR_uniform_buffer_standard_layout: a uniform block laid out by std430 rules (float array stride 4: b at 32,
// c at 44, d at 48), where std140 would put them elsewhere (array stride 16: b at 128, c at 140, d at 144).
#extension GL_EXT_scalar_block_layout : require
layout(std430, set = 0, binding = 0) uniform U {
    float a[8];
    vec3 b;
    float c;
    vec2 d;
} u;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed (adds 0)
layout(location = 0) out vec4 o;
void main() {
    int i = int(gl_FragCoord.x) & 7;
    o = vec4(u.a[i], u.b.y, u.c, u.d.y) + v_color * 0.0;
}
