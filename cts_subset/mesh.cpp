#include "mesh.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>

namespace tilevk::cts {

std::string model_dir() {
    const char* env = std::getenv("TILEVK_ASSIMP_MODELS");
    return env && *env ? env : "/usr/share/assimp/models";
}

Mesh load_mesh(const std::string& path, float yaw, float pitch) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                       aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (!scene) throw std::runtime_error("assimp cannot load " + path + ": " + importer.GetErrorString());
    std::vector<std::array<float, 3>> pos;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            for (int k = 0; k < 3; ++k) {
                const aiVector3D& v = mesh->mVertices[face.mIndices[k]];
                pos.push_back({v.x, v.y, v.z});
            }
        }
    }
    if (pos.empty()) throw std::runtime_error(path + " has no triangles");
    // Watertight test on the original positions: count each undirected edge between welded positions.
    std::map<std::array<float, 3>, int> ids;
    for (const auto& p : pos) ids.emplace(p, int(ids.size()));
    std::map<std::pair<int, int>, int> edges;
    for (size_t t = 0; t < pos.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            int a = ids[pos[t + k]], b = ids[pos[t + (k + 1) % 3]];
            edges[{std::min(a, b), std::max(a, b)}]++;
        }
    Mesh out;
    out.watertight = std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second % 2 == 0; });
    // Rotate, then scale the bounding box into the view: x,y in [-0.9,0.9] (aspect kept), z in [0.05,0.95].
    float cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
    std::array<float, 3> lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (auto& p : pos) {
        float x = cy * p[0] + sy * p[2], z = -sy * p[0] + cy * p[2];
        float y = cp * p[1] - sp * z;
        z = sp * p[1] + cp * z;
        p = {x, y, z};
        for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
    }
    float span = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-20f});
    float zspan = std::max(hi[2] - lo[2], 1e-20f);
    for (auto& p : pos) {
        p[0] = (p[0] - 0.5f * (lo[0] + hi[0])) * (1.8f / span);
        p[1] = -(p[1] - 0.5f * (lo[1] + hi[1])) * (1.8f / span);  // model y up, Vulkan y down
        p[2] = 0.05f + (p[2] - lo[2]) * (0.9f / zspan);
    }
    out.triangles = pos;
    for (size_t t = 0; t < pos.size(); t += 3) {
        std::array<float, 3> e1, e2;
        for (int i = 0; i < 3; ++i) e1[i] = pos[t + 1][i] - pos[t][i], e2[i] = pos[t + 2][i] - pos[t][i];
        std::array<float, 3> n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                  e1[0] * e2[1] - e1[1] * e2[0]};
        float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (float& c : n) c = len > 0 ? c / len : 0.0f;
        out.normals.push_back(n);
    }
    return out;
}

}  // namespace tilevk::cts
