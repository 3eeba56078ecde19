// Anisotropic filtering (shader/texture_aniso.h): the weight table against gallivm's printed table, the level from
// the minor axis, and the elliptical average worked out by hand for a footprint whose probes land on texel corners.
// The whole filter is compared with lavapipe by cts texture.aniso.*.
#include <gtest/gtest.h>

#include <vector>

#include "shader/texture_aniso.h"

using namespace tilevk::shader;
using namespace tilevk::shader::tex;

namespace {

constexpr float kUnorm8 = float(1.0 / 255.0);  // gallivm's UNORM8 -> float (lp_build_unsigned_norm_to_float)

// An RGBA8 image w x h, one level, texel (x, y) = (16x, 16y, 0, 255).
struct Image {
    std::vector<uint8_t> bytes;
    ImageView view;
    Image(uint32_t w, uint32_t h, uint32_t levels = 1) : bytes(size_t(w) * h * 4 * 2) {
        view.format = Format::R8G8B8A8_UNORM;
        view.width = w, view.height = h, view.levels = levels;
        for (uint32_t l = 0; l < levels; ++l) view.level[l] = ImageLevel{0, uint64_t(w) * 4, uint64_t(w) * h * 4};
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                uint8_t* p = bytes.data() + (size_t(y) * w + x) * 4;
                p[0] = uint8_t(16 * x), p[1] = uint8_t(16 * y), p[2] = 0, p[3] = 255;
            }
        view.base = bytes.data();
    }
};

}  // namespace

// Entries of lp_bld_sample.c's aniso_filter_table as Mesa 22.3.6 prints them (first row, a middle one, the last).
TEST(ShaderTextureAniso, WeightsAreGallivmsTable) {
    const auto& w = aniso_weights();
    EXPECT_EQ(w[0], 1.000000f);
    EXPECT_EQ(w[1], 0.998047f);
    EXPECT_EQ(w[7], 0.986408f);
    EXPECT_EQ(w[1016], 0.137200f);
    EXPECT_EQ(w[1022], 0.135600f);
    EXPECT_EQ(w[1023], 0.135335f);
    for (size_t i = 1; i < w.size(); ++i) EXPECT_LE(w[i], w[i - 1]) << i;
}

// lp_build_pmin: the LOD is half the fast log2 of the smaller of |d/dx|^2 and |d/dy|^2 in texels, whichever axis it
// is; lavapipe's clamp by maxAnisotropy^2 compares pmin^2 with itself and never fires, so a 4:1 footprint keeps
// the minor axis's LOD under maxAnisotropy 2 too.
TEST(ShaderTextureAniso, LevelFollowsTheMinorAxis) {
    Image img(64, 64, 7);
    QuadDerivs d;
    d.dsdx = 8.0f / 64.0f, d.dtdy = 2.0f / 64.0f;  // 8 texels along x, 2 along y
    EXPECT_EQ(aniso_raw_lambda(img.view, d, 16.0f), 1.0f);
    EXPECT_EQ(aniso_raw_lambda(img.view, d, 2.0f), 1.0f);
    std::swap(d.dsdx, d.dtdy);
    EXPECT_EQ(aniso_raw_lambda(img.view, d, 2.0f), 1.0f);
    d.dsdx = 3.0f / 64.0f, d.dtdy = 16.0f / 64.0f;  // 3^2 = 9 = 2^3 * 1.125: fast_log2 = 3.125
    EXPECT_EQ(aniso_raw_lambda(img.view, d, 4.0f), 1.5625f);
    // the level truncates the LOD (lp_build_itrunc), clamped to the view's levels
    EXPECT_EQ(aniso_level(img.view, 1.9f), 1u);
    EXPECT_EQ(aniso_level(img.view, -0.9f), 0u);
    EXPECT_EQ(aniso_level(img.view, -3.0f), 0u);
    EXPECT_EQ(aniso_level(img.view, 40.0f), 6u);
}

// Derivatives 0: the ellipse is the unit circle (A = C = 1, B = 0, F = 1, box 1), scaled so that q = 1023 r^2. At
// the texel corner (2, 2) the probes are the corners u, v in [1, 3]: the centre weighs table[0] = 1, its four
// neighbours table[1023], the diagonal ones (q = 2046) nothing. Sums run v-major, then divide by the weights' sum.
TEST(ShaderTextureAniso, UnitFootprintAveragesFiveCorners) {
    Image img(8, 8);
    SamplerState smp;
    smp.max_anisotropy = 16.0f;
    const float s = 2.5f / 8.0f, t = 2.5f / 8.0f;  // s * 8 - 0.5 = 2
    const Vec4 got = sample_aniso(img.view, smp, 0, 0, 0, s, t, QuadDerivs{}, SampleArgs{});
    const float w = aniso_weights()[1023];
    // probes in order: (2, 1), (1, 2), (2, 2), (3, 2), (2, 3)
    const int px[] = {2, 1, 2, 3, 2}, py[] = {1, 2, 2, 2, 3};
    const float pw[] = {w, w, 1.0f, w, w};
    float r = 0, g = 0, a = 0, den = 0;
    for (int i = 0; i < 5; ++i) {
        r = r + float(16 * px[i]) * kUnorm8 * pw[i];
        g = g + float(16 * py[i]) * kUnorm8 * pw[i];
        a = a + 255.0f * kUnorm8 * pw[i];
        den = den + pw[i];
    }
    EXPECT_EQ(got[0], r / den);
    EXPECT_EQ(got[1], g / den);
    EXPECT_EQ(got[2], 0.0f);
    EXPECT_EQ(got[3], a / den);
}
