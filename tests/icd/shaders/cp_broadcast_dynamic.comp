#version 450
// subgroupBroadcast with a dynamically uniform id (Vulkan 1.2 subgroupBroadcastDynamicId; SPIR-V 1.5 allows a
// non-constant id): compiled for Vulkan 1.2. ApiVulkan12.SubgroupBroadcastDynamicId compares tilevk with lavapipe.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
void main() {
    uint g = gl_GlobalInvocationID.x, v = x[g];
    // The same in every lane of a subgroup, different between subgroups and workgroups.
    uint id = (x[gl_WorkGroupID.x] + gl_SubgroupID * 3u) % gl_SubgroupSize;
    y[2u * g] = subgroupBroadcast(v, id);
    y[2u * g + 1u] = id;
}
