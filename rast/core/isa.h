// Instruction-set variants. The SIMD kernels (tile_kernels.h, rast/fragment/block_kernels.h) are written twice,
// scalar and AVX2/FMA, chosen by TILEVK_SIMD_AVX2 at compile time; the translation units that run them
// (rast/core/tile_raster.cpp, rast/render/fragment_block.cpp, rast/fragment/blend_rgba8.cpp) are built once per
// variant (rast/meson.build) with TILEVK_ISA naming the variant's namespace, and cpu.h picks the variant the CPU
// runs. The kernels have internal linkage (TILEVK_KERNEL): every translation unit keeps its own copy, so the AVX2
// copy of a kernel is never the one a portable translation unit links to.
#pragma once

#define TILEVK_KERNEL static inline

#ifndef TILEVK_ISA
#define TILEVK_ISA isa_base
#endif
#ifndef TILEVK_SIMD_AVX2
#define TILEVK_SIMD_AVX2 0
#endif
