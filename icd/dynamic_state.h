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

// maxVertexInputAttributes and maxVertexInputBindings (lavapipe's 32): every vertex-input table of icd/ is this
// long, as rast/render's are (kMaxVertexInputs, checked in execute_draw.cpp).
inline constexpr uint32_t kMaxVertexInputs = 32;

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
    // VK_EXT_vertex_input_dynamic_state: bindings (strides, rates, divisors) and attributes
    kVertexInput,
    // VK_EXT_extended_dynamic_state3: the members tilevk reports (device_features.cpp)
    kPolygonMode,
    kDepthClampEnable,
    kDepthClipEnable,
    kDepthClipNegativeOneToOne,
    kLogicOpEnable,
    kSampleMask,
    kAlphaToCoverageEnable,
    kLineRasterizationMode,
    kLineStippleEnable,
    kProvokingVertexMode,
    kColorBlendEnable,
    kColorBlendEquation,
    kColorWriteMask,
};
// One bit per DynamicState; bit 63 is BoundState::kDirtyPipeline.
using DynamicMask = uint64_t;
inline constexpr DynamicMask dynamic_bit(DynamicState s) {
    return DynamicMask(1) << uint32_t(s);
}

// The DynamicState of `v`; false for a VkDynamicState tilevk does not implement.
bool dynamic_state_of(VkDynamicState v, DynamicState* out);

// Pipeline::dynamic of a create info's pDynamicState; an empty string, or the state that is not implemented.
std::string dynamic_mask_of(const VkPipelineDynamicStateCreateInfo* info, DynamicMask* mask);

// vkCmdSetVertexInputEXT's bindings and attributes, translated (command_buffer_dynamic.cpp).
struct VertexInputValues {
    static constexpr uint32_t kMax = kMaxVertexInputs;
    struct Attribute {
        uint32_t location, binding, offset;
        VkFormat format;
    };
    struct Binding {
        uint32_t stride = 0;
        bool instance = false;
        uint32_t divisor = 1;
    };
    uint32_t attribute_count = 0, binding_count = 0;  // binding_count: highest binding number + 1
    Attribute attributes[kMax] = {};
    Binding bindings[kMax] = {};
};

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
    static constexpr uint32_t kMaxBindings = kMaxVertexInputs;
    uint32_t strides[kMaxBindings] = {};
    bool depth_test = false, depth_write = false, depth_bounds_test = false, stencil_test = false;
    VkCompareOp depth_compare = VK_COMPARE_OP_NEVER;
    VkStencilOpState stencil_ops[2] = {};  // failOp, passOp, depthFailOp, compareOp of front / back
    bool rasterizer_discard = false, depth_bias_enable = false, primitive_restart = false;
    VkLogicOp logic_op = VK_LOGIC_OP_COPY;
    // Bit i: attachment i writes (vkCmdSetColorWriteEnableEXT); all enabled until set, as lavapipe starts.
    uint32_t color_write_enables = ~0u;
    // VK_EXT_vertex_input_dynamic_state: the vertex input of vkCmdSetVertexInputEXT, as PipelineState holds it
    // (the strides also go to `strides`, which vkCmdBindVertexBuffers2 may set again later).
    VertexInputValues vertex_input;
    // VK_EXT_extended_dynamic_state3
    VkPolygonMode polygon_mode = VK_POLYGON_MODE_FILL;
    bool depth_clamp = false, depth_clip = false, negative_one_to_one = false, logic_op_enable = false;
    bool alpha_to_coverage = false, line_stipple = false, provoking_last = false;
    uint32_t sample_mask = ~0u;
    VkLineRasterizationModeEXT line_mode = VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT;
    static constexpr uint32_t kMaxAttachments = 8;
    uint32_t blend_enables = 0;  // bit i: attachment i
    VkColorBlendEquationEXT blend_equations[kMaxAttachments] = {};
    uint8_t write_masks[kMaxAttachments] = {};
};

// What the pipeline keeps of its static state beyond rast::render::PipelineState, for dynamic states that combine
// with static ones (the depth write applies only with the depth test, whichever of the two is dynamic).
struct StaticValues {
    bool depth_test = false, depth_write = false;
    bool rasterizer_discard = false;
    // No VkPipelineRasterizationDepthClipStateCreateInfoEXT: depth clipping follows depth clamping, also when the
    // clamp is dynamic (lavapipe's depth_clamp_sets_clip).
    bool depth_clamp_sets_clip = true;
    // VkPipelineColorWriteCreateInfoEXT: bit i set when attachment i writes; kept apart from the write masks so
    // that dynamic write masks (extended dynamic state 3) are still disabled by it.
    uint32_t color_write_enables = ~0u;
};

// `s` (a copy of the pipeline's state) with every dynamic state of `mask` taken from `values`.
void apply_dynamic_state(DynamicMask mask, const StaticValues& statics, const DynamicValues& values,
                         rast::render::PipelineState& s);

// Records `value` for a scalar state of extended dynamic state 3 (CmdSetDynamic); other states are left alone.
void set_dynamic3(DynamicValues& v, DynamicState state, uint32_t value);

// Why a draw with these dynamic values cannot be drawn as lavapipe draws it (empty: it can): line states whose
// static forms pipeline creation refuses (stippled and smooth lines, Bresenham lines with `samples` > 1).
std::string dynamic_refusal(DynamicMask mask, const DynamicValues& v, int samples);

// VK_EXT_color_write_enable: the write mask of every attachment whose bit of `enables` is clear becomes 0.
void disable_color_writes(uint32_t enables, rast::render::PipelineState& s);

// Whether a draw with this pipeline produces nothing (rasterizerDiscardEnable, static or dynamic).
bool discards(DynamicMask mask, const StaticValues& statics, const DynamicValues& values);

// VkPrimitiveTopology as rast/geometry numbers it; false for adjacency and patch topologies.
bool topology_of(VkPrimitiveTopology t, rast::geometry::Topology* out);

}  // namespace tilevk::icd
