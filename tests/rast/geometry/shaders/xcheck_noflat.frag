#version 450
// No flat input: llvmpipe's uses_constant_interp is off, which enables its triangle-list analysis (9-vertex quirk).
layout(location = 0) in vec4 v_smooth;
layout(location = 0) out vec4 o;
void main() { o = v_smooth; }
