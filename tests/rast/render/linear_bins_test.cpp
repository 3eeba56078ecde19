// llvmpipe's triangle binning as replayed for linear bins (rast/render/linear_bins.h), derived by hand.
#include <gtest/gtest.h>

#include <vector>

#include "rast/render/linear_bins.h"

using namespace tilevk::rast;
using namespace tilevk::rast::render;

TEST(LinearBins, RightTriangleWholePartialAndOut) {
    // Pixel-space right triangle (-10,-10) (300,-10) (-10,300) in 24.8 fixed point (pixel-centre offset already
    // applied): its area is negative (cw), so llvmpipe's ccw order is (v0, v2, v1). The hypotenuse x + y = 290.
    const int32_t x[3] = {-2560, -2560, 76800}, y[3] = {-2560, 76800, -2560};
    const ClipRect fb = {0, 0, 512, 512};
    std::vector<uint8_t> tiles(64, 1);  // 8 x 8 tiles
    mark_partial_triangle_bins(x, y, fb, 8, &tiles);
    // tiles (0,0) and (1,1): x + y <= 256 < 290 even one step past the tile: whole
    EXPECT_EQ(tiles[0], 1);
    EXPECT_EQ(tiles[9], 1);
    EXPECT_TRUE(triangle_covers_whole_bin(x, y, fb, 0, 0));
    EXPECT_TRUE(triangle_covers_whole_bin(x, y, fb, 1, 1));
    // tile (2,1): 128..191 x 64..127 reaches x + y = 318: partial
    EXPECT_EQ(tiles[8 + 2], 0);
    // tile (4,0): pixels 256..319 x 0..63, the hypotenuse passes through: partial
    EXPECT_EQ(tiles[4], 0);
    EXPECT_FALSE(triangle_covers_whole_bin(x, y, fb, 4, 0));
    // tile (3,0): 192..255 x 0..63: x + y <= 318 > 290 at its far corner: partial
    EXPECT_EQ(tiles[3], 0);
    // tile (6,0): x >= 384: trivially rejected, no command
    EXPECT_EQ(tiles[6], 1);
    EXPECT_FALSE(triangle_covers_whole_bin(x, y, fb, 6, 0));
}

TEST(LinearBins, WholeTileTestLooksOneStepPastTheTile) {
    // A right-angled triangle (-390,-390) (xr,-390) (xr,781) px, interior left of the vertical edge x = xr, its
    // hypotenuse far left of tile 0 in rows 0..63. llvmpipe's trivial accept evaluates each plane 64 pixel steps
    // from the tile origin: with xr = 63.5 (fixed 16256, between pixel 63's sample 16128 and pixel 64's 16384)
    // every sample of tile 0 is covered but the tile is not "whole"; with xr = 64.5 it is.
    for (int32_t xr : {16256, 16512}) {
        const int32_t x[3] = {-100000, xr, xr}, y[3] = {-100000, -100000, 200000};
        // area = dx01*dy20 - dx20*dy01 = (-100000 - xr)(300000) - (xr + 100000)(0) < 0: cw -> order (v0, v2, v1)
        const int32_t cx[3] = {x[0], x[2], x[1]}, cy[3] = {y[0], y[2], y[1]};
        EXPECT_EQ(triangle_covers_whole_bin(cx, cy, {0, 0, 256, 256}, 0, 0), xr == 16512) << xr;
    }
}

TEST(LinearBins, SingleTileAndScissorPlanes) {
    // a triangle whose box stays in one tile: always a partial command in that tile, even if tiny
    const int32_t x[3] = {70 * 256, 70 * 256, 80 * 256}, y[3] = {10 * 256, 20 * 256, 10 * 256};
    std::vector<uint8_t> tiles(4, 1);  // 2 x 2
    mark_partial_triangle_bins(x, y, {0, 0, 128, 128}, 2, &tiles);
    EXPECT_EQ(tiles[0], 1);
    EXPECT_EQ(tiles[1], 0);
    // a huge ccw triangle covering the framebuffer, draw region x >= 10 of a 256x256 target: the left scissor
    // plane makes column 0 partial; the right and bottom planes (x <= 255, y <= 255) make the last column and
    // row partial too, since the trivial accept looks one step past the tile (pixel 256 > 255)
    const int32_t bx[3] = {-100000, -100000, 300000}, by[3] = {-100000, 300000, -100000};
    std::vector<uint8_t> t2(16, 1);
    mark_partial_triangle_bins(bx, by, {10, 0, 256, 256}, 4, &t2);
    EXPECT_EQ(t2[4 * 1 + 0], 0);
    EXPECT_EQ(t2[4 * 1 + 1], 1);
    EXPECT_EQ(t2[4 * 2 + 2], 1);
    EXPECT_EQ(t2[4 * 1 + 3], 0);
    EXPECT_EQ(t2[4 * 3 + 1], 0);
    EXPECT_EQ(t2[0 + 1], 1);  // no top plane: the box starts at y = 0 after clamping
}
