#version 450
// Vertex data from a storage buffer: clip position and two attribute vectors per vertex.
layout(std430, set = 0, binding = 0) readonly buffer Verts { vec4 v[]; };
layout(location = 0) out vec4 smooth_attr;
layout(location = 1) noperspective out vec4 linear_attr;
void main() {
    gl_Position = v[gl_VertexIndex * 3];
    smooth_attr = v[gl_VertexIndex * 3 + 1];
    linear_attr = v[gl_VertexIndex * 3 + 2];
}
