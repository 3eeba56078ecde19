#version 450
// VK_EXT_shader_demote_to_helper_invocation: every third pixel (by x + y) demotes itself, then the quad's derivatives
// of a non-linear q still see it (a helper keeps running); the pixels that stay report helperInvocationEXT() false.
#extension GL_EXT_demote_to_helper_invocation : require
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed (adds 0)
layout(location = 0) out vec4 o;
void main() {
    vec2 p = gl_FragCoord.xy;
    float q = p.x * p.x * 0.25 + p.y * p.y * 0.125 + p.x * p.y;
    if ((int(p.x) + int(p.y)) % 3 == 0) demote;
    o = vec4(dFdx(q), dFdy(q), helperInvocationEXT() ? 1.0 : 0.5, 1.0) + v_color * 0.0;
}
