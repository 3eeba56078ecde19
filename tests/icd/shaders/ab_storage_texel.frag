#version 450
// Reads a storage texel buffer: tilevk has no imageLoad/imageStore, so its pipeline must be refused cleanly.
layout(set = 0, binding = 0, r32f) uniform readonly imageBuffer ib;
layout(location = 0) out vec4 o;
void main() { o = imageLoad(ib, int(gl_FragCoord.x)); }
