#version 450
// draw.vert with a flat colour output (VK_EXT_provoking_vertex tests).
layout(location = 0) in vec4 pos;
layout(location = 1) in vec4 color;
layout(location = 0) flat out vec4 v_color;
void main() {
    gl_Position = pos;
    v_color = color;
}
