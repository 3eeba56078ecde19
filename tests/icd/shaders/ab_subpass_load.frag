#version 450
// Reads the previous subpass's colour and depth at this pixel (input attachments).
layout(input_attachment_index = 0, set = 0, binding = 0) uniform subpassInput prev;
layout(input_attachment_index = 1, set = 0, binding = 1) uniform subpassInput depth;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() { o = subpassLoad(prev).bgra * 0.5 + v_color * 0.5 + vec4(subpassLoad(depth).r * 0.25); }
