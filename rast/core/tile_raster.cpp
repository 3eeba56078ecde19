// Per-tile rasterization of one primitive: the hierarchy (hier), the bounding-box scan (bbox), the brute-force
// oracle (reference) and the unsnapped float baseline (float).
#include "rast/core/tile_raster.h"

#include <algorithm>
#include <bit>

namespace tilevk::rast {

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

// Lanes of a 4x4 grid of 2^shift blocks at (ox, oy) whose block meets the tile-relative box [x0,x1]x[y0,y1].
uint32_t lanes_in_box(int32_t ox, int32_t oy, int shift, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    const uint32_t cols = lane_range(ox, shift, x0, x1), rows = lane_range(oy, shift, y0, y1);
    // Row bit r -> bit 4r; times cols (< 16) copies the column bits into each selected row without carries.
    const uint32_t spread = (rows & 1u) | ((rows & 2u) << 3) | ((rows & 4u) << 6) | ((rows & 8u) << 9);
    return spread * cols;
}

// Keeps the planes that do not accept lane `lane` (edges trivially inside a block are dropped within it).
[[gnu::always_inline]] inline int drop_accepted(PlaneList planes, int n, const uint32_t* acc, int lane,
                                                const TilePlane** kept) {
    int m = 0;
    for (int k = 0; k < n; ++k)
        if (!((acc[k] >> lane) & 1u)) kept[m++] = planes[k];
    return m;
}

// A 16x16 block at (ox, oy): classify its sixteen 4x4 blocks, accept whole ones, mask the partial ones.
void hier_block16(const Prim& prim, const TileGeom& t, PlaneList planes, int n, int32_t ox, int32_t oy, uint32_t valid,
                  TileScratch* out) {
    uint32_t live, full, acc[Prim::kMaxPlanes];
    classify_grid(planes, n, ox, oy, 2, valid, &live, &full, acc);
    for (uint32_t m = live; m; m &= m - 1) {
        const int lane = std::countr_zero(m);
        const int32_t bx = ox + 4 * (lane & 3), by = oy + 4 * (lane >> 2);
        if ((full >> lane) & 1u) {
            push_full(out, t.x0 + bx, t.y0 + by, 4);
        } else {
            // Mask with the planes that do not accept this lane, directly (no kept-plane list at the last level).
            uint32_t masks[4] = {0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF};
            for (int k = 0; k < n; ++k) {
                if ((acc[k] >> lane) & 1u) continue;
                for (int s = 0; s < t.samples; ++s) masks[s] &= mask4x4(planes + k, 1, s, bx, by);
            }
            push_block(out, t.x0 + bx, t.y0 + by, masks, t.samples, prim.sample_mask);
        }
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
void scan_blocks(const Prim& prim, const TileGeom& t, PlaneList planes, int n, const RelBox& r, TileScratch* out) {
    for (int32_t by = r.y0 & ~3; by <= r.y1; by += 4)
        for (int32_t bx = r.x0 & ~3; bx <= r.x1; bx += 4) hier_block4(prim, t, planes, n, bx, by, out);
}

void raster_hier(const Prim& prim, const TileGeom& t, PlaneList planes, int n, TileScratch* out) {
    // Small-primitive fast paths (the box bounds all coverage, so nothing outside it can be missed): a box spanning
    // at most twelve 4x4-blocks is masked directly (classifying would cost about as much); one spanning at most 4x4 of
    // them gets the 4-px level in one 16-px window at its own (4-aligned, not 16-aligned) origin. Windows reach at most
    // 15 px past the tile edge, where values stay within 2^30 + 15*2^24 < 2^31; lanes outside the box are ignored.
    const RelBox r = rel_box(prim, t);
    const int32_t bw = (r.x1 >> 2) - (r.x0 >> 2), bh = (r.y1 >> 2) - (r.y0 >> 2);
    if ((bw + 1) * (bh + 1) <= 12) return scan_blocks(prim, t, planes, n, r, out);
    if (bw <= 3 && bh <= 3) {
        // One 16x16-px window anchored at the box (the tile-aligned 16-px grid might cut it into four).
        for (int32_t oy = r.y0 & ~3; oy <= r.y1; oy += 16)
            for (int32_t ox = r.x0 & ~3; ox <= r.x1; ox += 16)
                hier_block16(prim, t, planes, n, ox, oy, lanes_in_box(ox, oy, 2, r.x0, r.y0, r.x1, r.y1), out);
        return;
    }
    if (t.size == 16) return hier_block16(prim, t, planes, n, 0, 0, lanes_in_box(0, 0, 2, r.x0, r.y0, r.x1, r.y1), out);
    uint32_t live, full, acc[Prim::kMaxPlanes];
    classify_grid(planes, n, 0, 0, 4, lanes_in_box(0, 0, 4, r.x0, r.y0, r.x1, r.y1), &live, &full, acc);
    for (uint32_t m = live; m; m &= m - 1) {
        const int lane = std::countr_zero(m);
        const int32_t bx = 16 * (lane & 3), by = 16 * (lane >> 2);
        if ((full >> lane) & 1u) {
            push_full(out, t.x0 + bx, t.y0 + by, 16);
        } else {
            const TilePlane* kept[Prim::kMaxPlanes];
            const int k = drop_accepted(planes, n, acc, lane, kept);
            hier_block16(prim, t, kept, k, bx, by, lanes_in_box(bx, by, 2, r.x0, r.y0, r.x1, r.y1), out);
        }
    }
}

// --- bbox: every 4x4 block of box ∩ tile, all live planes evaluated in 32 bits (Giesen-style scan) --------------

void raster_bbox(const Prim& prim, const TileGeom& t, PlaneList planes, int n, TileScratch* out) {
    scan_blocks(prim, t, planes, n, rel_box(prim, t), out);
}

// --- reference: per pixel, per sample, 64-bit, shape planes only, box as loop bounds ------------------------------

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

void raster_reference(const Prim& prim, const TileGeom& t, TileScratch* out) {
    raster_per_sample(
        prim, t,
        [&](int32_t px, int32_t py, int s) {
            int32_t sx, sy;
            sample_offset(t.samples, s, &sx, &sy);
            const int64_t X = int64_t{px} * kFixedOne + sx, Y = int64_t{py} * kFixedOne + sy;
            for (int k = 0; k < prim.num_shape_planes; ++k) {
                const EdgePlane& p = prim.planes[k];
                if (!(p.c + p.a * X + p.b * Y > 0)) return false;  // E = c + a*X + b*Y > 0
            }
            return true;
        },
        out);
}

// --- float: unsnapped float edge functions at the sample's window position ---------------------------------------

void raster_float(const Prim& prim, const TileGeom& t, TileScratch* out) {
    if (!prim.is_triangle) {
        raster_reference(prim, t, out);
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
                const float dy = prim.fy[i] - prim.fy[j], dx = prim.fx[i] - prim.fx[j];
                // E = DY*(x_i - X) - DX*(y_i - Y), top-left edges inclusive.
                const float e = dy * (prim.fx[i] - X) - dx * (prim.fy[i] - Y);
                const bool top_left = dy < 0.0f || (dy == 0.0f && dx > 0.0f);
                if (!(e > 0.0f || (e == 0.0f && top_left))) return false;
            }
            return true;
        },
        out);
}

}  // namespace

TileClass tile_setup(const Prim& prim, const TileGeom& tile, TilePlane* out, int* num_out) {
    int n = 0;
    const int64_t span = tile.size - 1;
    for (int k = 0; k < prim.num_planes; ++k) {
        const PixelPlane& p = prim.pix[k];
        // Value at the tile origin pixel: c0 + a*tx0 + b*ty0 (|.| < 2^39 + 2^38: 64-bit).
        const int64_t c = p.c0 + int64_t{p.a} * tile.x0 + int64_t{p.b} * tile.y0;
        const int64_t lo = c + p.dlo, hi = c + p.dhi;
        const int64_t min_v = lo + span * (int64_t{std::min(p.a, 0)} + std::min(p.b, 0));
        const int64_t max_v = hi + span * (int64_t{std::max(p.a, 0)} + std::max(p.b, 0));
        if (max_v <= 0) return TileClass::kReject;
        if (min_v > 0) continue;  // trivially inside the whole tile: drop
        if (!out) {
            ++n;
            continue;
        }
        // Live plane: every value over the tile is in (-2^30, 2^30] (tile_kernels.h), so 32 bits hold them.
        TilePlane& tp = out[n++];
        tp.a = p.a, tp.b = p.b;
        tp.lo = static_cast<int32_t>(lo), tp.hi = static_cast<int32_t>(hi);
        for (int s = 0; s < 4; ++s) tp.c[s] = static_cast<int32_t>(c + p.d[s]);
        fill_step_table(&tp);
    }
    *num_out = n;
    return n == 0 ? TileClass::kWhole : TileClass::kPartial;
}

void raster_prim_in_tile(Method method, const Prim& prim, const TileGeom& tile, bool whole, TileScratch* scratch) {
    scratch->num_blocks = 0;
    scratch->num_full = 0;
    if (method == Method::kReference) return raster_reference(prim, tile, scratch);
    if (method == Method::kFloat) return raster_float(prim, tile, scratch);
    if (whole) {
        push_full(scratch, tile.x0, tile.y0, tile.size);
        return;
    }
    TilePlane planes[Prim::kMaxPlanes];
    int n = 0;
    const TileClass cls = tile_setup(prim, tile, planes, &n);
    const TilePlane* list[Prim::kMaxPlanes];
    for (int k = 0; k < n; ++k) list[k] = &planes[k];
    if (cls == TileClass::kReject) return;
    if (cls == TileClass::kWhole && method == Method::kHier) {
        push_full(scratch, tile.x0, tile.y0, tile.size);
        return;
    }
    if (method == Method::kHier)
        raster_hier(prim, tile, list, n, scratch);
    else
        raster_bbox(prim, tile, list, n, scratch);
}

}  // namespace tilevk::rast
