#version 450
// A tree reduction in shared memory at workgroup size local_size_x_id 0 (any size, 24 included): each level reads
// what other invocations wrote before the barrier. Every shared word read was written first (lavapipe does not
// zero shared memory).
layout(local_size_x_id = 0) in;
layout(std430, set = 0, binding = 0) readonly buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer Y { uint sums[64]; uint after[]; };
shared uint s[1024];
void main() {
    uint i = gl_LocalInvocationIndex;
    s[i] = x[gl_GlobalInvocationID.x];
    memoryBarrierShared();
    barrier();
    for (uint width = gl_WorkGroupSize.x; width > 1u;) {
        uint half_ = (width + 1u) / 2u;
        if (i < width - half_) s[i] += s[i + half_];
        memoryBarrierShared();
        barrier();
        width = half_;
    }
    if (i == 0u) sums[gl_WorkGroupID.x] = s[0];
    // the partial sums other invocations left, read after the last barrier
    after[gl_GlobalInvocationID.x] = s[(i * 7u + 5u) % gl_WorkGroupSize.x];
}
