#version 450
// A compute shader whose workgroup (1024 x 2 = 2048 invocations) is larger than maxComputeWorkGroupInvocations
// (1024): its pipeline must be refused cleanly.
layout(local_size_x = 1024, local_size_y = 2) in;
layout(set = 0, binding = 0) buffer B { uint x[]; };
void main() { x[gl_GlobalInvocationID.x] = 1u; }
