// compute.image_atomic.* (every 32-bit integer atomic on R32_UINT / R32_SINT storage images), compute.texel_buffer.*
// (imageLoad / imageStore / imageSize / atomics on storage texel buffers), compute.stores.* (storage-buffer stores
// and atomics from vertex and fragment shaders, helper lanes and discarded fragments writing nothing) and
// compute.basic.dispatch_base.* (vkCmdDispatchBaseKHR). Every case is compared with the reference byte for byte and
// checked against the answer computed here; only results that do not depend on the order of the invocations.
#include <array>
#include <cstdio>

#include "compute_case.hpp"

namespace tilevk::cts {
namespace {

// --- compute.image_atomic ---

constexpr uint32_t kAtomicW = 16, kAtomicH = 16;
const char* const kImageAtomics[] = {"Add", "Min", "Max", "And", "Or", "Xor", "Exchange"};

// The operand of invocation (x, y), the same expression as the shader's.
uint32_t atomic_operand(uint32_t x, uint32_t y) {
    return x * 2654435761u + y * 40503u + 12345u;
}

// Rows 0..7: one invocation per texel, op = row (Add, Min, Max, And, Or, Xor, Exchange, CompSwap), its return value
// written to buffer 0. Rows 8..13: four invocations per texel with the commutative ops 0..5 (no return values, whose
// order would show). Rows 14, 15: untouched.
std::string image_atomic_glsl(bool sint) {
    const std::string t = sint ? "int" : "uint";
    std::string ops_single, ops_shared;
    for (int i = 0; i < 7; ++i) {
        ops_single += std::string(i ? "    else " : "    ") + "if (g.y == " + std::to_string(i) + "u) r = imageAtomic" +
                      kImageAtomics[i] + "(img, p, v);\n";
        if (i < 6)
            ops_shared += std::string(i ? "    else " : "    ") + "if (op == " + std::to_string(i) + "u) imageAtomic" +
                          kImageAtomics[i] + "(img, q, v);\n";
    }
    return glsl_header(16, 4) + "layout(std430, binding=0) buffer R { " + t + " ret[]; };\n" + "layout(binding=1, " +
           (sint ? "r32i) uniform iimage2D" : "r32ui) uniform uimage2D") + " img;\n" +
           "void main() {\n"
           "  uvec2 g = gl_GlobalInvocationID.xy;\n"
           "  " +
           t + " v = " + t +
           "(g.x * 2654435761u + g.y * 40503u + 12345u);\n"
           "  if (g.y < 8u) {\n"
           "    ivec2 p = ivec2(g);\n"
           "    " +
           t + " r = " + t + "(0);\n" + ops_single + "    else { " + t +
           " cur = imageLoad(img, p).x;\n"
           "      r = imageAtomicCompSwap(img, p, (g.x & 1u) == 0u ? cur : cur ^ " +
           t +
           "(1), v); }\n"
           "    ret[g.y * 16u + g.x] = r;\n"
           "  } else {\n"
           "    uint op = (g.y - 8u) / 4u;\n"
           "    ivec2 q = ivec2(g.x, 8u + op);\n" +
           ops_shared +
           "  }\n"
           "}\n";
}

// op 0..7 applied to the texel `t` with operand `v` (signed min/max for SINT); returns the old value.
uint32_t apply_atomic(int op, bool sint, uint32_t& t, uint32_t v, uint32_t compare = 0) {
    const uint32_t old = t;
    const auto smin = [](uint32_t a, uint32_t b) { return int32_t(a) < int32_t(b) ? a : b; };
    const auto smax = [](uint32_t a, uint32_t b) { return int32_t(a) > int32_t(b) ? a : b; };
    switch (op) {
        case 0:
            t = old + v;
            break;
        case 1:
            t = sint ? smin(old, v) : std::min(old, v);
            break;
        case 2:
            t = sint ? smax(old, v) : std::max(old, v);
            break;
        case 3:
            t = old & v;
            break;
        case 4:
            t = old | v;
            break;
        case 5:
            t = old ^ v;
            break;
        case 6:
            t = v;
            break;
        default:
            t = old == compare ? v : old;
            break;
    }
    return old;
}

void add_image_atomic_case(CaseList& out, bool sint) {
    std::vector<uint32_t> init(kAtomicW * kAtomicH);
    for (uint32_t y = 0; y < kAtomicH; ++y)
        for (uint32_t x = 0; x < kAtomicW; ++x)  // both signs, low and high bits set
            init[y * kAtomicW + x] = (x * 0x01000193u) ^ (y * 0x9E3779B9u) ^ (x & 2u ? 0x80000000u : 0u);
    std::vector<uint32_t> image = init, ret(kAtomicW * 8);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < kAtomicW; ++x) {
            uint32_t& t = image[y * kAtomicW + x];
            ret[y * kAtomicW + x] = apply_atomic(int(y), sint, t, atomic_operand(x, y), (x & 1u) ? t ^ 1u : t);
        }
    for (uint32_t y = 8; y < 32; ++y)
        for (uint32_t x = 0; x < kAtomicW; ++x) {
            const uint32_t op = (y - 8) / 4;
            apply_atomic(int(op), sint, image[(8 + op) * kAtomicW + x], atomic_operand(x, y));
        }
    ComputeSpec s;
    s.shaders = {image_atomic_glsl(sint)};
    s.buffers = {{std::vector<uint32_t>(kAtomicW * 8, kMarker)}};
    std::vector<uint8_t> bytes(init.size() * 4);
    std::memcpy(bytes.data(), init.data(), bytes.size());
    s.images = {{sint ? VK_FORMAT_R32_SINT : VK_FORMAT_R32_UINT, kAtomicW, kAtomicH, bytes}};
    s.steps = {dispatch(0, 1, 8)};
    Check image_is = [image](const std::vector<Plane>& planes) -> std::string {
        for (const Plane& p : planes) {
            if (p.name != "image0") continue;
            for (size_t i = 0; i < image.size(); ++i) {
                uint32_t w;
                std::memcpy(&w, &p.data[i * 4], 4);
                if (w != image[i])
                    return "image0 texel " + std::to_string(i) + " is " + std::to_string(w) + ", expected " +
                           std::to_string(image[i]);
            }
            return {};
        }
        return "no plane image0";
    };
    add_compute_case(out, std::string("image_atomic.") + (sint ? "r32_sint" : "r32_uint"), std::move(s),
                     all_of({words_are(0, ret), image_is}));
}

// --- compute.texel_buffer ---

// 64 RGBA8 texels loaded, stored reversed and swizzled into an RGBA32F texel buffer, 16 + 4 R32_UINT atomic slots
// (adds and maxima), imageSize of the three views and a load past the end of the first ((0, 0, 0, 0)) into buffer 3.
void add_texel_buffer_case(CaseList& out) {
    std::vector<uint32_t> src(64);
    Lcg g{77};
    for (uint32_t& w : src) w = uint32_t(g.next() * 65536.0f) | uint32_t(g.next() * 65536.0f) << 16;
    ComputeSpec s;
    s.shaders = {glsl_header(64) +
                 "layout(binding=0, rgba8) readonly uniform imageBuffer src;\n"
                 "layout(binding=1, rgba32f) writeonly uniform imageBuffer dst;\n"
                 "layout(binding=2, r32ui) uniform uimageBuffer cnt;\n"
                 "layout(std430, binding=3) buffer S { int sizes[3]; uint pad; vec4 past; };\n"
                 "void main() {\n"
                 "  int i = int(gl_GlobalInvocationID.x);\n"
                 "  imageStore(dst, 63 - i, imageLoad(src, i).wzyx);\n"
                 "  imageAtomicAdd(cnt, i % 16, uint(i) + 1u);\n"
                 "  imageAtomicMax(cnt, 16 + i % 4, uint(i * 7 % 64));\n"
                 "  if (i == 0) { sizes[0] = imageSize(src); sizes[1] = imageSize(dst); sizes[2] = imageSize(cnt);\n"
                 "    past = imageLoad(src, 69); }\n"
                 "}\n"};
    s.buffers = {{src, false, true, VK_FORMAT_R8G8B8A8_UNORM},
                 {std::vector<uint32_t>(256, kMarker), false, true, VK_FORMAT_R32G32B32A32_SFLOAT},
                 {std::vector<uint32_t>(20, 0), false, true, VK_FORMAT_R32_UINT},
                 {std::vector<uint32_t>(8, kMarker)}};
    s.steps = {dispatch(0, 1)};
    std::vector<uint32_t> dst(256), cnt(20, 0), info = {64, 64, 20, kMarker, 0, 0, 0, 0};
    for (uint32_t i = 0; i < 64; ++i) {
        for (uint32_t c = 0; c < 4; ++c)  // UNORM8 loads c * fl(1/255); the store swizzles .wzyx
            dst[(63 - i) * 4 + (3 - c)] = fbits(float((src[i] >> (8 * c)) & 0xffu) * float(1.0 / 255.0));
        cnt[i % 16] += i + 1;
        cnt[16 + i % 4] = std::max(cnt[16 + i % 4], i * 7 % 64);
    }
    add_compute_case(out, "texel_buffer.load_store_atomic_size", std::move(s),
                     all_of({words_are(0, src), words_are(1, dst), words_are(2, cnt), words_are(3, info)}));
}

// --- compute.stores (vertex and fragment stages) ---

constexpr uint32_t kTarget = 32;

// Vertex shader side effects: every vertex sets its bit, raises a maximum and writes its own word; results that do
// not depend on how many times a vertex is shaded (lavapipe may shade one more than once).
void add_vertex_store_case(CaseList& out) {
    constexpr uint32_t kVertices = 30;
    ComputeSpec s;
    s.buffers = {{std::vector<uint32_t>(3 + kVertices, 0)}};
    s.images = {{VK_FORMAT_R8G8B8A8_UNORM, kTarget, kTarget, {}, true}};
    s.draw = {
        "#version 450\n"
        "layout(std430, binding=0) buffer B { uint seen[2]; uint maxv; uint vals[]; };\n"
        "void main() {\n"
        "  uint i = uint(gl_VertexIndex);\n"
        "  atomicOr(seen[i / 32u], 1u << (i % 32u));\n"
        "  atomicMax(maxv, i * 3u + 1u);\n"
        "  vals[i] = i * i + 7u;\n"
        "  gl_Position = vec4(float(i % 3u) * 0.25 - 0.9, float(i / 3u) * 0.2 - 0.9, 0.0, 1.0);\n"
        "}\n",
        "#version 450\nlayout(location=0) out vec4 o;\nvoid main() { o = vec4(0.0, 0.5, 1.0, 1.0); }\n", kVertices, -1};
    s.steps = {draw()};
    std::vector<uint32_t> want = {(1u << kVertices) - 1u, 0, (kVertices - 1) * 3 + 1};
    for (uint32_t i = 0; i < kVertices; ++i) want.push_back(i * i + 7);
    add_compute_case(out, "stores.vertex_stage", std::move(s), words_are(0, want));
}

// Two overlapping triangles in window coordinates (multiples of 1/256 px, exact through the viewport transform).
constexpr std::array<std::array<int, 2>, 6> kTriangles = {
    {{{589, 435}}, {{7565, 1318}}, {{2022, 7795}}, {{7900, 7700}}, {{300, 5000}}, {{6000, 300}}}};

// How many of the triangles cover pixel (x, y)'s centre, and which (bit t). Returns false when a centre lies exactly
// on an edge (the fill rule would decide; the geometry is chosen so that none does).
bool coverage(uint32_t x, uint32_t y, uint32_t& count, uint32_t& mask) {
    const int64_t px = int64_t(x) * 256 + 128, py = int64_t(y) * 256 + 128;
    count = mask = 0;
    for (uint32_t t = 0; t < 2; ++t) {
        int positive = 0, negative = 0;
        for (uint32_t e = 0; e < 3; ++e) {
            const auto& a = kTriangles[t * 3 + e];
            const auto& b = kTriangles[t * 3 + (e + 1) % 3];
            const int64_t f = int64_t(b[0] - a[0]) * (py - a[1]) - int64_t(b[1] - a[1]) * (px - a[0]);
            if (f == 0) return false;
            (f > 0 ? positive : negative)++;
        }
        if (positive == 3 || negative == 3) {
            ++count;
            mask |= 1u << t;
        }
    }
    return true;
}

bool discarded(uint32_t x, uint32_t y) {
    return (x + 2 * y) % 7 == 3;
}

// Fragment shader side effects: per pixel an atomic count of the fragments that reached it, the set of triangles
// (atomicOr) and a plain store, plus one global counter; discarded fragments and the helper lanes of partly covered
// quads must write nothing. The count and set are known from the geometry.
void add_fragment_store_case(CaseList& out) {
    std::string positions;
    for (const auto& v : kTriangles) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%svec2(%.17g, %.17g)", positions.empty() ? "" : ", ",
                      double(v[0]) / 4096.0 - 1.0, double(v[1]) / 4096.0 - 1.0);
        positions += buf;
    }
    ComputeSpec s;
    const uint32_t n = kTarget * kTarget;
    s.buffers = {{std::vector<uint32_t>(n, 0)},
                 {std::vector<uint32_t>(n, 0)},
                 {std::vector<uint32_t>(n, kMarker)},
                 {std::vector<uint32_t>(1, 0)}};
    s.images = {{VK_FORMAT_R8G8B8A8_UNORM, kTarget, kTarget, std::vector<uint8_t>(n * 4, 0x20), true}};
    s.draw = {
        "#version 450\n"
        "const vec2 pos[6] = vec2[6](" +
            positions +
            ");\n"
            "layout(location=0) flat out uint tri;\n"
            "void main() { tri = uint(gl_VertexIndex) / 3u; gl_Position = vec4(pos[gl_VertexIndex], 0.0, 1.0); "
            "}\n",
        "#version 450\n"
        "layout(location=0) flat in uint tri;\n"
        "layout(std430, binding=0) buffer C { uint count[]; };\n"
        "layout(std430, binding=1) buffer M { uint tris[]; };\n"
        "layout(std430, binding=2) buffer V { uint val[]; };\n"
        "layout(std430, binding=3) buffer T { uint total; };\n"
        "layout(location=0) out vec4 o;\n"
        "void main() {\n"
        "  uvec2 p = uvec2(gl_FragCoord.xy);\n"
        "  uint i = p.y * 32u + p.x;\n"
        "  if ((p.x + 2u * p.y) % 7u == 3u) discard;\n"
        "  atomicAdd(count[i], 1u);\n"
        "  atomicOr(tris[i], 1u << tri);\n"
        "  val[i] = i * 3u + 1u;\n"
        "  atomicAdd(total, 1u);\n"
        "  o = vec4(float(tri) * 0.5, 1.0, 0.0, 1.0);\n"
        "}\n",
        6, -1};
    s.steps = {draw()};
    std::vector<uint32_t> count(n), tris(n), val(n, kMarker), total(1, 0);
    bool exact = true;
    for (uint32_t y = 0; y < kTarget; ++y)
        for (uint32_t x = 0; x < kTarget; ++x) {
            const uint32_t i = y * kTarget + x;
            exact = exact && coverage(x, y, count[i], tris[i]);
            if (discarded(x, y)) count[i] = tris[i] = 0;
            if (count[i] != 0) val[i] = i * 3 + 1;
            total[0] += count[i];
        }
    Check geometry = [exact](const std::vector<Plane>&) -> std::string {
        return exact ? std::string() : "the case's geometry puts a pixel centre on an edge";
    };
    add_compute_case(
        out, "stores.fragment_coverage_and_discard", std::move(s),
        all_of({geometry, words_are(0, count), words_are(1, tris), words_are(2, val), words_are(3, total)}));
}

// --- compute.basic.dispatch_base ---

// Each invocation writes its work group ID, global invocation ID and NumWorkgroups at its place among the
// dispatched groups: the IDs start at the base, NumWorkgroups is the group count alone.
void add_dispatch_base_case(CaseList& out, const std::string& name, std::array<uint32_t, 3> base,
                            std::array<uint32_t, 3> groups) {
    constexpr uint32_t kLx = 4, kLy = 2;
    const uint32_t ngroups = groups[0] * groups[1] * groups[2];
    ComputeSpec s;
    s.shaders = {glsl_header(kLx, kLy) + "layout(std430, binding=0) buffer O { uvec4 o[]; };\n" +
                 "void main() {\n"
                 "  uvec3 w = gl_WorkGroupID - uvec3(" +
                 std::to_string(base[0]) + "u, " + std::to_string(base[1]) + "u, " + std::to_string(base[2]) +
                 "u);\n"
                 "  uint g = (w.z * gl_NumWorkGroups.y + w.y) * gl_NumWorkGroups.x + w.x;\n"
                 "  o[g * 8u + gl_LocalInvocationIndex] = uvec4(gl_WorkGroupID.x | gl_WorkGroupID.y << 12 |\n"
                 "    gl_WorkGroupID.z << 24, gl_GlobalInvocationID.x, gl_GlobalInvocationID.y |\n"
                 "    gl_GlobalInvocationID.z << 16, gl_NumWorkGroups.x | gl_NumWorkGroups.y << 8 |\n"
                 "    gl_NumWorkGroups.z << 16);\n"
                 "}\n"};
    s.buffers = {{std::vector<uint32_t>(ngroups * kLx * kLy * 4 + 4, kMarker)}};
    s.steps = {dispatch_base(0, base.data(), groups.data())};
    std::vector<uint32_t> want(ngroups * kLx * kLy * 4 + 4, kMarker);
    for (uint32_t gz = 0; gz < groups[2]; ++gz)
        for (uint32_t gy = 0; gy < groups[1]; ++gy)
            for (uint32_t gx = 0; gx < groups[0]; ++gx)
                for (uint32_t ly = 0; ly < kLy; ++ly)
                    for (uint32_t lx = 0; lx < kLx; ++lx) {
                        const uint32_t g = (gz * groups[1] + gy) * groups[0] + gx, l = ly * kLx + lx;
                        const uint32_t wx = base[0] + gx, wy = base[1] + gy, wz = base[2] + gz;
                        uint32_t* o = &want[(g * 8 + l) * 4];
                        o[0] = wx | wy << 12 | wz << 24;
                        o[1] = wx * kLx + lx;
                        o[2] = (wy * kLy + ly) | wz << 16;
                        o[3] = groups[0] | groups[1] << 8 | groups[2] << 16;
                    }
    add_compute_case(out, "basic.dispatch_base." + name, std::move(s), words_are(0, want));
}

}  // namespace

void add_compute_store_cases(CaseList& out) {
    add_image_atomic_case(out, false);
    add_image_atomic_case(out, true);
    add_texel_buffer_case(out);
    add_vertex_store_case(out);
    add_fragment_store_case(out);
    add_dispatch_base_case(out, "base_2_1_3", {2, 1, 3}, {3, 2, 2});
    add_dispatch_base_case(out, "base_1000_x", {1000, 0, 0}, {5, 1, 1});
    add_dispatch_base_case(out, "base_0", {0, 0, 0}, {2, 3, 1});
}

}  // namespace tilevk::cts
