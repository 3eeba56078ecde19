// Shaders for the differential test of the two tiers (jit_diff_test.cpp). Together they reach every op of
// shader/ir.h that shader code can produce (the test checks that): arithmetic and comparisons with every kind of
// float (NaN, infinities, denormals, signed zeros come from the random inputs), integer and bit operations,
// conversions, packing, GLSL.std.450, derivatives, divergent control flow with discard and demote, local arrays
// indexed out of range, uniform/storage buffers and push constants, every kind of image access.
#pragma once

#include "bench/frame/lit_shader.h"

namespace tilevk::shader::test::jit_corpus {

struct GlslCase {
    const char* name;
    bool vertex;
    const char* glsl;
};

// Fragment inputs: a, b, c (smooth vec4), i (flat ivec4), u (flat uvec4). Resources: set 0, binding k holds a
// buffer, an image and a sampler at once (the harness), so every declaration kind finds something.
#define TVK_FS_HEAD                                                                               \
    "#version 450\n"                                                                              \
    "layout(location=0) in vec4 a; layout(location=1) in vec4 b; layout(location=2) in vec4 c;\n" \
    "layout(location=3) flat in ivec4 i; layout(location=4) flat in uvec4 u;\n"

inline const GlslCase kGlslCases[] = {
    {"float_basic", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out vec4 o2;
layout(location=3) out vec4 o3; layout(location=4) out vec4 o4; layout(location=5) out vec4 o5;
layout(location=6) out vec4 o6; layout(location=7) out vec4 o7;
void main() {
    o0 = vec4(a.x + b.x, a.y - b.y, a.z * b.z, a.w / b.w);
    o1 = vec4(-a.x, abs(a.y), min(a.z, b.z), max(a.w, b.w));
    o2 = vec4(mod(a.x, b.x), clamp(a.y, b.y, c.y), step(a.z, b.z), smoothstep(a.w, b.w, c.w));
    o3 = vec4(floor(a.x), ceil(a.y), trunc(a.z), round(a.w));
    o4 = vec4(roundEven(b.x), fract(b.y), sign(b.z), sqrt(b.w));
    o5 = vec4(inversesqrt(c.x), fma(a.x, b.x, c.x), mix(a.y, b.y, c.y), dot(a, b));
    o6 = vec4(length(a.xyz), distance(a.xy, b.xy), normalize(c.xyz).x, cross(a.xyz, b.xyz).y);
    o7 = vec4(reflect(a.xyz, normalize(b.xyz)).z, refract(a.xyz, normalize(b.xyz), c.w).x,
              faceforward(a.xyz, b.xyz, c.xyz).y, mix(a.z, b.z, 0.25));
})"},
    {"float_transcendental", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out vec4 o2;
layout(location=3) out vec4 o3; layout(location=4) out vec4 o4; layout(location=5) out vec4 o5;
void main() {
    o0 = vec4(exp(a.x), exp2(a.y), log(a.z), log2(a.w));
    o1 = vec4(pow(a.x, b.x), sin(b.y), cos(b.z), tan(b.w));
    o2 = vec4(asin(c.x), acos(c.y), atan(c.z), atan(a.x, b.x));
    o3 = vec4(sinh(a.y), cosh(a.z), tanh(a.w), asinh(b.x));
    o4 = vec4(acosh(b.y), atanh(b.z), degrees(b.w), radians(c.x));
    int e; float m = frexp(a.x, e);
    float whole; float fr = modf(b.x, whole);
    o5 = vec4(m, float(e), fr + whole, ldexp(c.y, i.x));
})"},
    // libm calls inside segments (lanes.cpp lane_call) with many values live across them, chained
    {"libm_in_segments", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1;
void main() {
    vec4 s = a * b + c, t = a - c, v = b * c;
    float p = pow(abs(s.x), t.y) + exp(v.z) * s.y;
    float q = sin(t.x + p) * cos(v.w) + log2(abs(s.z) + p);
    float r = atan(p, q) - tan(t.z) + s.w * v.x + pow(t.w, 3.0) + pow(-2.0, v.y);
    o0 = vec4(p, q, r, t.w + v.y);
    o1 = s * p + t * q + v * r;
})"},
    // the frame benchmark's meshes_lit fragment shader (bench/frame/lit_shader.h): normalize, pow, texture
    {"meshes_lit_fs", false, tilevk::bench::kLitFs},
    {"float_compare", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out uvec4 o2;
void main() {
    bvec4 lt = lessThan(a, b), le = lessThanEqual(a, b), gt = greaterThan(a, b), ge = greaterThanEqual(a, b);
    bvec4 eq = equal(a, b), ne = notEqual(a, b);
    o0 = vec4(lt) + 2.0 * vec4(le) + 4.0 * vec4(gt) + 8.0 * vec4(ge);
    o1 = vec4(eq) + 2.0 * vec4(ne) + 4.0 * vec4(isnan(a)) + 8.0 * vec4(isinf(b));
    o2 = uvec4(any(lt) ? 1u : 0u, all(ge) ? 2u : 3u, (a.x < b.x) != (c.x >= a.y) ? 4u : 5u,
               (a.z == c.z || b.w > 0.5) && !(c.w < a.w) ? 6u : 7u);
})"},
    {"integer", false, TVK_FS_HEAD R"(
layout(location=0) out ivec4 o0; layout(location=1) out ivec4 o1; layout(location=2) out uvec4 o2;
layout(location=3) out uvec4 o3; layout(location=4) out ivec4 o4; layout(location=5) out uvec4 o5;
layout(location=6) out ivec4 o6; layout(location=7) out uvec4 o7;
void main() {
    ivec4 j = ivec4(u);
    o0 = ivec4(i.x + j.x, i.y - j.y, i.z * j.z, i.w / j.w);
    o1 = ivec4(i.x % j.x, -i.y, abs(i.z), sign(i.w));
    o2 = uvec4(u.x / u.y, u.z % u.w, u.x * u.w, u.y - u.z);
    o3 = uvec4(u.x & u.y, u.y | u.z, u.z ^ u.w, ~u.x) + uvec4(u.x << u.y, u.y >> u.z, 0u, 0u);
    o4 = ivec4(i.x >> j.y, i.y << j.z, min(i.z, j.z), max(i.w, j.w));
    o5 = uvec4(min(u.x, u.y), max(u.z, u.w), bitCount(u.x), bitfieldReverse(u.y));
    o6 = ivec4(findLSB(i.x), findMSB(i.y), findMSB(u.z), bitfieldExtract(i.w, int(u.x & 31u), int(u.y & 31u)));
    o7 = uvec4(bitfieldExtract(u.z, i.x & 31, i.y & 31), bitfieldInsert(u.w, u.x, i.z & 31, i.w & 31),
               uint(i.x < j.x) + 2u * uint(i.y <= j.y) + 4u * uint(i.z > j.z) + 8u * uint(i.w >= j.w) +
                   16u * uint(u.x < u.y) + 32u * uint(u.y <= u.z) + 64u * uint(u.z > u.w) +
                   128u * uint(u.w >= u.x) + 256u * uint(i.x == j.y) + 512u * uint(i.y != j.z),
               uint(i.x) + u.x);
})"},
    {"integer_extended", false, TVK_FS_HEAD R"(
layout(location=0) out uvec4 o0; layout(location=1) out ivec4 o1; layout(location=2) out uvec4 o2;
void main() {
    uint carry, borrow, hi, lo; int shi, slo;
    uint s = uaddCarry(u.x, u.y, carry);
    uint d = usubBorrow(u.z, u.w, borrow);
    umulExtended(u.x, u.z, hi, lo);
    imulExtended(i.x, i.y, shi, slo);
    o0 = uvec4(s, carry, d, borrow);
    o1 = ivec4(hi, lo, shi, slo);
    o2 = uvec4(u.x >> 3u, uint(i.w) >> 31u, uint(-i.z) >> 1u, uint(i.y) / 7u);
})"},
    {"conversions_and_packing", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out ivec4 o1; layout(location=2) out uvec4 o2;
layout(location=3) out vec4 o3; layout(location=4) out vec4 o4; layout(location=5) out uvec4 o5;
void main() {
    o0 = vec4(float(i.x), float(u.y), intBitsToFloat(i.z), uintBitsToFloat(u.w));
    o1 = ivec4(int(a.x * 1e9), int(b.y), floatBitsToInt(c.z), int(a.w));
    o2 = uvec4(uint(a.x * 5e9), uint(b.y), floatBitsToUint(c.z), uint(c.w * 1e10));
    o3 = vec4(unpackHalf2x16(u.x), unpackUnorm2x16(u.y));
    o4 = unpackUnorm4x8(u.z) + unpackSnorm4x8(u.w) + vec4(unpackSnorm2x16(u.x), 0.0, 0.0);
    o5 = uvec4(packHalf2x16(a.xy), packUnorm4x8(b), packSnorm4x8(c), packUnorm2x16(a.zw) ^ packSnorm2x16(b.zw));
})"},
    {"derivatives", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out vec4 o2;
void main() {
    o0 = vec4(dFdx(a.x), dFdy(a.y), dFdxFine(b.x), dFdyFine(b.y));
    o1 = vec4(dFdxCoarse(c.x), dFdyCoarse(c.y), fwidth(a.z), fwidthCoarse(b.z));
    o2 = vec4(gl_FragCoord.xy, dFdx(gl_FragCoord.x * a.w), gl_FrontFacing ? 1.0 : -1.0);
})"},
    {"control_flow", false, TVK_FS_HEAD R"(
#extension GL_EXT_demote_to_helper_invocation : require
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out ivec4 o2;
void main() {
    vec4 acc = a;
    int n = i.x & 15;
    for (int k = 0; k < n; ++k) {
        if (acc.x > b.x) { acc.y += 1.0; continue; }
        acc = acc * 0.5 + b;
        if (acc.z > 100.0) break;
    }
    int sw = 0;
    switch (i.y & 7) {
        case 0: sw = 10; break;
        case 1: case 2: sw = 20;
        case 3: sw += 5; break;
        default: sw = i.z;
    }
    if (c.x > 0.75) discard;
    if (c.y < -0.75) demote;
    float w = 0.0;
    int k = 0;
    do { w += float(k) * c.z; k++; } while (k < (i.w & 7) && w < 10.0);
    o0 = acc;
    o1 = vec4(w, float(sw), helperInvocationEXT() ? 1.0 : 0.0, dFdx(acc.x));
    o2 = ivec4(n, sw, k, gl_SampleMaskIn[0]);
})"},
    {"local_arrays", false, TVK_FS_HEAD R"(
layout(location=0) out vec4 o0; layout(location=1) out ivec4 o1;
void main() {
    float arr[8];
    for (int k = 0; k < 8; ++k) arr[k] = a[k & 3] * float(k);
    arr[i.x & 7] = b.x;
    arr[i.y] = b.y;  // out of range indices clamp to the array
    vec4 v[3] = vec4[3](a, b, c);
    v[u.x % 3u] = vec4(arr[u.y & 7u]);
    int idx[4] = int[4](i.x, i.y, i.z, i.w);
    o0 = vec4(arr[i.z & 7], arr[u.w], v[i.w & 1].x, v[2].y);
    o1 = ivec4(idx[u.x & 3u], idx[u.y], idx[3], 0);
})"},
    {"buffers", false, TVK_FS_HEAD R"(
layout(set=0, binding=0, std140) uniform U { vec4 k[4]; mat4 m; ivec4 n; } ubo;
layout(set=0, binding=1, std430) buffer S { uint head; float data[]; } ssbo;
layout(set=0, binding=2, std430) readonly buffer R { vec4 rows[]; } ro;
layout(push_constant) uniform P { vec4 scale; uint mask; } pc;
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out uvec4 o2;
void main() {
    o0 = ubo.m * a + ubo.k[1] * pc.scale;
    o1 = ubo.k[i.x & 3] + ro.rows[u.x & 15u] + vec4(ssbo.data[u.y & 31u]);
    if (c.x > 0.0) ssbo.data[u.z & 31u] = a.x + float(ubo.n.x);
    o2 = uvec4(ssbo.data.length(), ro.rows.length(), pc.mask & u.w, ssbo.head);
    ubo.k[u.x].x > 0.5 ? o2.x++ : o2.y--;
})"},
    {"images", false, TVK_FS_HEAD R"(
layout(set=0, binding=3) uniform sampler2D t2d;
layout(set=0, binding=4) uniform sampler2DShadow tshadow;
layout(set=0, binding=5) uniform sampler2DArray tarray;
layout(set=0, binding=6) uniform sampler1D t1d;
layout(set=0, binding=7) uniform sampler2D tfloat;
layout(location=0) out vec4 o0; layout(location=1) out vec4 o1; layout(location=2) out vec4 o2;
layout(location=3) out vec4 o3; layout(location=4) out ivec4 o4; layout(location=5) out vec4 o5;
void main() {
    o0 = texture(t2d, a.xy) + texture(t2d, b.xy, c.x);
    o1 = textureLod(t2d, a.zw, b.z) + textureGrad(tfloat, b.xy, c.xy, c.zw) + textureProj(t2d, a.xyz);
    o2 = vec4(texture(tshadow, vec3(a.xy, b.w)), textureLod(tarray, vec3(b.xy, c.z * 4.0), 0.0).xyz);
    o3 = texture(t1d, c.w) + textureOffset(tfloat, a.xy, ivec2(1, -2)) + texelFetch(t2d, i.xy & 31, i.z & 3);
    o4 = ivec4(textureSize(t2d, i.w & 7), textureQueryLevels(t2d), textureSize(tarray, 0).z);
    o5 = texelFetch(tfloat, ivec2(u.xy), 0) + texture(tarray, vec3(c.xy, b.x));
})"},
    {"vertex_transform", true, R"(#version 450
layout(set=0, binding=0, std140) uniform U { mat4 mvp; mat3 nrm; vec4 light; } u;
layout(location=0) in vec4 pos; layout(location=1) in vec3 normal; layout(location=2) in ivec4 bones;
layout(location=0) out vec3 n; layout(location=1) out float d; layout(location=2) flat out int id;
out gl_PerVertex { vec4 gl_Position; float gl_PointSize; float gl_ClipDistance[2]; float gl_CullDistance[1]; };
void main() {
    gl_Position = u.mvp * pos;
    n = normalize(u.nrm * normal);
    d = max(dot(n, normalize(u.light.xyz)), 0.0);
    id = gl_VertexIndex * 3 + gl_InstanceIndex + bones[gl_VertexIndex & 3];
    gl_PointSize = abs(pos.w) + 1.0;
    gl_ClipDistance[0] = pos.x; gl_ClipDistance[1] = -pos.y;
    gl_CullDistance[0] = pos.z - 0.5;
})"},
    {"vertex_loops", true, R"(#version 450
layout(push_constant) uniform P { int count; float step; } p;
layout(location=0) in vec4 pos; layout(location=1) in uvec4 bits;
layout(location=0) out vec4 o;
void main() {
    vec4 acc = vec4(0.0);
    for (int k = 0; k < (p.count & 31); ++k) {
        acc += sin(pos * float(k) * p.step);
        if (acc.w > 3.0) break;
    }
    uint h = bits.x;
    for (uint k = 0u; k < (bits.y & 15u); ++k) h = h * 1664525u + 1013904223u;
    o = acc + vec4(float(h >> 8), float(gl_VertexIndex), 0.0, 1.0);
    gl_Position = pos;
})"},
};

// Ops glslang does not emit for GLSL: unordered comparisons, OpFRem, OpSRem, a loop that never ends.
inline const char* kAsmHeader = R"(
OpCapability Shader
OpMemoryModel Logical GLSL450
OpEntryPoint Fragment %main "main" %a %b %o %oi
OpExecutionMode %main OriginUpperLeft
OpDecorate %a Location 0
OpDecorate %b Location 1
OpDecorate %o Location 0
OpDecorate %oi Location 1
%void = OpTypeVoid
%fn = OpTypeFunction %void
%float = OpTypeFloat 32
%int = OpTypeInt 32 1
%bool = OpTypeBool
%v4f = OpTypeVector %float 4
%v4i = OpTypeVector %int 4
%v4b = OpTypeVector %bool 4
%pin = OpTypePointer Input %v4f
%pout = OpTypePointer Output %v4f
%pouti = OpTypePointer Output %v4i
%a = OpVariable %pin Input
%b = OpVariable %pin Input
%o = OpVariable %pout Output
%oi = OpVariable %pouti Output
%f0 = OpConstant %float 0
%f1 = OpConstant %float 1
%i0 = OpConstant %int 0
%i1 = OpConstant %int 1
%true = OpConstantTrue %bool
%v0 = OpConstantComposite %v4f %f0 %f0 %f0 %f0
%v1 = OpConstantComposite %v4f %f1 %f1 %f1 %f1
%main = OpFunction %void None %fn
%entry = OpLabel
%va = OpLoad %v4f %a
%vb = OpLoad %v4f %b
)";

struct AsmCase {
    const char* name;
    const char* body;  // after kAsmHeader, up to OpFunctionEnd
};

inline const AsmCase kAsmCases[] = {
    {"unordered_compares_frem_srem", R"(
%lt = OpFUnordLessThan %v4b %va %vb
%le = OpFUnordLessThanEqual %v4b %va %vb
%gt = OpFUnordGreaterThan %v4b %va %vb
%ge = OpFUnordGreaterThanEqual %v4b %va %vb
%eq = OpFUnordEqual %v4b %va %vb
%ne = OpFUnordNotEqual %v4b %va %vb
%one = OpFOrdNotEqual %v4b %va %vb
%s0 = OpSelect %v4f %lt %v1 %v0
%s1 = OpSelect %v4f %le %va %vb
%s2 = OpSelect %v4f %gt %s0 %s1
%s3 = OpSelect %v4f %ge %s2 %va
%s4 = OpSelect %v4f %eq %s3 %vb
%s5 = OpSelect %v4f %ne %s4 %v1
%s6 = OpSelect %v4f %one %s5 %va
%r = OpFRem %v4f %va %vb
%sum = OpFAdd %v4f %s6 %r
OpStore %o %sum
%ia = OpConvertFToS %v4i %va
%ib = OpConvertFToS %v4i %vb
%rem = OpSRem %v4i %ia %ib
%mod = OpSMod %v4i %ia %ib
%isum = OpIAdd %v4i %rem %mod
OpStore %oi %isum
OpReturn
OpFunctionEnd
)"},
    {"endless_loop", R"(
OpBranch %head
%head = OpLabel
%x = OpPhi %v4f %va %entry %next %body
OpLoopMerge %exit %body None
OpBranch %body
%body = OpLabel
%next = OpFAdd %v4f %x %v1
OpStore %o %next
OpBranchConditional %true %head %exit
%exit = OpLabel
OpStore %o %x
OpReturn
OpFunctionEnd
)"},
};

#undef TVK_FS_HEAD

}  // namespace tilevk::shader::test::jit_corpus
