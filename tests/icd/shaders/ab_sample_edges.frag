#version 450
// Samples a 4x4 texture over [-0.3, 1.3]^2 from an 8x8 target: texels near and past both edges, where
// CLAMP_TO_EDGE's clamping of the coordinate decides which texels and weights the bilinear filter takes.
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out vec4 o;
void main() { o = texture(tex, (gl_FragCoord.xy - 0.5) * (1.6 / 7.0) - 0.3) + v_color * 0.0; }
