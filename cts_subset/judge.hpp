// Judging: byte comparison against the reference device, and independent checks that need no reference.
// Everything here is pure (no device), so tests/cts_subset can exercise it on hand-made planes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scene.hpp"

namespace tilevk::cts {

struct PlaneDiff {
    std::string plane;
    uint64_t differing = 0;  // pixels with any differing byte
    uint64_t total = 0;
    double max_error = 0;  // largest per-channel difference in the format's units (unorm8 steps, D16 steps, ...)
    std::string first;     // the first differing pixel: "(x,y) ours v0,v1,.. reference v0,v1,.." in format units
    std::string problem;   // non-empty when the planes cannot be compared (size/format mismatch)
};

PlaneDiff compare_planes(const Plane& ours, const Plane& ref);

// RGBA8 visualisation of a plane (depth/stencil become grey) and of the differences (red where they differ).
std::vector<uint8_t> to_rgba8(const Plane& p);
std::vector<uint8_t> diff_rgba8(const Plane& ours, const Plane& ref);

// An independent check returns an empty string on success, else what is wrong (first offending pixel first).
using Check = std::function<std::string(const std::vector<Plane>& planes)>;

// Channel `ch` of an RGBA8 colour plane counts coverage in unorm8 steps (additive ONE,ONE blending of 1/255):
// every pixel must be 0 or 1 (no pixel drawn twice), and pixels inside `must_cover` (x0,y0,x1,y1; empty = none)
// must be exactly 1 (no pixel missed).
Check exactly_once(int ch, int x0 = 0, int y0 = 0, int x1 = 0, int y1 = 0);
// Every pixel's channel `ch` count is even: a ray through a closed (watertight) mesh crosses it an even number of
// times, so with culling off every pixel is covered an even number of times.
Check even_coverage(int ch);
// Every pixel of the colour plane is one of `palette` (RGBA8 words, R in the low byte).
Check palette_only(const std::vector<uint32_t>& palette);
// The colour plane at (x,y) is exactly `rgba`.
Check pixel_is(int x, int y, uint32_t rgba);
// Analytic coverage, as the CTS triangle verifier does with its fuzz band: every pixel whose centre lies inside some
// triangle of the scene by more than `margin` pixels must differ from the clear colour, and every pixel farther than
// `margin` outside all of them must equal it. Needs filled triangle topologies, no culling, the full-target
// viewport, and positions inside the clip volume (window x = (x/w + 1) * width / 2).
Check coverage_band(const Scene& scene, float margin);
// All checks in order; the first failure wins.
Check all_of(const std::vector<Check>& checks);

// Hook for an independent coverage oracle (oracle.hpp: rast/'s reference method), run on every case's scene
// and each device's planes. `applies` false: the case is outside the oracle's domain (`note` says why).
struct OracleVerdict {
    bool applies = false;
    std::string note;   // why not applicable, or what was checked
    std::string error;  // non-empty: the planes disagree with the oracle
};
using CoverageOracle = std::function<OracleVerdict(const Scene& scene, const std::vector<Plane>& planes)>;
void set_coverage_oracle(CoverageOracle oracle);
const CoverageOracle& coverage_oracle();

}  // namespace tilevk::cts
