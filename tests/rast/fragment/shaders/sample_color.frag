#version 450
// Per-sample shading: each sample outputs its own exact colour from a storage buffer.
layout(std430, set = 0, binding = 0) readonly buffer Colors { vec4 c[]; };
layout(push_constant) uniform Push { uint width; };
layout(location = 0) out vec4 o;
void main() {
    uvec2 p = uvec2(gl_FragCoord.xy);
    o = c[(p.y * width + p.x) * 4u + uint(gl_SampleID)];
}
