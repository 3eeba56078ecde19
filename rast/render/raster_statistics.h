// Pipeline-statistics counts the renderer makes for a draw (docs/lavapipe-rules.md §13; DrawCall::statistics).
#pragma once

#include <cstdint>

namespace tilevk::rast::render {

// Added to by the renderer: primitives reaching llvmpipe's setup functions (CLIPPING_PRIMITIVES) as the draw is
// set up, and calls of llvmpipe's 4x4-block fragment function (FRAGMENT_SHADER_INVOCATIONS / 16) when its tiles
// are rendered.
struct RasterStatistics {
    uint64_t clipping_primitives = 0;
    uint64_t fragment_blocks = 0;
};

}  // namespace tilevk::rast::render
