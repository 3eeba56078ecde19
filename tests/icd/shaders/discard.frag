#version 450
// Discards pixels whose x + y is odd (a checkerboard): exactly half of a pixel-aligned rectangle survives.
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    if (((int(gl_FragCoord.x) + int(gl_FragCoord.y)) & 1) != 0) discard;
    o = v_color;
}
