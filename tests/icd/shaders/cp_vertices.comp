#version 450
// Writes a triangle strip's positions and colours (ab_pull.vert's layout: position, colour per vertex) for a
// draw that follows the dispatch.
layout(local_size_x = 4) in;
layout(std430, set = 0, binding = 1) buffer Verts { vec4 data[]; };
void main() {
    uint v = gl_GlobalInvocationID.x;
    float x = float(v / 2u) / 3.0 * 1.6 - 0.8, y = (v % 2u) == 0u ? -0.7 : 0.6 + 0.1 * float(v);
    data[2u * v] = vec4(x, y, 0.5, 1.0);
    data[2u * v + 1u] = vec4(float(v) / 8.0, 1.0 - float(v) / 8.0, 0.25, 1.0);
}
