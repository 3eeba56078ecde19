#version 450
// The compute built-ins of one invocation of a dispatch from a base workgroup (vkCmdDispatchBase), as four uvec4
// records at its linear global index in a grid of `extent` invocations (base + count workgroups in each axis), so
// the index is unique whatever the base.
layout(local_size_x = 4, local_size_y = 2, local_size_z = 1) in;
layout(std430, set = 0, binding = 0) buffer Out { uvec4 rec[]; };
layout(push_constant) uniform Grid { uvec2 extent; };
void main() {
    uvec3 g = gl_GlobalInvocationID;
    uint i = g.x + extent.x * (g.y + extent.y * g.z);
    rec[i * 4 + 0] = uvec4(gl_LocalInvocationID, gl_LocalInvocationIndex);
    rec[i * 4 + 1] = uvec4(gl_GlobalInvocationID, 0xC0FFEEu);
    rec[i * 4 + 2] = uvec4(gl_WorkGroupID, 7u);
    rec[i * 4 + 3] = uvec4(gl_NumWorkGroups, 0xBA5Eu);
}
