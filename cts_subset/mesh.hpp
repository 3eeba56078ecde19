// Real meshes from Debian's assimp-testmodels, loaded with libassimp and normalised to the view.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace tilevk::cts {

struct Mesh {
    std::vector<std::array<float, 3>> triangles;  // 3 positions per triangle, normalised to [-0.9,0.9]^2 x [0.05,0.95]
    std::vector<std::array<float, 3>> normals;    // one face normal per triangle (unit length)
    bool watertight = false;                      // every edge (after welding equal positions) shared by 2k faces
};

// The directory holding the models (TILEVK_ASSIMP_MODELS overrides the Debian default).
std::string model_dir();
// Loads, triangulates, welds and normalises `path`; rotates by `yaw`,`pitch` (radians) for a non-axial view.
// Throws std::runtime_error with assimp's message if the file cannot be read.
Mesh load_mesh(const std::string& path, float yaw, float pitch);

}  // namespace tilevk::cts
