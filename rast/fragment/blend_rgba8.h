// The prepared RGBA8 / BGRA8 blend (blend.h prepare_rgba8_blend) on 16 pixels at once. Built once per instruction
// set (TILEVK_ISA, rast/meson.build): the caller's own build picks the one it links to.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rast/fragment/blend.h"

#ifndef TILEVK_ISA
#define TILEVK_ISA isa_base
#endif

namespace tilevk::rast::fragment {
inline namespace TILEVK_ISA {

// blend_block for a prepared RGBA8 / BGRA8 state on a block whose 16 pixels all exist: 16 pixels at once with
// AVX2 (mul_norm in 16-bit lanes, saturating 8-bit ops). Returns false, writing nothing, in the portable build:
// blend_block is its scalar twin (tests/rast/fragment/kernel_test.cpp compares them). `src` is read through
// may_alias vector loads only: it may be the shader's output lane words (rast/render/fragment_block.cpp).
bool blend_rgba8_block(const Rgba8Blend& b, const float src[4][kBlockLanes], uint16_t lane_mask, uint8_t* block,
                       size_t pitch);

}  // namespace TILEVK_ISA
}  // namespace tilevk::rast::fragment
