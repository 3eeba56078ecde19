// rasterization.interpolation.*: smooth, flat and noperspective varyings on triangles and lines, with and without
// perspective (varying w). Flat cases are judged analytically: only provoking-vertex colours may appear.
#include "case.hpp"

namespace tilevk::cts {

void add_interpolation_cases(CaseList& out) {
    struct Mode {
        const char* name;
        Interp interp;
    };
    const Mode modes[] = {
        {"smooth", Interp::kSmooth}, {"flat", Interp::kFlat}, {"noperspective", Interp::kNoPerspective}};
    struct Topo {
        const char* name;
        VkPrimitiveTopology topo;
        bool projected;
    };
    const Topo topos[] = {{"triangles", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, false},
                          {"triangles_projected", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, true},
                          {"triangle_strip", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, false},
                          {"triangle_fan_projected", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, true},
                          {"lines", VK_PRIMITIVE_TOPOLOGY_LINE_LIST, false},
                          {"line_strip_projected", VK_PRIMITIVE_TOPOLOGY_LINE_STRIP, true}};
    // Eight distinct colours whose unorm8 values are exact (0 or 255 per channel).
    static const std::array<float, 4> kColours[8] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0, 1},
                                                     {1, 0, 1, 1}, {0, 1, 1, 1}, {1, 1, 1, 1}, {1, 0.0f, 0.0f, 0.0f}};
    std::vector<uint32_t> palette = {0};
    for (const auto& c : kColours) palette.push_back(rgba8(c[0] * 255, c[1] * 255, c[2] * 255, c[3] * 255));
    uint32_t seed = 500;
    for (const Mode& m : modes)
        for (const Topo& t : topos) {
            ++seed;
            auto scene = [=] {
                Lcg rng{seed};
                Draw d;
                d.topology = t.topo;
                d.interp = m.interp;
                for (int i = 0; i < 12; ++i) {
                    float w = t.projected ? rng.range(0.3f, 4.0f) : 1.0f;
                    d.vertices.push_back(vtx(rng.range(-1, 1), rng.range(-1, 1), rng.range(0, 1), w, kColours[i % 8]));
                }
                return one_draw(d);
            };
            // Every vertex colour is non-zero, so coverage shows against the zero clear in every mode.
            bool filled = t.topo != VK_PRIMITIVE_TOPOLOGY_LINE_LIST && t.topo != VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
            Check band = filled ? band_of(scene) : Check();
            Check check = m.interp == Interp::kFlat
                              ? (filled ? all_of({palette_only(palette), band}) : palette_only(palette))
                              : band;
            out.push_back({std::string("rasterization.interpolation.") + m.name + "_" + t.name, scene, check, ""});
        }
}

}  // namespace tilevk::cts
