// Stability sweep: pushes each coverage method (bbox, hier, float) against the 64-bit reference along four axes
// (coordinate magnitude, sliver aspect, sub-pixel offset, triangle size) at 1x and 4x, and writes per-triangle
// mismatch rates as CSV: sweep,param,samples,method,triangles,mismatches,rate
//   build/bench/rast/stability_sweep out.csv [triangles_per_point=1000]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>

#include "bench_util.h"
#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"

using namespace tilevk::rast;
using namespace tilevk::rast::bench;

namespace {

struct Point {
    const char* sweep;
    double param;
    int w, h;  // framebuffer
    std::function<TriangleInput(std::mt19937&)> make;
};

std::vector<uint64_t> hashes(const std::vector<TriangleInput>& tris, const Point& p, int samples, Method m) {
    ThreadPool pool(1);
    Scene scene({.width = p.w, .height = p.h, .samples = samples, .method = m});
    for (const TriangleInput& t : tris) scene.add_triangle(t);
    PayloadHashConsumer c(tris.size());
    scene.rasterize(c, pool);
    return c.hash;
}

// A triangle of about `area` px at (cx, cy) with random orientation and a random sub-pixel position.
TriangleInput around(std::mt19937& rng, double cx, double cy, double area, int w, int h) {
    TriangleInput t = triangle_of_area(rng, area, 64, 64);
    for (int i = 0; i < 3; ++i) t.x[i] = float(t.x[i] - 32 + cx), t.y[i] = float(t.y[i] - 32 + cy);
    t.common.clip = {0, 0, w, h};
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s out.csv [triangles_per_point]\n", argv[0]);
        return 2;
    }
    const int n = argc > 2 ? std::max(1, std::atoi(argv[2])) : 1000;
    FILE* out = std::fopen(argv[1], "w");
    if (!out) {
        std::perror(argv[1]);
        return 1;
    }
    std::vector<Point> points;
    // 1. Coordinate magnitude: 16-px triangles centred at (M, M) in a 16384^2 framebuffer.
    for (double m : {8.0, 64.0, 512.0, 2048.0, 4096.0, 8192.0, 12000.0, 16000.0})
        points.push_back(
            {"magnitude", m, 16384, 16384, [m](std::mt19937& r) { return around(r, m, m, 16, 16384, 16384); }});
    // 2. Sliver aspect: length 200 px, width 200/aspect, random direction.
    for (double a : {1.0, 10.0, 100.0, 1000.0, 1e4, 1e5})
        points.push_back({"sliver_aspect", a, 256, 256, [a](std::mt19937& r) {
                              std::uniform_real_distribution<float> u(0, 1);
                              const float ang = u(r) * 6.2831853f, len = 200, wid = float(200 / a);
                              const float cx = 28 + 200 * u(r) * 0, cy = 28;
                              TriangleInput t;
                              const float dx = std::cos(ang) * len, dy = std::sin(ang) * len;
                              t.x[0] = 128 - dx / 2 + u(r), t.y[0] = 128 - dy / 2 + u(r);
                              t.x[1] = t.x[0] + dx, t.y[1] = t.y[0] + dy;
                              t.x[2] = t.x[0] + dx * 0.5f - std::sin(ang) * wid,
                              t.y[2] = t.y[0] + dy * 0.5f + std::cos(ang) * wid;
                              (void)cx, (void)cy;
                              t.common.clip = {0, 0, 256, 256};
                              return t;
                          }});
    // 3. Sub-pixel offset: vertices on exact 1/8-px positions plus an offset of `o` px (below the 1/256 snap).
    for (double o : {0.0, 1e-4, 1e-3, 1.0 / 512, 1.0 / 256, 0.01, 0.1})
        points.push_back({"subpixel_offset", o, 128, 128, [o](std::mt19937& r) {
                              std::uniform_int_distribution<int> q(8 * 8, 8 * 120);
                              TriangleInput t;
                              for (int i = 0; i < 3; ++i)
                                  t.x[i] = float(q(r) / 8.0 + o), t.y[i] = float(q(r) / 8.0 + o);
                              t.common.clip = {0, 0, 128, 128};
                              return t;
                          }});
    // 4. Size: triangles of 1..4096 px area.
    for (double s : {1.0, 4.0, 16.0, 64.0, 256.0, 1024.0, 4096.0})
        points.push_back({"size", s, 256, 256, [s](std::mt19937& r) { return triangle_of_area(r, s, 256, 256); }});

    std::fprintf(out, "sweep,param,samples,method,triangles,mismatches,rate\n");
    for (const Point& p : points) {
        for (int samples : {1, 4}) {
            std::mt19937 rng(12345);
            std::vector<TriangleInput> tris;
            for (int i = 0; i < n; ++i) {
                tris.push_back(p.make(rng));
                tris.back().common.payload = uint32_t(i);
            }
            const std::vector<uint64_t> ref = hashes(tris, p, samples, Method::kReference);
            for (Method m : {Method::kBBox, Method::kHier, Method::kFloat}) {
                const std::vector<uint64_t> got = hashes(tris, p, samples, m);
                int bad = 0;
                for (int i = 0; i < n; ++i) bad += got[i] != ref[i];
                std::fprintf(out, "%s,%g,%d,%s,%d,%d,%.6f\n", p.sweep, p.param, samples, to_string(m), n, bad,
                             double(bad) / n);
                std::printf("%-16s %10g %dx %-9s %5d/%d\n", p.sweep, p.param, samples, to_string(m), bad, n);
            }
        }
    }
    std::fclose(out);
    return 0;
}
