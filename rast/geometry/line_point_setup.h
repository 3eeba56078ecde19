// Line and point setup as llvmpipe does it (lp_setup_line.c try_setup_line, lp_setup_point.c try_setup_point):
// fixed-point edge planes / boxes for rast/core plus the attribute planes, computed in plain C float.
#pragma once

#include <cstdint>

#include "rast/geometry/planes.h"
#include "rast/geometry/vertex.h"

namespace tilevk::rast::geometry {

// One fixed-point edge plane, the same convention as rast/core's EdgePlane (rast/core/primitive.h): a sample at
// fixed (X, Y) (1/256 px, pixel centre at 1x = integer multiples of 256) is inside iff c + a*X + b*Y > 0.
// For the edge from corner i to corner j: a = -(y_i - y_j), b = x_i - x_j, c = DY*x_i - DX*y_i + bias,
// bias = 1 if DY < 0 || (DY == 0 && DX > 0) (top-left rule; lavapipe never sets bottom_edge_rule).
struct FixedPlane {
    int64_t c;
    int32_t a, b;
};

// util_iround on x86-64: f >= 0 ? (int)(f + 0.5f) : (int)(f - 0.5f) (float add, then truncation). The
// conversion of NaN or of values outside int32 gives INT32_MIN as cvttss2si does; `ok` reports that case.
int32_t util_iround(float f, bool* ok = nullptr);
// subpixel_snap(a) = util_iround(256 * a)
int32_t subpixel_snap(float a, bool* ok = nullptr);

enum class LineMode : uint8_t { kRectangular, kBresenham };

enum class PrimSetupStatus : uint8_t {
    kOk,
    kEmpty,       // zero-length line: lavapipe draws nothing
    kOutOfRange,  // a snapped coordinate overflowed int32 (lavapipe's result is undefined there): not drawn
};

struct LineSetupConfig {
    VertexLayout layout;
    LineMode mode = LineMode::kRectangular;
    float width = 1.0f;           // lineWidth (lavapipe range [1, 255])
    bool multisample = false;     // snap offset 0 in MSAA (the attribute planes still use 0.5: lavapipe quirk)
    bool flatshade_first = true;  // flat attributes from v0 (else v1)
};

// 4 planes for rast/core's ConvexInput (num_planes = 4) and the corner box [min, max] in fixed point
// (pass min_x/max_x etc. as ConvexInput's box; the core derives the pixel range).
struct LineSetup {
    FixedPlane planes[4];
    int32_t corner_x[4], corner_y[4];
    int32_t min_x, min_y, max_x, max_y;
    AttribPlane pos;  // lanes: x (a0 0, dadx 1), y (dady 1), z plane, 1/w plane; no depth bias for lines
};

// v0, v1: vertex records in draw order (v0 = first vertex). attribs[]: layout.num_attribs planes.
PrimSetupStatus setup_line(const LineSetupConfig& cfg, const float* v0, const float* v1, LineSetup* out,
                           AttribPlane* attribs);

struct PointSetupConfig {
    VertexLayout layout;
    bool multisample = false;
    // Attribute index that receives gl_PointCoord planes (-1: none), and whether that input is perspective.
    int32_t point_coord_attrib = -1;
    bool point_coord_perspective = false;
};

// A point is a square box: sample X covered iff x0 <= X < x1 (same for y), rast/core's BoxInput.
struct PointSetup {
    int32_t x0, y0, x1, y1;
    AttribPlane pos;  // z and 1/w constant (v0's), x/y identity planes
};

// size: PointSize as written by the vertex shader (pass 1.0 when it writes none); clamped to 255, NaN or <= 1 px
// give a 1-pixel square, as in lavapipe. Attributes must be in fragment-input order (point_persp_coeff indexes
// the vertex by input slot, which only equals the attribute when the layouts agree — they do for lavapipe).
// All attributes are constant: a0 = value (perspective ones premultiplied by 1/w), dadx = dady = 0.
PrimSetupStatus setup_point(const PointSetupConfig& cfg, const float* v, float size, PointSetup* out,
                            AttribPlane* attribs);

}  // namespace tilevk::rast::geometry
