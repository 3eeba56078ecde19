#version 450
// An atomic on a storage image (tilevk has no image atomics yet: refused by name).
layout(local_size_x = 16) in;
layout(r32ui, set = 0, binding = 1) uniform uimage2D img;
void main() { imageAtomicAdd(img, ivec2(gl_LocalInvocationIndex, 0), 1u); }
