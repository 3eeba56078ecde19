// lavapipe's "linear" mode as one module (docs/lavapipe-rules.md §0.3 and §8; rast/geometry/README.md "Linear
// mode"): whether a subpass's framebuffer puts llvmpipe in it, and whether a draw in it is shaded by llvmpipe's
// 8-bit linear path. What the mode then changes lives next to it: the guard band and rectangles
// (geometry/draw_module.h, geometry/rect_detect.h), which bins stay linear (linear_bins.h) and the linear shading
// (fragment/linear.h); the shader class comes from shader/ (Program::linear_shader, shader/linear_analysis.cpp).
#pragma once

#include <cstdint>

#include "format/format.h"
#include "rast/render/draw_state.h"
#include "rast/render/scene_records.h"

namespace tilevk::rast::render {

// The framebuffer state llvmpipe's check_linear_rasterizer reads (lp_state_derived.c), as lavapipe binds a subpass
// (lvp_execute.c): each colour attachment of the subpass is a cbuf, an unused one a null cbuf; the depth/stencil
// attachment is the zsbuf. Only the first cbuf's facts matter (the mode needs exactly one).
struct BoundFramebuffer {
    uint32_t color_buffers = 0;  // nr_cbufs: the subpass's colour attachments, unused ones included
    bool color0_bound = false;   // cbufs[0] is not null (the attachment is used and has a view)
    format::Format color0_format = format::Format::UNDEFINED;  // the view's format
    uint32_t color0_samples = 1;
    uint32_t color0_array_layers = 1;  // the image's; one array layer of a 2D image is PIPE_TEXTURE_2D (lvp_image.c)
    bool depth_stencil_bound = false;  // zsbuf: the subpass names a depth/stencil attachment
};

// check_linear_rasterizer's permit_linear: exactly one cbuf, bound, B8G8R8A8_UNORM (B8G8R8X8_UNORM, the other
// format it takes, is no Vulkan format lavapipe maps to it), single-sampled, PIPE_TEXTURE_2D, and no zsbuf. Its
// third condition, no shader writing a viewport index, always holds: tilevk has no such output.
bool lavapipe_linear_mode(const BoundFramebuffer& fb);

// Sets rec's linear fields (scene_records.h DrawRecord::linear...) for a draw in a subpass of mode `linear_mode`:
// whether llvmpipe's linear variant shades it (lp_state_fs.c linear_pipeline, lp_linear.c lp_fs_linear_run) and,
// if so, which varying slot feeds colour 0. Reads rec.push_constants and rec.varyings, which must be set.
void choose_linear_shading(bool linear_mode, const PipelineState& pipe, DrawRecord& rec);

}  // namespace tilevk::rast::render
