#version 450
// robustBufferAccess: invocation i reads element i of a uniform and a storage buffer and a uniform texel buffer,
// stores element i of a second storage buffer and does an atomic on element i of a third, each bound with a range
// that ends part-way (some accesses out of bounds, one vec4 straddling the end). Results go to `o`, 8 words each.
layout(local_size_x = 16) in;
layout(set = 0, binding = 0) uniform U { vec4 u[64]; } ub;
layout(set = 0, binding = 1, std430) readonly buffer S { uvec2 s[]; } sb;
layout(set = 0, binding = 2, std430) writeonly buffer W { uint w[]; } wb;
layout(set = 0, binding = 3, std430) buffer A { uint a[]; } ab;
layout(set = 0, binding = 4, std430) buffer O { uint o[]; } ob;
layout(set = 0, binding = 5) uniform samplerBuffer tb;
void main() {
    const uint i = gl_GlobalInvocationID.x;
    const vec4 u = ub.u[i];
    ob.o[i * 12u + 0u] = floatBitsToUint(u.x);
    ob.o[i * 12u + 1u] = floatBitsToUint(u.y);
    ob.o[i * 12u + 2u] = floatBitsToUint(u.z);
    ob.o[i * 12u + 3u] = floatBitsToUint(u.w);
    ob.o[i * 12u + 4u] = floatBitsToUint(ub.u[3].y);  // a constant index: the straddling vec4
    ob.o[i * 12u + 5u] = sb.s[i].x;
    ob.o[i * 12u + 6u] = sb.s[i].y;
    wb.w[i] = 0xAB000000u + i;
    ob.o[i * 12u + 7u] = atomicAdd(ab.a[i], 0x100u);
    const vec4 t = texelFetch(tb, int(i));
    ob.o[i * 12u + 8u] = floatBitsToUint(t.x);
    ob.o[i * 12u + 9u] = floatBitsToUint(t.y);
    ob.o[i * 12u + 10u] = floatBitsToUint(t.z);
    ob.o[i * 12u + 11u] = floatBitsToUint(t.w);
}
