#version 450
// One point per pixel of a 4x4 target (from gl_VertexIndex); the attribute under test is passed through.
layout(location = 0) in vec4 a;
layout(location = 0) out vec4 o;
void main() {
    gl_Position = vec4((float(gl_VertexIndex % 4) + 0.5) * 0.5 - 1.0, (float(gl_VertexIndex / 4) + 0.5) * 0.5 - 1.0, 0, 1);
    gl_PointSize = 1.0;
    o = a;
}
