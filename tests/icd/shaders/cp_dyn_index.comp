#version 450
// Storage buffer arrays read and written at push-constant indices (dynamically uniform).
layout(local_size_x = 8, local_size_y = 4) in;
layout(set = 0, binding = 0, std430) readonly buffer In { uint v[]; } ins[2];
layout(set = 0, binding = 1, std430) buffer Out { uint v[]; } outs[2];
layout(push_constant) uniform P { uint src, dst; } pc;
void main() {
    const uint i = gl_GlobalInvocationID.y * 16u + gl_GlobalInvocationID.x;
    outs[pc.dst].v[i] = ins[pc.src].v[i] * 3u + pc.src * 1000u + pc.dst;
}
