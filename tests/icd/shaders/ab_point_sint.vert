#version 450
layout(location = 0) in ivec4 a;
layout(location = 0) out vec4 o;
void main() {
    gl_Position = vec4((float(gl_VertexIndex % 4) + 0.5) * 0.5 - 1.0, (float(gl_VertexIndex / 4) + 0.5) * 0.5 - 1.0, 0, 1);
    gl_PointSize = 1.0;
    o = vec4(a);
}
