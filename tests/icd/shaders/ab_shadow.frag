#version 450
// Depth comparison (shadow) lookups: implicit LOD and with the coordinate's depth reference.
layout(set = 0, binding = 0) uniform sampler2DShadow shadow;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    float a = texture(shadow, vec3(v_color.xy, v_color.z));
    float b = textureLod(shadow, vec3(v_color.yx, 0.5), 0.0);
    o = vec4(a, b, a * 0.5 + b * 0.25, 1.0);
}
