#version 450
// A pass-through geometry shader: tilevk has no geometry stage, so its pipeline must be refused cleanly.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec4 v_in[];
layout(location = 0) out vec4 v_color;
void main() {
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        v_color = v_in[i];
        EmitVertex();
    }
    EndPrimitive();
}
