// The post-vertex-shader vertex as the geometry stage sees it: plain floats, one contiguous record per vertex.
#pragma once

#include <cstdint>

namespace tilevk::rast::geometry {

// How a fragment-shader input is interpolated (drives clipping and plane setup).
enum class Interp : uint8_t { kPerspective, kNoPerspective, kFlat };

// Record layout, `vertex_floats(layout)` floats per vertex:
//   [0..3]  clip position (x, y, z, w) as written by the vertex shader
//   [4..7]  window position (x, y, z, 1/w) after the viewport transform (see viewport.h)
//   [8..]   num_attribs vec4 attributes
struct VertexLayout {
    uint32_t num_attribs = 0;
    const Interp* interp = nullptr;  // num_attribs entries
};

inline constexpr uint32_t kClipPosOffset = 0;
inline constexpr uint32_t kWinPosOffset = 4;
inline constexpr uint32_t kAttribOffset = 8;

inline constexpr uint32_t vertex_floats(const VertexLayout& l) {
    return kAttribOffset + 4 * l.num_attribs;
}
inline const float* clip_pos(const float* v) {
    return v + kClipPosOffset;
}
inline const float* win_pos(const float* v) {
    return v + kWinPosOffset;
}
inline const float* attrib(const float* v, uint32_t i) {
    return v + kAttribOffset + 4 * i;
}

}  // namespace tilevk::rast::geometry
