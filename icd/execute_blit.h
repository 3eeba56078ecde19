// vkCmdBlitImage, computed the way lavapipe 22.3 computes it (icd/README.md, "Blits"):
//   same format, 1:1, not mirrored, NEAREST      -> a plain copy (util_try_blit_via_copy_region)
//   anything else                                -> util_blitter: a quad of two triangles over the destination box,
//     texture coordinates interpolated per pixel by llvmpipe's setup planes, then
//     1:1 (mirrored or converting)               -> texel fetch at floor(coordinate)          (use_txf)
//     scaled                                     -> normalized coordinates, CLAMP_TO_EDGE sampler, NEAREST/LINEAR
//   and the fragment's float colour stored with the fragment-output conversions of rast/fragment/color.h.
// The pure pieces (the quad's coverage and coordinates, the texel conversions, the filters) are exposed for tests.
#pragma once
#include <array>
#include <cstdint>

#include "commands.h"
#include "formats.h"

namespace tilevk::icd {

void exec_blit_image(const CmdBlitImage& c);

// True if the format can be a blit source and destination (BLIT_SRC|BLIT_DST); `linear` for FILTER_LINEAR.
bool blit_supported(const FormatInfo& f);
bool blit_linear_supported(const FormatInfo& f);

namespace blit {

// One attribute plane of a setup triangle: a(px, py) = fmuladd(dady, py, fmuladd(dadx, px, a0)).
struct AttribPlane {
    float a0 = 0, dadx = 0, dady = 0;
};

// One of the blitter's two triangles after llvmpipe's setup: 24.8 fixed-point vertices (pixel centres at multiples
// of 256), edge biases, the inclusive pixel bounding box and the planes of the two texture coordinates.
struct Triangle {
    bool valid = false;
    int32_t x[3] = {}, y[3] = {}, bias[3] = {};
    int32_t bx0 = 0, by0 = 0, bx1 = -1, by1 = -1;
    AttribPlane s, t;
    bool covers(int32_t px, int32_t py) const;
};

// The blitter's quad over destination pixels [x1,x2) x [y1,y2) of a surface of surf_w x surf_h, with texture
// coordinates (s1,t1) at the (x1,y1) corner and (s2,t2) at the (x2,y2) corner, drawn as the triangle fan
// (x1,y1) (x2,y1) (x2,y2) (x1,y2). `fused`: lavapipe's fmuladd is a true FMA (host has FMA).
// With `rect` (llvmpipe's linear mode), the fan is set up as one rectangle instead: a box and one plane pair.
struct Quad {
    Triangle tri[2];
    bool fused = true;
    bool rect = false;
    int32_t rx0 = INT32_MAX, ry0 = INT32_MAX, rx1 = -1, ry1 = -1;  // the rectangle's inclusive pixel box
    AttribPlane rs, rt;
    // The interpolated coordinates at pixel (px,py); false if neither triangle covers it.
    bool texcoord(int32_t px, int32_t py, float& s, float& t) const;
};
Quad make_quad(uint32_t surf_w, uint32_t surf_h, int32_t x1, int32_t y1, int32_t x2, int32_t y2, float s1, float t1,
               float s2, float t2, bool fused, bool rect = false);

using Rgba = std::array<float, 4>;
// A texel as lavapipe's sampler returns it (UNORM8 c*fl(1/255), sRGB polynomial, half exact, D16 c*fl(1/65535)),
// missing channels (0, 0, 1).
Rgba decode(const FormatInfo& f, const uint8_t* texel, bool fused);
// A fragment colour (or depth in [0]) stored as lavapipe's fragment output does.
void encode(const FormatInfo& f, const Rgba& c, uint8_t* texel, bool fused);

}  // namespace blit
}  // namespace tilevk::icd
