// What draw's pipeline does to a polygonMode LINE / POINT triangle after the clipper and the float cull
// (draw_pipe_validate.c order: clip -> cull -> offset -> flatshade -> unfilled), operation by operation:
//   offset    (draw_pipe_offset.c do_offset_tri, only with depthBiasEnable): every window z += the triangle's
//             offset, saturated to [0, 1]. llvmpipe's own setup never offsets lines or points (lp_setup_line.c,
//             lp_setup_point.c have no offset), so this is the only way lines and points get a depth bias.
//   flatshade (draw_pipe_flatshade.c flatshade_tri_0/_2): the provoking vertex's flat attributes are copied
//             to the other two vertices, so every edge or corner shows the triangle's flat values.
//   unfilled  (draw_pipe_unfilled.c lines()/points()): edges v2-v0, v0-v1, v1-v2 / corners v0, v1, v2, each
//             only when its edge flag is set (ClippedTriangle::edges).
#pragma once

#include <cstdint>

#include "rast/geometry/planes.h"
#include "rast/geometry/vertex.h"

namespace tilevk::rast::geometry {

struct UnfilledConfig {
    VertexLayout layout;
    bool bias_enable = false;
    DepthBias bias;  // with the depth format fields filled (units as depth_bias_units)
    bool flatshade_first = true;
};

// do_offset_tri's zoffset from the window positions (x, y, z) of the triangle as the cull stage saw it:
//   det = fl(ex*fy) - fl(ey*fx), e = v0 - v2, f = v1 - v2 (draw_pipe_cull.c); inv_det = 1/det
//   a = ey*fz - ez*fy ; b = ez*fx - ex*fz ; dzdx = |a*inv_det| ; dzdy = |b*inv_det|
//   mult = MAX2(dzdx, dzdy) * slope ; unorm: units + mult ; float: units * 2^(exp(max|z|) - 23) + mult
//   clamp != 0: clamp < 0 ? MAX2(off, clamp) : MIN2(off, clamp)
// Plain C float arithmetic, no FMA. A zero-area triangle gives Inf/NaN like draw.
float unfilled_depth_offset(const DepthBias& b, const float* w0, const float* w1, const float* w2);

// Copies the triangle's vertices v[0..2] into `scratch` (3 records of vertex_floats(layout) floats) with the
// offset (z = SATURATE(z + zoffset)) and the flat-attribute copy applied; out[k] points at the copies. When
// neither applies, out[k] = v[k] and scratch is untouched.
void prepare_unfilled_triangle(const UnfilledConfig& cfg, const float* const v[3], float* scratch, const float* out[3]);

// inject_front_face_info: gl_FrontFacing of the triangle's edges and corners (llvmpipe's line/point setup reads
// the injected value; line and point topologies are always front facing). det = fl(ex*fy) - fl(ey*fx) as the
// cull stage computes it; front = front_ccw ? det < 0 : det > 0 (zero or NaN: back).
bool unfilled_front_facing(bool front_ccw, const float* w0, const float* w1, const float* w2);

// The lines lines() emits for edge bits `edges`, in its order: (2,0) if bit 2, (0,1) if bit 0, (1,2) if bit 1.
// Writes vertex positions (0..2) pairs to out and returns how many lines.
uint32_t unfilled_lines(uint8_t edges, uint8_t out[3][2]);

}  // namespace tilevk::rast::geometry
