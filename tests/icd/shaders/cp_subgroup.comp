#version 450
// Subgroup basic, vote and ballot operations per invocation (tests/shader/subgroup_test.cpp models every word;
// icd_api_breadth ApiCompute.Subgroups compares tilevk with lavapipe). SPIR-V 1.3: compiled for Vulkan 1.1.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) readonly buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint y[]; };
void main() {
    uint i = gl_LocalInvocationIndex, base = gl_GlobalInvocationID.x * 16u, v = x[gl_GlobalInvocationID.x];
    y[base + 0u] = gl_SubgroupSize;
    y[base + 1u] = gl_SubgroupInvocationID;
    y[base + 2u] = gl_SubgroupID;
    y[base + 3u] = gl_NumSubgroups;
    y[base + 4u] = gl_SubgroupLtMask.x | gl_SubgroupEqMask.x << 8 | gl_SubgroupGtMask.x << 16 |
                   gl_SubgroupGeMask.x << 24;
    y[base + 5u] = gl_SubgroupLeMask.x | (gl_SubgroupLeMask.y | gl_SubgroupGeMask.w) << 8;
    if (v % 3u != 0u) {  // only these lanes take part
        y[base + 6u] = (subgroupElect() ? 1u : 0u) | (subgroupAll(v > 10u) ? 2u : 0u) |
                       (subgroupAny(v > 90u) ? 4u : 0u) | (subgroupAllEqual(v / 100u) ? 8u : 0u) |
                       (subgroupAllEqual(vec2(float(v / 100u), (i & 1u) == 0u ? 0.0 : -0.0)) ? 16u : 0u);
        y[base + 7u] = subgroupBroadcast(v, 5u);
        y[base + 8u] = subgroupBroadcastFirst(v);
        uvec4 b = subgroupBallot(v % 2u == 0u);
        y[base + 9u] = b.x;
        y[base + 10u] = b.y | b.z | b.w;
        y[base + 11u] = subgroupBallotBitCount(b) | subgroupBallotInclusiveBitCount(b) << 8 |
                        subgroupBallotExclusiveBitCount(b) << 16;
        y[base + 12u] = b.x == 0u ? 0xFFFFu : subgroupBallotFindLSB(b) | subgroupBallotFindMSB(b) << 8;
        y[base + 13u] = (subgroupInverseBallot(b) ? 1u : 0u) | (subgroupBallotBitExtract(b, 3u) ? 2u : 0u);
    }
    uint acc = 0u;  // each iteration, the lanes still in the loop
    for (uint k = 0u; k < v % 4u; ++k) acc += subgroupBallotBitCount(subgroupBallot(true)) << (8u * k);
    y[base + 14u] = acc;
}