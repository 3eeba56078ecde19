#version 450
// Writes f(x, y) = (x / 15, y / 7, (x + y) / 22, 1) to a 16x8 RGBA8 storage image (sampled by a draw afterwards).
layout(local_size_x = 8, local_size_y = 4) in;
layout(rgba8, set = 0, binding = 0) uniform writeonly image2D img;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(img, p, vec4(float(p.x) / 15.0, float(p.y) / 7.0, float(p.x + p.y) / 22.0, 1.0));
}
