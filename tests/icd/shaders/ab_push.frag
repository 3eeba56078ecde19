#version 450
layout(push_constant) uniform PC {
    layout(offset = 16) vec4 tint;
    layout(offset = 32) vec4 add;
} pc;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() { o = v_color * pc.tint + pc.add; }
