#version 450
// A float atomic on a storage image (tilevk has 32-bit integer image atomics only: refused by name).
layout(local_size_x = 16) in;
layout(r32f, set = 0, binding = 1) uniform image2D img;
void main() { imageAtomicExchange(img, ivec2(gl_LocalInvocationIndex, 0), 1.0); }
