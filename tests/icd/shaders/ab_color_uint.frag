#version 450
// Integer colour targets: the interpolated colour scaled past every channel's range (8, 10, 16 bits), so the stores'
// saturation shows; the scale keeps the values exact in float.
layout(location = 0) in vec4 v_color;
layout(location = 0) out uvec4 o;
void main() { o = uvec4(v_color * vec4(300.0, 1500.0, 70000.0, 4.0e9)); }
