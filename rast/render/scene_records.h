// What a binned scene remembers about each draw and each primitive until its tiles are rendered.
// The primitive stage (renderer.cpp) writes these; the fragment stage (fragment_stage.cpp) reads them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/linear.h"
#include "rast/geometry/planes.h"
#include "rast/render/draw_state.h"
#include "rast/render/vertex_stage.h"
#include "shader/program.h"

namespace tilevk::rast::render {

// vkCmdClearAttachments inside a render pass: binned as boxes so it stays in API order with the draws.
struct ClearRecord {
    uint32_t color_mask = 0;                         // bit i: clear colour target i
    uint8_t color_bytes[kMaxColorTargets][16] = {};  // packed clear value per target
    bool clear_depth = false, clear_stencil = false;
    uint32_t depth_bits = 0;
    uint8_t stencil = 0;
};

struct DrawRecord {
    const PipelineState* pipe = nullptr;
    shader::Bindings bindings;                  // copy: the draw's descriptors (pointers stay valid until end())
    std::vector<std::byte> push_constants;      // copy; bindings.push_constants points here
    VaryingMap varyings;                        // record slot -> fragment input location
    fragment::DepthStencilState depth_stencil;  // with the viewport depth range applied
    uint8_t depth_mode = 0;                     // fragment::DepthModeBits
    bool is_clear = false;
    ClearRecord clear;
    uint64_t* samples_passed = nullptr;  // DrawCall::samples_passed
    // llvmpipe's linear shading for this draw's rectangles (fragment/linear.h): the varying slot the shader copies
    // to colour 0, or -1 when tilevk does not shade this draw linearly (shader class, blending, write mask, ...).
    bool linear = false;
    int linear_slot = -1;  // -1 with `linear`: the shader writes constants only
    bool linear_perspective = true;
    fragment::LinearChannels linear_channels;
};

// kRect: llvmpipe's rectangle (lp_setup_rect.c): box coverage, planes from three corners.
enum class PrimKind : uint8_t { kTriangle, kLine, kPoint, kClear, kRect };

struct PrimRecord {
    uint32_t draw = 0;        // index into the draw records
    uint32_t plane_base = 0;  // first float of this primitive's planes in the plane store
    PrimKind kind = PrimKind::kTriangle;
    uint32_t rect = 0;  // kRect: index of its pixel box (Renderer's rect boxes, linear mode only)
};

// Plane store layout per primitive: [pos plane (12 floats)][depth offset][pad x3][attrib planes (12 floats each)]
inline constexpr uint32_t kPlaneFloats = 12;
inline constexpr uint32_t kPrimHeaderFloats = kPlaneFloats + 4;

}  // namespace tilevk::rast::render
