#include "fuzz.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>

#include "glsl.hpp"
#include "render.hpp"
#include "spirv_mutator.hpp"

namespace tilevk::cts {
namespace {

using Clock = std::chrono::steady_clock;

struct Env {
    const char* name;
    explicit Env(const char* n, const std::string& value) : name(n) { setenv(n, value.c_str(), 1); }
    ~Env() { unsetenv(name); }
};

std::string hex(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%x", v);
    return buf;
}

// Drops parts (bits of `mask`, read by the scene builder from `knob`) while the case still fails.
uint32_t minimise(const char* knob, uint32_t parts, const std::function<Case()>& make,
                  const std::function<CaseResult(const Case&)>& run) {
    uint32_t mask = parts >= 32 ? ~0u : (1u << parts) - 1;
    for (uint32_t i = 0; i < parts && i < 32; ++i) {
        const uint32_t trial = mask & ~(1u << i);
        if (trial == 0) continue;
        const Env e(knob, hex(trial));
        if (run(make()).status == Status::kFail) mask = trial;
    }
    return mask;
}

void report(const FuzzConfig& cfg, const std::string& line) {
    std::printf("fuzz: FAIL %s\n", line.c_str());
    std::fflush(stdout);
    if (cfg.log.empty()) return;
    if (FILE* f = std::fopen(cfg.log.c_str(), "a")) {
        std::fprintf(f, "%s\n", line.c_str());
        std::fclose(f);
    }
}

// One SPIR-V mutation: random.seed_N's first draw with one of its shaders mutated (seeded by N), on tilevk.
// Returns false when the device was lost (a mutated loop that never ends).
bool spirv_mutation(uint32_t seed, DeviceContext& ctx) {
    Scene s = random_seed_case(seed).scene();
    if (s.draws.empty()) return true;
    s.draws.resize(1);
    Draw& d = s.draws[0];
    std::mt19937 rng(seed);
    const bool vertex = rng() & 1;
    std::vector<uint32_t> spirv = vertex ? compile_glsl(Stage::kVertex, vertex_source(d))
                                         : compile_glsl(Stage::kFragment, fragment_source(d, true));
    spirv = fuzz::mutate(spirv, rng);
    if (rng() % 4 == 0 && spirv.size() > 6) spirv = fuzz::mutate(spirv, rng);
    (vertex ? d.vertex_spirv : d.fragment_spirv) = spirv;
    try {
        render(ctx, s, 0);
    } catch (const std::exception& e) {
        // A clean refusal (or a lost device) is what a mutated module may give.
        return std::string(e.what()).find("VK_ERROR_DEVICE_LOST") == std::string::npos;
    }
    return true;
}

}  // namespace

uint32_t date_seed() {
    return uint32_t(std::time(nullptr) / 86400) * 10000u;
}

int run_fuzz(const FuzzConfig& cfg, const std::function<CaseResult(const Case&)>& run,
             const std::function<bool(DeviceContext&)>& open_tilevk, const std::function<void(DeviceContext&)>& close) {
    const uint32_t first = cfg.first_seed ? cfg.first_seed : date_seed();
    std::printf("fuzz: seeds from %u (%s), %.1f minutes%s\n", first, cfg.first_seed ? "given" : "from the date",
                cfg.minutes, cfg.max_seeds ? (", at most " + std::to_string(cfg.max_seeds) + " seeds").c_str() : "");
    std::fflush(stdout);
    const auto end = Clock::now() + std::chrono::duration<double, std::ratio<60>>(cfg.minutes);
    DeviceContext spirv_ctx;
    bool have_spirv_ctx = false;
    int failures = 0;
    uint32_t n = 0;
    for (uint32_t seed = first; Clock::now() < end && (cfg.max_seeds == 0 || n < cfg.max_seeds); ++seed, ++n) {
        const Case rc = random_seed_case(seed);
        if (const CaseResult r = run(rc); r.status == Status::kFail) {
            ++failures;
            const uint32_t draws = uint32_t(rc.scene().draws.size());
            const uint32_t mask = minimise(
                "TILEVK_CTS_RANDOM_DRAWS", draws, [seed] { return random_seed_case(seed); }, run);
            report(cfg, rc.name + ": " + r.reason + " | TILEVK_CTS_RANDOM_SEEDS=" + std::to_string(seed) +
                            ":1 TILEVK_CTS_RANDOM_DRAWS=" + hex(mask) + " tilevk-cts --filter " + rc.name);
        }
        const Case ec = extreme_seed_case(seed);
        if (const CaseResult r = run(ec); r.status == Status::kFail) {
            ++failures;
            const uint32_t tris = uint32_t(ec.scene().draws[0].vertices.size() / 3);
            const uint32_t mask = minimise(
                "TILEVK_CTS_EXTREME_KEEP", tris, [seed] { return extreme_seed_case(seed); }, run);
            report(cfg, ec.name + ": " + r.reason + " | TILEVK_CTS_EXTREME_SEEDS=" + std::to_string(seed) +
                            ":1 TILEVK_CTS_EXTREME_KEEP=" + hex(mask) +
                            " TILEVK_CTS_EXTREME_DUMP=1 tilevk-cts --filter " + ec.name);
        }
        // A compute shader is one dispatch: no part to drop, the dump prints its GLSL.
        const Case cc = random_compute_seed_case(seed);
        if (const CaseResult r = run(cc); r.status == Status::kFail) {
            ++failures;
            report(cfg, cc.name + ": " + r.reason + " | TILEVK_CTS_RANDOM_COMPUTE_SEEDS=" + std::to_string(seed) +
                            ":1 TILEVK_CTS_RANDOM_DUMP=1 tilevk-cts --filter " + cc.name);
        }
        if (!have_spirv_ctx && !(have_spirv_ctx = open_tilevk(spirv_ctx))) {
            ++failures;
            report(cfg, "spirv seed " + std::to_string(seed) + ": no tilevk device to run mutations on");
            break;
        }
        std::printf("fuzz: spirv seed %u\n", seed);
        std::fflush(stdout);
        if (!spirv_mutation(seed, spirv_ctx)) {  // lost: the next mutation gets a new device
            close(spirv_ctx);
            have_spirv_ctx = false;
        }
    }
    if (have_spirv_ctx) close(spirv_ctx);
    std::printf("fuzz: %u seeds (%u..%u): %d failure(s)\n", n, first, first + n - (n ? 1 : 0), failures);
    return failures;
}

}  // namespace tilevk::cts
