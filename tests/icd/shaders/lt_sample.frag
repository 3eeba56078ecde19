#version 450
// The lifetime tests' fragment shader: half a texture lookup (set 0 binding 0), half a uniform (set 0 binding 1).
layout(location = 0) in vec4 v_color;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(set = 0, binding = 1) uniform U { vec4 u; };
layout(location = 0) out vec4 o;
void main() { o = texture(tex, v_color.xy) * 0.5 + u * 0.5; }
