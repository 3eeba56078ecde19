#include "dynamic_state.h"

#include <algorithm>
#include <cstring>

#include "rast/render/draw_state.h"
#include "vk_names.h"

namespace tilevk::icd {

bool dynamic_state_of(VkDynamicState v, DynamicState* out) {
    switch (v) {
        case VK_DYNAMIC_STATE_VIEWPORT:
            *out = DynamicState::kViewport;
            return true;
        case VK_DYNAMIC_STATE_SCISSOR:
            *out = DynamicState::kScissor;
            return true;
        case VK_DYNAMIC_STATE_LINE_WIDTH:
            *out = DynamicState::kLineWidth;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_BIAS:
            *out = DynamicState::kDepthBias;
            return true;
        case VK_DYNAMIC_STATE_BLEND_CONSTANTS:
            *out = DynamicState::kBlendConstants;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_BOUNDS:
            *out = DynamicState::kDepthBounds;
            return true;
        case VK_DYNAMIC_STATE_STENCIL_COMPARE_MASK:
            *out = DynamicState::kStencilCompareMask;
            return true;
        case VK_DYNAMIC_STATE_STENCIL_WRITE_MASK:
            *out = DynamicState::kStencilWriteMask;
            return true;
        case VK_DYNAMIC_STATE_STENCIL_REFERENCE:
            *out = DynamicState::kStencilReference;
            return true;
        case VK_DYNAMIC_STATE_CULL_MODE:
            *out = DynamicState::kCullMode;
            return true;
        case VK_DYNAMIC_STATE_FRONT_FACE:
            *out = DynamicState::kFrontFace;
            return true;
        case VK_DYNAMIC_STATE_PRIMITIVE_TOPOLOGY:
            *out = DynamicState::kPrimitiveTopology;
            return true;
        case VK_DYNAMIC_STATE_VIEWPORT_WITH_COUNT:
            *out = DynamicState::kViewportWithCount;
            return true;
        case VK_DYNAMIC_STATE_SCISSOR_WITH_COUNT:
            *out = DynamicState::kScissorWithCount;
            return true;
        case VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE:
            *out = DynamicState::kVertexInputBindingStride;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_TEST_ENABLE:
            *out = DynamicState::kDepthTestEnable;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_WRITE_ENABLE:
            *out = DynamicState::kDepthWriteEnable;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_COMPARE_OP:
            *out = DynamicState::kDepthCompareOp;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_BOUNDS_TEST_ENABLE:
            *out = DynamicState::kDepthBoundsTestEnable;
            return true;
        case VK_DYNAMIC_STATE_STENCIL_TEST_ENABLE:
            *out = DynamicState::kStencilTestEnable;
            return true;
        case VK_DYNAMIC_STATE_STENCIL_OP:
            *out = DynamicState::kStencilOp;
            return true;
        case VK_DYNAMIC_STATE_RASTERIZER_DISCARD_ENABLE:
            *out = DynamicState::kRasterizerDiscardEnable;
            return true;
        case VK_DYNAMIC_STATE_DEPTH_BIAS_ENABLE:
            *out = DynamicState::kDepthBiasEnable;
            return true;
        case VK_DYNAMIC_STATE_PRIMITIVE_RESTART_ENABLE:
            *out = DynamicState::kPrimitiveRestartEnable;
            return true;
        case VK_DYNAMIC_STATE_LOGIC_OP_EXT:
            *out = DynamicState::kLogicOp;
            return true;
        case VK_DYNAMIC_STATE_COLOR_WRITE_ENABLE_EXT:
            *out = DynamicState::kColorWriteEnable;
            return true;
        default:
            return false;
    }
}

std::string dynamic_mask_of(const VkPipelineDynamicStateCreateInfo* info, DynamicMask* mask) {
    *mask = 0;
    for (uint32_t i = 0; info != nullptr && i < info->dynamicStateCount; ++i) {
        DynamicState s;
        if (!dynamic_state_of(info->pDynamicStates[i], &s))
            return std::string("dynamic state ") + vk_enum_name(info->pDynamicStates[i]) + " is not supported";
        *mask |= dynamic_bit(s);
    }
    return {};
}

bool topology_of(VkPrimitiveTopology t, rast::geometry::Topology* out) {
    using rast::geometry::Topology;
    switch (t) {
        case VK_PRIMITIVE_TOPOLOGY_POINT_LIST:
            *out = Topology::kPointList;
            return true;
        case VK_PRIMITIVE_TOPOLOGY_LINE_LIST:
            *out = Topology::kLineList;
            return true;
        case VK_PRIMITIVE_TOPOLOGY_LINE_STRIP:
            *out = Topology::kLineStrip;
            return true;
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST:
            *out = Topology::kTriangleList;
            return true;
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP:
            *out = Topology::kTriangleStrip;
            return true;
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN:
            *out = Topology::kTriangleFan;
            return true;
        default:
            return false;
    }
}

namespace {

void set_stencil_ops(const VkStencilOpState& ops, rast::fragment::StencilFace& f) {
    namespace fr = rast::fragment;
    f.fail_op = fr::StencilOp(ops.failOp);  // VkStencilOp and VkCompareOp number their values as rast/ does
    f.pass_op = fr::StencilOp(ops.passOp);
    f.depth_fail_op = fr::StencilOp(ops.depthFailOp);
    f.compare_op = fr::CompareOp(ops.compareOp);
}

}  // namespace

void apply_dynamic_state(DynamicMask mask, const StaticValues& statics, const DynamicValues& v,
                         rast::render::PipelineState& s) {
    auto dyn = [mask](DynamicState d) { return (mask & dynamic_bit(d)) != 0; };
    // The WithCount forms replace the viewport and scissor the same way (viewport 0 is the one drawn with).
    if (dyn(DynamicState::kViewport) || dyn(DynamicState::kViewportWithCount))
        s.viewport = {v.viewport.x,      v.viewport.y,        v.viewport.width,
                      v.viewport.height, v.viewport.minDepth, v.viewport.maxDepth};
    if (dyn(DynamicState::kScissor) || dyn(DynamicState::kScissorWithCount)) {
        const VkRect2D& r = v.scissor;
        s.scissor = {r.offset.x, r.offset.y, int32_t(r.offset.x + int64_t(r.extent.width)),
                     int32_t(r.offset.y + int64_t(r.extent.height))};
    }
    if (dyn(DynamicState::kLineWidth)) s.line_width = v.line_width;
    if (dyn(DynamicState::kDepthBias)) {
        s.depth_bias.constant_factor = v.depth_bias[0];
        s.depth_bias.clamp = v.depth_bias[1];
        s.depth_bias.slope_factor = v.depth_bias[2];
    }
    if (dyn(DynamicState::kBlendConstants)) std::memcpy(s.blend_constants, v.blend_constants, 16);
    rast::fragment::StencilFace* faces[2] = {&s.depth_stencil.front, &s.depth_stencil.back};
    for (int f = 0; f < 2; ++f) {
        if (dyn(DynamicState::kStencilCompareMask)) faces[f]->compare_mask = uint8_t(v.stencil_compare[f]);
        if (dyn(DynamicState::kStencilWriteMask)) faces[f]->write_mask = uint8_t(v.stencil_write[f]);
        if (dyn(DynamicState::kStencilReference)) faces[f]->reference = uint8_t(v.stencil_ref[f]);
        if (dyn(DynamicState::kStencilOp)) set_stencil_ops(v.stencil_ops[f], *faces[f]);
    }
    if (dyn(DynamicState::kCullMode)) s.cull = rast::CullMode(v.cull_mode & 3);
    if (dyn(DynamicState::kFrontFace)) s.front_ccw = v.front_face == VK_FRONT_FACE_COUNTER_CLOCKWISE;
    if (dyn(DynamicState::kPrimitiveTopology)) topology_of(v.topology, &s.topology);
    if (dyn(DynamicState::kVertexInputBindingStride))
        for (size_t b = 0; b < s.bindings.size() && b < DynamicValues::kMaxBindings; ++b)
            s.bindings[b].stride = v.strides[b];
    const bool depth_test = dyn(DynamicState::kDepthTestEnable) ? v.depth_test : statics.depth_test;
    const bool depth_write = dyn(DynamicState::kDepthWriteEnable) ? v.depth_write : statics.depth_write;
    s.depth_stencil.depth_test = depth_test;
    s.depth_stencil.depth_write = depth_test && depth_write;
    if (dyn(DynamicState::kDepthCompareOp)) s.depth_stencil.depth_compare = rast::fragment::CompareOp(v.depth_compare);
    if (dyn(DynamicState::kStencilTestEnable)) s.depth_stencil.stencil_test = v.stencil_test;
    if (dyn(DynamicState::kDepthBiasEnable)) s.depth_bias_enable = v.depth_bias_enable;
    if (dyn(DynamicState::kPrimitiveRestartEnable)) s.primitive_restart = v.primitive_restart;
    if (dyn(DynamicState::kLogicOp))
        for (rast::fragment::BlendAttachment& b : s.blend) b.logic_op = rast::fragment::LogicOp(v.logic_op);
    if (dyn(DynamicState::kColorWriteEnable)) disable_color_writes(v.color_write_enables, s);
}

void disable_color_writes(uint32_t enables, rast::render::PipelineState& s) {
    // lavapipe's emit_state zeroes the colour mask of every disabled attachment (lvp_execute.c
    // color_write_disables); the blend state stays, and depth, stencil and queries are untouched.
    for (size_t i = 0; i < std::size(s.blend); ++i)
        if ((enables >> i & 1u) == 0) s.blend[i].write_mask = 0;
}

bool discards(DynamicMask mask, const StaticValues& statics, const DynamicValues& values) {
    return (mask & dynamic_bit(DynamicState::kRasterizerDiscardEnable)) ? values.rasterizer_discard
                                                                        : statics.rasterizer_discard;
}

}  // namespace tilevk::icd
