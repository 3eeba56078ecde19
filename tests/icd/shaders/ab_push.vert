#version 450
layout(push_constant) uniform PC {
    vec4 offset;      // vertex stage: bytes 0..15
    layout(offset = 16) vec4 tint;  // fragment stage
    layout(offset = 32) vec4 add;   // fragment stage
} pc;
layout(location = 0) in vec4 pos;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 v_color;
void main() {
    gl_Position = pos + vec4(pc.offset.xy, 0, 0);
    v_color = color;
}
