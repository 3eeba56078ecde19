#version 450
// Reads a uniform texel buffer: tilevk reports no texel-buffer format, so its pipeline must be refused cleanly.
layout(set = 0, binding = 0) uniform samplerBuffer tb;
layout(location = 0) out vec4 o;
void main() { o = texelFetch(tb, int(gl_FragCoord.x)); }
