// The fused full-square kernel (fragment_plan.h SquarePlan): a fully covered square of a draw whose fragment shader
// copies one interpolated vec4 to an RGBA8/BGRA8 target, opaque or with standard alpha blending, at 1x without
// depth or stencil. Built once per instruction set like fragment_block.cpp; only the AVX2 build has the kernel.
//
// Why it exists: on such squares the block pipeline spends most of its time moving lanes between its steps (lane
// coordinates, the shader's input and output words, lane order <-> raster order), not computing (blend16's profile:
// shade_block_fast 39 %, blend_rgba8_block 34 % of the frame). Here each row of 8 pixels goes from plane to memory in
// registers, in raster order. The arithmetic per pixel is the block pipeline's, operation for operation:
//   a   = fmuladd(dady, py, fmuladd(dadx, px, a0))            (the inner term depends on the column only: computed
//                                                               once per column, the same bits)
//   a  *= fl(1 / w) for perspective inputs, w the position's 1/w plane at the pixel (mul_oow's NaN choice)
//   u8  = packus(packs(cvtps2dq(fl(min(1, a) * 255))))          (pack_rgba8_pairs, UnormPath::Avx8)
//   out = adds(mul_norm(s, sa), mul_norm(d, 255 - sa)) per byte (blend_over), or u8 (opaque), under the write mask.
// tests/rast/fragment/stage_test.cpp compares the squares with the reference pipeline byte for byte.
#include <cmath>
#include <cstring>

#include "rast/fragment/block_kernels.h"
#include "rast/render/fragment_plan.h"

namespace tilevk::rast::render::TILEVK_ISA {

#if TILEVK_SIMD_AVX2
namespace {

constexpr int kMaxSquare = 64;  // the tile size: the largest FullBlock

// The per-column terms of one plane: t[i] = fmuladd(dadx, px_i, a0) for the square's columns.
void column_terms(const fragment::Plane& p, const float* px, int size, bool fused, float* t) {
    const __m256 dadx = _mm256_set1_ps(p.dadx), a0 = _mm256_set1_ps(p.a0);
    for (int i = 0; i < size; i += 8) {
        const __m256 x = _mm256_load_ps(px + i);
        // -ffp-contract=off keeps the unfused form's two roundings apart
        _mm256_store_ps(t + i, fused ? _mm256_fmadd_ps(dadx, x, a0) : _mm256_add_ps(_mm256_mul_ps(dadx, x), a0));
    }
}

inline __m256 row_value(__m256 dady, __m256 py, __m256 t, bool fused) {
    return fused ? _mm256_fmadd_ps(dady, py, t) : _mm256_add_ps(_mm256_mul_ps(dady, py), t);
}

// blend_rgba8.cpp over_pair: every byte adds(mul_norm(s, sa), mul_norm(d, 255 - sa)) in 16-bit lanes.
inline __m256i over8(__m256i s, __m256i d) {
    const __m256i zero = _mm256_setzero_si256(), half = _mm256_set1_epi16(0x80), inv = _mm256_set1_epi16(0xff);
    const __m256i bcast_alpha16 = _mm256_setr_epi8(6, -1, 6, -1, 6, -1, 6, -1, 14, -1, 14, -1, 14, -1, 14, -1, 6, -1, 6,
                                                   -1, 6, -1, 6, -1, 14, -1, 14, -1, 14, -1, 14, -1);
    auto norm = [&](__m256i p) {
        p = _mm256_add_epi16(p, _mm256_srli_epi16(p, 8));
        return _mm256_srli_epi16(_mm256_add_epi16(p, half), 8);
    };
    auto part = [&](__m256i s16, __m256i d16) {
        const __m256i sa = _mm256_shuffle_epi8(s16, bcast_alpha16);
        return _mm256_add_epi16(norm(_mm256_mullo_epi16(s16, sa)),
                                norm(_mm256_mullo_epi16(d16, _mm256_xor_si256(sa, inv))));
    };
    return _mm256_packus_epi16(part(_mm256_unpacklo_epi8(s, zero), _mm256_unpacklo_epi8(d, zero)),
                               part(_mm256_unpackhi_epi8(s, zero), _mm256_unpackhi_epi8(d, zero)));
}

// What stays fixed over one square.
struct SquareCtx {
    const SquarePlan* sp = nullptr;
    fragment::Plane wplane, inputs[4];
    alignas(32) float t[5][kMaxSquare];  // column terms: the four channels, then w
    __m256i write_bytes;
    __m256 oow;  // kConstW: fl(1 / w) of every pixel
};

// How w varies over the square: not at all (the plane's steps are zero and a0 is finite and non-zero, so every
// pixel's fmuladds give a0 exactly and fl(1/w) is one value) or per pixel.
enum class WMode { kNone, kConstW, kPerPixel };

// One row of the square: `size` pixels at `row`, y coordinate py. Specialised on the per-draw choices so that the
// row loop is straight-line code.
template <bool kFused, WMode kW, bool kOver>
void shade_row(const SquareCtx& c, float py_value, int size, uint8_t* row) {
    const __m256 py = _mm256_set1_ps(py_value);
    const __m256 dady0 = _mm256_set1_ps(c.inputs[0].dady), dady1 = _mm256_set1_ps(c.inputs[1].dady);
    const __m256 dady2 = _mm256_set1_ps(c.inputs[2].dady), dady3 = _mm256_set1_ps(c.inputs[3].dady);
    const __m256 wdady = _mm256_set1_ps(c.wplane.dady), one = _mm256_set1_ps(1.0f);
    const bool bgra = c.sp->bgra;
    for (int i = 0; i < size; i += 8) {
        __m256 r = row_value(dady0, py, _mm256_load_ps(c.t[0] + i), kFused);
        __m256 g = row_value(dady1, py, _mm256_load_ps(c.t[1] + i), kFused);
        __m256 b = row_value(dady2, py, _mm256_load_ps(c.t[2] + i), kFused);
        __m256 a = row_value(dady3, py, _mm256_load_ps(c.t[3] + i), kFused);
        if constexpr (kW == WMode::kPerPixel) {
            const __m256 oow = _mm256_div_ps(one, row_value(wdady, py, _mm256_load_ps(c.t[4] + i), kFused));
            r = fragment::mul_oow(r, oow);
            g = fragment::mul_oow(g, oow);
            b = fragment::mul_oow(b, oow);
            a = fragment::mul_oow(a, oow);
        } else if constexpr (kW == WMode::kConstW) {
            // oow is not NaN: mul_oow's NaN choice is moot
            r = _mm256_mul_ps(r, c.oow);
            g = _mm256_mul_ps(g, c.oow);
            b = _mm256_mul_ps(b, c.oow);
            a = _mm256_mul_ps(a, c.oow);
        }
        const __m256i s = fragment::detail::pack_row8(bgra, r, g, b, a);
        auto* p = reinterpret_cast<__m256i*>(row + size_t(i) * 4);
        if constexpr (kOver) {
            const __m256i d = _mm256_loadu_si256(p);
            _mm256_storeu_si256(p, _mm256_blendv_epi8(d, over8(s, d), c.write_bytes));
        } else {
            _mm256_storeu_si256(p, s);  // opaque: every channel written
        }
    }
}

using RowFn = void (*)(const SquareCtx&, float, int, uint8_t*);

template <bool kFused, WMode kW>
RowFn row_function(bool over) {
    return over ? shade_row<kFused, kW, true> : shade_row<kFused, kW, false>;
}

RowFn row_function(bool fused, WMode w, bool over) {
    switch (w) {
        case WMode::kNone:
            return fused ? row_function<true, WMode::kNone>(over) : row_function<false, WMode::kNone>(over);
        case WMode::kConstW:
            return fused ? row_function<true, WMode::kConstW>(over) : row_function<false, WMode::kConstW>(over);
        case WMode::kPerPixel:
            break;
    }
    return fused ? row_function<true, WMode::kPerPixel>(over) : row_function<false, WMode::kPerPixel>(over);
}

}  // namespace

bool shade_square_fast(const BlockArgs& a, int32_t x, int32_t y, int32_t size) {
    if (size % 8 != 0 || size > kMaxSquare) return false;
    SquareCtx c;
    c.sp = &a.plan->square;
    const SquarePlan& sp = *c.sp;
    const float* attribs = a.planes + kPrimHeaderFloats;
    for (int k = 0; k < 4; ++k) c.inputs[k] = plane_of(attribs + sp.plane[k], k);
    c.wplane = plane_of(a.planes, 3);
    uint32_t word = 0;
    for (int i = 0; i < 4; ++i)
        if (sp.wmask_mem & (1u << i)) word |= 0xffu << (8 * i);
    c.write_bytes = _mm256_set1_epi32(int(word));
    WMode wmode = WMode::kNone;
    if (sp.perspective) {
        const fragment::Plane& w = c.wplane;
        const bool const_w = w.dadx == 0.0f && w.dady == 0.0f && std::isfinite(w.a0) && w.a0 != 0.0f;
        wmode = const_w ? WMode::kConstW : WMode::kPerPixel;
        c.oow = _mm256_set1_ps(1.0f / w.a0);
    }

    // Lane coordinates as make_lane_coords forms them: fl(fl(lane) + fl(block origin)) + offset.
    const fragment::EvalOffset off = fragment::plane_offset(1, -1);
    alignas(32) float px[kMaxSquare];
    for (int i = 0; i < size; ++i) {
        const int32_t xi = x + i;
        px[i] = (float(xi & 3) + float(xi & ~3)) + off.x;
    }
    for (int k = 0; k < 4; ++k) column_terms(c.inputs[k], px, size, a.fused, c.t[k]);
    if (wmode == WMode::kPerPixel) column_terms(c.wplane, px, size, a.fused, c.t[4]);

    const RowFn row = row_function(a.fused, wmode, sp.over);
    const ColorTarget& t = a.fb->color[0];
    uint8_t* origin = t.data + size_t(y) * t.row_pitch + size_t(x) * 4;
    for (int j = 0; j < size; ++j) {
        const int32_t yj = y + j;
        const float py = (float(yj & 3) + float(yj & ~3)) + off.y;
        row(c, py, size, origin + size_t(j) * t.row_pitch);
    }
    return true;
}

#else

bool shade_square_fast(const BlockArgs&, int32_t, int32_t, int32_t) {
    return false;  // the portable build shades squares block by block
}

#endif

}  // namespace tilevk::rast::render::TILEVK_ISA
