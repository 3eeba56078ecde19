#version 450
// Reads a uniform texel buffer: texel x + 4y for pixel (x, y) of a 4x4 target; textureSize in the alpha of pixel 0.
layout(set = 0, binding = 0) uniform samplerBuffer tb;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out vec4 o;
void main() {
    int i = int(gl_FragCoord.x) + 4 * int(gl_FragCoord.y);
    o = texelFetch(tb, i) + v_color * 0.0;
    if (i == 0) o.a = float(textureSize(tb));
}
