#version 450
#extension GL_EXT_multiview : require
// Multiview: the view (gl_ViewIndex, read in the fragment stage too) scales green and sets blue.
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    const float view = float(gl_ViewIndex);
    o = vec4(v_color.r, v_color.g * (1.0 - 0.25 * view), 0.125 + 0.25 * view, v_color.a);
}
