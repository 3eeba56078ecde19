#version 450
// Counts its own invocations (pipeline_statistics_test.cpp: compute shader invocations = groups x 4*2*3).
layout(local_size_x = 4, local_size_y = 2, local_size_z = 3) in;
layout(std430, set = 0, binding = 0) buffer Counter { uint n; };
void main() { atomicAdd(n, 1u); }
