#version 450
// A triangle covering the whole target; colour from the vertex index.
layout(location = 0) out vec4 v_color;
void main() {
    vec2 p = vec2((gl_VertexIndex & 1) * 4.0 - 1.0, (gl_VertexIndex & 2) * 2.0 - 1.0);
    gl_Position = vec4(p, 0.5, 1);
    v_color = vec4(p * 0.25 + 0.5, 0.75, 1.0);
}
