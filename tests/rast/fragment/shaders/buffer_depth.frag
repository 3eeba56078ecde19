#version 450
// Writes an exact per-pixel depth read from a storage buffer.
layout(std430, set = 0, binding = 0) readonly buffer Depths { float z[]; };
layout(push_constant) uniform Push { uint width; };
void main() {
    uvec2 p = uvec2(gl_FragCoord.xy);
    gl_FragDepth = z[p.y * width + p.x];
}
