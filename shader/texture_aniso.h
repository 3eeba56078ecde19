// Anisotropic filtering of 2D views (texture_aniso.cpp): lavapipe's level choice and elliptical weighted average.
#pragma once
#include <array>
#include <cstdint>

#include "shader/texture_internal.h"

namespace tilevk::shader::tex {

// A 2x2 quad's differences from its top-left lane (lp_build_packed_ddx_ddy_twocoord), in normalized coordinates.
struct QuadDerivs {
    float dsdx = 0, dsdy = 0, dtdx = 0, dtdy = 0;
};

// gallivm's weight table (lp_bld_sample.c aniso_filter_table), indexed by the ellipse's scaled radius squared.
const std::array<float, 1024>& aniso_weights();
// The LOD before bias and clamps: half the fast log2 of the minor axis squared (lp_build_pmin).
float aniso_raw_lambda(const ImageView& img, const QuadDerivs& d, float max_anisotropy);
// The level a final LOD selects: truncated, clamped to the view's levels.
uint32_t aniso_level(const ImageView& img, float lambda);
// The filtered (unswizzled) value at level `lv` of the view, `layer` its array layer; the probes' texel corners
// are normalized by the size of level `size_lv` (lavapipe's, which is not always `lv`: texture.cpp).
Vec4 sample_aniso(const ImageView& img, const SamplerState& smp, uint32_t lv, uint32_t size_lv, uint32_t layer, float s,
                  float t, const QuadDerivs& d, const SampleArgs& args);

}  // namespace tilevk::shader::tex
