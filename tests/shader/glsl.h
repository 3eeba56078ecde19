// Test helper: compile GLSL 450 to SPIR-V with the glslang library.
#pragma once

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

}  // namespace tilevk::shader::test
