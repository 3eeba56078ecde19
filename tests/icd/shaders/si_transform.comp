#version 450
// imageLoad -> transform -> imageStore between four storage images (maxPerStageDescriptorStorageImages), loads
// past every edge (negative coordinates included) and stores outside the image.
layout(local_size_x = 8, local_size_y = 4) in;
layout(rgba8, set = 0, binding = 0) uniform readonly image2D src;
layout(r32ui, set = 0, binding = 1) uniform readonly uimage2D srcu;
layout(rgba32f, set = 0, binding = 2) uniform image2D dst;
layout(rgba32ui, set = 0, binding = 3) uniform writeonly uimage2D dstu;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(dst, p, imageLoad(src, p + ivec2(-2, 1)) * 2.0 - 0.25);
    imageStore(dstu, p, imageLoad(srcu, p + ivec2(3, -1)) + uvec4(1u));
    imageStore(dst, p + ivec2(16, 0), vec4(7.0));      // past the right edge: dropped
    imageStore(dst, ivec2(-1 - p.x, p.y), vec4(9.0));  // negative x: dropped
}
