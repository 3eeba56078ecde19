#version 450
// Image atomics on an r32ui and an r32i image (16x8, 8 texels per row used): every invocation (x, y) of 16x8 applies
// each operation to texel (x % 8, row) of its row, so each texel takes 16 operands; exchange and compare-exchange
// are done by one invocation per texel (their returned values go to `o`), and three atomics outside the image
// return 0 into `o`.
layout(local_size_x = 8, local_size_y = 4) in;
layout(set = 0, binding = 0, r32ui) uniform uimage2D u;
layout(set = 0, binding = 1, r32i) uniform iimage2D s;
layout(set = 0, binding = 2, std430) buffer O { uint o[]; } ob;
void main() {
    const uvec2 g = gl_GlobalInvocationID.xy;
    const uint i = g.x + 16u * g.y;  // 0..127
    const int t = int(g.x % 8u);
    imageAtomicAdd(u, ivec2(t, 0), i + 1u);
    imageAtomicMax(u, ivec2(t, 1), i * 2654435761u);
    imageAtomicMin(u, ivec2(t, 2), i * 2654435761u);
    imageAtomicOr(u, ivec2(t, 3), 1u << (i % 32u));
    imageAtomicAnd(u, ivec2(t, 4), ~(1u << ((i * 7u) % 32u)));
    imageAtomicXor(u, ivec2(t, 5), i * 0x01010101u);
    imageAtomicMin(s, ivec2(t, 0), int(i) * 40503 - 2000000);
    imageAtomicMax(s, ivec2(t, 1), int(i) * -40503 + 100);
    imageAtomicAdd(s, ivec2(t, 2), -int(i));
    if (g.y == 0u && g.x < 8u) {
        ob.o[g.x] = imageAtomicExchange(u, ivec2(t, 6), i + 1000u);
        ob.o[8u + g.x] = imageAtomicCompSwap(u, ivec2(t, 7), 3u * uint(t), 500u + i);  // succeeds for even x
        ob.o[16u + g.x] = uint(imageAtomicCompSwap(s, ivec2(t, 3), -int(t), int(i) - 50));
    }
    if (i == 5u) {
        ob.o[24] = imageAtomicAdd(u, ivec2(-1, 0), 1u);
        ob.o[25] = imageAtomicAdd(u, ivec2(16, 0), 1u);
        ob.o[26] = imageAtomicAdd(u, ivec2(0, 8), 1u);
    }
}
