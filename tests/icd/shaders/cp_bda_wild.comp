#version 460
// Loads, stores and atomics through addresses outside every buffer with device addresses (the application's bug):
// invocation i uses the address wild[i] (tilevk alone: ApiBufferDeviceAddress.AddressesOutsideEveryBuffer).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
layout(local_size_x = 4) in;
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Words { uint w[]; };
layout(push_constant) uniform PC {
    Words out_words;
    uvec2 wild[3];
} pc;

void main() {
    uint i = gl_LocalInvocationID.x;
    if (i < 3u) {
        Words p = Words(pc.wild[i]);
        uint loaded = p.w[0];
        p.w[0] = 0xdeadbeefu;
        uint old = atomicAdd(p.w[0], 5u);
        pc.out_words.w[2u * i] = loaded;
        pc.out_words.w[2u * i + 1u] = old;
    }
}
