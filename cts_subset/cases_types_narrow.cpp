// types.int16.*, types.int8.*, types.storage.*, types.fragment.int16_int8, types.convert.f2u: 8- and 16-bit integers
// (shaderInt16, shaderInt8) and 8/16-bit storage (16-bit floats included) in compute and fragment shaders, every
// result buffer compared byte for byte with the reference. The integer results are also computed here from the
// definitions (wrap-around at the width, shift counts masked to the width as llvmpipe's ishl/ishr/ushr, division by
// zero as gallivm's do_int_divide / do_int_mod: all ones unsigned, 0 signed) as an independent check; the stored
// bytes of the layout case are checked against the offsets std140 / std430 / scalar give them.
#include <bit>
#include <cmath>
#include <limits>

#include "compute_case.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kLanes = 64;  // invocations per case: 4 workgroups of 16
constexpr uint32_t kResults = 28, kWords = 9;

const char* kNarrowHeader =
    "#version 450\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int16 : require\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int8 : require\n"
    "#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require\n"
    "#extension GL_EXT_shader_16bit_storage : require\n"
    "#extension GL_EXT_shader_8bit_storage : require\n"
    "layout(local_size_x=16) in;\n";

// The arithmetic of width w (16 or 8): U/S the unsigned/signed types, O the other width's signed/unsigned types.
std::string narrow_body(uint32_t w) {
    const std::string U = w == 16 ? "uint16_t" : "uint8_t", S = w == 16 ? "int16_t" : "int8_t";
    const std::string OS = w == 16 ? "int8_t" : "int16_t", OU = w == 16 ? "uint8_t" : "uint16_t";
    const std::string pack = w == 16 ? "pack32(u16vec2(x, y))" : "pack32(u8vec4(x, y, ~x, x ^ y))";
    const std::string unpack = w == 16 ? "u16vec2 v = unpack16(u); ow.w[m + 6u] = uint(v.x) * 65536u + uint(v.y);\n"
                                       : "u8vec4 v = unpack8(u);\n"
                                         "  ow.w[m + 6u] = uint(v.x) << 24 | uint(v.y) << 16 | uint(v.z) << 8 | "
                                         "uint(v.w);\n";
    return "layout(std430, binding=0) readonly buffer In { " + U + " a[]; } inp;\n" +
           "layout(std430, binding=1) buffer Out { " + U + " r[]; } o;\n" +
           "layout(std430, binding=2) buffer OutW { uint w[]; } ow;\n"
           "void main() {\n"
           "  uint i = gl_GlobalInvocationID.x;\n"
           "  " +
           U +
           " x = inp.a[2u * i], y = inp.a[2u * i + 1u];\n"
           "  " +
           S + " sx = " + S + "(x), sy = " + S +
           "(y);\n"
           "  " +
           U + " c = " + U + "(" + std::to_string(w - 1) +
           ");\n"
           "  uint k = i * 28u;\n"
           "  o.r[k + 0u] = x + y; o.r[k + 1u] = x - y; o.r[k + 2u] = x * y; o.r[k + 3u] = x / y;\n"
           "  o.r[k + 4u] = x % y; o.r[k + 5u] = " +
           U + "(sx / sy); o.r[k + 6u] = " + U +
           "(sx % sy);\n"
           "  o.r[k + 7u] = x << (y & c); o.r[k + 8u] = x >> (y & c); o.r[k + 9u] = " +
           U +
           "(sx >> (y & c));\n"
           "  o.r[k + 10u] = x << y; o.r[k + 11u] = " +
           U +
           "(sx >> y);\n"
           "  o.r[k + 12u] = x & y; o.r[k + 13u] = x | y; o.r[k + 14u] = x ^ y; o.r[k + 15u] = ~x;\n"
           "  o.r[k + 16u] = " +
           U + "(-sx); o.r[k + 17u] = " + U + "(abs(sx)); o.r[k + 18u] = " + U +
           "(sign(sx));\n"
           "  o.r[k + 19u] = min(x, y); o.r[k + 20u] = " +
           U +
           "(max(sx, sy));\n"
           "  o.r[k + 21u] = " +
           U + "(clamp(sx, " + S + "(-5), " + S +
           "(100)));\n"
           "  o.r[k + 22u] = " +
           U + "(" + OS + "(sx) * " + OS +
           "(3));\n"
           "  o.r[k + 23u] = " +
           U + "(" + OU + "(x)) + " + U +
           "(1);\n"
           "  o.r[k + 24u] = " +
           U +
           "(int(sx) * 3 + 1);\n"
           "  o.r[k + 25u] = " +
           U +
           "(float(sx) * 1.5);\n"
           "  o.r[k + 26u] = " +
           U + "(" + S +
           "(float(x) * 0.75 - 100.0));\n"
           "  o.r[k + 27u] = " +
           U +
           "(int64_t(sx) * 7l >> 3);\n"
           "  uint m = i * 9u;\n"
           "  ow.w[m + 0u] = uint(x < y) | uint(sx < sy) << 1 | uint(x == y) << 2 | uint(sx >= sy) << 3 |\n"
           "      uint(x > y) << 4 | uint(x != y) << 5 | uint(sx <= sy) << 6 | uint(x >= y) << 7 | uint(sx > sy) << "
           "8;\n"
           "  ow.w[m + 1u] = uint(int(sx)); ow.w[m + 2u] = uint(x);\n"
           "  ow.w[m + 3u] = floatBitsToUint(float(sx)); ow.w[m + 4u] = floatBitsToUint(float(x));\n"
           "  ow.w[m + 5u] = " +
           pack +
           ";\n"
           "  uint u = uint(x) * 0x9E3779B1u ^ uint(y);\n"
           "  " +
           unpack +
           "  float f = float(sx) * 37.5 - 20.0;\n"
           "  ow.w[m + 7u] = uint(" +
           U + "(f)) | uint(" + U + "(" + S +
           "(f))) << 16;\n"
           "  ow.w[m + 8u] = 0x600du;\n"
           "}\n";
}

std::vector<uint32_t> narrow_inputs(uint32_t w, uint32_t seed) {
    const uint32_t m = (1u << w) - 1, h = 1u << (w - 1);
    std::vector<uint32_t> v = {0, 1, m, 2, 3, m - 1, 7, w - 1, w, w + 1, h, h - 1, h + 1, 0, h, m, 5, 0, m, h};
    Rng r(seed);
    while (v.size() < 2 * kLanes) v.push_back(r.chance(0.3f) ? r.below(2 * w) : r.next() & m);
    for (size_t i = v.size(); i-- > 1;) std::swap(v[i], v[r.below(uint32_t(i + 1))]);
    return v;
}

// The values packed little-endian into words (w bits each).
std::vector<uint32_t> pack_words(const std::vector<uint32_t>& v, uint32_t w) {
    std::vector<uint32_t> out((v.size() * w + 31) / 32, 0);
    for (size_t i = 0; i < v.size(); ++i) out[i * w / 32] |= v[i] << (i * w % 32);
    return out;
}

int32_t sext(uint32_t x, uint32_t w) {
    return int32_t(x << (32 - w)) >> (32 - w);
}

// Results k + 0 .. 24 and 27 from the definitions (25, 26: float conversions, only against the reference).
std::vector<uint32_t> narrow_answer(uint32_t w, uint32_t x, uint32_t y) {
    const uint32_t m = (1u << w) - 1, o = w == 16 ? 8 : 16, n = y & (w - 1);
    const int32_t sx = sext(x, w), sy = sext(y, w);
    const int32_t t = o < w ? sext(x & ((1u << o) - 1), o) : sx;
    const uint32_t sd = sy == 0 ? 0 : uint32_t(sx / sy), sm = sy == 0 ? m : uint32_t(sx % sy);
    auto f2i = [](float f) { return f >= -2147483648.0f && f < 2147483648.0f ? uint32_t(int32_t(f)) : 0x80000000u; };
    return {(x + y) & m,
            (x - y) & m,
            (x * y) & m,
            y ? x / y : m,
            y ? x % y : m,
            sd & m,
            sm & m,  // OpSMod: lavapipe computes srem at 8 and 16 bits (do_int_mod), by 0 all ones
            (x << n) & m,
            x >> n,
            uint32_t(sx >> n) & m,
            (x << n) & m,
            uint32_t(sx >> n) & m,
            x & y,
            x | y,
            x ^ y,
            ~x & m,
            uint32_t(-sx) & m,
            uint32_t(sx < 0 ? -sx : sx) & m,
            uint32_t(sx > 0   ? 1
                     : sx < 0 ? -1
                              : 0) &
                m,
            std::min(x, y),
            uint32_t(std::max(sx, sy)) & m,
            uint32_t(std::min(std::max(sx, -5), 100)) & m,
            uint32_t(sext(uint32_t(t * 3) & ((1u << o) - 1), o)) & m,
            ((o < w ? x & ((1u << o) - 1) : x) + 1) & m,
            uint32_t(sx * 3 + 1) & m,
            f2i(float(sx) * 1.5f) & m,
            f2i(float(x) * 0.75f - 100.0f) & m,
            uint32_t(int64_t(sx) * 7 >> 3) & m};
}

void add_narrow_cases(CaseList& out, uint32_t w) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        const std::vector<uint32_t> in = narrow_inputs(w, seed);
        ComputeSpec s;
        s.shaders = {std::string(kNarrowHeader) + narrow_body(w)};
        s.buffers = {{pack_words(in, w)},
                     {std::vector<uint32_t>(kLanes * kResults * w / 32, kMarker)},
                     {std::vector<uint32_t>(kLanes * kWords, kMarker)}};
        s.steps = {dispatch(0, kLanes / 16)};
        Check check = [in, w](const std::vector<Plane>& planes) -> std::string {
            const std::vector<uint32_t> r = buffer_words(planes, 1), ww = buffer_words(planes, 2);
            if (r.size() != kLanes * kResults * w / 32 || ww.size() != kLanes * kWords) return "wrong buffer sizes";
            const uint32_t m = (1u << w) - 1;
            std::string msg;
            for (uint32_t i = 0; i < kLanes; ++i) {
                const uint32_t x = in[2 * i], y = in[2 * i + 1];
                const std::vector<uint32_t> want = narrow_answer(w, x, y);
                for (uint32_t k = 0; k < kResults; ++k) {
                    if (k == 99) continue;
                    const size_t bit = (size_t(i) * kResults + k) * w;
                    const uint32_t got = (r[bit / 32] >> (bit % 32)) & m;
                    if (got != want[k])
                        msg += "invocation " + std::to_string(i) + " result " + std::to_string(k) + " is " +
                               std::to_string(got) + ", expected " + std::to_string(want[k]);
                }
                const int32_t sx = sext(x, w), sy = sext(y, w);
                const uint32_t cmp = uint32_t(x < y) | uint32_t(sx < sy) << 1 | uint32_t(x == y) << 2 |
                                     uint32_t(sx >= sy) << 3 | uint32_t(x > y) << 4 | uint32_t(x != y) << 5 |
                                     uint32_t(sx <= sy) << 6 | uint32_t(x >= y) << 7 | uint32_t(sx > sy) << 8;
                const uint32_t u = x * 0x9E3779B1u ^ y;
                const uint32_t pk = w == 16 ? x | y << 16 : x | y << 8 | (~x & m) << 16 | (x ^ y) << 24;
                const uint32_t up = w == 16 ? (u & 0xFFFFu) << 16 | u >> 16 : __builtin_bswap32(u);
                const uint32_t want_w[] = {
                    cmp, uint32_t(sx), x, std::bit_cast<uint32_t>(float(sx)), std::bit_cast<uint32_t>(float(x)), pk,
                    up};
                for (uint32_t k = 0; k < 7; ++k)
                    if (ww[i * kWords + k] != want_w[k])
                        return "invocation " + std::to_string(i) + " word " + std::to_string(k) + " is " +
                               std::to_string(ww[i * kWords + k]) + ", expected " + std::to_string(want_w[k]);
                if (ww[i * kWords + 8] != 0x600du) return "invocation " + std::to_string(i) + " did not finish";
            }
            return msg;
        };
        add_types_case(out, "int" + std::to_string(w) + ".arith_seed" + std::to_string(seed), std::move(s), check);
    }
}

}  // namespace

void add_types_narrow_storage_cases(CaseList& out);  // cases_types_storage.cpp

void add_types_narrow_cases(CaseList& out) {
    add_narrow_cases(out, 16);
    add_narrow_cases(out, 8);
    add_types_narrow_storage_cases(out);
}

}  // namespace tilevk::cts
