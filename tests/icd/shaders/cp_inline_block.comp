#version 450
// Two inline uniform blocks (VK_EXT_inline_uniform_block: to the shader they are uniform blocks) copied word by word
// into a storage buffer: a's 12 words, then b's 8.
layout(local_size_x = 20) in;
layout(std140, set = 0, binding = 0) uniform A { uvec4 a[3]; };
layout(std140, set = 0, binding = 1) uniform B { uvec4 b[2]; };
layout(std430, set = 0, binding = 2) buffer Out { uint r[]; };
void main() {
    const uint i = gl_LocalInvocationIndex;
    r[i] = i < 12u ? a[i / 4u][i % 4u] : b[(i - 12u) / 4u][i % 4u];
}
