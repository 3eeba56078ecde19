#version 450
// Workgroup memory of 4 * N bytes (N a specialization constant): at most maxComputeSharedMemorySize.
layout(local_size_x = 16) in;
layout(constant_id = 0) const uint N = 8192u;
layout(std430, set = 0, binding = 0) buffer B { uint x[]; };
shared uint s[N];
void main() {
    s[gl_LocalInvocationIndex * 512u] = gl_LocalInvocationIndex;
    barrier();
    x[gl_LocalInvocationIndex] = s[(15u - gl_LocalInvocationIndex) * 512u];
}
