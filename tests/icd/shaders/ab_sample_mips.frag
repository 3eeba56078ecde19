#version 450
// Samples with a level of detail that changes across the target (the coordinates grow quadratically): the quads of
// one draw read different mip levels, from magnification to past the last level, most pixels between two levels.
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out vec4 o;
void main() {
    vec2 p = gl_FragCoord.xy / 32.0;
    o = texture(tex, p * p * vec2(7.0, 5.0) + vec2(0.13, -0.31)) + v_color * 0.0;
}
