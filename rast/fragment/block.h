// Shared layout of the per-fragment stage: one 4x4 pixel block, 16 SIMD lanes, up to 4 samples.
//
// Lane order (the shader interpreter's, shader/program.h): pixels are grouped in 2x2 quads so derivatives work,
//   quad = (y>>1)*2 + (x>>1),  lane = quad*4 + (y&1)*2 + (x&1)      (x, y in 0..3 inside the block)
// Coverage masks from rast/core use the raster order  bit = y*4 + x.  The two are converted explicitly below.
#pragma once

#include <cstdint>

namespace tilevk::rast::fragment {

inline constexpr int kBlockLanes = 16;
inline constexpr int kMaxSamples = 4;

// lane = quad*4 + (y&1)*2 + (x&1), quad = (y>>1)*2 + (x>>1)
constexpr int lane_of(int x, int y) {
    return (((y >> 1) * 2 + (x >> 1)) * 4) + (y & 1) * 2 + (x & 1);
}
// x of lane: (quad&1)*2 + (lane&1)
constexpr int lane_x(int lane) {
    return ((lane >> 2) & 1) * 2 + (lane & 1);
}
// y of lane: (quad>>1)*2 + ((lane>>1)&1)
constexpr int lane_y(int lane) {
    return ((lane >> 3) & 1) * 2 + ((lane >> 1) & 1);
}

// Raster-order mask (bit y*4+x) -> lane-order mask (bit lane_of(x,y)). The permutation swaps bits 2,3 with
// bits 4,5 in each byte (raster (2,0),(3,0) are lanes 4,5; raster (0,1),(1,1) are lanes 2,3) and is its own inverse.
constexpr uint16_t raster_to_lanes(uint16_t raster) {
    return uint16_t((raster & 0xC3C3u) | ((raster >> 2) & 0x0C0Cu) | ((raster << 2) & 0x3030u));
}

// Lane-order mask -> raster-order mask.
constexpr uint16_t lanes_to_raster(uint16_t lanes) {
    return raster_to_lanes(lanes);
}

// lavapipe's standard 4x sample positions relative to the pixel corner (lp_rast.c lp_sample_pos_4x).
inline constexpr float kSamplePos4x[4][2] = {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};

}  // namespace tilevk::rast::fragment
