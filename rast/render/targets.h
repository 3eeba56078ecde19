// Render targets as the render core sees them: plain memory with a format, pitches and sample planes.
// Sample s of pixel (x, y) lives at data + s*sample_stride + y*row_pitch + x*bytes_per_pixel.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rast/fragment/color.h"
#include "rast/fragment/depth_stencil.h"

namespace tilevk::rast::render {

inline constexpr int kMaxColorTargets = 8;

struct ColorTarget {
    uint8_t* data = nullptr;  // null: attachment unused (VK_ATTACHMENT_UNUSED)
    fragment::ColorFormat format = fragment::ColorFormat::R8G8B8A8_UNORM;
    size_t row_pitch = 0;
    size_t sample_stride = 0;
};

// Depth in one plane (D16: 2 bytes, D32F: 4 bytes per sample) and stencil in its own 8-bit plane.
struct DepthStencilTarget {
    uint8_t* depth = nullptr;  // null: no depth aspect
    fragment::DepthFormat format = fragment::DepthFormat::None;
    size_t depth_row_pitch = 0;
    size_t depth_sample_stride = 0;
    uint8_t* stencil = nullptr;  // null: no stencil aspect
    size_t stencil_row_pitch = 0;
    size_t stencil_sample_stride = 0;
};

struct Framebuffer {
    int32_t width = 0, height = 0;  // pixels, 1..16384
    int samples = 1;                // 1 or 4
    ColorTarget color[kMaxColorTargets];
    uint32_t num_color = 0;
    DepthStencilTarget depth_stencil;
    // llvmpipe's "linear" mode (lp_state_derived.c check_linear_rasterizer: one single-sampled 2D B8G8R8A8/X8
    // colour buffer, no depth/stencil buffer, one viewport). The driver decides; the renderer then clips x/y
    // against draw's 2x guard band instead of the viewport (rast/geometry/README.md, "Linear mode").
    bool linear_mode = false;
    // Multiview: the view these targets are (ViewIndex of every draw rendered into them); 0 otherwise. The driver
    // renders each view of a multiview subpass as its own pass over that view's layers.
    uint32_t view_index = 0;
};

// Colour resolves (4 samples -> 1, rast/fragment resolve_rect) that the driver hands the last scene of a render pass
// (Renderer::end): each tile resolves its pixels inside the rect right after its last primitive, while they are in
// the worker's cache, instead of a pass over the whole multisampled image afterwards. Each tile writes only its own
// destination pixels with the very function the whole-image resolve calls, so the bytes are the same.
struct TileResolve {
    uint32_t target = 0;     // the colour target resolved (4 samples)
    uint8_t* dst = nullptr;  // pixel (x, y) of the framebuffer at dst + y*dst_pitch + x*bytes (one sample)
    size_t dst_pitch = 0;
    int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the pixels resolved: [x0, x1) x [y0, y1)
};
struct TileResolves {
    TileResolve items[kMaxColorTargets];
    uint32_t count = 0;
};

inline size_t depth_bytes(fragment::DepthFormat f) {
    return f == fragment::DepthFormat::D16 ? 2 : (f == fragment::DepthFormat::None ? 0 : 4);
}

}  // namespace tilevk::rast::render
