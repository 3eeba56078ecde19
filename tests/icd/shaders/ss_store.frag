#version 450
// Fragment-stage side effects that do not depend on the order of fragments: a counter of fragments that got past
// the discard, a bit per draw in each pixel's word, (draw 0 only) a value per pixel in an r32ui storage image, and
// per 4x4 block a count of fragments per draw (a byte each) by image atomics.
// Every fourth diagonal discards; the colour uses a derivative, so the quads at the edges have helper lanes.
#ifdef EARLY
layout(early_fragment_tests) in;
#endif
layout(push_constant) uniform P {
    uint draw_id;
    float z;
    uint partial;
} pc;
layout(set = 0, binding = 0, std430) buffer B {
    uint count;
    uint pixel[];
} b;
layout(set = 0, binding = 1, r32ui) uniform uimage2D img;
layout(set = 0, binding = 3, r32ui) uniform uimage2D blocks;
layout(location = 0) out vec4 o;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    o = vec4(1.0, dFdx(gl_FragCoord.x) - 1.0, float(pc.draw_id) * 0.5, 1.0);
    if (((p.x ^ p.y) & 3) == 0) discard;
    atomicAdd(b.count, 1u);
    atomicOr(b.pixel[p.y * 32 + p.x], 1u << pc.draw_id);
    if (pc.draw_id == 0u) imageStore(img, p, uvec4(uint(p.x + 32 * p.y) + 1u));
    imageAtomicAdd(blocks, p / 4, 1u << (8u * pc.draw_id));
}
