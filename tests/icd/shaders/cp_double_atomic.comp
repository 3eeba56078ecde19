#version 450
#extension GL_EXT_shader_atomic_float : require
// A 64-bit float atomic (shaderBufferFloat64Atomics is VK_FALSE in tilevk, as in lavapipe: refused by name).
layout(local_size_x = 16) in;
layout(std430, set = 0, binding = 0) buffer B { double d[]; };
void main() { atomicExchange(d[gl_LocalInvocationIndex], 1.0lf); }
