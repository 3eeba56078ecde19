#version 450
#extension GL_EXT_null_initializer : require
// shaderZeroInitializeWorkgroupMemory: null-initialized shared variables. Only the invocations whose input is odd
// write their word of s and count themselves; the rest of s must read as the zero it was initialized to, in every
// workgroup (the words another workgroup wrote do not leak into this one).
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer In { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Out { uint r[]; };
shared uint s[64] = {};
shared uint odd = {};
void main() {
    const uint v = x[gl_GlobalInvocationID.x];
    if ((v & 1u) != 0u) {
        s[gl_LocalInvocationIndex] = v;
        atomicAdd(odd, 1u);
    }
    barrier();
    r[2u * gl_GlobalInvocationID.x] = s[63u - gl_LocalInvocationIndex];
    r[2u * gl_GlobalInvocationID.x + 1u] = odd;
}
