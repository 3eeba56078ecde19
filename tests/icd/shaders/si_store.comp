#version 450
// imageStore of the words of a storage buffer into a 16x8 storage image of any format: FMT (the format
// qualifier), IMG (image2D / iimage2D / uimage2D) and CONV (the words as the image's texel type) are set by the
// build (tests/icd/meson.build), one module per storage format.
layout(local_size_x = 8, local_size_y = 4) in;
layout(FMT, set = 0, binding = 0) uniform writeonly IMG img;
layout(std430, set = 0, binding = 1) readonly buffer Words { uvec4 w[]; } src;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(img, p, CONV(src.w[p.y * 16 + p.x]));
}
