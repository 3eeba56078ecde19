// scene.mesh.*: real models from assimp-testmodels. "shaded" draws them with depth testing and face-normal colours
// (compared byte for byte); "coverage" counts every triangle additively with culling off, and for watertight
// models every pixel must be covered an even number of times (each ray enters and leaves a closed surface).
#include "case.hpp"
#include "mesh.hpp"

namespace tilevk::cts {
namespace {

Scene shaded(const Mesh& m, uint32_t size) {
    Draw d;
    d.depth_test = d.depth_write = true;
    d.interp = Interp::kFlat;
    for (size_t t = 0; t < m.normals.size(); ++t) {
        const auto& n = m.normals[t];
        std::array<float, 4> c = {0.5f + 0.5f * n[0], 0.5f + 0.5f * n[1], 0.5f + 0.5f * n[2], 1.0f};
        for (int k = 0; k < 3; ++k) {
            const auto& p = m.triangles[t * 3 + k];
            d.vertices.push_back(vtx(p[0], p[1], p[2], 1.0f, c));
        }
    }
    Scene s = one_draw(d, size, size);
    s.target.depth = VK_FORMAT_D32_SFLOAT;
    return s;
}

Scene coverage(const Mesh& m, uint32_t size) {
    Draw d;
    d.frag = Frag::kCount;
    d.blend = additive();
    for (const auto& p : m.triangles) d.vertices.push_back(vtx(p[0], p[1], p[2]));
    return one_draw(d, size, size);
}

}  // namespace

void add_mesh_cases(CaseList& out) {
    struct Model {
        const char* name;
        const char* file;
        float yaw, pitch;
        bool watertight;  // expected: the even-coverage check runs only where the model really is closed
    };
    const Model models[] = {{"box_obj", "OBJ/box.obj", 0.6f, 0.4f, true},
                            {"cube_ply", "PLY/cube.ply", 0.3f, -0.5f, true},
                            {"wuson_stl", "STL/Wuson.stl", 0.9f, 0.2f, false},
                            {"spider_obj", "OBJ/spider.obj", 0.4f, 0.7f, false},
                            {"sphere_with_hole_stl", "STL/sphereWithHole.stl", 0.2f, 0.3f, false},
                            {"wuson_ply", "PLY/Wuson.ply", -0.7f, 0.1f, false}};
    for (const Model& md : models) {
        std::string path = model_dir() + "/" + md.file;
        out.push_back({std::string("scene.mesh.") + md.name + "_shaded",
                       [=] { return shaded(load_mesh(path, md.yaw, md.pitch), 192); }, nullptr, ""});
        Check check;
        if (md.watertight) {
            // Judge parity only if the loaded mesh really is closed; otherwise say so.
            check = [=](const std::vector<Plane>& planes) -> std::string {
                if (!load_mesh(path, md.yaw, md.pitch).watertight) return "model " + path + " is not watertight";
                return even_coverage(0)(planes);
            };
        }
        out.push_back({std::string("scene.mesh.") + md.name + "_coverage",
                       [=] { return coverage(load_mesh(path, md.yaw, md.pitch), 192); }, check, ""});
    }
    // Frames big enough for the timings to mean something (the small cases mostly time per-submit overhead).
    const std::string wuson = model_dir() + "/PLY/Wuson.ply", spider = model_dir() + "/OBJ/spider.obj";
    out.push_back(
        {"scene.perf.wuson_shaded_1024", [=] { return shaded(load_mesh(wuson, 0.5f, 0.2f), 1024); }, nullptr, ""});
    out.push_back(
        {"scene.perf.spider_shaded_1024", [=] { return shaded(load_mesh(spider, 0.4f, 0.7f), 1024); }, nullptr, ""});
    out.push_back({"scene.perf.random_triangles_20000_1024",
                   [] {
                       Lcg rng{4242};
                       Draw d;
                       d.depth_test = d.depth_write = true;
                       for (int t = 0; t < 20000; ++t) {
                           float cx = rng.range(-1, 1), cy = rng.range(-1, 1), z = rng.next();
                           std::array<float, 4> c = {rng.next(), rng.next(), rng.next(), 1};
                           for (int k = 0; k < 3; ++k)
                               d.vertices.push_back(
                                   vtx(cx + rng.range(-0.05f, 0.05f), cy + rng.range(-0.05f, 0.05f), z, 1, c));
                       }
                       Scene s = one_draw(d, 1024, 1024);
                       s.target.depth = VK_FORMAT_D32_SFLOAT;
                       return s;
                   },
                   nullptr, ""});
}

}  // namespace tilevk::cts
