#version 450
// Signed integer colour targets: the interpolated colour mapped to [-x, x] past each channel's range.
layout(location = 0) in vec4 v_color;
layout(location = 0) out ivec4 o;
void main() { o = ivec4((v_color - 0.5) * vec4(600.0, 3000.0, 140000.0, 4.0e9)); }
