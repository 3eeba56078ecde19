#version 450
// Half a texture lookup (set 0 binding 0), half a push constant.
layout(location = 0) in vec4 v_color;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(push_constant) uniform P { vec4 p; };
layout(location = 0) out vec4 o;
void main() { o = texture(tex, v_color.xy) * 0.5 + p * 0.5; }
