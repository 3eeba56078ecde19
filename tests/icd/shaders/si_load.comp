#version 450
// imageLoad of a 16x8 storage image of any format, one texel to the left of each invocation's (so column 0 loads
// outside the image), the texel's bits written to a storage buffer: FMT (the format qualifier), IMG (image2D /
// iimage2D / uimage2D) and BITS (the texel as uvec4) are set by the build (tests/icd/meson.build).
layout(local_size_x = 8, local_size_y = 4) in;
layout(FMT, set = 0, binding = 0) uniform readonly IMG img;
layout(std430, set = 0, binding = 1) writeonly buffer Out { uvec4 w[]; } dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    dst.w[p.y * 16 + p.x] = BITS(imageLoad(img, p - ivec2(1, 0)));
}
