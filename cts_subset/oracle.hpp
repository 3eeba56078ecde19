// Coverage oracle: rast/'s reference method (brute-force 64-bit per-sample coverage) run on a case's triangles,
// then every pixel of the device's colour plane judged against it. Independent of shading: only for scenes whose
// image is a pure function of coverage (see oracle_coverage for the domain).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "judge.hpp"
#include "scene.hpp"

namespace tilevk::cts {

// Per-pixel sample coverage (bit s = sample s, union over every triangle of every draw), the colour every covered
// pixel must have and the clear colour (RGBA8 words, R in the low byte).
struct OracleCoverage {
    uint32_t width = 0, height = 0;
    int samples = 1;
    std::vector<uint8_t> mask;
    uint32_t draw_rgba = 0, clear_rgba = 0;
    uint64_t triangles = 0;  // triangles handed to the oracle (before culling)
    // Counting scenes (Frag::kCount / kFacing with ONE,ONE additive blending, 1x only): per-pixel number of
    // front- and back-facing triangles covering the pixel; the expected pixel is clear + count per channel.
    Frag counting = Frag::kColor;
    std::vector<uint16_t> front, back;
};

// Empty string: `out` holds the oracle's coverage. Else why the scene is outside the domain: the colour must be
// RGBA8 UNORM at 1x or 4x, every draw a FILL triangle topology with Frag::kColor, no blending (or, at 1x, every draw
// Frag::kCount or every draw kFacing with ONE,ONE additive blending), full write mask, no
// depth/stencil test, no alpha-to-coverage, one colour for every vertex (components 0 or 1 unless flat), and no
// vertex of any assembled triangle needing clipping (non-zero clip mask: the clipper makes new vertices and
// reorders them, which the oracle does not model), and every window coordinate within rast's range.
std::string oracle_coverage(const Scene& scene, OracleCoverage& out);

// Judges a colour plane: a pixel with every sample covered must be draw_rgba, with none the clear colour; at 4x a
// partly covered pixel (a resolved mix) is not judged. Empty on agreement, else the count of disagreeing pixels
// and the first one.
std::string oracle_judge(const OracleCoverage& cov, const std::vector<Plane>& planes);

// Both together, in the hook's shape (set_coverage_oracle(rast_reference_oracle)).
OracleVerdict rast_reference_oracle(const Scene& scene, const std::vector<Plane>& planes);

}  // namespace tilevk::cts
