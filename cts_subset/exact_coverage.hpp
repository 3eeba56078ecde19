// The exact answer for triangles with extreme clip-space vertices: which pixel centres a triangle covers, computed
// from the float inputs with exact integer arithmetic (no rounding anywhere), independently of any rasterizer.
//
// Homogeneous rasterization: for clip-space vertices V0, V1, V2 with (x, y, w) and a pixel centre P = (X, Y, 1) in
// NDC, the point of the triangle that projects to P is sum(a_i V_i) with a_i proportional to the edge function
// E_i(P) = det(V_j, V_k, P) (i, j, k cyclic) divided by D = det(V0, V1, V2). It lies on the triangle (a_i >= 0) and
// in front of the eye (w > 0) exactly when every E_i(P) has the sign of D; its depth is sum(E_i z_i) / sum(E_i w_i),
// which Vulkan's clip volume keeps in [0, 1] (unless depth clamp is on). This holds for any signs of the vertices'
// w, so it also covers triangles crossing w = 0. Every float is an integer times 2^-149, so E_i and the depth
// comparisons are exact in 2048-bit integers. Pixel centres within 1/128 px of an edge (or of the depth range's
// limits) are "on an edge": both drivers snap vertices to 1/256 px and the top-left rule decides ties, so the
// check does not judge them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "judge.hpp"
#include "scene.hpp"

namespace tilevk::cts {

enum class ExactCover : uint8_t { kOutside, kInside, kOnEdge };

// Per pixel centre of a width x height target with the full-target viewport (depth range [0, 1]): whether the
// triangle (clip-space positions, all components finite) covers it. `clip_z`: the z planes 0 <= z <= w apply
// (no depth clamp).
std::vector<ExactCover> exact_triangle_coverage(const float v0[4], const float v1[4], const float v2[4], uint32_t width,
                                                uint32_t height, bool clip_z = true);

// True if every component of the position is finite (the exact answer is defined).
bool finite_position(const float v[4]);

// Coverage of the scene's triangle-list draws (filled, no culling, full viewport, no scissor), pixel by pixel:
// covered by some triangle, by none, or undecided (on an edge of one, or a triangle with a non-finite vertex
// touches nothing decidable: such triangles make the scene undecidable and are reported by `exact_applies`).
std::vector<ExactCover> exact_scene_coverage(const Scene& scene);
// Empty if exact_scene_coverage can judge `scene`, else why not.
std::string exact_applies(const Scene& scene);

// The check: every decided pixel of the colour plane differs from the clear colour exactly when the exact answer
// covers it. `expected_inside` (if non-negative) must also equal the number of covered pixel centres.
Check exact_coverage(const Scene& scene, int64_t expected_inside = -1);

}  // namespace tilevk::cts
