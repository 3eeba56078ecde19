// types.layout.* and types.fragment.*: 64-bit values in memory — std140 uniform buffers (dmat3 columns padded to
// 32 bytes), std430 and row-major storage buffers, push constants, local arrays with dynamic indices — matrix and
// vector products of doubles, and doubles and 64-bit integers in a fragment shader, compared byte for byte with the
// reference (cases_types.cpp has the arithmetic).
#include <bit>

#include "compute_case.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

std::vector<uint32_t> random_doubles(uint32_t seed, size_t n) {
    Rng r(seed);
    std::vector<uint32_t> w;
    for (size_t i = 0; i < n; ++i) {
        const double v = double(r.range(-4.0f, 4.0f)) + double(r.next()) * 1e-12;
        const uint64_t b = std::bit_cast<uint64_t>(v);
        w.push_back(uint32_t(b));
        w.push_back(uint32_t(b >> 32));
    }
    return w;
}

const char* kMatrixShader =
    "#version 450\n"
    "#extension GL_ARB_gpu_shader_int64 : require\n"
    "layout(local_size_x=16) in;\n"
    "layout(std140, binding=0) uniform U { dmat4 m; dmat3 n; dvec3 t; double s; dmat2x3 q; } u;\n"
    "layout(std430, binding=1) readonly buffer V { dvec4 v[]; } vin;\n"
    "layout(std430, binding=2) readonly buffer R { layout(row_major) dmat3x4 rm; i64vec3 iv; u64vec2 uv[2]; } rb;\n"
    "layout(std430, binding=3) buffer Out { dvec4 r[]; } o;\n"
    "layout(push_constant) uniform P { double scale; int64_t bias; } pc;\n"
    "void main() {\n"
    "  uint i = gl_GlobalInvocationID.x;\n"
    "  dvec4 v = vin.v[i];\n"
    "  uint k = i * 10u;\n"
    "  o.r[k + 0u] = u.m * v;\n"
    "  o.r[k + 1u] = u.m * (v * 0.5lf);\n"
    "  o.r[k + 2u] = dvec4(u.n * v.xyz + u.t, u.s);\n"
    "  dmat4 mm = u.m * transpose(u.m);\n"
    "  o.r[k + 3u] = mm[i % 4u];\n"
    "  o.r[k + 4u] = (rb.rm * v.xyz) * pc.scale;\n"
    "  o.r[k + 5u] = dvec4(dvec3(rb.iv) + double(pc.bias), double(rb.uv[i % 2u].y));\n"
    "  dmat3 op = outerProduct(v.xyz, u.t);\n"
    "  o.r[k + 6u] = dvec4(op[0].x, op[1].y, op[2].z, v.x * v.w - v.y * v.z + 0.0lf * op[2].x);\n"
    "  double arr[5] = double[5](v.x, v.y, v.z, v.w, u.s);\n"
    "  o.r[k + 7u] = dvec4(arr[i % 5u], arr[(i + 2u) % 5u], v[i % 4u], u.q[1][i % 3u]);\n"
    "  dvec3 nv = normalize(v.xyz);\n"
    "  o.r[k + 8u] = dvec4(nv, faceforward(v.x, v.y, v.z));\n"
    "  o.r[k + 9u] = dvec4(reflect(v.xyz, nv), v.w * 2.0lf);\n"
    "}\n";

void add_matrix_cases(CaseList& out) {
    for (uint32_t seed : {5u, 6u}) {
        ComputeSpec s;
        s.shaders = {kMatrixShader};
        // std140 U: dmat4 at 0 (128 bytes), dmat3 at 128 (3 columns of 32 bytes), dvec3 t at 224, double s at 248,
        // dmat2x3 q at 256 (2 columns of 32): 320 bytes = 40 doubles
        std::vector<uint32_t> uni = random_doubles(seed, 40);
        std::vector<uint32_t> rbuf = random_doubles(seed + 100, 12);  // row-major dmat3x4: 3 rows of dvec4
        Rng r(seed);
        for (int j = 0; j < 4; ++j) rbuf.push_back(r.next());  // i64vec3 at 96 (and padding to 128)
        rbuf.resize(32);
        for (int j = 0; j < 8; ++j) rbuf.push_back(r.next());  // u64vec2 uv[2] at 128
        s.buffers = {{uni, true},
                     {random_doubles(seed + 200, 16 * 4 * 4)},
                     {rbuf},
                     {std::vector<uint32_t>(64 * 10 * 8, kMarker)}};
        const uint64_t scale = std::bit_cast<uint64_t>(1.25), bias = uint64_t(-3000000000ll);
        s.push = {uint32_t(scale), uint32_t(scale >> 32), uint32_t(bias), uint32_t(bias >> 32)};
        s.steps = {dispatch(0, 4)};
        add_types_case(out, "layout.matrices_seed" + std::to_string(seed), std::move(s));
    }
}

// A fragment shader with doubles and 64-bit integers: each pixel writes its results into a storage buffer at its
// own index, and a colour computed in double precision to the attachment.
void add_fragment_case(CaseList& out) {
    constexpr uint32_t kSize = 16;
    ComputeSpec s;
    s.buffers = {{std::vector<uint32_t>(kSize * kSize * 4, kMarker)}};
    s.images = {{VK_FORMAT_R32G32B32A32_SFLOAT, kSize, kSize, {}, true}};
    s.draw = {
        "#version 450\n"
        "void main() {\n"
        "  vec2 p = vec2(float(gl_VertexIndex & 1) * 4.0 - 1.0, float(gl_VertexIndex >> 1) * 4.0 - 1.0);\n"
        "  gl_Position = vec4(p, 0.0, 1.0);\n"
        "}\n",
        "#version 450\n"
        "#extension GL_ARB_gpu_shader_int64 : require\n"
        "layout(std430, binding=0) buffer B { uint64_t w[]; } b;\n"
        "layout(location=0) out vec4 o;\n"
        "void main() {\n"
        "  uvec2 q = uvec2(gl_FragCoord.xy);\n"
        "  uint i = q.y * 16u + q.x;\n"
        "  double x = double(gl_FragCoord.x) / 3.0lf, y = double(gl_FragCoord.y) * 1e10lf;\n"
        "  int64_t h = int64_t(i) * 0x9E3779B97F4A7C15l;\n"
        "  b.w[2u * i] = doubleBitsToUint64(sqrt(x * y + 1.0lf));\n"
        "  b.w[2u * i + 1u] = uint64_t(h >> (i & 63u)) ^ uint64_t(y);\n"
        "  o = vec4(float(fract(x)), float(y / 3e11lf), float(h & 255l) / 255.0, float(x * x));\n"
        "}\n",
        3, -1};
    s.steps = {draw()};
    add_types_case(out, "fragment.float64_int64", std::move(s));
}

}  // namespace

void add_types_matrix_cases(CaseList& out) {
    add_matrix_cases(out);
    add_fragment_case(out);
}

}  // namespace tilevk::cts
