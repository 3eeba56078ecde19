// What a binned scene remembers about each draw and each primitive until its tiles are rendered.
// The primitive stage (renderer.cpp) writes these; the fragment stage (fragment_stage.cpp) reads them.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rast/core/recycled_list.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/linear.h"
#include "rast/geometry/planes.h"
#include "rast/render/draw_state.h"
#include "rast/render/vertex_stage.h"
#include "shader/program.h"

namespace tilevk::rast::render {

struct DrawRecord {
    const PipelineState* pipe = nullptr;
    uint32_t id = 0;                            // DrawCall::id
    shader::Bindings bindings;                  // copy: the draw's descriptors (pointers stay valid until end())
    std::vector<std::byte> push_constants;      // copy; bindings.push_constants points here
    VaryingMap varyings;                        // record slot -> fragment input location
    fragment::DepthStencilState depth_stencil;  // with the viewport depth range applied
    uint8_t depth_mode = 0;                     // fragment::DepthModeBits
    uint64_t* samples_passed = nullptr;         // DrawCall::samples_passed
    // llvmpipe's linear shading for this draw's rectangles (fragment/linear.h): the varying slot the shader copies
    // to colour 0, or -1 when tilevk does not shade this draw linearly (shader class, blending, write mask, ...).
    bool linear = false;
    int linear_slot = -1;  // -1 with `linear`: the shader writes constants only
    bool linear_perspective = true;
    fragment::LinearChannels linear_channels;

    // Back to a fresh record, keeping the storage of its vectors (RecycledList).
    void reset() {
        pipe = nullptr;
        id = 0;
        bindings.clear();
        bindings.push_constants = {};
        push_constants.clear();
        varyings.slot_location.clear();
        varyings.slot_interp.clear();
        varyings.carry_point_size = false;
        varyings.point_coord_slot = -1;
        varyings.distance_slot = -1;
        varyings.num_clip_distances = varyings.num_cull_distances = 0;
        depth_stencil = {};
        depth_mode = 0;
        samples_passed = nullptr;
        linear = false;
        linear_slot = -1;
        linear_perspective = true;
        linear_channels = {};
    }
};

// The draws of a scene, reused from scene to scene.
using DrawRecords = RecycledList<DrawRecord>;

// What the driver's stop flag (Renderer::set_stop_flag) interrupted: the DrawCall::id of a draw whose shader run was
// cut short, and of one whose work was skipped. Written by whichever thread saw it first.
struct Interruption {
    static constexpr uint32_t kNone = ~0u;
    std::atomic<uint32_t> cut{kNone}, skipped{kNone};
    void note(bool was_cut, uint32_t id) {
        uint32_t none = kNone;
        (was_cut ? cut : skipped).compare_exchange_strong(none, id, std::memory_order_relaxed);
    }
    void reset() {
        cut.store(kNone, std::memory_order_relaxed);
        skipped.store(kNone, std::memory_order_relaxed);
    }
};

// kRect: llvmpipe's rectangle (lp_setup_rect.c): box coverage, planes from three corners.
enum class PrimKind : uint8_t { kTriangle, kLine, kPoint, kRect };

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
