// Helpers shared by the compute-spec case tables (cases_compute*.cpp, cases_types*.cpp, ...): adding a case, GLSL
// headers, word checks.
#pragma once

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "case.hpp"
#include "compute.hpp"

namespace tilevk::cts {

constexpr uint32_t kMarker = 0xDEADBEEFu;  // a word a shader must not write

// A case that runs `s` on both drivers under the full name `name`; the spec is shared by the scene lambda so that
// the case list stays cheap to copy.
inline Case compute_case(std::string name, ComputeSpec s, Check check = {}) {
    auto spec = std::make_shared<ComputeSpec>(std::move(s));
    Case c;
    c.name = std::move(name);
    c.scene = [spec] { return compute_scene(*spec); };
    c.check = std::move(check);
    return c;
}

inline void add_compute_case(CaseList& out, const std::string& name, ComputeSpec s, Check check) {
    out.push_back(compute_case("compute." + name, std::move(s), std::move(check)));
}

// types.* (cases_types*.cpp): 64-, 16- and 8-bit types in compute and fragment shaders.
inline void add_types_case(CaseList& out, const std::string& name, ComputeSpec s, Check check = {}) {
    out.push_back(compute_case("types." + name, std::move(s), std::move(check)));
}

inline std::string glsl_header(uint32_t x, uint32_t y = 1, uint32_t z = 1) {
    return "#version 450\nlayout(local_size_x=" + std::to_string(x) + ", local_size_y=" + std::to_string(y) +
           ", local_size_z=" + std::to_string(z) + ") in;\n";
}

// Buffer `i` must equal `want`, word by word.
inline Check words_are(uint32_t i, const std::vector<uint32_t>& want) {
    return [i, want](const std::vector<Plane>& planes) -> std::string {
        const std::vector<uint32_t> got = buffer_words(planes, i);
        if (got.size() != want.size()) return "buffer" + std::to_string(i) + " has the wrong size";
        for (size_t k = 0; k < want.size(); ++k)
            if (got[k] != want[k])
                return "buffer" + std::to_string(i) + " word " + std::to_string(k) + " is " + std::to_string(got[k]) +
                       ", expected " + std::to_string(want[k]);
        return {};
    };
}

inline uint32_t fbits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

}  // namespace tilevk::cts
