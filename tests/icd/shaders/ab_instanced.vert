#version 450
// Two bindings: per-vertex position (vec2) and per-instance offset + colour.
layout(location = 0) in vec2 pos;
layout(location = 1) in vec4 inst_offset;  // xy used
layout(location = 2) in vec4 inst_color;
layout(location = 3) in vec4 tint;         // binding with stride 0
layout(location = 0) out vec4 v_color;
void main() {
    gl_Position = vec4(pos + inst_offset.xy, 0, 1);
    v_color = inst_color * tint;
}
