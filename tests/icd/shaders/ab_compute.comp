#version 450
// A trivial compute shader: tilevk has no compute, so its pipeline must be refused cleanly.
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) buffer B { uint x[]; };
void main() { x[gl_GlobalInvocationID.x] = 1u; }
