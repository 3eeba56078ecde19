// Fixed point 15.8 window coordinates, snapped exactly as lavapipe does (lavapipe-rules §1 "Snapping to fixed point").
#pragma once

#include <cmath>
#include <cstdint>

namespace tilevk::rast {

inline constexpr int kSubpixelBits = 8;
inline constexpr int32_t kFixedOne = 1 << kSubpixelBits;  // 256 units per pixel
// Representable window range is +-16384 px: |X| < 2^22 fixed units. Edge deltas then stay below 2^23, which is what
// every 32/64-bit bound in setup.cpp and tile_raster.cpp is proved against.
inline constexpr int32_t kMaxFixed = 1 << 22;
inline constexpr int kMaxSamples = 4;

// Sample positions of 4x MSAA in 1/256 px from the pixel corner (lp_rast.c lp_sample_pos_4x, util_iround(pos*256)).
inline constexpr int32_t kSamplePos4x[4][2] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};

// Offset subtracted before snapping triangles: 0.5 at 1 sample (moves pixel centres to integer fixed coordinates),
// 0 at 4 samples (the lattice is the pixel corner and samples sit at kSamplePos4x).
inline constexpr float triangle_snap_offset(int samples) {
    return samples > 1 ? 0.0f : 0.5f;
}

// Triangle snap: X = rne(fl(x - offset) * 256) (SSE cvtps2dq in round-to-nearest-even). Returns false for NaN/Inf
// or anything outside |X| < 2^22, leaving *out untouched; never overflows.
inline bool snap_triangle_coord(float x, float offset, int32_t* out) {
    const float shifted = x - offset;                                        // fl(x - offset)
    const float scaled = shifted * 256.0f;                                   // exact scaling by a power of two (or Inf)
    if (!(std::fabs(scaled) < static_cast<float>(kMaxFixed))) return false;  // NaN fails too
    *out = static_cast<int32_t>(std::nearbyint(scaled));  // default FP environment: round half to even
    return *out > -kMaxFixed && *out < kMaxFixed;
}

// lavapipe's own range for triangles (lp_setup_tri.c calc_fixed_position: cvtps2dq, exact for |X| < 2^31; larger
// values, NaN and Inf become INT_MIN there): the same snap without the 2^22 bound. Triangles with a coordinate past
// 2^22 take setup's wide range (setup.cpp: edges must then stay inside llvmpipe's exact integer range).
inline constexpr int64_t kMaxFixedLavapipe = int64_t{1} << 31;
inline constexpr int64_t kMaxLavapipeEdge = int64_t{1} << 23;  // |DX| + |DY| of an edge, fixed point (setup.cpp)
inline constexpr float kMaxLavapipePixels = 8388608.0f;        // 2^31 / 256
inline constexpr float kMaxLavapipeEdgePixels = 32768.0f;      // 2^23 / 256
inline bool snap_triangle_coord_lavapipe(float x, float offset, int32_t* out) {
    const float shifted = x - offset;
    const float scaled = shifted * 256.0f;
    if (!(std::fabs(scaled) < static_cast<float>(kMaxFixedLavapipe))) return false;  // NaN fails too
    *out = static_cast<int32_t>(std::nearbyint(scaled));  // |scaled| <= 2^31 - 128: no overflow
    return true;
}

// Line/point/rect snap: util_iround(256*a), half away from zero with a float add first (u_math.h):
// f >= 0 ? (int)(f + 0.5f) : (int)(f - 0.5f). Same range rule as snap_triangle_coord.
inline bool snap_round_half_away(float a, int32_t* out) {
    const float f = 256.0f * a;
    if (!(std::fabs(f) < static_cast<float>(kMaxFixed))) return false;
    const int32_t v = f >= 0.0f ? static_cast<int32_t>(f + 0.5f) : static_cast<int32_t>(f - 0.5f);
    if (v <= -kMaxFixed || v >= kMaxFixed) return false;
    *out = v;
    return true;
}

// ceil(a / 2^k) for signed 64-bit a (arithmetic shift is floor in C++20).
inline constexpr int64_t ceil_shift(int64_t a, int k) {
    return -((-a) >> k);
}

}  // namespace tilevk::rast
