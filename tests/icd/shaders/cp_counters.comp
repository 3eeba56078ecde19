#version 450
// Atomics whose final values do not depend on the order the invocations run in: on a storage buffer from every
// workgroup, and on shared memory within each workgroup (initialised by invocation 0 first: lavapipe does not
// zero shared memory). The compare-exchange maximum loops until its exchange succeeds.
layout(local_size_x = 48) in;
layout(std430, set = 0, binding = 0) readonly buffer X { uint x[]; };
layout(std430, set = 0, binding = 1) buffer C {
    uint sum; int smin; int smax; uint umin; uint umax; uint andv; uint orv; uint xorv; uint count; uint exch;
    uint swapped; uint winners; uint cas_max; uint pad[3];
    uvec4 group[];  // per workgroup: shared sum, shared max, shared compare-exchange maximum, shared min
} c;
shared uint ssum, smax_, scas, smin_;
void main() {
    uint v = x[gl_GlobalInvocationID.x];
    if (gl_LocalInvocationIndex == 0u) { ssum = 0u; smax_ = 0u; scas = 0u; smin_ = 0xFFFFFFFFu; }
    barrier();
    atomicAdd(c.sum, v);
    atomicMin(c.smin, int(v) - 50000);
    atomicMax(c.smax, int(v) - 50000);
    atomicMin(c.umin, v);
    atomicMax(c.umax, v);
    atomicAnd(c.andv, ~(1u << (v % 32u)));
    atomicOr(c.orv, 1u << (v % 31u));
    atomicXor(c.xorv, v);
    atomicAdd(c.count, 1u);
    atomicExchange(c.exch, 7u);
    if (atomicCompSwap(c.swapped, 0u, 1u) == 0u) atomicAdd(c.winners, 1u);
    uint old = atomicAdd(c.cas_max, 0u);  // an atomic read: other workgroups are exchanging it
    for (;;) {
        uint got = atomicCompSwap(c.cas_max, old, max(old, v));
        if (got == old) break;
        old = got;
    }
    atomicAdd(ssum, v);
    atomicMax(smax_, v);
    atomicMin(smin_, v);
    uint sold = scas;
    for (;;) {
        uint got = atomicCompSwap(scas, sold, max(sold, v ^ 0x5555u));
        if (got == sold) break;
        sold = got;
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) c.group[gl_WorkGroupID.x] = uvec4(ssum, smax_, scas, smin_);
}
