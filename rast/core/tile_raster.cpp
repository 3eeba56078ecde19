// Per-tile rasterization of one primitive: the hierarchy (hier), the bounding-box scan (bbox), the brute-force
// oracle (reference) and the unsnapped float baseline (float). Built once per instruction set (rast/core/isa.h);
// tile_dispatch.cpp calls the one the CPU runs.
#include "rast/core/tile_raster.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>

#if TILEVK_SIMD_AVX2
#include <immintrin.h>
#endif

namespace tilevk::rast::TILEVK_ISA {

namespace {

void sample_offset(int samples, int s, int32_t* sx, int32_t* sy) {
    if (samples == 1) {
        *sx = 0, *sy = 0;
    } else {
        *sx = kSamplePos4x[s][0], *sy = kSamplePos4x[s][1];
    }
}

// Appends a 4x4 block from per-sample masks after ANDing the primitive's sample mask; drops empty blocks.
[[gnu::always_inline]] inline void push_block(TileScratch* out, int32_t x, int32_t y, const uint32_t* masks,
                                              int samples, uint16_t sample_mask) {
    Block4& b = out->blocks[out->num_blocks];
    b.x = x, b.y = y;
    if (samples == 1) {
        // 1x: one mask; the other slots must still read zero for the consumer.
        const uint16_t m = static_cast<uint16_t>((sample_mask & 1u) ? masks[0] : 0u);
        b.mask[0] = m, b.mask[1] = 0, b.mask[2] = 0, b.mask[3] = 0;
        out->num_blocks += m != 0;
        return;
    }
    uint32_t any = 0;
    for (int s = 0; s < kMaxSamples; ++s) {
        b.mask[s] = static_cast<uint16_t>(s < samples && ((sample_mask >> s) & 1u) ? masks[s] : 0u);
        any |= b.mask[s];
    }
    out->num_blocks += any != 0;  // the slot is reused when empty
}

[[gnu::always_inline]] inline void push_full(TileScratch* out, int32_t x, int32_t y, int32_t size) {
    out->full[out->num_full++] = {x, y, size};
}

// Packed positions for the hot loops: x in the low, y in the high 32 bits (the memory order of Block4/FullBlock).
inline uint64_t pack_xy(int32_t x, int32_t y) {
    return static_cast<uint32_t>(x) | (uint64_t{static_cast<uint32_t>(y)} << 32);
}
// Offset of lane i's 4x4 block in a 16x16 block: (4*(i&3), 4*(i>>2)) packed.
inline constexpr uint64_t kLaneXY4[16] = {0x000000000ull, 0x000000004ull, 0x000000008ull, 0x00000000Cull,
                                          0x400000000ull, 0x400000004ull, 0x400000008ull, 0x40000000Cull,
                                          0x800000000ull, 0x800000004ull, 0x800000008ull, 0x80000000Cull,
                                          0xC00000000ull, 0xC00000004ull, 0xC00000008ull, 0xC0000000Cull};
static_assert(sizeof(Block4) == 16 && offsetof(Block4, mask) == 8 && sizeof(FullBlock) == 12);

// Block4 from packed xy and the four 16-bit sample masks packed (sample s in bits 16s..16s+15).
[[gnu::always_inline]] inline void store_block(Block4* b, uint64_t xy, uint64_t masks) {
    std::memcpy(static_cast<void*>(b), &xy, 8);  // Block4 is trivially copyable; the cast says the bytes are meant
    std::memcpy(reinterpret_cast<char*>(b) + 8, &masks, 8);
}
// The primitive's sample mask as a 4x lane mask over packed sample masks (sample s in bits 16s..16s+15).
inline uint64_t sample_keep(uint16_t sample_mask) {
    return (sample_mask & 1u ? 0xFFFFull : 0) | (sample_mask & 2u ? 0xFFFFull << 16 : 0) |
           (sample_mask & 4u ? 0xFFFFull << 32 : 0) | (sample_mask & 8u ? 0xFFFFull << 48 : 0);
}
[[gnu::always_inline]] inline void store_full(FullBlock* f, uint64_t xy, int32_t size) {
    std::memcpy(static_cast<void*>(f), &xy, 8);
    f->size = size;
}

// --- hier: 64 -> 16 -> 4 -----------------------------------------------------------------------------------------

using PlaneList = const TilePlane* const*;

// A 4x4 block at tile-relative (ox, oy) known not to be rejected by the level above.
[[gnu::always_inline]] inline void hier_block4(const Prim& prim, const TileGeom& t, PlaneList planes, int n, int32_t ox,
                                               int32_t oy, TileScratch* out) {
    uint32_t masks[4];
    for (int s = 0; s < t.samples; ++s) masks[s] = mask4x4(planes, n, s, ox, oy);
    push_block(out, t.x0 + ox, t.y0 + oy, masks, t.samples, prim.sample_mask);
}

// Classifies the 4x4 grid of sub-blocks of size 2^shift at (ox, oy) over the live planes; only lanes in `valid`
// are considered (sub-blocks that meet the primitive's box inside the tile). Returns the lanes rejected by no plane
// and those accepted by all; per plane, acc[k] says which lanes that plane accepts (so it can be dropped there).
[[gnu::always_inline]] inline void classify_grid(PlaneList planes, int n, int32_t ox, int32_t oy, int shift,
                                                 uint32_t valid, uint32_t* live, uint32_t* full, uint32_t* acc) {
    uint32_t rej_any = 0, acc_all = valid;
    for (int k = 0; k < n; ++k) {
        uint32_t rej, a;
        classify16(*planes[k], ox, oy, shift, &rej, &a);
        rej_any |= rej;
        acc_all &= a;
        acc[k] = a;
    }
    *live = valid & ~rej_any;
    *full = *live & acc_all;
}

// Bits i of the 4 lanes along one axis whose block [o + i*w, o + i*w + w-1] (w = 2^shift) meets [lo, hi]:
// floor((lo-o)/w) <= i <= floor((hi-o)/w) (arithmetic shift is floor), clamped to [0, 3].
inline uint32_t lane_range(int32_t o, int shift, int32_t lo, int32_t hi) {
    const int32_t first = std::max((lo - o) >> shift, 0), last = std::min((hi - o) >> shift, 3);
    return first > last ? 0u : (2u << last) - (1u << first);
}

// The 4x4 lane set of row bits `rows` and column bits `cols` (both < 16): row bit r -> bit 4r, then times cols
// copies the column bits into each selected row without carries.
inline uint32_t lane_grid(uint32_t rows, uint32_t cols) {
    return ((rows & 1u) | ((rows & 2u) << 3) | ((rows & 4u) << 6) | ((rows & 8u) << 9)) * cols;
}

// Lanes of a 4x4 grid of 2^shift blocks at (ox, oy) whose block meets the tile-relative box [x0,x1]x[y0,y1].
inline uint32_t lanes_in_box(int32_t ox, int32_t oy, int shift, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    return lane_grid(lane_range(oy, shift, y0, y1), lane_range(ox, shift, x0, x1));
}

// Keeps the planes that do not accept lane `lane` (edges trivially inside a block are dropped within it).
[[gnu::always_inline]] inline int drop_accepted(PlaneList planes, int n, const uint32_t* acc, int lane,
                                                const TilePlane** kept) {
    int m = 0;
    for (int k = 0; k < n; ++k) {  // branch-free compaction: write every plane, advance past the kept ones
        kept[m] = planes[k];
        m += static_cast<int>(((acc[k] >> lane) & 1u) ^ 1u);
    }
    return m;
}

// 1x, in two steps so that the kernels of several 16x16 blocks can overlap (they are independent; emitting right
// after each one would chain every block behind the previous one's stores). Block16Result = one 16x16 block's
// result: the sixteen 4x4 masks from one fixed-cost kernel (block16_rows, no per-lane branch), its position and the
// lanes that meet the primitive's box within the tile (`valid`).
struct Block16Result {
    Block16Masks bm;
    int32_t x, y;  // absolute pixel origin
    uint32_t valid;
};

template <int kN>
[[gnu::always_inline]] inline void compute_block16_1x(const TileGeom& t, PlaneList planes, int n, int32_t ox,
                                                      int32_t oy, uint32_t valid, Block16Result* r) {
    int32_t base[Prim::kMaxPlanes];
    for (int k = 0; k < n; ++k) base[k] = planes[k]->c[0] + planes[k]->a * ox + planes[k]->b * oy;
    block16_rows<kN>(planes, n, base, &r->bm);
    r->x = t.x0 + ox, r->y = t.y0 + oy;
    r->valid = valid;
}

// Any plane count >= 1: compile-time kernels for 1, 2 and 3 planes (p0, p1 = the first two planes).
[[gnu::always_inline]] inline void compute_block16_1x_any(const TileGeom& t, const TilePlane* p0, const TilePlane* p1,
                                                          PlaneList planes, int n, int32_t ox, int32_t oy,
                                                          uint32_t valid, Block16Result* r) {
    if (n == 1) return compute_block16_1x<1>(t, &p0, 1, ox, oy, valid, r);
    if (n == 2) {
        const TilePlane* two[2] = {p0, p1};
        return compute_block16_1x<2>(t, two, 2, ox, oy, valid, r);
    }
    if (n == 3) return compute_block16_1x<3>(t, planes, 3, ox, oy, valid, r);
    compute_block16_1x<0>(t, planes, n, ox, oy, valid, r);
}

// Hands one 16x16 block's result over as a Block16 entry at *b (1x): the kernel's sixteen masks with the lanes
// outside `valid` zeroed, written unconditionally and kept when some lane has coverage (TileScratch has one spare
// entry). No per-lane list is built: full 4x4 lanes travel as 0xFFFF masks and the consumer walks the non-zero ones.
[[gnu::always_inline]] inline void emit_block16_1x(const Block16Result& r, Block16*& b) {
    b->x = r.x, b->y = r.y;
#if TILEVK_SIMD_AVX2
    // valid's bit j -> word j all ones: isolate bit j in word j, compare with it.
    const __m256i bit = _mm256_setr_epi16(1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384,
                                          static_cast<int16_t>(0x8000));
    const __m256i keep =
        _mm256_cmpeq_epi16(_mm256_and_si256(_mm256_set1_epi16(static_cast<int16_t>(r.valid)), bit), bit);
    const __m256i masks = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.bm.mask));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(b->mask), _mm256_and_si256(masks, keep));
#else
    for (int j = 0; j < 16; ++j) b->mask[j] = (r.valid >> j) & 1u ? r.bm.mask[j] : uint16_t{0};
#endif
    b += (r.valid & ~r.bm.empty) != 0;
}

[[gnu::always_inline]] inline void emit_block16_1x(const Block16Result& r, TileScratch* out) {
    Block16* b = out->blocks16 + out->num_blocks16;
    emit_block16_1x(r, b);
    out->num_blocks16 = static_cast<size_t>(b - out->blocks16);
}

// 4x: a 16x16 block at (ox, oy): classify its sixteen 4x4 blocks, emit the accepted ones as whole 4x4 blocks (no
// pixel work), mask the partial ones. Per plane the value at the block origin is computed once; a lane's 4x4 block
// then starts at base + step4[lane] (the pre-shifted corner step table), so a lane costs one broadcast-add-movemask
// per plane and sample. kN = number of planes when known at compile time (1..3, the usual case), 0 = use n. Full
// and partial lanes have their own loops (a full lane would cost 4 masks per plane). (1x: compute_block16_1x.)
template <int kN>
void hier_block16_n(const Prim& prim, const TileGeom& t, PlaneList planes, int n, int32_t ox, int32_t oy,
                    uint32_t valid, TileScratch* out) {
    if constexpr (kN != 0) n = kN;
    uint32_t rej_any = 0, acc_all = valid;
    for (int k = 0; k < n; ++k) {
        uint32_t rej, acc;
        classify16(*planes[k], ox, oy, 2, &rej, &acc);
        rej_any |= rej, acc_all &= acc;
    }
    const uint32_t live = valid & ~rej_any, full = live & acc_all;
    // Positions as packed (x | y << 32) words: one add per lane gives both (x, y >= 0, so no carry crosses).
    const uint64_t xy0 = pack_xy(t.x0 + ox, t.y0 + oy);
    size_t nb = out->num_blocks, nf = out->num_full;
    const uint64_t keep = sample_keep(prim.sample_mask);
    for (uint32_t m = full; m; m &= m - 1) store_full(&out->full[nf++], xy0 + kLaneXY4[std::countr_zero(m)], 4);
    for (uint32_t m = live & ~full; m; m &= m - 1) {
        const int lane = std::countr_zero(m);
        const uint64_t masks = keep & mask4x4_samples4<kN>(planes, n, ox + 4 * (lane & 3), oy + 4 * (lane >> 2));
        store_block(&out->blocks[nb], xy0 + kLaneXY4[lane], masks);
        nb += masks != 0;
    }
    out->num_blocks = nb, out->num_full = nf;
}

void hier_block16(const Prim& prim, const TileGeom& t, PlaneList planes, int n, int32_t ox, int32_t oy, uint32_t valid,
                  TileScratch* out) {
    if (t.samples == 1) {
        Block16Result r;
        compute_block16_1x_any(t, planes[0], planes[(n >> 1) & 1], planes, n, ox, oy, valid, &r);
        return emit_block16_1x(r, out);
    }
    switch (n) {
        case 1:
            return hier_block16_n<1>(prim, t, planes, n, ox, oy, valid, out);
        case 2:
            return hier_block16_n<2>(prim, t, planes, n, ox, oy, valid, out);
        case 3:
            return hier_block16_n<3>(prim, t, planes, n, ox, oy, valid, out);
        default:
            return hier_block16_n<0>(prim, t, planes, n, ox, oy, valid, out);
    }
}

// Box ∩ tile in tile-relative pixels (inclusive).
struct RelBox {
    int32_t x0, y0, x1, y1;
};
RelBox rel_box(const Prim& prim, const TileGeom& t) {
    return {std::max(prim.x0, t.x0) - t.x0, std::max(prim.y0, t.y0) - t.y0, std::min(prim.x1, t.x0 + t.size - 1) - t.x0,
            std::min(prim.y1, t.y0 + t.size - 1) - t.y0};
}

// Every 4x4 block of the box, masked directly (no classification).
// Kept out of line: inlined into raster_prim_in_tile, GCC 12 compiles its loop nest less well (+10% instructions).
// 4x: one kernel call gives a block's four sample masks (the small-triangle scenes' hot loop at 4x). kN = plane
// count known at compile time (0: use n).
template <int kN>
void scan_blocks_4x(const Prim& prim, const TileGeom& t, PlaneList planes, int n, const RelBox& r, TileScratch* out) {
    const uint64_t keep = sample_keep(prim.sample_mask);
    size_t nb = out->num_blocks;
#if TILEVK_SIMD_AVX2
    // Small steps (tile_kernels.h SampleSteps16): the four samples of a block in four 16-bit vectors per plane.
    if constexpr (kN != 0) {
        SampleSteps16 steps[kN];
        bool small = true;
        for (int k = 0; k < kN; ++k) small &= fill_sample_steps16(*planes[k], &steps[k]);
        if (small) {
            for (int32_t by = r.y0 & ~3; by <= r.y1; by += 4)
                for (int32_t bx = r.x0 & ~3; bx <= r.x1; bx += 4) {
                    const uint64_t masks = keep & mask4x4_samples4_16_avx2<kN>(planes, steps, kN, bx, by);
                    store_block(&out->blocks[nb], pack_xy(t.x0 + bx, t.y0 + by), masks);
                    nb += masks != 0;
                }
            out->num_blocks = nb;
            return;
        }
    }
#endif
    for (int32_t by = r.y0 & ~3; by <= r.y1; by += 4)
        for (int32_t bx = r.x0 & ~3; bx <= r.x1; bx += 4) {
            const uint64_t masks = keep & mask4x4_samples4<kN>(planes, n, bx, by);
            store_block(&out->blocks[nb], pack_xy(t.x0 + bx, t.y0 + by), masks);
            nb += masks != 0;  // the slot is reused when empty
        }
    out->num_blocks = nb;
}

[[gnu::noinline]] void scan_blocks(const Prim& prim, const TileGeom& t, PlaneList planes, int n, const RelBox& r,
                                   TileScratch* out) {
    if (t.samples == 1) {
        for (int32_t by = r.y0 & ~3; by <= r.y1; by += 4)
            for (int32_t bx = r.x0 & ~3; bx <= r.x1; bx += 4) hier_block4(prim, t, planes, n, bx, by, out);
        return;
    }
    switch (n) {
        case 1:
            return scan_blocks_4x<1>(prim, t, planes, n, r, out);
        case 2:
            return scan_blocks_4x<2>(prim, t, planes, n, r, out);
        case 3:
            return scan_blocks_4x<3>(prim, t, planes, n, r, out);
        default:
            return scan_blocks_4x<0>(prim, t, planes, n, r, out);
    }
}

// planes: Prim::kMaxPlanes slots pointing into the TilePlane array `tp`, the first n of them the live planes (the 1x
// path reads three slots whatever n is).
// Small-primitive fast path: a box (within the tile) spanning at most twelve 4x4 blocks is masked directly by
// scan_blocks, which hier shares with bbox (classifying would cost about as much). The box bounds all coverage, so
// nothing outside it can be missed.
inline bool box_is_small(const RelBox& r) {
    return ((r.x1 >> 2) - (r.x0 >> 2) + 1) * ((r.y1 >> 2) - (r.y0 >> 2) + 1) <= 12;
}

// Not inlined: its frame (sixteen block results) would otherwise be set up for every small primitive too.
// A box spanning at most 4x4 blocks (more than twelve: exactly 4x4, so the window below covers exactly its blocks)
// gets the 4-px level in one 16-px window at its own (4-aligned, not 16-aligned) origin.
[[gnu::noinline]] void raster_hier(const Prim& prim, const TileGeom& t, TilePlane* tp, PlaneList planes, int n,
                                   const RelBox& r, TileScratch* out) {
    const int32_t bw = (r.x1 >> 2) - (r.x0 >> 2), bh = (r.y1 >> 2) - (r.y0 >> 2);
    if (t.samples == 1)
        for (int k = 0; k < n; ++k) fill_row_table(&tp[k]);  // the 1x 16x16 kernel's tables (block16_rows)
    if (bw <= 3 && bh <= 3) {
        // One 16x16-px window anchored at the box (the tile-aligned 16-px grid might cut it into four).
        for (int32_t oy = r.y0 & ~3; oy <= r.y1; oy += 16)
            for (int32_t ox = r.x0 & ~3; ox <= r.x1; ox += 16)
                hier_block16(prim, t, planes, n, ox, oy, lanes_in_box(ox, oy, 2, r.x0, r.y0, r.x1, r.y1), out);
        return;
    }
    if (t.size == 16) return hier_block16(prim, t, planes, n, 0, 0, lanes_in_box(0, 0, 2, r.x0, r.y0, r.x1, r.y1), out);
    // acc of the planes past n: accepting everywhere (the 1x path below reads three).
    uint32_t live, full, acc[Prim::kMaxPlanes] = {0, 0xFFFF, 0xFFFF};
    classify_grid(planes, n, 0, 0, 4, lanes_in_box(0, 0, 4, r.x0, r.y0, r.x1, r.y1), &live, &full, acc);
    for (uint32_t m = full; m; m &= m - 1) {
        const int lane = std::countr_zero(m);
        push_full(out, t.x0 + 16 * (lane & 3), t.y0 + 16 * (lane >> 2), 16);
    }
    // 4-px columns/rows of the tile that meet the box (bit j = pixels [4j, 4j+3]); a 16-px lane takes 4 of each.
    const uint32_t cols4 = (2u << (r.x1 >> 2)) - (1u << (r.x0 >> 2)), rows4 = (2u << (r.y1 >> 2)) - (1u << (r.y0 >> 2));
    if (t.samples == 1 && n <= 3) {
        // 1x with up to three planes (every triangle): the planes kept per 16x16 lane are chosen from a fixed three
        // (slots past n accept everywhere, so they are never kept; the list's slots all point into the caller's
        // plane array), so neither the choice nor the kernel dispatch branches on the tile's plane count.
        Block16Result blocks[16];
        int count = 0;
        for (uint32_t m = live & ~full; m; m &= m - 1) {
            const int lane = std::countr_zero(m);
            const int col = lane & 3, row = lane >> 2;
            // Sized for any prim (not 3) so that the generic kernel instance compute_block16_1x_any may reach for
            // n > 3 has no out-of-bounds path the compiler must warn about; here k is 1..3.
            const TilePlane* kept[Prim::kMaxPlanes];
            const int k = drop_accepted(planes, 3, acc, lane, kept);  // 1..3: the lane is not full
            const uint32_t valid = lane_grid((rows4 >> (4 * row)) & 15u, (cols4 >> (4 * col)) & 15u);
            compute_block16_1x_any(t, kept[0], kept[k >> 1], kept, k, 16 * col, 16 * row, valid, &blocks[count++]);
        }
        Block16* b = out->blocks16 + out->num_blocks16;
        for (int i = 0; i < count; ++i) emit_block16_1x(blocks[i], b);
        out->num_blocks16 = static_cast<size_t>(b - out->blocks16);
        return;
    }
    for (uint32_t m = live & ~full; m; m &= m - 1) {
        const int lane = std::countr_zero(m);
        const int col = lane & 3, row = lane >> 2;
        const TilePlane* kept[Prim::kMaxPlanes];
        const int k = drop_accepted(planes, n, acc, lane, kept);
        const uint32_t valid = lane_grid((rows4 >> (4 * row)) & 15u, (cols4 >> (4 * col)) & 15u);
        hier_block16(prim, t, kept, k, 16 * col, 16 * row, valid, out);
    }
}

// --- bbox: every 4x4 block of box ∩ tile, all live planes evaluated in 32 bits (Giesen-style scan): scan_blocks ---

// --- reference: per pixel, per sample, 64-bit, shape and scissor planes only, box as loop bounds
// ------------------------------

template <typename Inside>
void raster_per_sample(const Prim& prim, const TileGeom& t, Inside inside, TileScratch* out) {
    const int32_t x0 = std::max(prim.x0, t.x0), x1 = std::min(prim.x1, t.x0 + t.size - 1);
    const int32_t y0 = std::max(prim.y0, t.y0), y1 = std::min(prim.y1, t.y0 + t.size - 1);
    for (int32_t by = y0 & ~3; by <= y1; by += 4) {
        for (int32_t bx = x0 & ~3; bx <= x1; bx += 4) {
            uint32_t masks[4] = {0, 0, 0, 0};
            for (int i = 0; i < 16; ++i) {
                const int32_t px = bx + (i & 3), py = by + (i >> 2);
                if (px < x0 || px > x1 || py < y0 || py > y1) continue;
                for (int s = 0; s < t.samples; ++s)
                    if (inside(px, py, s)) masks[s] |= 1u << i;
            }
            push_block(out, bx, by, masks, t.samples, prim.sample_mask);
        }
    }
}

void raster_reference(const Prim& prim, const PrimEdges& edges, const TileGeom& t, TileScratch* out) {
    raster_per_sample(
        prim, t,
        [&](int32_t px, int32_t py, int s) {
            int32_t sx, sy;
            sample_offset(t.samples, s, &sx, &sy);
            const int64_t X = int64_t{px} * kFixedOne + sx, Y = int64_t{py} * kFixedOne + sy;
            // The scissor planes cut samples (lavapipe's 4x scissor, setup.cpp), so the box cannot stand for them.
            for (int k = 0; k < prim.num_shape_planes + prim.num_scissor_planes; ++k) {
                const EdgePlane& p = edges.planes[k];
                if (!(p.c + p.a * X + p.b * Y > 0)) return false;  // E = c + a*X + b*Y > 0
            }
            return true;
        },
        out);
}

// --- float: unsnapped float edge functions at the sample's window position ---------------------------------------

void raster_float(const Prim& prim, const PrimEdges& edges, const TileGeom& t, TileScratch* out) {
    if (!prim.is_triangle) {
        raster_reference(prim, edges, t, out);
        return;
    }
    raster_per_sample(
        prim, t,
        [&](int32_t px, int32_t py, int s) {
            // Window position of the sample: pixel centre at 1x, corner + pos/256 at 4x.
            float X, Y;
            if (t.samples == 1) {
                X = static_cast<float>(px) + 0.5f, Y = static_cast<float>(py) + 0.5f;
            } else {
                X = static_cast<float>(px) + kSamplePos4x[s][0] / 256.0f;
                Y = static_cast<float>(py) + kSamplePos4x[s][1] / 256.0f;
            }
            for (int i = 0; i < 3; ++i) {
                const int j = (i + 1) % 3;
                const float dy = edges.fy[i] - edges.fy[j], dx = edges.fx[i] - edges.fx[j];
                // E = DY*(x_i - X) - DX*(y_i - Y), top-left edges inclusive.
                const float e = dy * (edges.fx[i] - X) - dx * (edges.fy[i] - Y);
                const bool top_left = dy < 0.0f || (dy == 0.0f && dx > 0.0f);
                if (!(e > 0.0f || (e == 0.0f && top_left))) return false;
            }
            const int64_t SX = int64_t{px} * kFixedOne + kSamplePos4x[s][0],
                          SY = int64_t{py} * kFixedOne + kSamplePos4x[s][1];
            for (int k = prim.num_shape_planes; k < prim.num_shape_planes + prim.num_scissor_planes; ++k) {
                const EdgePlane& p = edges.planes[k];  // only at 4x
                if (!(p.c + p.a * SX + p.b * SY > 0)) return false;
            }
            return true;
        },
        out);
}

// tile_setup for kSamples samples (1 or 4). At 1x only c[0] is written and no step4 table (the 4x levels' table):
// nothing at 1x reads them, and this runs once per primitive and tile for every method.
template <int kSamples>
TileClass tile_setup_n(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out) {
    int n = 0;
    const int64_t span = tile.size - 1;
    for (int k = 0; k < prim.num_planes; ++k) {
        const PixelPlane& p = prim.pix[k];
        // Value at the tile origin pixel: c0 + a*tx0 + b*ty0 (|.| < 2^48 + 2^38: 64-bit).
        const int64_t c = p.c0 + int64_t{p.a} * tile.x0 + int64_t{p.b} * tile.y0;
        int32_t d[4] = {0, 0, 0, 0};  // the samples' offsets; sample 0's is 0
        int32_t dlo = 0, dhi = 0;
        if constexpr (kSamples == 4)
            for (int s = 1; s < 4; ++s) {
                d[s] = prim.d[k][s - 1];
                dlo = std::min(dlo, d[s]), dhi = std::max(dhi, d[s]);
            }
        const int32_t up = std::max(p.a, 0) + std::max(p.b, 0), dn = std::min(p.a, 0) + std::min(p.b, 0);
        const int64_t lo = c + dlo, hi = c + dhi;
        const int64_t min_v = lo + span * dn, max_v = hi + span * up;  // extremes over the tile
        if (max_v <= 0) return TileClass::kReject;
        if (!out) {
            n += min_v <= 0;  // planes > 0 over the whole tile are dropped
            continue;
        }
        // Written unconditionally and kept only if live (branch-free: whether an edge is trivially inside a tile
        // is unpredictable). A dropped plane's slot is overwritten by the next live one or ignored (its 32-bit
        // casts may wrap; they are never read). Live plane: every value over the tile is in (-2^30, 2^30]
        // (tile_kernels.h), so 32 bits hold them.
        TilePlane& tp = out[n];
        n += min_v <= 0;
        tp.a = p.a, tp.b = p.b;
        tp.lo = static_cast<int32_t>(lo), tp.hi = static_cast<int32_t>(hi);
        for (int s = 0; s < kSamples; ++s) tp.c[s] = static_cast<int32_t>(c + d[s]);
        fill_step_table<kSamples == 4>(&tp);
    }
    *num_out = n;
    return n == 0 ? TileClass::kWhole : TileClass::kPartial;
}

}  // namespace

TileClass tile_setup(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out) {
    return tile.samples == 1 ? tile_setup_n<1>(prim, tile, out, num_out) : tile_setup_n<4>(prim, tile, out, num_out);
}

void raster_prim_in_tile(Method method, const Prim& prim, const PrimEdges* edges, const TileGeom& tile, bool whole,
                         TileScratch* scratch) {
    scratch->num_blocks = 0;
    scratch->num_full = 0;
    scratch->num_blocks16 = 0;
    if (method == Method::kReference) return raster_reference(prim, *edges, tile, scratch);
    if (method == Method::kFloat) return raster_float(prim, *edges, tile, scratch);
    if (whole) {
        push_full(scratch, tile.x0, tile.y0, tile.size);
        return;
    }
    TilePlane planes[Prim::kMaxPlanes];
    int n = 0;
    const TileClass cls = TILEVK_ISA::tile_setup(prim, tile, planes, &n);
    const TilePlane* list[Prim::kMaxPlanes];
    for (int k = 0; k < Prim::kMaxPlanes; ++k) list[k] = &planes[k];  // all slots: a fixed loop, no branch on n
    if (cls == TileClass::kReject) return;
    if (cls == TileClass::kWhole && method == Method::kHier) {
        push_full(scratch, tile.x0, tile.y0, tile.size);
        return;
    }
    const RelBox r = rel_box(prim, tile);
    if (method == Method::kHier && !box_is_small(r)) return raster_hier(prim, tile, planes, list, n, r, scratch);
    scan_blocks(prim, tile, list, n, r, scratch);  // bbox; hier's small-primitive path
}

}  // namespace tilevk::rast::TILEVK_ISA
