// Which of llvmpipe's 64x64 bins can be "linear" (lp_rast.c rasterize_bin: every command of the bin is a clear,
// a rectangle or a whole-tile shade): the renderer replays llvmpipe's triangle binning (lp_setup_tri.c
// do_triangle_ccw planes, scissor planes, lp_setup_bin_triangle) to find the tiles where a triangle leaves a
// partial-tile command, which forces llvmpipe's general rasterizer on that bin.
#pragma once

#include <cstdint>
#include <vector>

#include "rast/core/primitive.h"

namespace tilevk::rast::render {

// One triangle: fixed-point (24.8, pixel-centre offset applied) vertices in llvmpipe's ccw order, `region` =
// draw_regions[0] (scissor ∩ framebuffer ∩ viewport rectangle, half-open). Clears tile_linear[ty*tiles_x+tx]
// for every tile that gets a partial triangle command (lp_setup_bin_triangle's single-tile path or a tile
// that is neither trivially rejected nor trivially accepted by all planes). Whole-tile tiles are left alone.
void mark_partial_triangle_bins(const int32_t x[3], const int32_t y[3], const ClipRect& region, int32_t tiles_x,
                                std::vector<uint8_t>* tile_linear);

// Whether llvmpipe shades tile (tx, ty) of this triangle with a whole-tile command (all planes trivially accept).
bool triangle_covers_whole_bin(const int32_t x[3], const int32_t y[3], const ClipRect& region, int32_t tx, int32_t ty);

}  // namespace tilevk::rast::render
