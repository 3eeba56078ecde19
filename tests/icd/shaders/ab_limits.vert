#version 450
// At the limits tilevk reports: 16 vertex inputs (one per binding), 14 vec4 outputs (56 components; the
// layer counts the built-in outputs too), 128 bytes of push constants shared by both stages, four descriptor sets.
layout(location = 0) in vec4 a0;
layout(location = 1) in vec4 a1;
layout(location = 2) in vec4 a2;
layout(location = 3) in vec4 a3;
layout(location = 4) in vec4 a4;
layout(location = 5) in vec4 a5;
layout(location = 6) in vec4 a6;
layout(location = 7) in vec4 a7;
layout(location = 8) in vec4 a8;
layout(location = 9) in vec4 a9;
layout(location = 10) in vec4 a10;
layout(location = 11) in vec4 a11;
layout(location = 12) in vec4 a12;
layout(location = 13) in vec4 a13;
layout(location = 14) in vec4 a14;
layout(location = 15) in vec4 a15;
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
layout(location = 2) out vec4 o2;
layout(location = 3) out vec4 o3;
layout(location = 4) out vec4 o4;
layout(location = 5) out vec4 o5;
layout(location = 6) out vec4 o6;
layout(location = 7) out vec4 o7;
layout(location = 8) out vec4 o8;
layout(location = 9) out vec4 o9;
layout(location = 10) out vec4 o10;
layout(location = 11) out vec4 o11;
layout(location = 12) out vec4 o12;
layout(location = 13) out vec4 o13;
layout(push_constant) uniform PC { vec4 v[8]; } pc;
void main() {
    gl_Position = vec4(a0.xy + pc.v[0].xy, 0.0, 1.0);
    o0 = a1 * pc.v[1] + a15 * 0.125;
    o1 = a2 * pc.v[2] + a15 * 0.125;
    o2 = a3 * pc.v[3] + a15 * 0.125;
    o3 = a4 * pc.v[4] + a15 * 0.125;
    o4 = a5 * pc.v[5] + a15 * 0.125;
    o5 = a6 * pc.v[6] + a15 * 0.125;
    o6 = a7 * pc.v[7] + a15 * 0.125;
    o7 = a8 * pc.v[1] + a15 * 0.125;
    o8 = a9 * pc.v[2] + a15 * 0.125;
    o9 = a10 * pc.v[3] + a15 * 0.125;
    o10 = a11 * pc.v[4] + a15 * 0.125;
    o11 = a12 * pc.v[5] + a15 * 0.125;
    o12 = a13 * pc.v[6] + a15 * 0.125;
    o13 = a14 * pc.v[7] + a15 * 0.125;
}
