// rasterization.culling.*: cull mode x front face x topology, on random primitives of both windings.
// Front faces add to red, back faces to green (gl_FrontFacing); what is culled must leave its channel at zero.
#include "case.hpp"

namespace tilevk::cts {
namespace {

Check channel_zero(int ch, const char* what) {
    return [=](const std::vector<Plane>& planes) -> std::string {
        for (const Plane& p : planes) {
            if (p.name != "color") continue;
            for (size_t i = 0; i < size_t(p.width) * p.height; ++i)
                if (p.data[i * 4 + ch])
                    return std::string(what) + " faces drawn at pixel (" + std::to_string(i % p.width) + "," +
                           std::to_string(i / p.width) + ") although culled";
        }
        return {};
    };
}

}  // namespace

void add_culling_cases(CaseList& out) {
    struct Cull {
        const char* name;
        VkCullModeFlags mode;
    };
    const Cull culls[] = {{"none", VK_CULL_MODE_NONE},
                          {"front", VK_CULL_MODE_FRONT_BIT},
                          {"back", VK_CULL_MODE_BACK_BIT},
                          {"both", VK_CULL_MODE_FRONT_AND_BACK}};
    struct Face {
        const char* name;
        VkFrontFace face;
    };
    const Face faces[] = {{"ccw", VK_FRONT_FACE_COUNTER_CLOCKWISE}, {"cw", VK_FRONT_FACE_CLOCKWISE}};
    struct Topo {
        const char* name;
        VkPrimitiveTopology topo;
        uint32_t count;
    };
    const Topo topos[] = {{"list", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, 12},
                          {"strip", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP, 10},
                          {"fan", VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN, 10}};
    uint32_t seed = 100;
    for (const Cull& c : culls)
        for (const Face& f : faces)
            for (const Topo& t : topos) {
                ++seed;
                auto scene = [=] {
                    Lcg rng{seed};
                    Draw d;
                    d.topology = t.topo;
                    d.cull = c.mode;
                    d.front_face = f.face;
                    d.frag = Frag::kFacing;
                    d.blend = additive();
                    for (uint32_t i = 0; i < t.count; ++i)
                        d.vertices.push_back(vtx(rng.range(-1, 1), rng.range(-1, 1)));
                    return one_draw(d);
                };
                std::vector<Check> checks;
                if (c.mode & VK_CULL_MODE_FRONT_BIT) checks.push_back(channel_zero(0, "front"));
                if (c.mode & VK_CULL_MODE_BACK_BIT) checks.push_back(channel_zero(1, "back"));
                if (c.mode == VK_CULL_MODE_NONE) checks.push_back(band_of(scene));  // nothing culled: all drawn
                out.push_back({std::string("rasterization.culling.") + c.name + "_" + f.name + "_" + t.name, scene,
                               checks.empty() ? Check() : all_of(checks), ""});
            }
    // Culling applies to polygons drawn as lines or points too.
    for (VkPolygonMode mode : {VK_POLYGON_MODE_LINE, VK_POLYGON_MODE_POINT}) {
        auto scene = [=] {
            Lcg rng{7};
            Draw d;
            d.cull = VK_CULL_MODE_BACK_BIT;
            d.polygon_mode = mode;
            d.frag = Frag::kFacing;
            d.blend = additive();
            for (int i = 0; i < 12; ++i) d.vertices.push_back(vtx(rng.range(-1, 1), rng.range(-1, 1)));
            return one_draw(d);
        };
        out.push_back({std::string("rasterization.culling.back_ccw_list_polygon_mode_") +
                           (mode == VK_POLYGON_MODE_LINE ? "line" : "point"),
                       scene, channel_zero(1, "back"), ""});
    }
}

}  // namespace tilevk::cts
