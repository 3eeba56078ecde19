// vkCmdBlitImage as lavapipe 22.3 computes it (lvp_execute.c handle_blit_image -> llvmpipe lp_blit ->
// util_blitter_blit_generic), on rast/'s own pieces (docs/lavapipe-rules.md, "Blits"):
//   boxes      the destination box is made positive (x = the smaller offset); a mirror becomes a negative source
//              width (mirroring both boxes cancels); array layers, or a 3D source's slices, are the box's z
//   copy       same format, NEAREST, same size, not mirrored: a plain copy (util_try_blit_via_copy_region)
//   slices     one quad per destination layer or slice (u_blitter.c do_blits); a 3D source is read at the slice
//              coordinate of blit_source_z, through the 3D sampler (shader::sample_3d: LINEAR lerps across slices)
//   draw       otherwise the blitter's quad over the destination box: vertices in NDC computed in C, draw's
//              viewport transform (geometry/viewport.h), two triangles of a fan set up by rast/core with the
//              blitter's bottom-left fill rule (or, in llvmpipe's linear mode, one rectangle: geometry/rect_detect.h),
//              texture coordinates interpolated from lp_state_setup's planes (geometry/planes.h, fragment/interp.h),
//              then 1:1 blits fetch texels at floor(coordinate) (TXF), scaled ones sample with a CLAMP_TO_EDGE sampler
//              (NEAREST or LINEAR: shader::sample_2d, the sampler of every fragment shader), and the colour is stored
//              with the fragment output conversion (format::encode_color)
#pragma once

#include <cstdint>
#include <functional>

#include "format/format.h"

namespace tilevk::rast {
class ThreadPool;
}

namespace tilevk::rast::render {

// One mip level of an image as the blit reads or writes it: single-sample texels, layers (or slices) one after
// another.
struct BlitSurface {
    uint8_t* base = nullptr;  // texel (0, 0) of layer 0 of the level
    format::Format format = format::Format::UNDEFINED;
    uint32_t width = 0, height = 0;
    uint32_t layers = 1;   // layers of the level present at `base`: the array layers, or a 3D level's depth
    bool three_d = false;  // a 3D image (gallium's PIPE_TEXTURE_3D): `layers` are depth slices
    uint64_t row_pitch = 0, layer_pitch = 0;
};

// A VkImageBlit region in plain numbers: each box's two corners in either order (the order mirrors). The third axis
// is the box's z as lavapipe passes it (lvp_execute.c handle_blit_image): for a 3D source both boxes' z offsets
// (their order flips too), else [baseArrayLayer, baseArrayLayer + layerCount) of each subresource.
struct BlitRegion {
    int32_t src[2][3] = {}, dst[2][3] = {};  // [corner][x, y, z]
};

enum class BlitFilter : uint8_t { kNearest, kLinear };

// The source z coordinate of destination layer or slice `dst_z` of a box `dst_depth` deep reading `src_depth` source
// layers or slices from `src_z` on (src_depth < 0: flipped), as u_blitter.c do_blits computes it in float:
// src_z + (dst_z * step + offset), step = |src_depth| / dst_depth, offset = 0.5 / dst_depth * |src_depth| (in double,
// for a 3D source only; both negated when flipped). Texel fetches floor it; a 3D source samples it divided by the
// level's depth.
float blit_source_z(int32_t src_z, int32_t src_depth, int32_t dst_depth, int32_t dst_z, bool three_d_source);

// Blits one region (the caller has checked it against both surfaces). `fused`: the host fuses lavapipe's fmuladd.
// The destination's tiles are drawn in parallel on `pool`; the result does not depend on its size.
void blit(const BlitSurface& src, const BlitSurface& dst, const BlitRegion& region, BlitFilter filter, bool fused,
          ThreadPool& pool);

// The blitter's quad over destination pixels [x1, x2) x [y1, y2) of a surf_w x surf_h surface with texture
// coordinates (s1, t1) at the (x1, y1) corner and (s2, t2) at the (x2, y2) corner; `rect`: llvmpipe's linear-mode
// rectangle instead of the two triangles. blit() draws through it.
struct BlitQuad {
    uint32_t surf_w = 0, surf_h = 0;
    int32_t x1 = 0, y1 = 0, x2 = 0, y2 = 0;
    float s1 = 0, t1 = 0, s2 = 0, t2 = 0;
    bool fused = true;
    bool rect = false;
};
// Calls fn(px, py, s, t) once for every covered pixel with its interpolated coordinates, from pool's workers
// (tiles in parallel, so fn must only write what belongs to its pixel).
void rasterize_blit_quad(const BlitQuad& quad, ThreadPool& pool,
                         const std::function<void(int32_t px, int32_t py, float s, float t)>& fn);

}  // namespace tilevk::rast::render
