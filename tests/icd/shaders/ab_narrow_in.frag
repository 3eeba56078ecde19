#version 450
// VK_KHR_maintenance4: a smaller input than the vertex stage's output at the same location (draw.vert writes a vec4
// there); the extra components are discarded.
layout(location = 0) in vec2 v_color;
layout(location = 0) out vec4 o;
void main() { o = vec4(v_color, 0.25, 1.0); }
