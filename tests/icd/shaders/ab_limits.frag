#version 450
layout(location = 0) in vec4 o0;
layout(location = 1) in vec4 o1;
layout(location = 2) in vec4 o2;
layout(location = 3) in vec4 o3;
layout(location = 4) in vec4 o4;
layout(location = 5) in vec4 o5;
layout(location = 6) in vec4 o6;
layout(location = 7) in vec4 o7;
layout(location = 8) in vec4 o8;
layout(location = 9) in vec4 o9;
layout(location = 10) in vec4 o10;
layout(location = 11) in vec4 o11;
layout(location = 12) in vec4 o12;
layout(location = 13) in vec4 o13;
// At the limits tilevk reports: eight descriptor sets, eight colour outputs.
layout(set = 0, binding = 0) uniform U0 { vec4 u0; };
layout(set = 1, binding = 0) uniform U1 { vec4 u1; };
layout(set = 2, binding = 0) uniform U2 { vec4 u2; };
layout(set = 3, binding = 0) uniform U3 { vec4 u3; };
layout(set = 4, binding = 0) uniform U4 { vec4 u4; };
layout(set = 5, binding = 0) uniform U5 { vec4 u5; };
layout(set = 6, binding = 0) uniform U6 { vec4 u6; };
layout(set = 7, binding = 0) uniform U7 { vec4 u7; };
layout(push_constant) uniform PC { vec4 v[8]; } pc;
layout(location = 0) out vec4 c0;
layout(location = 1) out vec4 c1;
layout(location = 2) out vec4 c2;
layout(location = 3) out vec4 c3;
layout(location = 4) out vec4 c4;
layout(location = 5) out vec4 c5;
layout(location = 6) out vec4 c6;
layout(location = 7) out vec4 c7;
void main() {
    c0 = o0 + o1 * 0.5 + o2 * 0.25 + o3 * u0;
    c1 = o4 + o5 * 0.5 + o6 * 0.25 + o7 * u1;
    c2 = o8 + o9 * 0.5 + o10 * 0.25 + o11 * u2;
    c3 = o12 + o13 * u3 + pc.v[7];
    c4 = o1 * u4 - o13 * 0.5;
    c5 = o3 + u5 * o9;
    c6 = o5 * 0.75 + u6;
    c7 = (o7 - o11) * u7 + pc.v[3];
}
