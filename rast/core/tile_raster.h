// Internal: rasterizing one primitive within one tile with each method, into per-worker scratch lists.
#pragma once

#include <cstdint>
#include <vector>

#include "rast/core/coverage.h"
#include "rast/core/method.h"
#include "rast/core/setup.h"
#include "rast/core/tile_kernels.h"

namespace tilevk::rast {

struct TileGeom {
    int32_t x0, y0;  // tile origin in pixels
    int32_t size;    // tile size T (16, 32 or 64)
    int samples;     // 1 or 4
};

// Result of tile_setup.
enum class TileClass { kReject, kWhole, kPartial };

// Evaluates every plane of `prim` for the tile in 64-bit (the only 64-bit step of the rasterizer), rejects the tile
// if a plane is <= 0 over all of it, drops planes that are > 0 over all of it, and writes the others as 32-bit
// TilePlanes (see tile_kernels.h for the proof); out may be null to classify only (binning). kWhole: no plane left and
// the tile lies inside the prim's box.
// Both run the instruction-set build cpu.h picks (tile_dispatch.cpp); isa_base:: and isa_avx2:: name the builds.
TileClass tile_setup(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out);

// Fixed capacity: one primitive covers each 4x4 block of a tile at most once (<= (64/4)^2 = 256 blocks), and full
// blocks (4, 16 or tile sized) never overlap, so neither list can exceed 256 entries; an entry is written at the
// count before it is known to be kept, which stays below 256 by the same argument. Block16 entries (hier at 1x): at
// most one per 16x16 block of the tile (16; the 16-px window of a small primitive makes one), written
// unconditionally and kept when non-empty, hence one spare entry. No allocation per primitive.
struct TileScratch {
    static constexpr size_t kCapacity = 256, kCapacity16 = 16;
    Block4 blocks[kCapacity];
    FullBlock full[kCapacity];
    Block16 blocks16[kCapacity16 + 1];
    size_t num_blocks = 0, num_full = 0, num_blocks16 = 0;
};

// Appends the coverage of `prim` in `tile` to scratch (cleared first). `whole` = binned as a whole-tile command.
// `edges`: the primitive's PrimEdges, read by the reference and float methods only (may be null for the others).
void raster_prim_in_tile(Method method, const Prim& prim, const PrimEdges* edges, const TileGeom& tile, bool whole,
                         TileScratch* scratch);

namespace isa_base {
TileClass tile_setup(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out);
void raster_prim_in_tile(Method method, const Prim& prim, const PrimEdges* edges, const TileGeom& tile, bool whole,
                         TileScratch* scratch);
}  // namespace isa_base
namespace isa_avx2 {
TileClass tile_setup(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out);
void raster_prim_in_tile(Method method, const Prim& prim, const PrimEdges* edges, const TileGeom& tile, bool whole,
                         TileScratch* scratch);
}  // namespace isa_avx2

}  // namespace tilevk::rast
