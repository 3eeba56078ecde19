// quirks.transcendental.*: the GLSL.std450 ops lavapipe evaluates with gallivm's polynomial approximations (exp2,
// log2, pow, sin, cos) and those NIR builds from them (exp, log, tan, sinh, cosh), over a few thousand inputs each:
// specials (±0, denormals, ±Inf, NaNs), exponents over the whole float range, values near 0 and 1, the reduction
// points of sin/cos, huge arguments and, for pow, the specular exponents of lit scenes. Every result word is judged
// byte for byte with lavapipe; the check here holds what is known without gallivm: exact powers of two, the
// special values gallivm defines, and closeness to libm where the approximation is accurate.
#include <cmath>
#include <limits>

#include "compute_case.hpp"
#include "rng.hpp"

namespace tilevk::cts {
namespace {

constexpr uint32_t kCount = 4096;  // inputs per op: 64 workgroups of 64

float fl(uint32_t bits) {
    return std::bit_cast<float>(bits);
}

// Specials every op sees, then random words over every exponent, then `ranged` values in [lo, hi].
std::vector<float> inputs(uint32_t seed, float lo, float hi) {
    std::vector<float> v = {0.0f,
                            -0.0f,
                            fl(1),
                            fl(0x80000001u),
                            fl(0x007fffffu),
                            fl(0x807fffffu),
                            std::numeric_limits<float>::min(),
                            -std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max(),
                            INFINITY,
                            -INFINITY,
                            fl(0x7fc00000u),
                            fl(0xffc00000u),
                            fl(0x7fc12345u),
                            1.0f,
                            -1.0f,
                            0.5f,
                            2.0f,
                            std::nextafter(1.0f, 2.0f),
                            std::nextafter(1.0f, 0.0f),
                            128.0f,
                            -127.0f,
                            127.99999f,
                            -126.99999f,
                            -126.5f,
                            -150.0f,
                            3.14159265f,
                            1.57079633f,
                            0.78539816f,
                            1e8f,
                            -1e8f,
                            1e20f,
                            3e38f,
                            8388608.5f,
                            16777216.0f};
    for (int k = -149; k <= 127; k += 3) v.push_back(std::ldexp(1.0f, k));
    for (int k = -130; k <= 130; ++k) v.push_back(float(k));
    for (int k = -40; k <= 40; ++k) v.push_back(float(k) * 0.78539816f);  // the octants of sin/cos
    Rng r(seed);
    while (v.size() < kCount / 2) v.push_back(fl((r.next() & 0x80000000u) | ((r.below(255)) << 23) | (r.next() >> 9)));
    while (v.size() < kCount * 7 / 8) v.push_back(r.range(lo, hi));
    while (v.size() < kCount) v.push_back(1.0f + r.range(-1e-3f, 1e-3f));
    return v;
}

// pow's exponents: specular powers with bases in (0, 1], then random pairs, then the specials against each other.
void pow_inputs(std::vector<float>& x, std::vector<float>& y) {
    const float powers[] = {1,  2,  3,   4,   5,   8,   10,   16,   20,       32, 40, 50,
                            64, 80, 100, 128, 200, 256, 0.5f, 2.2f, 1 / 2.2f, 0,  -1, -2};
    Rng r(11);
    for (float p : powers)
        for (int i = 0; i < 100; ++i) {
            x.push_back(i < 4 ? float(i) / 3 : r.unit());
            y.push_back(p);
        }
    // Two NaNs meeting in log2(x)·y: log2 of a negative or NaN base is NaN, and so is y; which NaN's bits win is
    // the order of the multiplication's operands (a NaN base is selected away to 0 after).
    const float bases[] = {-2.0f, -0.0f - 1e-30f, -INFINITY, fl(0xff812345u)};
    const float nans[] = {fl(0x7fc12345u), fl(0xffc00000u), fl(0x7fa00001u), fl(0xffbedcbau)};
    for (float b : bases)
        for (float n : nans) {
            x.push_back(b);
            y.push_back(n);
        }
    const std::vector<float> s = inputs(12, -20.0f, 20.0f);
    for (size_t i = 0; i < 48; ++i)
        for (size_t j = 0; j < 16; ++j) {
            x.push_back(s[i]);
            y.push_back(s[j * 3]);
        }
    while (x.size() < kCount) {
        x.push_back(r.chance(0.5f) ? r.range(0.0f, 4.0f) : fl(r.below(0x7f800000u)));
        y.push_back(r.range(-40.0f, 40.0f));
    }
}

// What a result must be, when known without gallivm: an exact value (NaN: any NaN), or libm's within
// max(rel·|libm|, abs).
struct Want {
    bool known = false;
    float exact = 0.0f;
    double approx = 0.0, rel = 0.0, abs = 0.0;
};
using Rule = Want (*)(float x, float y);

Want exactly(float v) {
    return {true, v, 0.0, -1.0, 1.0};
}
Want near(double v, double rel, double abs = 0.0) {
    return {true, 0.0f, v, rel, abs};
}
bool is_int(float x) {
    return std::isfinite(x) && x == std::floor(x);
}

Want exp2_rule(float x, float) {
    if (std::isnan(x)) return exactly(NAN);
    if (x >= 128.0f) return exactly(INFINITY);
    if (x <= -127.0f) return exactly(0.0f);
    if (is_int(x)) return exactly(std::ldexp(1.0f, int(x)));
    return std::fabs(x) < 120 ? near(std::exp2(double(x)), 1e-6) : Want{};
}
Want log2_rule(float x, float) {
    if (std::isnan(x) || x < 0.0f) return exactly(NAN);
    if (x == 0.0f) return exactly(-INFINITY);
    if (std::isinf(x)) return exactly(INFINITY);
    int e = 0;
    if (std::frexp(x, &e) == 0.5f && x >= std::numeric_limits<float>::min()) return exactly(float(e - 1));
    return x >= std::numeric_limits<float>::min() ? near(std::log2(double(x)), 1e-7, 1e-6) : Want{};
}
Want pow_rule(float x, float y) {
    if (x == 0.0f || std::isnan(x)) return exactly(0.0f);  // gallivm: 0 wherever x == 0 (unordered)
    if (x < 0.0f) return exactly(NAN);
    int e = 0;
    if (std::frexp(x, &e) == 0.5f && is_int(y) && std::fabs(y) < 8 && x >= 1e-30f && x <= 1e30f) {
        const double k = double(e - 1) * y;
        if (k > -126 && k < 127) return exactly(std::ldexp(1.0f, int(k)));
    }
    const double l = std::log2(double(x)) * y;
    // log2's absolute error (about 1e-7) is scaled by y
    const bool accurate = std::isfinite(l) && std::fabs(l) < 100 && std::fabs(y) <= 300 && x >= 1e-30f;
    return accurate ? near(std::pow(double(x), y), 1e-6 * (4 + std::fabs(y) + std::fabs(l))) : Want{};
}
Want exp_rule(float x, float) {
    if (std::isnan(x)) return exactly(NAN);
    return std::fabs(x) < 80 ? near(std::exp(double(x)), 2e-6 * (1 + std::fabs(x))) : Want{};
}
Want log_rule(float x, float) {
    if (std::isnan(x) || x < 0.0f) return exactly(NAN);
    if (x == 0.0f) return exactly(-INFINITY);
    return x >= std::numeric_limits<float>::min() && std::isfinite(x) ? near(std::log(double(x)), 1e-7, 1e-6) : Want{};
}
Want sin_rule(float x, float) {
    if (!std::isfinite(x)) return exactly(NAN);
    if (x == 0.0f) return exactly(x);
    return std::fabs(x) < 100 ? near(std::sin(double(x)), 0.0, 1e-6) : Want{};
}
Want cos_rule(float x, float) {
    if (!std::isfinite(x)) return exactly(NAN);
    if (x == 0.0f) return exactly(1.0f);
    return std::fabs(x) < 100 ? near(std::cos(double(x)), 0.0, 1e-6) : Want{};
}
Want tan_rule(float x, float) {
    if (!std::isfinite(x)) return exactly(NAN);
    return std::fabs(x) < 1.5 ? near(std::tan(double(x)), 1e-5) : Want{};
}
Want sinh_rule(float x, float) {
    if (std::isnan(x)) return exactly(NAN);
    return std::fabs(x) > 0.5 && std::fabs(x) < 80 ? near(std::sinh(double(x)), 1e-5 * (1 + std::fabs(x))) : Want{};
}
Want cosh_rule(float x, float) {
    if (std::isnan(x)) return exactly(NAN);
    return std::fabs(x) < 80 ? near(std::cosh(double(x)), 1e-5 * (1 + std::fabs(x))) : Want{};
}

std::string judge(const Want& w, float got) {
    if (!w.known) return {};
    if (w.rel < 0) {
        if (std::isnan(w.exact) ? std::isnan(got) : fbits(got) == fbits(w.exact)) return {};
        return "expected " + std::to_string(w.exact);
    }
    if (std::fabs(double(got) - w.approx) <= std::max(w.rel * std::fabs(w.approx), w.abs)) return {};
    return "expected about " + std::to_string(w.approx);
}

struct Op {
    const char* name;
    const char* expr;
    Rule rule;
    float lo, hi;  // the ranged inputs
};

void add_op(CaseList& out, const Op& op) {
    std::vector<float> x, y;
    if (std::string(op.name) == "pow")
        pow_inputs(x, y);
    else
        x = inputs(uint32_t(std::hash<std::string>{}(op.name)), op.lo, op.hi);
    y.resize(kCount, 1.0f);
    ComputeSpec s;
    s.shaders = {glsl_header(64) +
                 "layout(std430, binding=0) buffer X { float x[]; };\n"
                 "layout(std430, binding=1) buffer Y { float y[]; };\n"
                 "layout(std430, binding=2) buffer O { float o[]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x; float a = x[i], b = y[i]; o[i] = " +
                 std::string(op.expr) + "; }\n"};
    std::vector<uint32_t> xw(kCount), yw(kCount);
    for (uint32_t i = 0; i < kCount; ++i) {
        xw[i] = fbits(x[i]);
        yw[i] = fbits(y[i]);
    }
    s.buffers = {{xw, false, false}, {yw, false, false}, {std::vector<uint32_t>(kCount, kMarker)}};
    s.steps = {dispatch(0, kCount / 64)};
    auto spec = std::make_shared<ComputeSpec>(std::move(s));
    Case c;
    c.name = std::string("quirks.transcendental.") + op.name;
    c.scene = [spec] { return compute_scene(*spec); };
    c.check = [x, y, rule = op.rule](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> got = buffer_words(planes, 2);
        if (got.size() != kCount) return "buffer2 has the wrong size";
        for (uint32_t i = 0; i < kCount; ++i) {
            const std::string e = judge(rule(x[i], y[i]), fl(got[i]));
            if (!e.empty())
                return "word " + std::to_string(i) + " (x=" + std::to_string(x[i]) + ", y=" + std::to_string(y[i]) +
                       ") is " + std::to_string(fl(got[i])) + ", " + e;
        }
        return {};
    };
    out.push_back(std::move(c));
}

// pow with a constant exponent 1, 2, 4 or 0.5 and with base 2: NIR rewrites some of these (a, a·a, (a·a)·(a·a),
// exp2(b)) before gallivm sees them. Four results per input; the check: close to the true power where accurate,
// exact for 2^integer.
void add_pow_constants(CaseList& out) {
    const std::vector<float> x = inputs(21, -8.0f, 8.0f);
    ComputeSpec s;
    s.shaders = {glsl_header(64) +
                 "layout(std430, binding=0) buffer X { float x[]; };\n"
                 "layout(std430, binding=1) buffer O { vec4 o[]; };\n"
                 "void main() { uint i = gl_GlobalInvocationID.x; float a = x[i];\n"
                 "  o[i] = vec4(pow(a, 1.0), pow(a, 2.0), pow(a, 4.0) + pow(a, 0.5), pow(2.0, a)); }\n"};
    std::vector<uint32_t> xw(kCount);
    for (uint32_t i = 0; i < kCount; ++i) xw[i] = fbits(x[i]);
    s.buffers = {{xw, false, false}, {std::vector<uint32_t>(kCount * 4, kMarker)}};
    s.steps = {dispatch(0, kCount / 64)};
    auto spec = std::make_shared<ComputeSpec>(std::move(s));
    Case c;
    c.name = "quirks.transcendental.pow_constant";
    c.scene = [spec] { return compute_scene(*spec); };
    c.check = [x](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> got = buffer_words(planes, 1);
        if (got.size() != kCount * 4) return "buffer1 has the wrong size";
        for (uint32_t i = 0; i < kCount; ++i) {
            const float a = x[i];
            const bool moderate = a >= 1e-6f && a <= 1e6f;
            const Want w[4] = {moderate ? near(a, 1e-5) : Want{}, moderate ? near(double(a) * a, 1e-5) : Want{},
                               moderate ? near(std::pow(double(a), 4.0) + std::sqrt(double(a)), 1e-5) : Want{},
                               exp2_rule(a, 1.0f)};
            for (int k = 0; k < 4; ++k) {
                const std::string e = judge(w[k], fl(got[i * 4 + k]));
                if (!e.empty()) return "word " + std::to_string(i * 4 + k) + " (x=" + std::to_string(a) + ") " + e;
            }
        }
        return {};
    };
    out.push_back(std::move(c));
}

}  // namespace

void add_transcendental_cases(CaseList& out) {
    add_pow_constants(out);
    const Op ops[] = {{"pow", "pow(a, b)", pow_rule, 0, 1},    {"exp2", "exp2(a)", exp2_rule, -130, 130},
                      {"log2", "log2(a)", log2_rule, 0, 4},    {"exp", "exp(a)", exp_rule, -90, 90},
                      {"log", "log(a)", log_rule, 0, 100},     {"sin", "sin(a)", sin_rule, -20, 20},
                      {"cos", "cos(a)", cos_rule, -20, 20},    {"tan", "tan(a)", tan_rule, -3, 3},
                      {"sinh", "sinh(a)", sinh_rule, -20, 20}, {"cosh", "cosh(a)", cosh_rule, -20, 20}};
    for (const Op& op : ops) add_op(out, op);
}

}  // namespace tilevk::cts
