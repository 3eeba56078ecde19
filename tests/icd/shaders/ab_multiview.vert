#version 450
#extension GL_EXT_multiview : require
// Multiview: each view (gl_ViewIndex) and each instance moves the triangle by its own amount.
layout(location = 0) in vec4 pos;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 v_color;
void main() {
    const float view = float(gl_ViewIndex), inst = float(gl_InstanceIndex);
    gl_Position = vec4(pos.x + 0.125 * view - 0.25 * inst, pos.y - 0.0625 * view + 0.2 * inst, pos.z, pos.w);
    v_color = color;
}
