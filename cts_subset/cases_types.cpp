// types.*: 64-bit integers and doubles (shaderInt64, shaderFloat64) in compute and fragment shaders, every result
// buffer compared byte for byte with the reference. Inputs are edge values (zeros, ±1, the int64 limits, 2^32
// neighbours, denormals, infinities, one NaN, halves for rounding, values past every conversion's range) and random
// bit patterns; the integer results are also computed here from the definitions (wrap-around arithmetic, shift
// counts masked to 0..63, lavapipe's division by zero: gallivm do_int_divide / do_int_mod) as an independent check.
#include <bit>
#include <cmath>
#include <limits>

#include "compute_case.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

void push64(std::vector<uint32_t>& w, uint64_t v) {
    w.push_back(uint32_t(v));
    w.push_back(uint32_t(v >> 32));
}

constexpr uint32_t kLanes = 64;  // pairs of inputs per case: 4 workgroups of 16

std::vector<uint64_t> double_inputs(uint32_t seed) {
    const double edges[] = {0.0,
                            -0.0,
                            1.0,
                            -1.0,
                            0.5,
                            1.5,
                            2.5,
                            -2.5,
                            3.0,
                            0.1,
                            1.0 / 3.0,
                            3.141592653589793,
                            1e308,
                            -1e308,
                            std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::denorm_min(),
                            -4.9e-310,
                            INFINITY,
                            -INFINITY,
                            std::numeric_limits<double>::quiet_NaN(),
                            9007199254740993.0,
                            3e9,
                            -3e9,
                            4.5e9,
                            -2147483648.5,
                            2147483647.75,
                            1e19,
                            -1e19,
                            9223372036854775808.0,
                            18446744073709551616.0,
                            65504.5,
                            1e-40,
                            3.4028235677973366e38};
    std::vector<uint64_t> v;
    for (double e : edges) v.push_back(std::bit_cast<uint64_t>(e));
    Rng r(seed);
    while (v.size() < 2 * kLanes) {
        const uint64_t bits = (uint64_t(r.next()) << 32) | r.next();
        if (r.chance(0.5f)) {  // a moderate exponent: finite products and sums that round
            const uint64_t e = 1023 - 40 + r.below(80);
            v.push_back((bits & 0x800FFFFFFFFFFFFFull) | (e << 52));
        } else if ((bits & 0x7FF0000000000000ull) != 0x7FF0000000000000ull) {  // random bits, one NaN only
            v.push_back(bits);
        }
    }
    // shuffle so that edge values meet each other and random ones
    for (size_t i = v.size(); i-- > 1;) std::swap(v[i], v[r.below(uint32_t(i + 1))]);
    return v;
}

std::vector<uint64_t> int64_inputs(uint32_t seed) {
    const uint64_t edges[] = {0,
                              1,
                              ~0ull,
                              2,
                              3,
                              ~1ull,
                              7,
                              31,
                              32,
                              33,
                              63,
                              64,
                              65,
                              0x7FFFFFFFFFFFFFFFull,
                              0x8000000000000000ull,
                              0xFFFFFFFFull,
                              0x100000000ull,
                              0x100000001ull,
                              0xFFFFFFFF00000000ull,
                              0x80000000ull,
                              0xFFFFFFFF80000000ull,
                              1000000007ull,
                              0x123456789ABCDEF0ull,
                              0xFEDCBA9876543210ull,
                              uint64_t(-1000000000000ll)};
    std::vector<uint64_t> v(std::begin(edges), std::end(edges));
    Rng r(seed);
    while (v.size() < 2 * kLanes) {
        const uint64_t bits = (uint64_t(r.next()) << 32) | r.next();
        const uint32_t shape = r.below(4);  // full width, 32-bit, small, negative small
        v.push_back(shape == 0 ? bits : shape == 1 ? bits >> 32 : shape == 2 ? bits >> 58 : 0 - (bits >> 50));
    }
    for (size_t i = v.size(); i-- > 1;) std::swap(v[i], v[r.below(uint32_t(i + 1))]);
    return v;
}

std::vector<uint32_t> words_of(const std::vector<uint64_t>& v) {
    std::vector<uint32_t> w;
    for (uint64_t x : v) push64(w, x);
    return w;
}

const char* kHeader =
    "#version 450\n"
    "#extension GL_ARB_gpu_shader_int64 : require\n"
    "layout(local_size_x=16) in;\n";

// --- types.float64: arithmetic, GLSL functions, comparisons and conversions of doubles ---

constexpr uint32_t kDoubleResults = 40, kDoubleWords = 24;
const char* kFloat64Body =
    "layout(std430, binding=0) readonly buffer In { double a[]; } inp;\n"
    "layout(std430, binding=1) buffer Out { double r[]; } o;\n"
    "layout(std430, binding=2) buffer OutW { uint w[]; } ow;\n"
    "void main() {\n"
    "  uint i = gl_GlobalInvocationID.x;\n"
    "  double x = inp.a[2u * i], y = inp.a[2u * i + 1u];\n"
    "  uint k = i * 40u;\n"
    "  o.r[k + 0u] = x + y; o.r[k + 1u] = x - y; o.r[k + 2u] = x * y; o.r[k + 3u] = x / y;\n"
    "  o.r[k + 4u] = sqrt(abs(x)); o.r[k + 5u] = inversesqrt(abs(y)); o.r[k + 6u] = floor(x);\n"
    "  o.r[k + 7u] = ceil(x); o.r[k + 8u] = trunc(x); o.r[k + 9u] = round(x); o.r[k + 10u] = roundEven(y);\n"
    "  o.r[k + 11u] = fract(x); o.r[k + 12u] = sign(x); o.r[k + 13u] = min(x, y); o.r[k + 14u] = max(x, y);\n"
    "  o.r[k + 15u] = clamp(x, -2.0lf, y); o.r[k + 16u] = mod(x, y); o.r[k + 17u] = -x; o.r[k + 18u] = abs(y);\n"
    "  o.r[k + 19u] = step(x, y); o.r[k + 20u] = smoothstep(-1.0lf, 2.0lf, x); o.r[k + 21u] = fma(x, y, x);\n"
    "  o.r[k + 22u] = mix(x, y, 0.25lf); o.r[k + 23u] = double(float(x)); o.r[k + 24u] = double(int(x));\n"
    "  o.r[k + 25u] = double(uint(y)); o.r[k + 26u] = double(int64_t(x)); o.r[k + 27u] = double(uint64_t(y));\n"
    "  o.r[k + 28u] = double(float(x) * 0.5); o.r[k + 29u] = x * 3.0lf + y;\n"
    "  o.r[k + 30u] = double(i) * 0.1lf; o.r[k + 31u] = double(int(i) - 7) / 3.0lf;\n"
    "  dvec3 v = dvec3(x, y, 1.5lf);\n"
    "  dvec3 c = cross(v, dvec3(y, 0.25lf, x));\n"
    "  o.r[k + 32u] = c.x; o.r[k + 33u] = c.y; o.r[k + 34u] = c.z;\n"
    "  o.r[k + 35u] = dot(v, v); o.r[k + 36u] = length(v.xz); o.r[k + 37u] = distance(v, v.zxy);\n"
    "  o.r[k + 38u] = packDouble2x32(unpackDouble2x32(x).yx); o.r[k + 39u] = double(int64_t(i) - 40l);\n"
    "  uint m = i * 24u;\n"
    "  ow.w[m + 0u] = uint(x < y) | uint(x <= y) << 1 | uint(x > y) << 2 | uint(x >= y) << 3 | uint(x == y) << 4 |\n"
    "      uint(x != y) << 5 | uint(isnan(x)) << 6 | uint(isinf(x)) << 7 | uint(isnan(y)) << 8 | uint(isinf(y)) << 9;\n"
    "  ow.w[m + 1u] = floatBitsToUint(float(x)); ow.w[m + 2u] = floatBitsToUint(float(y));\n"
    "  ow.w[m + 3u] = uint(int(x)); ow.w[m + 4u] = uint(int(y)); ow.w[m + 5u] = uint(x); ow.w[m + 6u] = uint(y);\n"
    "  uint64_t sx = uint64_t(int64_t(x)), ux = uint64_t(x), uy = uint64_t(y);\n"
    "  ow.w[m + 7u] = uint(sx); ow.w[m + 8u] = uint(sx >> 32); ow.w[m + 9u] = uint(ux); ow.w[m + 10u] = uint(ux >> "
    "32);\n"
    "  ow.w[m + 11u] = uint(uy); ow.w[m + 12u] = uint(uy >> 32);\n"
    "  uvec2 b = unpackDouble2x32(x); ow.w[m + 13u] = b.x; ow.w[m + 14u] = b.y;\n"
    "  ow.w[m + 15u] = floatBitsToUint(float(uint64_t(sx))); ow.w[m + 16u] = floatBitsToUint(float(int64_t(sx)));\n"
    "  ow.w[m + 17u] = floatBitsToUint(float(x * y)); ow.w[m + 18u] = uint(x * y < x + y);\n"
    "  ow.w[m + 19u] = uint(int64_t(float(y))); ow.w[m + 20u] = uint(uint64_t(float(y)) >> 32);\n"
    "  dvec2 s = x < y ? dvec2(x, 1.0lf) : dvec2(y, 2.0lf); ow.w[m + 21u] = uint(s.y) + uint(s.x == x) * 4u;\n"
    "  ow.w[m + 22u] = uint(any(lessThan(dvec2(x, y), dvec2(0.0lf)))); ow.w[m + 23u] = 0x600du;\n"
    "}\n";

void add_float64_cases(CaseList& out) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        ComputeSpec s;
        s.shaders = {std::string(kHeader) + kFloat64Body};
        s.buffers = {{words_of(double_inputs(seed))},
                     {std::vector<uint32_t>(kLanes * kDoubleResults * 2, kMarker)},
                     {std::vector<uint32_t>(kLanes * kDoubleWords, kMarker)}};
        s.steps = {dispatch(0, kLanes / 16)};
        // every invocation ran: its last word is the marker 0x600d
        Check check = [](const std::vector<Plane>& planes) -> std::string {
            const std::vector<uint32_t> w = buffer_words(planes, 2);
            for (uint32_t i = 0; i < kLanes; ++i)
                if (w.size() != kLanes * kDoubleWords || w[i * kDoubleWords + 23] != 0x600du)
                    return "invocation " + std::to_string(i) + " did not finish";
            return {};
        };
        add_types_case(out, "float64.arith_seed" + std::to_string(seed), std::move(s), check);
    }
}

// --- types.int64: arithmetic, bit operations, shifts, comparisons and conversions of 64-bit integers ---

constexpr uint32_t kIntResults = 28;
const char* kInt64Body =
    "layout(std430, binding=0) readonly buffer In { uint64_t a[]; } inp;\n"
    "layout(std430, binding=1) buffer Out { uint64_t r[]; } o;\n"
    "void main() {\n"
    "  uint i = gl_GlobalInvocationID.x;\n"
    "  uint64_t x = inp.a[2u * i], y = inp.a[2u * i + 1u];\n"
    "  int64_t sx = int64_t(x), sy = int64_t(y);\n"
    "  uint k = i * 28u;\n"
    "  o.r[k + 0u] = x + y; o.r[k + 1u] = x - y; o.r[k + 2u] = x * y; o.r[k + 3u] = x / y;\n"
    "  o.r[k + 4u] = x % y; o.r[k + 5u] = uint64_t(sx / sy); o.r[k + 6u] = uint64_t(sx % sy);\n"
    "  o.r[k + 7u] = x << (y & 63ul); o.r[k + 8u] = x >> (y & 63ul); o.r[k + 9u] = uint64_t(sx >> (y & 63ul));\n"
    "  o.r[k + 10u] = x << 40; o.r[k + 11u] = uint64_t(sx >> 33); o.r[k + 12u] = x & y; o.r[k + 13u] = x | y;\n"
    "  o.r[k + 14u] = x ^ y; o.r[k + 15u] = ~x; o.r[k + 16u] = uint64_t(-sx); o.r[k + 17u] = uint64_t(abs(sx));\n"
    "  o.r[k + 18u] = uint64_t(sign(sx)); o.r[k + 19u] = min(x, y); o.r[k + 20u] = uint64_t(max(sx, sy));\n"
    "  o.r[k + 21u] = uint64_t(clamp(sx, -5l, 1l << 40)); o.r[k + 22u] = uint64_t(int(x)) ^ uint64_t(uint(y));\n"
    "  o.r[k + 23u] = uint64_t(x < y) | uint64_t(sx < sy) << 1 | uint64_t(x == y) << 2 | uint64_t(sx >= sy) << 3 |\n"
    "      uint64_t(x > y) << 4 | uint64_t(x != y) << 5 | uint64_t(sx <= sy) << 6 | uint64_t(x >= y) << 7;\n"
    "  o.r[k + 24u] = uint64_t(int64_t(int(sx)));\n"
    "  o.r[k + 25u] = doubleBitsToUint64(double(sx) + double(y));\n"
    "  o.r[k + 26u] = uint64_t(floatBitsToUint(float(sx))) | uint64_t(floatBitsToUint(float(y))) << 32;\n"
    "  o.r[k + 27u] = uint64_t(bitCount(uint(x >> 3))) | (packUint2x32(unpackUint2x32(y).yx) << 8);\n"
    "}\n";

uint64_t sdiv(int64_t a, int64_t b) {
    if (b == 0) return 0;
    if (b == -1) return 0 - uint64_t(a);
    return uint64_t(a / b);
}
// GLSL % on signed values is OpSMod, whose sign would be b's; lavapipe 22.3 computes the 64-bit one as srem (the
// sign of a; gallivm do_int_mod), and by 0 all ones. (GLSL leaves % of negative operands undefined.)
uint64_t smod(int64_t a, int64_t b) {
    if (b == 0) return ~0ull;
    if (b == -1) return 0;
    return uint64_t(a % b);
}

// The integer results computed from the definitions (k + 0 .. 21, 23, 24); the rest only against the reference.
std::vector<uint64_t> int64_answer(const std::vector<uint64_t>& in, uint32_t i) {
    const uint64_t x = in[2 * i], y = in[2 * i + 1];
    const auto sx = int64_t(x), sy = int64_t(y);
    const uint32_t n = uint32_t(y & 63);
    return {x + y,
            x - y,
            x * y,
            y ? x / y : ~0ull,
            y ? x % y : ~0ull,
            sdiv(sx, sy),
            smod(sx, sy),
            x << n,
            x >> n,
            uint64_t(sx >> n),
            x << 40,
            uint64_t(sx >> 33),
            x & y,
            x | y,
            x ^ y,
            ~x,
            0 - x,
            sx < 0 ? 0 - x : x,
            uint64_t(sx > 0   ? 1
                     : sx < 0 ? -1
                              : 0),
            std::min(x, y),
            uint64_t(std::max(sx, sy)),
            uint64_t(std::min(std::max(sx, int64_t(-5)), int64_t(1) << 40)),
            0,
            uint64_t(x < y) | uint64_t(sx < sy) << 1 | uint64_t(x == y) << 2 | uint64_t(sx >= sy) << 3 |
                uint64_t(x > y) << 4 | uint64_t(x != y) << 5 | uint64_t(sx <= sy) << 6 | uint64_t(x >= y) << 7,
            uint64_t(int64_t(int32_t(uint32_t(x))))};
}

void add_int64_cases(CaseList& out) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        const std::vector<uint64_t> in = int64_inputs(seed);
        ComputeSpec s;
        s.shaders = {std::string(kHeader) + kInt64Body};
        s.buffers = {{words_of(in)}, {std::vector<uint32_t>(kLanes * kIntResults * 2, kMarker)}};
        s.steps = {dispatch(0, kLanes / 16)};
        Check check = [in](const std::vector<Plane>& planes) -> std::string {
            const std::vector<uint32_t> w = buffer_words(planes, 1);
            if (w.size() != kLanes * kIntResults * 2) return "buffer1 has the wrong size";
            for (uint32_t i = 0; i < kLanes; ++i) {
                const std::vector<uint64_t> want = int64_answer(in, i);
                for (uint32_t r = 0; r < want.size(); ++r) {
                    if (r == 22) continue;
                    const size_t at = (size_t(i) * kIntResults + r) * 2;
                    const uint64_t got = w[at] | uint64_t(w[at + 1]) << 32;
                    if (got != want[r])
                        return "invocation " + std::to_string(i) + " result " + std::to_string(r) + " is " +
                               std::to_string(got) + ", expected " + std::to_string(want[r]);
                }
            }
            return {};
        };
        add_types_case(out, "int64.arith_seed" + std::to_string(seed), std::move(s), check);
    }
}

}  // namespace

void add_types_matrix_cases(CaseList& out);  // cases_types_matrix.cpp

void add_types_cases(CaseList& out) {
    add_float64_cases(out);
    add_int64_cases(out);
    add_types_matrix_cases(out);
}

}  // namespace tilevk::cts
