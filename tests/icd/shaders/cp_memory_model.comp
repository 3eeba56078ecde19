#version 450
#pragma use_vulkan_memory_model
#extension GL_KHR_memory_scope_semantics : require
// The Vulkan memory model (SPIR-V 1.5, OpMemoryModel Logical Vulkan): coherent buffer and image accesses carry
// MakePointer/TexelAvailable|Visible and NonPrivate operands, atomics and barriers explicit scopes and semantics
// (Workgroup, Device, QueueFamily). Workgroups of 64; v = x[mirror] + x[g] through Workgroup memory.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer In { uint x[]; };
layout(std430, set = 0, binding = 1) coherent buffer Out { uint r[]; };
layout(set = 0, binding = 2, r32ui) uniform coherent uimage2D img;
shared uint s[64];
void main() {
    const uint i = gl_LocalInvocationIndex, g = gl_GlobalInvocationID.x;
    s[i] = x[g];
    controlBarrier(gl_ScopeWorkgroup, gl_ScopeWorkgroup, gl_StorageSemanticsShared, gl_SemanticsAcquireRelease);
    const uint v = s[63u - i] + atomicLoad(s[i], gl_ScopeWorkgroup, gl_StorageSemanticsShared, gl_SemanticsRelaxed);
    r[g] = v;
    atomicStore(r[g + 256u], v * 3u, gl_ScopeDevice, gl_StorageSemanticsBuffer,
                gl_SemanticsRelease | gl_SemanticsMakeAvailable);
    imageStore(img, ivec2(g % 16u, g / 16u), uvec4(v));
    memoryBarrier(gl_ScopeDevice, gl_StorageSemanticsBuffer | gl_StorageSemanticsImage, gl_SemanticsAcquireRelease);
    const uint back = imageLoad(img, ivec2(g % 16u, g / 16u)).x;
    r[g + 512u] = back + atomicAdd(r[g + 256u], 1u, gl_ScopeQueueFamily, gl_StorageSemanticsBuffer,
                                   gl_SemanticsAcquireRelease);
}
