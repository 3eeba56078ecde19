#version 450
// Reads a 16x8 RGBA8 storage image a draw rendered into and writes every texel to a buffer as a uvec4 of bytes.
layout(local_size_x = 8, local_size_y = 4) in;
layout(rgba8, set = 0, binding = 0) uniform readonly image2D img;
layout(std430, set = 0, binding = 1) writeonly buffer Out { uvec4 t[]; } o;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    o.t[p.y * 16 + p.x] = uvec4(round(imageLoad(img, p) * 255.0));
}
