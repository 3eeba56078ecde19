#include "rast/geometry/lavapipe_quirks.h"

namespace tilevk::rast::geometry {

NineVertexQuirk nine_vertex_quirk(const TriangleListBatch& b, const float (*v)[2]) {
    const uint32_t trimmed = b.vertex_count - b.vertex_count % 3;  // draw drops an incomplete last triangle
    if (b.indexed || b.any_vertex_clipped || b.fs_has_flat_input || trimmed != 9 || v == nullptr)
        return NineVertexQuirk::kNone;
    // is_zero_area: the y of vertices 8, 7, 6 all equal (float ==, so NaN never matches)
    if (!(v[8][1] == v[7][1] && v[8][1] == v[6][1])) return NineVertexQuirk::kNone;
    const bool aero = v[0][0] == v[1][0] && v[0][0] == v[5][0] && v[2][0] == v[3][0] && v[2][0] == v[4][0] &&
                      v[0][1] == v[3][1] && v[0][1] == v[5][1] && v[1][1] == v[2][1] && v[1][1] == v[4][1];
    return aero ? NineVertexQuirk::kAeroRect : NineVertexQuirk::kSwallowed;
}

}  // namespace tilevk::rast::geometry
