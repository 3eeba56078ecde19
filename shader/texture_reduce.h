// One step of the linear filter under the sampler's reduction mode (VkSamplerReductionModeCreateInfo), as
// gallivm's lp_build_reduce_filter does it (lp_bld_sample.c): WEIGHTED_AVERAGE lerps, MIN and MAX take the smaller
// or larger of the two texels unless the weight of the second is 0, when the first is kept as it is. The float
// filter (lp_bld_sample_soa.c) and the 8-bit filter (lp_bld_sample_aos.c, also between mip levels) both step this
// way: x within each row, then y, then r; the float filter blends mip levels with a plain lerp whatever the mode.
#pragma once

#include <cmath>
#include <cstdint>

#include "shader/program.h"
#include "shader/texture_fixed8.h"

namespace tilevk::shader {

// lp_build_sample_min / lp_build_sample_max on float texels: the weight compared unordered-not-equal with 0 (a NaN
// weight reduces), then minps / maxps (the second texel when either is NaN); the lerp fmuladd(w, q - p, p).
inline float reduce_step(Reduction m, float w, float p, float q) {
    switch (m) {
        case Reduction::Min:
            return !(w == 0.0f) ? (p < q ? p : q) : p;
        case Reduction::Max:
            return !(w == 0.0f) ? (p > q ? p : q) : p;
        default:
            return std::fma(w, q - p, p);
    }
}

// The same on 8-bit values with an 8-bit weight (unsigned byte min / max; fixed8::lerp).
inline int32_t reduce_step8(Reduction m, int32_t w, int32_t a, int32_t b) {
    switch (m) {
        case Reduction::Min:
            return w != 0 ? (a < b ? a : b) : a;
        case Reduction::Max:
            return w != 0 ? (a > b ? a : b) : a;
        default:
            return fixed8::lerp(w, a, b);
    }
}

}  // namespace tilevk::shader
