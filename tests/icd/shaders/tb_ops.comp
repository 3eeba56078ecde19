#version 450
// Storage texel buffers: invocation i (0..31) loads texel i of an rgba8 view (20 texels) and stores it doubled plus
// 0.25 into texel i of an rgba32f view (24 texels), adds i + 1 to texel i % 10 of an r32ui view (8 texels) by an
// atomic, loads texel i of an r32f view (10 texels) into `o`, and records an atomic far outside and the sizes.
layout(local_size_x = 16) in;
layout(set = 0, binding = 0, rgba8) uniform readonly imageBuffer src;
layout(set = 0, binding = 1, rgba32f) uniform writeonly imageBuffer dst;
layout(set = 0, binding = 2, r32ui) uniform uimageBuffer cnt;
layout(set = 0, binding = 3, r32f) uniform readonly imageBuffer fsrc;
layout(set = 0, binding = 4, std430) buffer O { uint o[]; } ob;
void main() {
    const int i = int(gl_GlobalInvocationID.x);
    imageStore(dst, i, imageLoad(src, i) * 2.0 + vec4(0.25));
    imageAtomicAdd(cnt, i % 10, uint(i) + 1u);
    const vec4 f = imageLoad(fsrc, i);
    for (int c = 0; c < 4; ++c) ob.o[i * 5 + c] = floatBitsToUint(f[c]);
    ob.o[i * 5 + 4] = imageAtomicOr(cnt, i + 100, 1u);
    if (i == 0) {
        ob.o[160] = uint(imageSize(src));
        ob.o[161] = uint(imageSize(dst));
        ob.o[162] = uint(imageSize(cnt));
    }
}
