#version 450
#extension GL_EXT_shader_atomic_float : require
// VK_EXT_shader_atomic_float (api_breadth_atomic_float_test.cpp): atomicAdd / atomicExchange on 32-bit floats in a
// storage buffer, shared memory and an R32_SFLOAT storage image, 4 workgroups of 64. Contended adds take quarters
// (their sums are exact in any order); the returned values kept come from one-writer words only.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) buffer B { float sums[8]; float own[256]; float ret[512]; float shout[16]; };
layout(r32f, set = 0, binding = 1) uniform image2D img;
shared float acc[4];
void main() {
    uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;
    if (l < 4u) acc[l] = float(l) * 10.0;
    barrier();
    float q = float(int(i % 13u) - 6) * 0.25;
    atomicAdd(sums[i % 8u], q);
    atomicAdd(acc[l % 4u], q);
    imageAtomicAdd(img, ivec2(i % 4u, 0), q);
    ret[2u * i] = atomicAdd(own[i], 0.1);
    ret[2u * i + 1u] = imageAtomicExchange(img, ivec2(i % 16u, 1u + i / 16u), float(i) * 0.5);
    barrier();
    if (l < 4u) shout[gl_WorkGroupID.x * 4u + l] = acc[l];
}
