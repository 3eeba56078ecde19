#version 450
// A control barrier between a storage-buffer write and a read of a neighbour's value in the same workgroup.
layout(local_size_x = 32) in;
layout(std430, set = 0, binding = 0) buffer B { uint x[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    x[i] = i * 3u + 1u;
    memoryBarrierBuffer();
    barrier();
    x[i + 64u] = x[i ^ 17u];
}
