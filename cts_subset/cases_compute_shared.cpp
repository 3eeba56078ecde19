// compute.shared.* (workgroup memory with barriers: reductions, prefix sums, a transpose, a tiled matrix product)
// and compute.ssbo.* (std430/std140 layouts of storage buffers: arrays, structs, matrices in both majors). Every
// shared variable is written before it is read (lavapipe leaves workgroup memory undefined, tilevk zeroes it).
#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

// --- compute.shared ---

// A tree reduction over one workgroup of n invocations (any n: the step count rounds up), per workgroup.
void add_reduction(CaseList& out, uint32_t n, uint32_t groups) {
    const std::string size = std::to_string(n);
    ComputeSpec s;
    s.shaders = {glsl_header(n) + "shared uint part[" + size +
                 "];\n"
                 "layout(std430, binding=0) readonly buffer I { uint v[]; };\n"
                 "layout(std430, binding=1) buffer O { uint sums[]; };\n"
                 "void main() {\n"
                 "  uint l = gl_LocalInvocationIndex;\n"
                 "  part[l] = v[gl_GlobalInvocationID.x];\n"
                 "  barrier();\n"
                 "  for (uint stride = 1u; stride < " +
                 size +
                 "u; stride *= 2u) {\n"
                 "    uint other = (l % (2u * stride) == 0u && l + stride < " +
                 size +
                 "u) ? part[l + stride] : 0u;\n"
                 "    barrier();\n"
                 "    part[l] += other;\n"
                 "    barrier();\n"
                 "  }\n"
                 "  if (l == 0u) sums[gl_WorkGroupID.x] = part[0];\n"
                 "}\n"};
    std::vector<uint32_t> v(size_t(n) * groups), want(groups, 0);
    Lcg g{n * 31 + groups};
    for (size_t i = 0; i < v.size(); ++i) {
        v[i] = uint32_t(g.next() * 100000.0f);
        want[i / n] += v[i];
    }
    s.buffers = {{v, false, false}, {std::vector<uint32_t>(groups, kMarker)}};
    s.steps = {dispatch(0, groups)};
    add_compute_case(out, "shared.reduce_" + size, std::move(s), words_are(1, want));
}

// Hillis-Steele inclusive prefix sum over one workgroup (double-buffered in shared memory), per workgroup.
void add_prefix_sum(CaseList& out, uint32_t n, uint32_t groups) {
    const std::string size = std::to_string(n);
    ComputeSpec s;
    s.shaders = {glsl_header(n) + "shared uint buf[2][" + size +
                 "];\n"
                 "layout(std430, binding=0) buffer D { uint d[]; };\n"
                 "void main() {\n"
                 "  uint l = gl_LocalInvocationIndex, g = gl_GlobalInvocationID.x, src = 0u;\n"
                 "  buf[0][l] = d[g];\n"
                 "  barrier();\n"
                 "  for (uint off = 1u; off < " +
                 size +
                 "u; off *= 2u) {\n"
                 "    buf[1u - src][l] = l >= off ? buf[src][l] + buf[src][l - off] : buf[src][l];\n"
                 "    src = 1u - src;\n"
                 "    barrier();\n"
                 "  }\n"
                 "  d[g] = buf[src][l];\n"
                 "}\n"};
    std::vector<uint32_t> d(size_t(n) * groups), want(d.size());
    for (size_t i = 0; i < d.size(); ++i) {
        d[i] = uint32_t(i * 13 % 101);
        want[i] = d[i] + (i % n ? want[i - 1] : 0);
    }
    s.buffers = {{d}};
    s.steps = {dispatch(0, groups)};
    add_compute_case(out, "shared.prefix_sum_" + size, std::move(s), words_are(0, want));
}

// A 32x32 matrix transposed through 8x8 (or 16x4) shared tiles.
void add_transpose(CaseList& out, uint32_t tx, uint32_t ty) {
    const std::string x = std::to_string(tx), y = std::to_string(ty);
    ComputeSpec s;
    s.shaders = {
        glsl_header(tx, ty) + "shared uint tile[" + y + "][" + x +
        "];\n"
        "layout(std430, binding=0) readonly buffer I { uint m[]; };\n"
        "layout(std430, binding=1) buffer O { uint t[]; };\n"
        "void main() {\n"
        "  uvec2 l = gl_LocalInvocationID.xy, p = gl_GlobalInvocationID.xy;\n"
        "  tile[l.y][l.x] = m[p.y * 32u + p.x];\n"
        "  barrier();\n"
        "  // invocation k of the tile takes the tile's k-th element in column order: its writes are consecutive\n"
        "  uint k = l.y * " +
        x +
        "u + l.x;\n"
        "  uint sx = k / " +
        y + "u, sy = k % " + y +
        "u;\n"
        "  uvec2 q = gl_WorkGroupID.xy * gl_WorkGroupSize.xy + uvec2(sx, sy);\n"
        "  t[q.x * 32u + q.y] = tile[sy][sx];\n"
        "}\n"};
    std::vector<uint32_t> m(1024), want(1024);
    for (uint32_t i = 0; i < 1024; ++i) m[i] = i * 2654435761u;
    for (uint32_t r = 0; r < 32; ++r)
        for (uint32_t c = 0; c < 32; ++c) want[c * 32 + r] = m[r * 32 + c];
    s.buffers = {{m, false, false}, {std::vector<uint32_t>(1024, kMarker)}};
    s.steps = {dispatch(0, 32 / tx, 32 / ty)};
    add_compute_case(out, "shared.transpose_" + x + "x" + y, std::move(s), words_are(1, want));
}

// C = A * B for n x n float matrices of small integers (every product and sum exact), 8x8 tiles through shared
// memory. The answer is computed here.
void add_matmul(CaseList& out, uint32_t n) {
    const std::string ns = std::to_string(n);
    ComputeSpec s;
    s.shaders = {glsl_header(8, 8) +
                 "shared float ta[8][8];\nshared float tb[8][8];\n"
                 "layout(std430, binding=0) readonly buffer A { float a[]; };\n"
                 "layout(std430, binding=1) readonly buffer B { float b[]; };\n"
                 "layout(std430, binding=2) buffer C { float c[]; };\n"
                 "void main() {\n"
                 "  uint row = gl_GlobalInvocationID.y, col = gl_GlobalInvocationID.x;\n"
                 "  uint ly = gl_LocalInvocationID.y, lx = gl_LocalInvocationID.x;\n"
                 "  float acc = 0.0;\n"
                 "  for (uint t = 0u; t < " +
                 ns +
                 "u; t += 8u) {\n"
                 "    ta[ly][lx] = a[row * " +
                 ns +
                 "u + t + lx];\n"
                 "    tb[ly][lx] = b[(t + ly) * " +
                 ns +
                 "u + col];\n"
                 "    barrier();\n"
                 "    for (uint k = 0u; k < 8u; ++k) acc += ta[ly][k] * tb[k][lx];\n"
                 "    barrier();\n"
                 "  }\n"
                 "  c[row * " +
                 ns +
                 "u + col] = acc;\n"
                 "}\n"};
    std::vector<uint32_t> a(n * n), b(n * n), want(n * n);
    std::vector<float> fa(n * n), fb(n * n);
    for (uint32_t i = 0; i < n * n; ++i) {
        fa[i] = float(int(i * 7 % 9) - 4);
        fb[i] = float(int(i * 5 % 11) - 5);
        a[i] = fbits(fa[i]);
        b[i] = fbits(fb[i]);
    }
    for (uint32_t r = 0; r < n; ++r)
        for (uint32_t c = 0; c < n; ++c) {
            float acc = 0;
            for (uint32_t k = 0; k < n; ++k) acc += fa[r * n + k] * fb[k * n + c];
            want[r * n + c] = fbits(acc);
        }
    s.buffers = {{a, false, false}, {b, false, false}, {std::vector<uint32_t>(n * n, kMarker)}};
    s.steps = {dispatch(0, n / 8, n / 8)};
    add_compute_case(out, "shared.matmul_" + ns + "x" + ns, std::move(s), words_are(2, want));
}

// --- compute.ssbo ---

// The shader copies every member of every element of an input block into an output block of the same layout;
// the output starts as markers. Judged: every word is the input's or the marker, and exactly `member_words` words
// per element were copied (padding is never written).
void add_layout_copy(CaseList& out, const std::string& name, const std::string& decl, uint32_t element_words,
                     uint32_t member_words, const std::string& copy = "o.e[i] = s.e[i];") {
    constexpr uint32_t kElems = 24;
    ComputeSpec s;
    s.shaders = {glsl_header(kElems) + decl + "\nlayout(binding=0) readonly buffer In { E e[]; } s;\n" +
                 "layout(binding=1) buffer Out { E e[]; } o;\n"
                 "void main() { uint i = gl_LocalInvocationIndex; " +
                 copy + " }\n"};
    // The layout qualifier of the blocks is the first line of decl (a default for buffers).
    std::vector<uint32_t> in(kElems * element_words);
    for (uint32_t i = 0; i < in.size(); ++i) in[i] = fbits(float(i) + 0.25f);
    s.buffers = {{in, false, false}, {std::vector<uint32_t>(in.size(), kMarker)}};
    Check check = [in, element_words, member_words](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> o = buffer_words(planes, 1);
        if (o.size() != in.size()) return "buffer1 has the wrong size";
        for (uint32_t e = 0; e < o.size() / element_words; ++e) {
            uint32_t copied = 0;
            for (uint32_t w = e * element_words; w < (e + 1) * element_words; ++w) {
                if (o[w] == in[w]) {
                    ++copied;
                } else if (o[w] != kMarker) {
                    return "word " + std::to_string(w) + " is neither the input nor untouched";
                }
            }
            if (copied != member_words)
                return "element " + std::to_string(e) + ": " + std::to_string(copied) + " words copied, expected " +
                       std::to_string(member_words);
        }
        return {};
    };
    add_compute_case(out, "ssbo.layout." + name, std::move(s), std::move(check));
}

void add_ssbo_cases(CaseList& out) {
    add_layout_copy(out, "std430_float", "layout(std430) buffer;\nstruct E { float f; };", 1, 1);
    add_layout_copy(out, "std430_vec3_float", "layout(std430) buffer;\nstruct E { vec3 v; float f; };", 4, 4);
    add_layout_copy(out, "std430_float_vec3", "layout(std430) buffer;\nstruct E { float f; vec3 v; };", 8, 4);
    add_layout_copy(out, "std430_vec2_array", "layout(std430) buffer;\nstruct E { vec2 a[3]; float f; };", 8, 7);
    add_layout_copy(out, "std140_vec2_array", "layout(std140) buffer;\nstruct E { vec2 a[3]; float f; };", 16, 7);
    add_layout_copy(out, "std430_mat2", "layout(std430) buffer;\nstruct E { mat2 m; };", 4, 4);
    add_layout_copy(out, "std140_mat2", "layout(std140) buffer;\nstruct E { mat2 m; };", 8, 4);
    add_layout_copy(out, "std430_mat3_column_major", "layout(std430, column_major) buffer;\nstruct E { mat3 m; };", 12,
                    9);
    add_layout_copy(out, "std430_mat3x2_row_major", "layout(std430, row_major) buffer;\nstruct E { mat3x2 m; };", 8, 6);
    add_layout_copy(out, "std430_mat2x3_row_major",
                    "layout(std430, row_major) buffer;\nstruct E { mat2x3 m; float f; };", 8, 7);
    add_layout_copy(out, "std430_nested_struct",
                    "layout(std430) buffer;\nstruct S { float a; vec2 b; };\nstruct E { S s[2]; vec4 c; uint d; };", 16,
                    11);
    add_layout_copy(out, "std430_array_of_arrays", "layout(std430) buffer;\nstruct E { float a[2][3]; vec3 v; };", 12,
                    9);
    add_layout_copy(out, "std430_ivec3_uint", "layout(std430) buffer;\nstruct E { ivec3 i; uint u; uvec2 w; };", 8, 6);
    // A row-major matrix read member by member and multiplied by a column-major one: the majors must be decoded.
    {
        ComputeSpec s;
        s.shaders = {glsl_header(16) +
                     "layout(std430, binding=0) readonly buffer M { layout(row_major) mat4 r[16]; "
                     "layout(column_major) mat4 c[16]; };\n"
                     "layout(std430, binding=1) buffer O { vec4 o[]; };\n"
                     "void main() { uint i = gl_LocalInvocationIndex;\n"
                     "  o[i * 2u] = r[i] * vec4(1.0, 2.0, 3.0, 4.0);\n"
                     "  o[i * 2u + 1u] = c[i] * vec4(1.0, 2.0, 3.0, 4.0); }\n"};
        std::vector<uint32_t> m(16 * 16 * 2), want(16 * 8);
        for (uint32_t i = 0; i < m.size(); ++i) m[i] = fbits(float(int(i % 13) - 6));
        for (uint32_t i = 0; i < 16; ++i)
            for (uint32_t row = 0; row < 4; ++row) {
                float rr = 0, cc = 0;
                for (uint32_t k = 0; k < 4; ++k) {
                    float r_elem, c_elem;  // element (row, k): row-major stores rows, column-major columns
                    uint32_t rb = m[i * 16 + row * 4 + k], cb = m[256 + i * 16 + k * 4 + row];
                    std::memcpy(&r_elem, &rb, 4);
                    std::memcpy(&c_elem, &cb, 4);
                    rr += r_elem * float(k + 1);
                    cc += c_elem * float(k + 1);
                }
                want[i * 8 + row] = fbits(rr);
                want[i * 8 + 4 + row] = fbits(cc);
            }
        s.buffers = {{m, false, false}, {std::vector<uint32_t>(16 * 8, kMarker)}};
        add_compute_case(out, "ssbo.matrix_majors_times_vector", std::move(s), words_are(1, want));
    }
    // Unsized array length (OpArrayLength) of a buffer bound whole.
    {
        ComputeSpec s;
        s.shaders = {glsl_header(1) +
                     "layout(std430, binding=0) readonly buffer I { vec4 head; vec2 tail[]; };\n"
                     "layout(std430, binding=1) buffer O { uint n; };\n"
                     "void main() { n = uint(tail.length()); }\n"};
        s.buffers = {{std::vector<uint32_t>(4 + 2 * 37, 0), false, false}, {{kMarker}}};
        add_compute_case(out, "ssbo.runtime_array_length", std::move(s), words_are(1, {37}));
    }
}

}  // namespace

void add_compute_shared_cases(CaseList& out) {
    add_reduction(out, 64, 5);
    add_reduction(out, 256, 3);
    add_reduction(out, 24, 7);
    add_reduction(out, 100, 2);
    add_prefix_sum(out, 64, 3);
    add_prefix_sum(out, 128, 2);
    add_prefix_sum(out, 37, 4);
    add_transpose(out, 8, 8);
    add_transpose(out, 16, 4);
    add_matmul(out, 32);
    add_matmul(out, 64);
    add_ssbo_cases(out);
}

}  // namespace tilevk::cts
