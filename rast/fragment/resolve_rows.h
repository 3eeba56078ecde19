// The 4x resolve of four-byte UNORM8 texels in sample planes (the renderer's layout), eight pixels per step in the
// AVX2 build. Built once per instruction set (rast/meson.build, rast/core/isa.h); msaa.cpp resolve_unorm8_row<4>
// is its twin (four pixels per step with SSE2), calls the build the CPU runs and resolves the pixels it leaves.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tilevk::rast::fragment {
namespace isa_base {
int resolve_rgba8_planes(const uint8_t* src, size_t sample_stride, uint8_t* dst, int w);
}
namespace isa_avx2 {
// Resolves pixels [0, n) of the row, n = w rounded down to a multiple of 8, and returns n; the portable build
// returns 0. Per byte the same float operations as resolve_pixel, in the same order.
int resolve_rgba8_planes(const uint8_t* src, size_t sample_stride, uint8_t* dst, int w);
}  // namespace isa_avx2
}  // namespace tilevk::rast::fragment
