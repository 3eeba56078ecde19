#version 450
layout(set = 0, binding = 0) uniform sampler2DArray tex;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() { o = texture(tex, vec3(v_color.xy, v_color.z * 4.0)); }
