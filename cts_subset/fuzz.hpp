// tilevk-cts --fuzz MINUTES: fuzzing that keeps running. From a start seed (by default derived from the date and
// printed, so any failure can be reproduced), seed after seed until the time or the seed budget is spent:
//   the random differential scene random.seed_N (tilevk against lavapipe, byte for byte),
//   the extreme-vertex scene extreme.random.seed_N (byte for byte, or the exact answer where lavapipe is wrong),
//   the random compute shader random.compute.seed_N (byte for byte),
//   and a SPIR-V mutation of seed N of random.seed_N's shaders, created and drawn on tilevk alone (a clean error or
//   a frame; never a crash or a hang: the last "fuzz: spirv seed N" line names the culprit if the process dies).
// A failing scene is minimised (draws / triangles dropped while it still fails) and reported with the command that
// reproduces it; tools/run_main.sh runs a window every time the main job runs, CI a fixed one (meson cts_fuzz_window).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "case.hpp"
#include "results.hpp"
#include "vk_context.hpp"

namespace tilevk::cts {

struct FuzzConfig {
    double minutes = 0;       // time budget
    uint32_t first_seed = 0;  // 0: date_seed()
    uint32_t max_seeds = 0;   // 0: until the time is up
    std::string log;          // failures are appended here too (one reproduction line each)
};

// The first seed of today's window: days since 1970-01-01 (UTC) times 10000.
uint32_t date_seed();

// `run` judges one case as the runner does (both devices); `open_tilevk` opens a fresh device under test for the
// SPIR-V mutations (a mutation may loop forever and lose its device; the next one gets a new device). Returns the
// number of failures.
int run_fuzz(const FuzzConfig& cfg, const std::function<CaseResult(const Case&)>& run,
             const std::function<bool(DeviceContext&)>& open_tilevk, const std::function<void(DeviceContext&)>& close);

}  // namespace tilevk::cts
