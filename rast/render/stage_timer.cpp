#include "rast/render/stage_timer.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

namespace tilevk::rast::render {
namespace detail {
namespace {
bool env_on() {
    const char* e = std::getenv("TILEVK_STAGE_TIMES");
    return e && *e && std::strcmp(e, "0") != 0;
}
}  // namespace
const bool g_stage_timers = env_on();
}  // namespace detail

namespace {

std::atomic<uint64_t> g_totals[kNumStages];

uint64_t now_ns() {
    return uint64_t(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count());
}

// Ticks per nanosecond, from the tick and clock readings since the process started (no calibration loop: the
// ratio sharpens as the process runs; the first frames are the benchmark's warm-up).
struct Calibration {
    uint64_t ticks0 = stage_ticks(), ns0 = now_ns();
    double ticks_per_ns() const {
        const uint64_t dn = now_ns() - ns0, dt = stage_ticks() - ticks0;
        return dn > 0 && dt > 0 ? double(dt) / double(dn) : 1.0;
    }
};
const Calibration g_calibration;

}  // namespace

uint64_t stage_ticks_portable() {
    return now_ns();
}

uint64_t steady_ns() {
    return now_ns();
}

uint64_t thread_cpu_ns() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}

double ticks_to_ns(uint64_t ticks) {
    return double(ticks) / g_calibration.ticks_per_ns();
}

void add_stage_ns(Stage stage, uint64_t ns) {
    g_totals[static_cast<int>(stage)].fetch_add(ns, std::memory_order_relaxed);
}

std::array<double, kNumStages> take_stage_times() {
    std::array<double, kNumStages> out{};
    for (int s = 0; s < kNumStages; ++s) out[s] = double(g_totals[s].exchange(0, std::memory_order_relaxed));
    return out;
}

const char* stage_times_path() {
    return stage_timers_on() ? std::getenv("TILEVK_STAGE_TIMES") : nullptr;
}

void report_stage_times() {
    const char* path = stage_times_path();
    if (!path) return;
    const std::array<double, kNumStages> ns = take_stage_times();
    std::FILE* f = std::fopen(path, "a");
    if (!f) return;
    std::fputc('{', f);
    for (int s = 0; s < kNumStages; ++s) std::fprintf(f, "%s\"%s\": %.0f", s ? ", " : "", kStageNames[s], ns[s]);
    std::fputs("}\n", f);
    std::fclose(f);
}

}  // namespace tilevk::rast::render
