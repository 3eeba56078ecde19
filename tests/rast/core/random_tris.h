// Test helper: seeded random triangle generators for the method-equivalence tests and the stability sweep.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include "rast/core/primitive.h"

namespace tilevk::rast::test {

enum class TriKind { kTiny, kSliver, kHuge, kTileBorder, kExtreme, kDegenerate, kMedium, kExact };

class TriGen {
  public:
    TriGen(uint64_t seed, int w, int h) : rng_(seed), w_(w), h_(h) {}

    float uni(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
    int irand(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }

    TriangleInput make(TriKind kind, uint32_t payload) {
        TriangleInput t;
        const float cx = uni(-8.0f, w_ + 8.0f), cy = uni(-8.0f, h_ + 8.0f);
        switch (kind) {
            case TriKind::kTiny:
                for (int i = 0; i < 3; ++i) t.x[i] = cx + uni(-2.5f, 2.5f), t.y[i] = cy + uni(-2.5f, 2.5f);
                break;
            case TriKind::kMedium:
                for (int i = 0; i < 3; ++i) t.x[i] = cx + uni(-60.0f, 60.0f), t.y[i] = cy + uni(-60.0f, 60.0f);
                break;
            case TriKind::kSliver: {
                const float ang = uni(0.0f, 6.2831853f), len = uni(4.0f, 400.0f), wid = uni(0.0f, 0.3f);
                const float dx = std::cos(ang) * len, dy = std::sin(ang) * len;
                t.x[0] = cx, t.y[0] = cy;
                t.x[1] = cx + dx, t.y[1] = cy + dy;
                const float f = uni(0.0f, 1.0f);
                t.x[2] = cx + f * dx - std::sin(ang) * wid, t.y[2] = cy + f * dy + std::cos(ang) * wid;
                break;
            }
            case TriKind::kHuge:
                // One vertex near the framebuffer so most of them cover it; the others anywhere in range.
                t.x[0] = cx, t.y[0] = cy;
                for (int i = 1; i < 3; ++i) t.x[i] = uni(-16000.0f, 16000.0f), t.y[i] = uni(-16000.0f, 16000.0f);
                break;
            case TriKind::kExtreme:
                // Vertices at the edge of the representable range (some beyond it: must be rejected cleanly).
                for (int i = 0; i < 3; ++i) {
                    const float m = uni(16380.0f, 16384.2f);
                    t.x[i] = irand(0, 1) ? m : -m + w_ * (irand(0, 1));
                    t.y[i] = irand(0, 2) == 0 ? uni(-16384.2f, 16384.2f) : (irand(0, 1) ? m : -m);
                }
                if (irand(0, 1)) t.x[irand(0, 2)] = cx, t.y[irand(0, 2)] = cy;
                break;
            case TriKind::kTileBorder:
                // Vertices on or within a pixel of 16/64-px block borders, quantized to 1/8 px.
                for (int i = 0; i < 3; ++i) {
                    const int step = irand(0, 1) ? 64 : 16;
                    t.x[i] = float(irand(-1, w_ / step + 1) * step) + float(irand(-8, 8)) / 8.0f;
                    t.y[i] = float(irand(-1, h_ / step + 1) * step) + float(irand(-8, 8)) / 8.0f;
                }
                break;
            case TriKind::kDegenerate: {
                // Collinear or repeated vertices (snapping may leave a tiny non-zero area).
                t.x[0] = cx, t.y[0] = cy;
                const float dx = uni(-80.0f, 80.0f), dy = uni(-80.0f, 80.0f);
                const float f = irand(0, 2) == 0 ? 0.0f : uni(-1.0f, 2.0f);
                t.x[1] = cx + dx, t.y[1] = cy + dy;
                t.x[2] = cx + f * dx, t.y[2] = cy + f * dy;
                if (irand(0, 3) == 0) t.x[2] = t.x[1], t.y[2] = t.y[1];
                break;
            }
            case TriKind::kExact:
                // Quantized to 1/8 px: vertices and edges land exactly on 1x centres and 4x sample points.
                for (int i = 0; i < 3; ++i)
                    t.x[i] = float(irand(-16, w_ * 8 + 16)) / 8.0f, t.y[i] = cy + float(irand(-96, 96)) / 8.0f;
                break;
        }
        if (irand(0, 1)) std::swap(t.x[1], t.x[2]), std::swap(t.y[1], t.y[2]);
        t.cull = static_cast<CullMode>(irand(0, 9) < 7 ? 0 : irand(1, 3));
        t.front_ccw = irand(0, 1);
        t.flatshade_first = irand(0, 3) != 0;
        t.common.payload = payload;
        t.common.sample_mask = irand(0, 9) == 0 ? uint16_t(irand(0, 15)) : 0xF;
        if (irand(0, 1)) {
            const int x0 = irand(-4, w_ - 1), y0 = irand(-4, h_ - 1);
            t.common.clip = {x0, y0, irand(x0, w_ + 4), irand(y0, h_ + 4)};
        } else {
            t.common.clip = {0, 0, w_, h_};
        }
        return t;
    }

  private:
    std::mt19937_64 rng_;
    int w_, h_;
};

}  // namespace tilevk::rast::test
