#include "rast/render/linear_bins.h"

#include <algorithm>

namespace tilevk::rast::render {
namespace {

constexpr int kTileOrder = 6;  // 64x64 tiles
constexpr int kTileSize = 1 << kTileOrder;

struct Plane {
    int64_t c;
    int32_t dcdx, dcdy;
    uint32_t eo;
};

// Inclusive rectangles, as u_rect.
struct URect {
    int32_t x0, y0, x1, y1;
};

struct Binning {
    Plane planes[7];
    int nr_planes = 0;
    URect bbox{};     // x0, y0 clamped to 0
    URect trimmed{};  // bbox ∩ region
    bool culled = true;
    bool single_tile = false;
};

uint32_t floor_pot(uint32_t n) {
    if (n == 0) return 0;
    return 1u << (31 - __builtin_clz(n));
}

Binning setup(const int32_t x[3], const int32_t y[3], const ClipRect& clip) {
    Binning b;
    const URect region = {clip.x0, clip.y0, clip.x1 - 1, clip.y1 - 1};
    URect bbox = {std::min({x[0], x[1], x[2]}) >> 8, std::min({y[0], y[1], y[2]}) >> 8,
                  (std::max({x[0], x[1], x[2]}) - 1) >> 8, (std::max({y[0], y[1], y[2]}) - 1) >> 8};
    // u_rect_test_intersection
    if (bbox.x1 < region.x0 || region.x1 < bbox.x0 || bbox.y1 < region.y0 || region.y1 < bbox.y0) return b;
    bbox.x0 = std::max(bbox.x0, 0);
    bbox.y0 = std::max(bbox.y0, 0);
    // do_triangle_ccw: plane i from vertex i to i+1, c with the top-left bias, then dcdx/dcdy scaled by 256
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        Plane& p = b.planes[i];
        p.dcdx = y[i] - y[j];
        p.dcdy = x[i] - x[j];
        p.c = int64_t{p.dcdx} * x[i] - int64_t{p.dcdy} * y[i];
        if (p.dcdx < 0 || (p.dcdx == 0 && p.dcdy > 0)) p.c++;
        p.dcdx = static_cast<int32_t>(static_cast<uint32_t>(p.dcdx) << 8);
        p.dcdy = static_cast<int32_t>(static_cast<uint32_t>(p.dcdy) << 8);
        p.eo = 0;
        if (p.dcdx < 0) p.eo -= static_cast<uint32_t>(p.dcdx);
        if (p.dcdy > 0) p.eo += static_cast<uint32_t>(p.dcdy);
    }
    b.nr_planes = 3;
    // scissor_planes_needed + lp_setup_add_scissor_planes (single-sampled: adj 0)
    if (bbox.x0 < region.x0) b.planes[b.nr_planes++] = {-(int64_t{region.x0 - 1} << 8), -256, 0, 256};
    if (bbox.x1 > region.x1) b.planes[b.nr_planes++] = {(int64_t{region.x1} << 8) + 127, 256, 0, 0};
    if (bbox.y0 < region.y0) b.planes[b.nr_planes++] = {-(int64_t{region.y0 - 1} << 8), 0, 256, 256};
    if (bbox.y1 > region.y1) b.planes[b.nr_planes++] = {(int64_t{region.y1} << 8) + 127, 0, -256, 0};
    b.bbox = bbox;
    b.trimmed = {std::max(bbox.x0, region.x0), std::max(bbox.y0, region.y0), std::min(bbox.x1, region.x1),
                 std::min(bbox.y1, region.y1)};
    const uint32_t dx = floor_pot(static_cast<uint32_t>((bbox.x0 ^ bbox.x1) | (bbox.y0 ^ bbox.y1)));
    b.single_tile = dx < uint32_t(kTileSize);
    b.culled = false;
    return b;
}

enum class TileCmd { kOut, kPartial, kWhole };

TileCmd classify(const Binning& b, int32_t tx, int32_t ty) {
    bool out = false, partial = false;
    for (int i = 0; i < b.nr_planes; ++i) {
        const Plane& p = b.planes[i];
        const int64_t cx = p.c + int64_t{p.dcdy} * ty * kTileSize - int64_t{p.dcdx} * tx * kTileSize;
        // (dcdy - dcdx) is an int32 subtraction in llvmpipe (wraps for huge triangles), then - (int64)eo, << 6
        const int32_t d = static_cast<int32_t>(static_cast<uint32_t>(p.dcdy) - static_cast<uint32_t>(p.dcdx));
        const int64_t ei = (int64_t{d} - int64_t{p.eo}) * kTileSize;
        const int64_t eo = int64_t{p.eo} * kTileSize;
        out |= cx + eo < 0;
        partial |= cx + ei - 1 < 0;
    }
    return out ? TileCmd::kOut : partial ? TileCmd::kPartial : TileCmd::kWhole;
}

}  // namespace

void mark_partial_triangle_bins(const int32_t x[3], const int32_t y[3], const ClipRect& region, int32_t tiles_x,
                                std::vector<uint8_t>* tile_linear) {
    const Binning b = setup(x, y, region);
    if (b.culled) return;
    auto mark = [&](int32_t tx, int32_t ty) {
        const size_t i = size_t(ty) * size_t(tiles_x) + size_t(tx);
        if (tx >= 0 && tx < tiles_x && i < tile_linear->size()) (*tile_linear)[i] = 0;
    };
    if (b.single_tile) {
        mark(b.bbox.x0 / kTileSize, b.bbox.y0 / kTileSize);
        return;
    }
    const int32_t ix0 = b.trimmed.x0 / kTileSize, iy0 = b.trimmed.y0 / kTileSize;
    const int32_t ix1 = b.trimmed.x1 / kTileSize, iy1 = b.trimmed.y1 / kTileSize;
    for (int32_t ty = iy0; ty <= iy1; ++ty) {
        bool in = false;
        for (int32_t tx = ix0; tx <= ix1; ++tx) {
            const TileCmd c = classify(b, tx, ty);
            if (c == TileCmd::kOut) {
                if (in) break;  // exiting the triangle: the rest of the row is not visited
                continue;
            }
            in = true;
            if (c == TileCmd::kPartial) mark(tx, ty);
        }
    }
}

bool triangle_covers_whole_bin(const int32_t x[3], const int32_t y[3], const ClipRect& region, int32_t tx, int32_t ty) {
    const Binning b = setup(x, y, region);
    if (b.culled || b.single_tile) return false;
    if (tx < b.trimmed.x0 / kTileSize || tx > b.trimmed.x1 / kTileSize || ty < b.trimmed.y0 / kTileSize ||
        ty > b.trimmed.y1 / kTileSize)
        return false;
    return classify(b, tx, ty) == TileCmd::kWhole;
}

}  // namespace tilevk::rast::render
