#version 450
// An atomic add on a storage buffer (refused until tilevk has atomics).
layout(local_size_x = 16) in;
layout(std430, set = 0, binding = 0) buffer B { uint count; uint x[]; };
void main() { x[gl_GlobalInvocationID.x] = atomicAdd(count, 1u); }
