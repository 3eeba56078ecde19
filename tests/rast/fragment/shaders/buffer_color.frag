#version 450
// Outputs an exact float colour per pixel, read from a storage buffer (no arithmetic on the values).
layout(std430, set = 0, binding = 0) readonly buffer Colors { vec4 c[]; };
layout(push_constant) uniform Push { uint width; };
layout(location = 0) out vec4 o;
void main() {
    uvec2 p = uvec2(gl_FragCoord.xy);
    o = c[p.y * width + p.x];
}
