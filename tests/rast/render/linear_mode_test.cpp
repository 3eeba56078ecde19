// lavapipe's linear-mode decision per subpass (rast/render/linear_mode.h), against lp_state_derived.c
// check_linear_rasterizer's conditions read by hand: each one broken alone turns the mode off.
#include <gtest/gtest.h>

#include "rast/render/linear_mode.h"

using namespace tilevk;
using namespace tilevk::rast::render;

namespace {

// One bound single-sampled, single-layer B8G8R8A8_UNORM cbuf and no zsbuf: every condition holds.
BoundFramebuffer linear_one() {
    BoundFramebuffer b;
    b.color_buffers = 1;
    b.color0_bound = true;
    b.color0_format = format::Format::B8G8R8A8_UNORM;
    b.color0_samples = 1;
    b.color0_array_layers = 1;
    b.depth_stencil_bound = false;
    return b;
}

}  // namespace

TEST(LinearMode, OneSingleSampledBgra8TargetWithoutDepth) {
    EXPECT_TRUE(lavapipe_linear_mode(linear_one()));
}

TEST(LinearMode, EachConditionBrokenAloneTurnsItOff) {
    BoundFramebuffer b = linear_one();
    b.color_buffers = 2;  // nr_cbufs == 1
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.color_buffers = 0;
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.color0_bound = false;  // cbufs[0] null: an unused attachment
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.color0_format = format::Format::R8G8B8A8_UNORM;  // only B8G8R8A8 (or X8, which no Vulkan format maps to)
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.color0_format = format::Format::B8G8R8A8_SRGB;
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.color0_samples = 4;  // util_res_sample_count == 1
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.color0_array_layers = 2;  // PIPE_TEXTURE_2D_ARRAY, not PIPE_TEXTURE_2D
    EXPECT_FALSE(lavapipe_linear_mode(b));
    b = linear_one();
    b.depth_stencil_bound = true;  // a zsbuf
    EXPECT_FALSE(lavapipe_linear_mode(b));
}
