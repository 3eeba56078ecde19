#version 450
// Every compute built-in of one invocation, as four uvec4 records at its linear global index. The workgroup size
// comes from specialization constants 0 and 1 (LocalSizeId / the WorkgroupSize built-in), z is 2.
layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z = 2) in;
layout(std430, set = 0, binding = 0) buffer Out { uvec4 rec[]; };
void main() {
    uvec3 total = gl_NumWorkGroups * gl_WorkGroupSize;
    uvec3 g = gl_GlobalInvocationID;
    uint i = g.x + total.x * (g.y + total.y * g.z);
    rec[i * 4 + 0] = uvec4(gl_LocalInvocationID, gl_LocalInvocationIndex);
    rec[i * 4 + 1] = uvec4(gl_GlobalInvocationID, 0xC0FFEEu);
    rec[i * 4 + 2] = uvec4(gl_WorkGroupID, 7u);
    rec[i * 4 + 3] = uvec4(gl_NumWorkGroups, gl_WorkGroupSize.x * 10000u + gl_WorkGroupSize.y * 100u + gl_WorkGroupSize.z);
}
