#version 460
// Buffer device addresses (GL_EXT_buffer_reference, buffer_reference_uvec2): each invocation walks its linked list
// (head pointers in a storage buffer, next pointers in the nodes), counts its visits with atomics through the nodes'
// pointers, finds its element of an array of structs behind a pointer from a uniform buffer by address arithmetic on
// a uvec2 (buffer_reference2's ptr[i] needs 64-bit integers, shaderInt64, which tilevk does not report), reads and
// stores through that and through a pointer to one of its members, and adds to two counters behind a uvec2 address
// in the push constants.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
layout(local_size_x = 64) in;

layout(buffer_reference) buffer Node;
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Node {
    Node next;
    uint value;
    uint visits;
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Words { uint w[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Pair {
    uvec2 a;
    uint b;
    uint c;
};

layout(set = 0, binding = 0, std430) readonly buffer Heads { Node head[]; };
layout(set = 0, binding = 1, std140) uniform Params {
    Pair pairs;
    uint n;
};
layout(push_constant) uniform PC {
    Words out_words;
    uvec2 counters;
} pc;

// address a + off, with the carry into the high word
uvec2 add(uvec2 a, uint off) {
    uint lo = a.x + off;
    return uvec2(lo, a.y + (lo < a.x ? 1u : 0u));
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint sum = 0, len = 0;
    for (Node node = head[i]; uvec2(node) != uvec2(0); node = node.next) {
        sum += node.value * (len + 1);
        len++;
        atomicAdd(node.visits, 1u);
    }
    uvec2 at = add(uvec2(pairs), (i % n) * 16u);  // 16 bytes per Pair
    Pair p = Pair(at);
    Words b = Words(add(at, 8u));  // member b of the same Pair
    uint via_address = b.w[0];
    p.c = p.a.x * 3u + p.a.y + i;
    b.w[1] += 7u;  // p.c again, through the other pointer
    Words counters = Words(pc.counters);
    atomicAdd(counters.w[0], len);
    atomicMax(counters.w[1], sum);
    pc.out_words.w[4 * i] = sum;
    pc.out_words.w[4 * i + 1] = len;
    pc.out_words.w[4 * i + 2] = via_address + p.b;
    pc.out_words.w[4 * i + 3] = all(equal(uvec2(head[i]), uvec2(0))) ? 1u : 0u;
}
