// Stage timers: where a frame's time goes (vertex shading, clip/setup/bin, coverage, fragment shading,
// depth/blend/store, attachment work, resolve), for the frame benchmark (bench/frame/README.md).
//
// Off unless TILEVK_STAGE_TIMES is set (read once per process). Off, every timing point is one test of a
// process-wide flag that never changes, and nothing is read or written. On, the front end (per draw) and each
// tile count the thread's CPU time (CLOCK_THREAD_CPUTIME_ID, so time the thread spent descheduled on a busy
// machine is not counted); within a tile the split between the core's descent, shading and depth/blend/store comes
// from the time-stamp counter (cheap enough per primitive, sampled per block). Each thread adds nanoseconds to
// process-wide atomic totals once per tile, draw or attachment operation, and `take_stage_times` returns (and
// clears) them. The totals are thread time: stages that run on several worker threads add up all of them.
// Attachment clears/copies and resolves are the submitting thread's wall time.
#pragma once

#include <array>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace tilevk::rast::render {

enum class Stage : uint8_t {
    kVertex,    // vertex fetch and the vertex shader
    kSetup,     // primitive assembly, clip codes, clipping, triangle setup, binning
    kCoverage,  // the 64->16->4 descent (per tile, everything but the fragment stage's own time)
    kShade,     // interpolation and the fragment shader
    // depth/stencil, alpha to coverage, blending, colour stores; and the whole of a square that the fused full-square
    // kernel shades (fragment_square.cpp: its interpolation cannot be timed apart)
    kOutput,
    kAttach,   // load-op clears and staging copies of attachments (icd/)
    kResolve,  // multisample resolve (icd/)
    kCount
};
inline constexpr int kNumStages = static_cast<int>(Stage::kCount);

// Short names, in Stage order (the keys of the benchmark's JSON).
inline constexpr std::array<const char*, kNumStages> kStageNames = {
    "vertex", "setup_bin", "coverage", "shade", "depth_blend_store", "attach", "resolve"};

namespace detail {
extern const bool g_stage_timers;
}

// Whether stage timing is on (TILEVK_STAGE_TIMES set and not "0").
inline bool stage_timers_on() {
    return detail::g_stage_timers;
}

// Nanoseconds of a steady clock (the tick source where there is no time-stamp counter).
uint64_t stage_ticks_portable();

// A tick count (time-stamp counter where there is one, nanoseconds elsewhere).
inline uint64_t stage_ticks() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return stage_ticks_portable();
#endif
}

// The calling thread's CPU time in nanoseconds.
uint64_t thread_cpu_ns();

// Nanoseconds of `ticks` time-stamp-counter ticks (for short intervals).
double ticks_to_ns(uint64_t ticks);

// Adds `ns` to the process-wide total of `stage` (thread-safe).
void add_stage_ns(Stage stage, uint64_t ns);

// The totals since the last call, in nanoseconds, and clears them.
std::array<double, kNumStages> take_stage_times();

// The file named by TILEVK_STAGE_TIMES, or null when stage timing is off.
const char* stage_times_path();

// When stage timing is on: takes the totals and appends them to that file as one JSON line
// {"vertex": ns, "setup_bin": ns, ...} (the driver calls this once per vkQueueSubmit).
void report_stage_times();

// Nanoseconds of the steady clock (long intervals: a time-stamp difference that spans a move to another CPU may
// be off by the CPUs' counter offset on a virtual machine).
uint64_t steady_ns();

// Times one scope (wall time of the calling thread) into `stage` when stage timing is on.
class StageScope {
  public:
    explicit StageScope(Stage stage) : stage_(stage), start_(stage_timers_on() ? steady_ns() : 0) {}
    ~StageScope() {
        if (stage_timers_on()) add_stage_ns(stage_, steady_ns() - start_);
    }
    StageScope(const StageScope&) = delete;
    StageScope& operator=(const StageScope&) = delete;

  private:
    Stage stage_;
    uint64_t start_;
};

}  // namespace tilevk::rast::render
