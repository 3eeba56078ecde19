// Test helper: compile GLSL 450 to SPIR-V with the glslang library.
#pragma once

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "shader/program.h"

namespace tilevk::shader::test {

// Compiles `source` for `stage`; fails the current test (and returns {}) on a compile error.
// spirv_1_3: target SPIR-V 1.3 / Vulkan 1.1 instead of 1.0.
std::vector<uint32_t> compile_glsl(Stage stage, const std::string& source, bool spirv_1_3 = false);

// Compile and create a Program; fails the test with the creation error when it does not succeed.
std::shared_ptr<const Program> make_program(Stage stage, const std::string& source);

// A lane word as the float it holds, and back: the registers hold 32-bit words, the tests state floats.
inline float f(uint32_t bits) {
    return std::bit_cast<float>(bits);
}
inline uint32_t u(float x) {
    return std::bit_cast<uint32_t>(x);
}

}  // namespace tilevk::shader::test
