// Clip mask and viewport transform (draw_llvm.c generate_clipmask / generate_viewport, lvp_execute.c
// get_viewport_xform / set_viewport_depth_xform, draw_context.c identity_viewport).
#pragma once

#include <cstdint>

namespace tilevk::rast::geometry {

struct Viewport {
    float scale[3];
    float translate[3];
};

// lavapipe: scale.x = fl(0.5f*width), translate.x = fl(scale.x + x) (same for y);
// z with clip_halfz (Vulkan): scale = (float)(f - n), translate = (float)n in double;
// without halfz (VK_EXT_depth_clip_control negativeOneToOne): scale = (float)(0.5*(f-n)), translate =
// (float)(0.5*(n+f)).
Viewport make_viewport(float x, float y, float width, float height, float min_depth, float max_depth,
                       bool clip_halfz = true);

// The depth range llvmpipe clamps to (lp_setup.c lp_setup_set_viewports, util_viewport_zmin_zmax): computed from
// the float scale and translate, so it may lie an ulp off the viewport's minDepth/maxDepth:
//   halfz: a = tz, b = fl(tz + sz); else a = fl(tz - sz), b = fl(tz + sz); zmin = min(a, b), zmax = max(a, b).
void viewport_depth_range(const Viewport& vp, bool clip_halfz, float* zmin, float* zmax);

// draw->identity_viewport: exactly one viewport with scale (1,1,1) and translate (0,0,0). lavapipe then bypasses
// the viewport entirely: the window position is the raw clip position, w not inverted (quirk, lavapipe-rules §1).
bool is_identity_viewport(const Viewport& vp);

// The whole-pixel rectangle llvmpipe derives from viewport 0 (lp_setup.c lp_setup_set_viewports, "vpwh") and
// intersects with every primitive's draw region (lavapipe sets point_tri_clip): with sy = |scale.y|,
//   x0 = (int)(fl(tx - sx) + 0.499f)   x1 = (int)(fl(fl(sx*2) + fl(tx - sx)) - 0.501f)   (inclusive, truncation)
// Returned half-open: [x0, x1 + 1) x [y0, y1 + 1). It matters for points (never x/y clipped) and fractional
// viewports. Non-finite or out-of-int values convert like cvttss2si (INT32_MIN).
struct PixelRect {
    int32_t x0, y0, x1, y1;
};
PixelRect viewport_pixel_rect(const Viewport& vp);

struct ViewportConfig {
    Viewport vp;
    bool fused = true;    // fmuladd fused (host FMA) or mul+add
    bool bypass = false;  // identity-viewport bypass (set from is_identity_viewport by the caller)
};

// Unclipped vertices (the JIT path): oow = 1.0f/w; win = fmuladd(fl(x*oow), scale, translate) for x, y, z; win.w = oow.
// Bypass: win = clip (x, y, z, w) unchanged.
void viewport_transform(const ViewportConfig& cfg, const float clip[4], float win[4]);

// Vertices made by the clipper (draw_pipe_clip.c interp(), C without FMA): win = fl(fl(fl(x*oow)*s)+t).
// The clipper does this even when the viewport is bypassed (it reads draw->viewports[] directly).
void viewport_transform_c(const Viewport& vp, const float clip[4], float win[4]);

// Clip mask bits (generate_clipmask, unordered compares: NaN sets the bit).
enum ClipBits : uint32_t {
    kClipRight = 1u << 0,   // x > w
    kClipLeft = 1u << 1,    // x + w < 0
    kClipBottom = 1u << 2,  // y > w
    kClipTop = 1u << 3,     // y + w < 0
    kClipNear = 1u << 4,    // halfz: z < 0; else z + w < 0
    kClipFar = 1u << 5,     // z > w
};
// User plane i (ClipDistance[i]) is bit kClipUserShift + i.
inline constexpr uint32_t kClipUserShift = 6;

// The user-plane bits of a vertex's clip mask (generate_clipmask): bit 6 + i when 0 > d[i] (unordered: NaN sets
// it) or d[i] is infinite.
uint32_t clip_distance_mask(const float* distances, uint32_t num_clip_distances);

struct ClipMaskConfig {
    bool clip_xy = true;     // always on in lavapipe (no guard band outside linear mode)
    bool clip_z = true;      // depth_clip_near = !depthClampEnable (or VK_EXT_depth_clip_enable)
    bool clip_halfz = true;  // Vulkan [0,1] depth
};

uint32_t compute_clipmask(const ClipMaskConfig& cfg, const float clip[4]);

// What lavapipe's vertex JIT does after the vertex shader, for every vertex (clipped or not): clip mask from the
// clip position, then the viewport transform into the record's window lanes (vertex.h layout). Surviving
// original vertices of a clipped triangle keep these window coordinates; only new ones are made in C.
uint32_t prepare_vertex(const ClipMaskConfig& cm, const ViewportConfig& vp, float* record);

}  // namespace tilevk::rast::geometry
