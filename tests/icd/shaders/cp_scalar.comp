#version 450
// VK_EXT_scalar_block_layout in storage buffers: scalar-aligned vec3 arrays and a mat2x3 read, and vec3 and float
// arrays written at scalar offsets (In: a at 0, v at 4 with stride 12, m at 52 with column stride 12; Out: r at 0
// with stride 12, s at 48 with stride 4, t at 64).
#extension GL_EXT_scalar_block_layout : require
layout(local_size_x = 4) in;
layout(scalar, set = 0, binding = 0) readonly buffer In {
    float a;
    vec3 v[4];
    mat2x3 m;
} src;
layout(scalar, set = 0, binding = 1) buffer Out {
    vec3 r[4];
    float s[4];
    vec3 t;
} dst;
void main() {
    uint i = gl_LocalInvocationID.x;
    dst.r[i] = src.v[i] * src.a + src.m[i & 1u];
    dst.s[i] = src.v[i].y + src.m[1].z;
    if (i == 3u) dst.t = vec3(src.a, src.m[0].x, src.v[3].z);
}
