#version 450
// A uniform buffer, a dynamic storage buffer and push constants at the compute bind point; a loop and a branch
// whose trip count depends on the invocation.
layout(local_size_x = 8, local_size_y = 4) in;
layout(set = 0, binding = 0) uniform U { vec4 scale; uint rounds; } u;
layout(std430, set = 0, binding = 1) buffer O { vec4 o[]; };
layout(push_constant) uniform P { vec4 bias; } pc;
void main() {
    uint i = gl_LocalInvocationIndex + gl_WorkGroupID.x * 32u;
    vec4 v = u.scale * float(i) + pc.bias;
    for (uint r = 0u; r < (i % u.rounds); ++r) v = v * 0.75 + vec4(r);
    if ((i & 1u) == 1u) v = -v;
    o[i] = v;
}
