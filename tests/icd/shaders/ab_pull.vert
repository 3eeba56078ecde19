#version 450
// Vertex pulling: positions and colours read from a storage buffer by gl_VertexIndex (no vertex input).
layout(set = 0, binding = 1, std430) readonly buffer Verts { vec4 data[]; };
layout(location = 0) out vec4 v_color;
void main() {
    gl_Position = data[2 * gl_VertexIndex];
    v_color = data[2 * gl_VertexIndex + 1];
}
