#version 450
// A fragment shader reading a storage image (readonly: fragmentStoresAndAtomics is not needed) at its pixel.
layout(rgba8, set = 0, binding = 0) uniform readonly image2D img;
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed so the interfaces match exactly
layout(location = 0) out vec4 o;
void main() { o = imageLoad(img, ivec2(gl_FragCoord.xy)).bgra + v_color * 0.0; }
