#version 450
// Dynamic uniform buffers: an array of two at set 0 binding 2, one at set 0 binding 0, one at set 1 binding 1.
layout(set = 0, binding = 0) uniform A { vec4 a; };
layout(set = 0, binding = 2) uniform B { vec4 b; } bs[2];
layout(set = 1, binding = 1) uniform C { vec4 c; };
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() { o = a * 0.4 + bs[0].b * 0.3 + bs[1].b * 0.2 + c * 0.1 + v_color * 0.05; }
