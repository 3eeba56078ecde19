// Dynamic state: which VkDynamicState values a pipeline takes from vkCmdSet* (Vulkan 1.0, extended dynamic state
// 1 and 2), the values those commands set, and how they replace the pipeline's state at each draw.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

// Declared here so that commands.h, which records DynamicState values, needs no render-core header.
namespace tilevk::rast::render {
struct PipelineState;
}
namespace tilevk::rast::geometry {
enum class Topology : uint8_t;
}

namespace tilevk::icd {

// The dynamic states tilevk implements, one bit each in Pipeline::dynamic.
enum class DynamicState : uint8_t {
    kViewport,
    kScissor,
    kLineWidth,
    kDepthBias,
    kBlendConstants,
    kDepthBounds,
    kStencilCompareMask,
    kStencilWriteMask,
    kStencilReference,
    // VK_EXT_extended_dynamic_state (core in Vulkan 1.3)
    kCullMode,
    kFrontFace,
    kPrimitiveTopology,
    kViewportWithCount,
    kScissorWithCount,
    kVertexInputBindingStride,
    kDepthTestEnable,
    kDepthWriteEnable,
    kDepthCompareOp,
    kDepthBoundsTestEnable,
    kStencilTestEnable,
    kStencilOp,
    // VK_EXT_extended_dynamic_state2 (the first three core in Vulkan 1.3)
    kRasterizerDiscardEnable,
    kDepthBiasEnable,
    kPrimitiveRestartEnable,
    kLogicOp,
    // VK_EXT_color_write_enable
    kColorWriteEnable,
};
using DynamicMask = uint32_t;
inline constexpr DynamicMask dynamic_bit(DynamicState s) {
    return DynamicMask(1) << uint32_t(s);
}

// The DynamicState of `v`; false for a VkDynamicState tilevk does not implement.
bool dynamic_state_of(VkDynamicState v, DynamicState* out);

// Pipeline::dynamic of a create info's pDynamicState; an empty string, or the state that is not implemented.
std::string dynamic_mask_of(const VkPipelineDynamicStateCreateInfo* info, DynamicMask* mask);

// Everything vkCmdSet* and vkCmdBindVertexBuffers2 set (lives in BoundState, for one command buffer).
struct DynamicValues {
    VkViewport viewport{};
    VkRect2D scissor{};
    float line_width = 1.0f;
    float depth_bias[3] = {0, 0, 0};  // constant, clamp, slope
    float blend_constants[4] = {0, 0, 0, 0};
    uint32_t stencil_compare[2] = {0xff, 0xff}, stencil_write[2] = {0xff, 0xff}, stencil_ref[2] = {0, 0};
    VkCullModeFlags cull_mode = VK_CULL_MODE_NONE;
    VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    static constexpr uint32_t kMaxBindings = 16;
    uint32_t strides[kMaxBindings] = {};
    bool depth_test = false, depth_write = false, depth_bounds_test = false, stencil_test = false;
    VkCompareOp depth_compare = VK_COMPARE_OP_NEVER;
    VkStencilOpState stencil_ops[2] = {};  // failOp, passOp, depthFailOp, compareOp of front / back
    bool rasterizer_discard = false, depth_bias_enable = false, primitive_restart = false;
    VkLogicOp logic_op = VK_LOGIC_OP_COPY;
    // Bit i: attachment i writes (vkCmdSetColorWriteEnableEXT); all enabled until set, as lavapipe starts.
    uint32_t color_write_enables = ~0u;
};

// What the pipeline keeps of its static state beyond rast::render::PipelineState, for dynamic states that combine
// with static ones (the depth write applies only with the depth test, whichever of the two is dynamic).
struct StaticValues {
    bool depth_test = false, depth_write = false;
    bool rasterizer_discard = false;
};

// `s` (a copy of the pipeline's state) with every dynamic state of `mask` taken from `values`.
void apply_dynamic_state(DynamicMask mask, const StaticValues& statics, const DynamicValues& values,
                         rast::render::PipelineState& s);

// VK_EXT_color_write_enable: the write mask of every attachment whose bit of `enables` is clear becomes 0.
void disable_color_writes(uint32_t enables, rast::render::PipelineState& s);

// Whether a draw with this pipeline produces nothing (rasterizerDiscardEnable, static or dynamic).
bool discards(DynamicMask mask, const StaticValues& statics, const DynamicValues& values);

// VkPrimitiveTopology as rast/geometry numbers it; false for adjacency and patch topologies.
bool topology_of(VkPrimitiveTopology t, rast::geometry::Topology* out);

}  // namespace tilevk::icd
