#include "judge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace tilevk::cts {
namespace {

// The value of channel `i` of texel `t` in the format's units, for error reporting.
double channel(const Plane& p, const uint8_t* t, uint32_t i) {
    if (p.name == "queries") {  // 64-bit result, 64-bit availability (cases_query.cpp)
        uint64_t v;
        std::memcpy(&v, t + 8 * i, 8);
        return double(v);
    }
    if (p.name.rfind("buffer", 0) == 0) {  // a compute case's buffer: 32-bit words (compute.hpp)
        uint32_t v;
        std::memcpy(&v, t, 4);
        return v;
    }
    if (p.name == "depth") {
        if (p.format == VK_FORMAT_D16_UNORM || p.format == VK_FORMAT_D16_UNORM_S8_UINT) {
            uint16_t v;
            std::memcpy(&v, t, 2);
            return v;
        }
        uint32_t v;
        std::memcpy(&v, t, 4);
        if (p.format == VK_FORMAT_D24_UNORM_S8_UINT || p.format == VK_FORMAT_X8_D24_UNORM_PACK32) return v & 0xFFFFFFu;
        float f;
        std::memcpy(&f, t, 4);
        return f;
    }
    return t[i];
}

uint32_t channels(const Plane& p) {
    // Colour and a compute case's storage images: one value per byte.
    if (p.name == "color" || p.name.rfind("image", 0) == 0) return p.texel_bytes;
    return p.name == "queries" ? 2 : 1;
}

const Plane* find_color(const std::vector<Plane>& planes) {
    for (const Plane& p : planes)
        if (p.name == "color" && p.texel_bytes == 4) return &p;
    return nullptr;
}

std::string at(uint32_t x, uint32_t y) {
    return "(" + std::to_string(x) + "," + std::to_string(y) + ")";
}

CoverageOracle& oracle_slot() {
    static CoverageOracle oracle;
    return oracle;
}

}  // namespace

PlaneDiff compare_planes(const Plane& a, const Plane& b) {
    PlaneDiff d;
    d.plane = a.name;
    if (a.name != b.name || a.format != b.format || a.width != b.width || a.height != b.height ||
        a.texel_bytes != b.texel_bytes || a.data.size() != b.data.size()) {
        d.problem = "plane '" + a.name + "' shape differs from the reference's '" + b.name + "'";
        return d;
    }
    d.total = uint64_t(a.width) * a.height;
    for (uint64_t i = 0; i < d.total; ++i) {
        const uint8_t* ta = a.data.data() + i * a.texel_bytes;
        const uint8_t* tb = b.data.data() + i * b.texel_bytes;
        if (std::memcmp(ta, tb, a.texel_bytes) == 0) continue;
        if (d.differing++ == 0) {
            auto values = [&](const Plane& p, const uint8_t* t) {
                std::string v;
                for (uint32_t c = 0; c < channels(p); ++c) {
                    char buf[32];
                    std::snprintf(buf, sizeof buf, "%s%.9g", c ? "," : "", channel(p, t, c));
                    v += buf;
                }
                return v;
            };
            d.first = at(uint32_t(i % a.width), uint32_t(i / a.width)) + " ours " + values(a, ta) + " reference " +
                      values(b, tb);
        }
        for (uint32_t c = 0; c < channels(a); ++c) {
            double e = std::fabs(channel(a, ta, c) - channel(b, tb, c));
            if (std::isnan(e)) e = INFINITY;
            d.max_error = std::max(d.max_error, e);
        }
    }
    return d;
}

std::vector<uint8_t> to_rgba8(const Plane& p) {
    size_t n = size_t(p.width) * p.height;
    std::vector<uint8_t> out(n * 4, 255);
    for (size_t i = 0; i < n; ++i) {
        const uint8_t* t = p.data.data() + i * p.texel_bytes;
        if (p.name == "color") {
            std::memcpy(&out[i * 4], t, 4);
            out[i * 4 + 3] = 255;  // show colour regardless of alpha
            continue;
        }
        double v = channel(p, t, 0);
        double scale = p.name == "stencil"                       ? 1.0
                       : p.format == VK_FORMAT_D16_UNORM         ? 255.0 / 65535.0
                       : p.format == VK_FORMAT_D24_UNORM_S8_UINT ? 255.0 / 16777215.0
                                                                 : 255.0;
        uint8_t g = uint8_t(std::clamp(v * scale, 0.0, 255.0));
        out[i * 4] = out[i * 4 + 1] = out[i * 4 + 2] = g;
    }
    return out;
}

std::vector<uint8_t> diff_rgba8(const Plane& a, const Plane& b) {
    size_t n = size_t(a.width) * a.height;
    std::vector<uint8_t> out(n * 4, 0);
    for (size_t i = 0; i < n; ++i) {
        bool same =
            i * a.texel_bytes + a.texel_bytes <= b.data.size() &&
            std::memcmp(a.data.data() + i * a.texel_bytes, b.data.data() + i * a.texel_bytes, a.texel_bytes) == 0;
        out[i * 4] = same ? 0 : 255;
        out[i * 4 + 3] = 255;
    }
    return out;
}

Check exactly_once(int ch, int x0, int y0, int x1, int y1) {
    return [=](const std::vector<Plane>& planes) -> std::string {
        const Plane* p = find_color(planes);
        if (!p) return "exactly_once: no RGBA8 colour plane";
        for (uint32_t y = 0; y < p->height; ++y)
            for (uint32_t x = 0; x < p->width; ++x) {
                int v = p->data[(size_t(y) * p->width + x) * 4 + ch];
                bool inside = int(x) >= x0 && int(x) < x1 && int(y) >= y0 && int(y) < y1;
                if (v > 1) return "pixel " + at(x, y) + " covered " + std::to_string(v) + " times";
                if (inside && v != 1) return "pixel " + at(x, y) + " not covered";
            }
        return {};
    };
}

Check even_coverage(int ch) {
    return [=](const std::vector<Plane>& planes) -> std::string {
        const Plane* p = find_color(planes);
        if (!p) return "even_coverage: no RGBA8 colour plane";
        for (uint32_t y = 0; y < p->height; ++y)
            for (uint32_t x = 0; x < p->width; ++x) {
                int v = p->data[(size_t(y) * p->width + x) * 4 + ch];
                if (v % 2) return "pixel " + at(x, y) + " covered an odd number of times (" + std::to_string(v) + ")";
            }
        return {};
    };
}

Check palette_only(const std::vector<uint32_t>& palette) {
    return [palette](const std::vector<Plane>& planes) -> std::string {
        const Plane* p = find_color(planes);
        if (!p) return "palette_only: no RGBA8 colour plane";
        for (uint32_t y = 0; y < p->height; ++y)
            for (uint32_t x = 0; x < p->width; ++x) {
                uint32_t v;
                std::memcpy(&v, &p->data[(size_t(y) * p->width + x) * 4], 4);
                if (std::find(palette.begin(), palette.end(), v) == palette.end()) {
                    char buf[16];
                    std::snprintf(buf, sizeof buf, "%08x", v);
                    return "pixel " + at(x, y) + " has colour 0x" + buf + " (ABGR) outside the expected palette";
                }
            }
        return {};
    };
}

Check pixel_is(int x, int y, uint32_t rgba) {
    return [=](const std::vector<Plane>& planes) -> std::string {
        const Plane* p = find_color(planes);
        if (!p || x < 0 || y < 0 || uint32_t(x) >= p->width || uint32_t(y) >= p->height)
            return "pixel_is: no such pixel";
        uint32_t v;
        std::memcpy(&v, &p->data[(size_t(y) * p->width + x) * 4], 4);
        if (v == rgba) return {};
        char buf[64];
        std::snprintf(buf, sizeof buf, "0x%08x, expected 0x%08x (ABGR)", v, rgba);
        return "pixel " + at(x, y) + " is " + buf;
    };
}

Check all_of(const std::vector<Check>& checks) {
    return [checks](const std::vector<Plane>& planes) -> std::string {
        for (const Check& c : checks)
            if (auto e = c(planes); !e.empty()) return e;
        return {};
    };
}

Check coverage_band(const Scene& scene, float margin) {
    // Window-space triangles, from each draw's topology.
    std::vector<std::array<double, 2>> tri;
    const double w = scene.target.width, h = scene.target.height;
    for (const Draw& d : scene.draws) {
        auto win = [&](size_t i) {
            const Vertex& v = d.vertices[i];
            return std::array<double, 2>{(v.pos[0] / v.pos[3] + 1.0) * w / 2, (v.pos[1] / v.pos[3] + 1.0) * h / 2};
        };
        size_t n = d.vertices.size();
        for (size_t i = 0; i + 2 < n;) {
            if (d.topology == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST) {
                for (size_t k = 0; k < 3; ++k) tri.push_back(win(i + k));
                i += 3;
            } else if (d.topology == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP) {
                for (size_t k = 0; k < 3; ++k) tri.push_back(win(i + k));
                i += 1;
            } else {  // fan
                tri.push_back(win(0));
                tri.push_back(win(i + 1));
                tri.push_back(win(i + 2));
                i += 1;
            }
        }
    }
    uint32_t clear = 0;
    for (int c = 0; c < 4; ++c)
        clear |= uint32_t(std::lround(std::clamp(scene.target.clear_color[c], 0.0f, 1.0f) * 255.0f)) << (8 * c);
    return [tri, clear, margin](const std::vector<Plane>& planes) -> std::string {
        const Plane* p = find_color(planes);
        if (!p) return "coverage_band: no RGBA8 colour plane";
        for (uint32_t y = 0; y < p->height; ++y)
            for (uint32_t x = 0; x < p->width; ++x) {
                double cx = x + 0.5, cy = y + 0.5;
                bool inside = false, near = false;
                for (size_t t = 0; t + 2 < tri.size(); t += 3) {
                    // Signed distances of the centre to the three edges, oriented so that inside is positive.
                    double area = (tri[t + 1][0] - tri[t][0]) * (tri[t + 2][1] - tri[t][1]) -
                                  (tri[t + 2][0] - tri[t][0]) * (tri[t + 1][1] - tri[t][1]);
                    if (area == 0) continue;
                    double dmin = INFINITY;
                    for (int e = 0; e < 3; ++e) {
                        const auto& a = tri[t + e];
                        const auto& b = tri[t + (e + 1) % 3];
                        double ex = b[0] - a[0], ey = b[1] - a[1];
                        double len = std::hypot(ex, ey);
                        double dist = (ex * (cy - a[1]) - ey * (cx - a[0])) / len * (area > 0 ? 1 : -1);
                        dmin = std::min(dmin, dist);
                    }
                    inside |= dmin > margin;
                    near |= dmin > -margin;
                }
                uint32_t v;
                std::memcpy(&v, &p->data[(size_t(y) * p->width + x) * 4], 4);
                if (inside && v == clear) return "pixel " + at(x, y) + " lies inside a triangle but was not drawn";
                if (!near && v != clear) return "pixel " + at(x, y) + " lies outside every triangle but was drawn";
            }
        return {};
    };
}

void set_coverage_oracle(CoverageOracle oracle) {
    oracle_slot() = std::move(oracle);
}
const CoverageOracle& coverage_oracle() {
    return oracle_slot();
}

}  // namespace tilevk::cts
