// GLSL -> SPIR-V at run time with glslang, and the runner's shader variants.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene.hpp"

namespace tilevk::cts {

enum class Stage { kVertex, kFragment, kCompute };

// The SPIR-V version compile_glsl targets (--spirv): 1.0 for Vulkan 1.0 by default; 1.3 (Vulkan 1.1) and 1.5
// (Vulkan 1.2) run the same cases through the later forms of the same shaders (SPIR-V 1.4 lists every global in the
// entry point's interface, for one). Set before the first compile; the instance asks for the matching Vulkan version.
enum class SpirvTarget { kSpirv10, kSpirv13, kSpirv15, kSpirv16 };
void set_spirv_target(SpirvTarget target);
uint32_t spirv_target_vulkan_minor();  // 0, 1 or 2: the Vulkan 1.x whose environment the SPIR-V version belongs to

// Compiles one GLSL 450 shader for the SPIR-V target; throws std::runtime_error with glslang's log on error.
// Results are cached by source text (the cache is shared by both devices: the SPIR-V is identical by design).
const std::vector<uint32_t>& compile_glsl(Stage stage, const std::string& source);

// The vertex and fragment GLSL for a draw (depends on interpolation, fragment kind and topology only). A target
// without a colour attachment gets a fragment shader without a colour output (the validation layer warns about
// an output that no attachment consumes). A draw's own vertex_glsl / fragment_glsl, when set, is returned as is.
std::string vertex_source(const Draw& d);
std::string fragment_source(const Draw& d, bool color_output = true);

}  // namespace tilevk::cts
