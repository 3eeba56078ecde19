#version 450
// Samples a 4x4 unsigned-integer texture at the pixel centres of a 4x4 R32G32B32A32_UINT target.
layout(set = 0, binding = 0) uniform usampler2D tex;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out uvec4 o;
void main() { o = texture(tex, gl_FragCoord.xy / 4.0) + uvec4(v_color * 0.0); }
