// GLSL -> SPIR-V at run time with glslang, and the runner's shader variants.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene.hpp"

namespace tilevk::cts {

enum class Stage { kVertex, kFragment };

// Compiles one GLSL 450 shader for Vulkan 1.0; throws std::runtime_error with glslang's log on error.
// Results are cached by source text (the cache is shared by both devices: the SPIR-V is identical by design).
const std::vector<uint32_t>& compile_glsl(Stage stage, const std::string& source);

// The vertex and fragment GLSL for a draw (depends on interpolation, fragment kind and topology only). A target
// without a colour attachment gets a fragment shader without a colour output (the validation layer warns about
// an output that no attachment consumes). A draw's own vertex_glsl / fragment_glsl, when set, is returned as is.
std::string vertex_source(const Draw& d);
std::string fragment_source(const Draw& d, bool color_output = true);

}  // namespace tilevk::cts
