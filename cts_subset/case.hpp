// A conformance case: a dEQP-style name, a scene builder and an optional independent check.
// Case groups are generated from small tables in cases_<group>.cpp; helpers for building scenes live here.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "judge.hpp"
#include "scene.hpp"

namespace tilevk::cts {

struct Case {
    std::string name;
    std::function<Scene()> scene;  // built lazily: mesh cases load files only when they run
    Check check;                   // optional; applied to both devices' planes
    std::string note;              // e.g. "bgra-linear-path": deliberately hits lavapipe's linear rasterizer
    // A read-back plane in which the reference (lavapipe) is known to violate the spec, set from expectations.txt
    // (CASE:PLANE,ReferenceDefect): it is not compared byte for byte; how many values differ is reported in the
    // result's note instead. The plane must still be judged: by `check` and by a test that pins both drivers'
    // values (e.g. tests/icd/query_test.cpp). Everything else of the case is compared as usual.
    struct ReferenceDefect {
        std::string plane;
        std::string reason;
    };
    ReferenceDefect reference_defect;  // empty plane: none
    // A named difference decided per frame (icd/README.md "Named differences"): when the planes differ from the
    // reference, the case still passes if `check` holds on the device under test and fails on the reference (the
    // reference is provably wrong); the note then says so with this text. `check` must hold on the device under
    // test in any case.
    std::string named_difference;
};
using CaseList = std::vector<Case>;

void add_api_cases(CaseList& out);
void add_primitive_cases(CaseList& out);
void add_fill_rule_cases(CaseList& out);
void add_culling_cases(CaseList& out);
void add_interpolation_cases(CaseList& out);
void add_interpolate_at_cases(CaseList& out);  // cases_interpolate_at.cpp
void add_multisample_cases(CaseList& out);
void add_depth_cases(CaseList& out);
void add_stencil_cases(CaseList& out);
void add_blend_cases(CaseList& out);
void add_overdraw_cases(CaseList& out);
void add_viewport_cases(CaseList& out);
void add_texture_cases(CaseList& out);
void add_texture_3d_cases(CaseList& out);  // cases_texture_3d.cpp
void add_texture_1d_cases(CaseList& out);  // cases_texture_1d.cpp
void add_texture_cube_cases(CaseList& out);
void add_texture_bc_cases(CaseList& out);  // cases_texture_bc.cpp
void add_texture_aniso_cases(CaseList& out);  // cases_texture_aniso.cpp
void add_mesh_cases(CaseList& out);
void add_blit_cases(CaseList& out);
void add_query_cases(CaseList& out);
void add_raster_ext_cases(CaseList& out);  // cases_raster_ext.cpp
void add_statistics_cases(CaseList& out);
CaseList all_cases();
// The fuzzers' cases for one seed (tilevk-cts --fuzz): random.seed_N and extreme.random.seed_N, built from the
// minimisation knobs in the environment at the time of the call (TILEVK_CTS_RANDOM_DRAWS, TILEVK_CTS_EXTREME_KEEP),
// and random.compute.seed_N (cases_random_compute.cpp; one dispatch, nothing to minimise).
Case random_seed_case(uint32_t seed);
Case extreme_seed_case(uint32_t seed);
Case random_compute_seed_case(uint32_t seed);

// --- scene helpers ---
inline Vertex vtx(float x, float y, float z = 0.0f, float w = 1.0f, std::array<float, 4> c = {1, 1, 1, 1}) {
    Vertex v;
    v.pos[0] = x * w;  // positions are given in NDC; w scales them into clip space
    v.pos[1] = y * w;
    v.pos[2] = z * w;
    v.pos[3] = w;
    for (int i = 0; i < 4; ++i) v.color[i] = c[i];
    return v;
}
inline Vertex vtxc(float x, float y, std::array<float, 4> c) {
    return vtx(x, y, 0.0f, 1.0f, c);
}

inline Scene one_draw(Draw d, uint32_t w = 64, uint32_t h = 64) {
    Scene s;
    s.target.width = w;
    s.target.height = h;
    s.draws.push_back(std::move(d));
    return s;
}

// The analytic coverage check of the scene `make` builds (built again when the check runs, so that mesh files are
// read only by cases that run). 1/64 px keeps clear of 8-bit sub-pixel snapping (at most 1/256 px).
inline Check band_of(const std::function<Scene()>& make, float margin = 1.0f / 64.0f) {
    return [make, margin](const std::vector<Plane>& planes) { return coverage_band(make(), margin)(planes); };
}

// ONE,ONE additive blending, used by the coverage-counting checks.
inline VkPipelineColorBlendAttachmentState additive() {
    return {VK_TRUE,
            VK_BLEND_FACTOR_ONE,
            VK_BLEND_FACTOR_ONE,
            VK_BLEND_OP_ADD,
            VK_BLEND_FACTOR_ONE,
            VK_BLEND_FACTOR_ONE,
            VK_BLEND_OP_ADD,
            0xF};
}

// SRC_ALPHA, ONE_MINUS_SRC_ALPHA colour over the target ("alpha over"), alpha ONE, ZERO: the usual translucent layer.
inline VkPipelineColorBlendAttachmentState alpha_over() {
    return {VK_TRUE,
            VK_BLEND_FACTOR_SRC_ALPHA,
            VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
            VK_BLEND_OP_ADD,
            VK_BLEND_FACTOR_ONE,
            VK_BLEND_FACTOR_ZERO,
            VK_BLEND_OP_ADD,
            0xF};
}

// An RGBA8 word as read back (R in the low byte).
constexpr uint32_t rgba8(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
    return r | g << 8 | b << 16 | a << 24;
}

// A deterministic pseudo-random generator for random-primitive cases (identical on every platform).
struct Lcg {
    uint32_t s;
    float next() {  // in [0,1)
        s = s * 1664525u + 1013904223u;
        return float(s >> 8) * (1.0f / 16777216.0f);
    }
    float range(float a, float b) { return a + (b - a) * next(); }
};

}  // namespace tilevk::cts
