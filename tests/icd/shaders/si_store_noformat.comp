#version 450
// si_store.comp without a format qualifier (shaderStorageImageWriteWithoutFormat): the bound view's format decides
// the conversion. IMG and CONV as in si_store.comp.
layout(local_size_x = 8, local_size_y = 4) in;
layout(set = 0, binding = 0) uniform writeonly IMG img;
layout(std430, set = 0, binding = 1) readonly buffer Words { uvec4 w[]; } src;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(img, p, CONV(src.w[p.y * 16 + p.x]));
}
