#version 450
// Vertex-stage side effects whose result does not depend on how often a vertex is shaded: the largest index + 1,
// a bit per index and a per-index value. Draws a full-target triangle, or a smaller one, at depth pc.z.
layout(push_constant) uniform P {
    uint draw_id;
    float z;
    uint partial;
} pc;
layout(set = 0, binding = 2, std430) buffer V {
    uint vmax;
    uint vbits;
    uint vid[];
} v;
void main() {
    const vec2 full[3] = vec2[](vec2(-1, -1), vec2(3, -1), vec2(-1, 3));
    const vec2 part[3] = vec2[](vec2(-0.8, -0.7), vec2(0.9, -0.3), vec2(-0.1, 0.85));
    const int i = gl_VertexIndex % 3;
    gl_Position = vec4(pc.partial != 0u ? part[i] : full[i], pc.z, 1);
    atomicMax(v.vmax, uint(gl_VertexIndex) + 1u);
    atomicOr(v.vbits, 1u << uint(gl_VertexIndex));
    v.vid[gl_VertexIndex] = uint(gl_VertexIndex) * 7u + 3u;
}
