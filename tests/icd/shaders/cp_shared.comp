#version 450
// Shared memory and a control barrier: a workgroup reverses its 32 values.
layout(local_size_x = 32) in;
layout(std430, set = 0, binding = 0) buffer B { uint x[]; };
shared uint s[32];
void main() {
    s[gl_LocalInvocationIndex] = x[gl_GlobalInvocationID.x];
    barrier();
    x[gl_GlobalInvocationID.x] = s[31u - gl_LocalInvocationIndex];
}
