#version 450
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
void main() {
    o0 = v_color;
    o1 = vec4(v_color.g * 3.0 - 0.7, v_color.r + 0.25, 0.5 - v_color.b, v_color.a * 0.5);
}
