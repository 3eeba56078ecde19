#version 450
// ab_texel_buffer.frag for UINT formats: texel x + 4y for pixel (x, y), raw; textureSize in the alpha of pixel 0.
layout(set = 0, binding = 0) uniform usamplerBuffer tb;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out uvec4 o;
void main() {
    int i = int(gl_FragCoord.x) + 4 * int(gl_FragCoord.y);
    o = texelFetch(tb, i) + uvec4(v_color * 0.0);
    if (i == 0) o.a = uint(textureSize(tb));
}
