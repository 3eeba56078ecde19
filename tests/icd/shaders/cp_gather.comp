#version 450
// textureGather in every form tilevk offers, one coordinate per invocation: the four components, constant offsets at
// the ends of the reported range, an array layer, an integer texture and a depth comparison (sampler2DShadow); and
// the linear and the nearest filter of a float texture (their REPEAT rules on a size that is not a power of 2).
layout(local_size_x = 16) in;
layout(set = 0, binding = 0) uniform sampler2D color_tex;
layout(set = 0, binding = 1) uniform sampler2DArray array_tex;
layout(set = 0, binding = 2) uniform usampler2D uint_tex;
layout(set = 0, binding = 3) uniform sampler2DShadow depth_tex;
layout(set = 0, binding = 6) uniform sampler2D float_tex;
layout(set = 0, binding = 7) uniform sampler2D float_nearest_tex;
layout(set = 0, binding = 4, std430) readonly buffer Coords { vec4 coords[]; };
layout(set = 0, binding = 5, std430) writeonly buffer Out { vec4 o[]; };
void main() {
    const uint i = gl_GlobalInvocationID.x;
    const vec4 c = coords[i];
    const uint b = i * 11u;
    o[b + 0u] = textureGather(color_tex, c.xy, 0);
    o[b + 1u] = textureGather(color_tex, c.xy, 1);
    o[b + 2u] = textureGather(color_tex, c.xy, 2);
    o[b + 3u] = textureGather(color_tex, c.xy, 3);
    o[b + 4u] = textureGatherOffset(color_tex, c.xy, ivec2(-32, 31), 1);
    o[b + 5u] = textureGatherOffset(color_tex, c.xy, ivec2(3, -2));
    o[b + 6u] = textureGather(array_tex, vec3(c.xy, c.z), 2);
    o[b + 7u] = uintBitsToFloat(textureGather(uint_tex, c.xy, 3));
    o[b + 8u] = textureGather(depth_tex, c.xy, c.w);
    o[b + 9u] = textureLod(float_tex, c.xy, 0.0);
    // Not at |coordinate| > 1e5 (infinities included): there tilevk's nearest float texel differs from lavapipe's
    // (shader/README.md, known differences).
    const bool moderate = !(abs(c.x) > 1e5 || abs(c.y) > 1e5);
    o[b + 10u] = moderate ? textureLod(float_nearest_tex, c.xy, 0.0) : vec4(0.0);
}
