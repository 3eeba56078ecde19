// tile_setup and raster_prim_in_tile of the instruction-set build this process runs (cpu.h).
#include "rast/core/cpu.h"
#include "rast/core/tile_raster.h"

namespace tilevk::rast {

TileClass tile_setup(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out) {
#if TILEVK_AVX2_VARIANT
    if (kernel_isa() == Isa::kAvx2) return isa_avx2::tile_setup(prim, tile, out, num_out);
#endif
    return isa_base::tile_setup(prim, tile, out, num_out);
}

void raster_prim_in_tile(Method method, const Prim& prim, const PrimEdges* edges, const TileGeom& tile, bool whole,
                         TileScratch* scratch) {
#if TILEVK_AVX2_VARIANT
    if (kernel_isa() == Isa::kAvx2) return isa_avx2::raster_prim_in_tile(method, prim, edges, tile, whole, scratch);
#endif
    isa_base::raster_prim_in_tile(method, prim, edges, tile, whole, scratch);
}

}  // namespace tilevk::rast
