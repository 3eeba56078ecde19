// Cube-map sampling as llvmpipe does it (gallivm lp_bld_sample.c lp_build_cube_lookup, lp_build_cube_new_coords;
// lp_bld_sample_soa.c lp_build_sample_common, lp_build_sample_image_linear's seamless branch): face selection and
// projection, the per-pixel derivatives and LOD of cube maps, and the seamless bilinear footprint across face edges
// and corners. The pieces are exposed for unit tests (tests/shader/texture_cube_test.cpp); exec_sample_cube runs
// one Sample instruction flagged kSampleCube.
#pragma once

#include <array>
#include <cstdint>

#include "shader/ir.h"
#include "shader/program.h"

namespace tilevk::shader::cube {

// Faces in gallium's order (PIPE_TEX_FACE_*), which is also Vulkan's layer order of a cube view.
enum Face : uint32_t { kPosX = 0, kNegX = 1, kPosY = 2, kNegY = 3, kPosZ = 4, kNegZ = 5 };

// A direction on its face: the face and the face coordinates (s, t) in [0, 1].
struct FaceCoord {
    uint32_t face = 0;
    float s = 0.0f, t = 0.0f;
};

// lp_build_cube_lookup without derivatives: the major axis is z when |z| >= max(|x|, |y|), else x when |x| > |y|,
// else y; sc/tc are the spec's table ("Cube Map Face Selection") made by sign flips; s = sc * (0.5 / |ma|) + 0.5
// (a zero major axis gives 0.5).
FaceCoord lookup(float x, float y, float z);

// Derivatives of the face coordinates, per pixel (lp_build_cube_lookup with need_derivs).
struct FaceDerivs {
    float dsdx = 0.0f, dtdx = 0.0f, dsdy = 0.0f, dtdy = 0.0f;
};

// lp_build_cube_lookup with need_derivs: the same face and (s, t), computed as s = sc * |0.5 * (1 / ma)| + 0.5, and
// the direction's derivatives carried to the face: ds = 0.5 * (dsc - sc * (dma * (1 / ma))) * (1 / ma).
FaceCoord lookup_with_derivs(float x, float y, float z, const float ddx[3], const float ddy[3], FaceDerivs* out);

// One texel of the seamless footprint: face (before the cube array's layer is added) and texel coordinates.
struct Texel {
    uint32_t face = 0;
    int32_t x = 0, y = 0;
};

// The 2x2 bilinear footprint of (s, t) on `face` of a level of `size` x `size` texels, as llvmpipe's seamless cube
// filter builds it: texels 00 (x0, y0), 01 (x1, y0), 10 (x0, y1), 11 (x1, y1) with x0 = floor(s * size - 0.5)
// (a NaN s counts as 0); a texel past an edge is taken from the neighbouring face (lp_build_cube_new_coords); at a
// corner (past an x and a y edge at once) `corner` marks the texel that does not exist, which the filter leaves
// out, giving a third of its weight to each of the others.
struct Footprint {
    std::array<Texel, 4> texel{};
    float ws = 0.0f, wt = 0.0f;  // weights of the x1 column and the y1 row
    std::array<bool, 4> corner{};
};
Footprint footprint(uint32_t face, float s, float t, int32_t size);

// The texel past one edge of `face`, as lp_build_cube_new_coords maps it: `edge` 0 = x < 0, 1 = x > max, 2 = y < 0,
// 3 = y > max; (x, y) the texel's coordinates on `face` with the other axis already inside [0, max].
Texel across_edge(uint32_t face, int edge, int32_t x, int32_t y, int32_t max);

// One Sample instruction on a cube or cube-array view (texture(), textureLod(), textureGrad(), bias,
// samplerCubeShadow), all lanes: coordinate registers b (x, y, z[, layer][, reference]), gradients n..n+5 (dx.xyz,
// dy.xyz).
void exec_sample_cube(const Inst& in, uint32_t* R, const Descriptor* const* slots, uint32_t num_slots);

}  // namespace tilevk::shader::cube

namespace tilevk::shader {

// texture.cpp's view rules, shared with the cube sampler: the view's component mapping applied to a sampled value
// (ONE is the integer 1 on integer views), and whether a view can be sampled at all.
std::array<float, 4> apply_view_swizzle(const std::array<float, 4>& v, const ImageView& img);
bool view_usable(const ImageView* img);

}  // namespace tilevk::shader
