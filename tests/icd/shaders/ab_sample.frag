#version 450
// Samples a 4x4 texture at the pixel centre of a 4x4 target (nearest: one texel per pixel).
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out vec4 o;
void main() { o = texture(tex, gl_FragCoord.xy / 4.0) + v_color * 0.0; }
