#include "dynamic_state.h"

#include <algorithm>
#include <cstring>

#include "formats.h"
#include "rast/render/draw_state.h"
#include "vk_names.h"

namespace tilevk::icd {

namespace {

// VK_EXT_vertex_input_dynamic_state and the extended dynamic state 3 members tilevk reports.
bool dynamic_state3_of(VkDynamicState v, DynamicState* out) {
    static constexpr struct {
        VkDynamicState vk;
        DynamicState state;
    } kStates[] = {
        {VK_DYNAMIC_STATE_VERTEX_INPUT_EXT, DynamicState::kVertexInput},
        {VK_DYNAMIC_STATE_POLYGON_MODE_EXT, DynamicState::kPolygonMode},
        {VK_DYNAMIC_STATE_DEPTH_CLAMP_ENABLE_EXT, DynamicState::kDepthClampEnable},
        {VK_DYNAMIC_STATE_DEPTH_CLIP_ENABLE_EXT, DynamicState::kDepthClipEnable},
        {VK_DYNAMIC_STATE_DEPTH_CLIP_NEGATIVE_ONE_TO_ONE_EXT, DynamicState::kDepthClipNegativeOneToOne},
        {VK_DYNAMIC_STATE_LOGIC_OP_ENABLE_EXT, DynamicState::kLogicOpEnable},
        {VK_DYNAMIC_STATE_SAMPLE_MASK_EXT, DynamicState::kSampleMask},
        {VK_DYNAMIC_STATE_ALPHA_TO_COVERAGE_ENABLE_EXT, DynamicState::kAlphaToCoverageEnable},
        {VK_DYNAMIC_STATE_LINE_RASTERIZATION_MODE_EXT, DynamicState::kLineRasterizationMode},
        {VK_DYNAMIC_STATE_LINE_STIPPLE_ENABLE_EXT, DynamicState::kLineStippleEnable},
        {VK_DYNAMIC_STATE_PROVOKING_VERTEX_MODE_EXT, DynamicState::kProvokingVertexMode},
        {VK_DYNAMIC_STATE_COLOR_BLEND_ENABLE_EXT, DynamicState::kColorBlendEnable},
        {VK_DYNAMIC_STATE_COLOR_BLEND_EQUATION_EXT, DynamicState::kColorBlendEquation},
        {VK_DYNAMIC_STATE_COLOR_WRITE_MASK_EXT, DynamicState::kColorWriteMask},
    };
    for (const auto& e : kStates)
        if (e.vk == v) {
            *out = e.state;
            return true;
        }
    return false;
}

}  // namespace

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
            return dynamic_state3_of(v, out);
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

namespace {

// kVertexInput: the attributes and bindings of vkCmdSetVertexInputEXT replace the pipeline's (which has none).
void apply_vertex_input(const VertexInputValues& in, rast::render::PipelineState& s) {
    s.attribs.clear();
    s.attrib_locations.clear();
    s.bindings.clear();
    s.bindings.resize(in.binding_count);
    for (uint32_t b = 0; b < in.binding_count; ++b) {
        const VertexInputValues::Binding& ib = in.bindings[b];
        s.bindings[b].stride = ib.stride;
        s.bindings[b].rate = ib.instance ? rast::geometry::InputRate::kInstance : rast::geometry::InputRate::kVertex;
        s.bindings[b].divisor = ib.divisor;  // 0: every instance reads the first (geometry::VertexBufferView)
    }
    for (uint32_t i = 0; i < in.attribute_count; ++i) {
        const VertexInputValues::Attribute& a = in.attributes[i];
        rast::geometry::VertexAttribDesc d;
        d.format = find_format(a.format)->id;  // checked when recorded (command_buffer_dynamic3.cpp)
        d.binding = a.binding;
        d.offset = a.offset;
        s.attribs.push_back(d);
        s.attrib_locations.push_back(a.location);
    }
}

// The states of extended dynamic state 3.
void apply_dynamic_state3(DynamicMask mask, const StaticValues& statics, const DynamicValues& v,
                          rast::render::PipelineState& s) {
    namespace fr = rast::fragment;
    auto dyn = [mask](DynamicState d) { return (mask & dynamic_bit(d)) != 0; };
    if (dyn(DynamicState::kPolygonMode))
        s.polygon_mode = v.polygon_mode == VK_POLYGON_MODE_LINE    ? rast::render::PolygonMode::kLine
                         : v.polygon_mode == VK_POLYGON_MODE_POINT ? rast::render::PolygonMode::kPoint
                                                                   : rast::render::PolygonMode::kFill;
    if (dyn(DynamicState::kDepthClampEnable)) {
        s.depth_clamp = v.depth_clamp;
        // lavapipe's depth_clamp_sets_clip: without a depth clip struct or state, clipping is !depthClampEnable.
        if (statics.depth_clamp_sets_clip && !dyn(DynamicState::kDepthClipEnable)) s.depth_clip = !v.depth_clamp;
    }
    if (dyn(DynamicState::kDepthClipEnable)) s.depth_clip = v.depth_clip;
    if (dyn(DynamicState::kDepthClipNegativeOneToOne)) s.clip_halfz = !v.negative_one_to_one;
    if (dyn(DynamicState::kSampleMask)) s.sample_mask = v.sample_mask;
    if (dyn(DynamicState::kAlphaToCoverageEnable)) s.alpha_to_coverage = v.alpha_to_coverage;
    // lavapipe's line_rectangular: every mode but BRESENHAM (RECTANGULAR_SMOOTH is invalid: smoothLines VK_FALSE).
    if (dyn(DynamicState::kLineRasterizationMode))
        s.line_mode = v.line_mode == VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT ? rast::geometry::LineMode::kBresenham
                                                                               : rast::geometry::LineMode::kRectangular;
    if (dyn(DynamicState::kProvokingVertexMode)) s.flatshade_first = !v.provoking_last;
    for (uint32_t i = 0; i < std::size(s.blend) && i < DynamicValues::kMaxAttachments; ++i) {
        fr::BlendAttachment& b = s.blend[i];
        if (dyn(DynamicState::kLogicOpEnable)) b.logic_op_enable = v.logic_op_enable;
        if (dyn(DynamicState::kColorBlendEnable)) b.blend_enable = (v.blend_enables >> i & 1u) != 0;
        if (dyn(DynamicState::kColorWriteMask)) b.write_mask = uint8_t(v.write_masks[i] & 0xf);
        if (dyn(DynamicState::kColorBlendEquation)) {
            const VkColorBlendEquationEXT& e = v.blend_equations[i];
            // VkBlendFactor and VkBlendOp number their values as rast/fragment does.
            b.src_color = fr::BlendFactor(e.srcColorBlendFactor);
            b.dst_color = fr::BlendFactor(e.dstColorBlendFactor);
            b.color_op = fr::BlendOp(e.colorBlendOp);
            b.src_alpha = fr::BlendFactor(e.srcAlphaBlendFactor);
            b.dst_alpha = fr::BlendFactor(e.dstAlphaBlendFactor);
            b.alpha_op = fr::BlendOp(e.alphaBlendOp);
        }
    }
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
    if (dyn(DynamicState::kVertexInput)) apply_vertex_input(v.vertex_input, s);
    // vkCmdSetVertexInputEXT writes the strides too: the later of it and vkCmdBindVertexBuffers2 holds.
    if (dyn(DynamicState::kVertexInputBindingStride) || dyn(DynamicState::kVertexInput))
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
    apply_dynamic_state3(mask, statics, v, s);
    // After the write masks, whichever of the two is dynamic: a disabled attachment writes nothing.
    disable_color_writes(dyn(DynamicState::kColorWriteEnable) ? v.color_write_enables : statics.color_write_enables,
                         s);
}

void set_dynamic3(DynamicValues& v, DynamicState state, uint32_t value) {
    switch (state) {
        case DynamicState::kPolygonMode:
            v.polygon_mode = VkPolygonMode(value);
            break;
        case DynamicState::kDepthClampEnable:
            v.depth_clamp = value != 0;
            break;
        case DynamicState::kDepthClipEnable:
            v.depth_clip = value != 0;
            break;
        case DynamicState::kDepthClipNegativeOneToOne:
            v.negative_one_to_one = value != 0;
            break;
        case DynamicState::kLogicOpEnable:
            v.logic_op_enable = value != 0;
            break;
        case DynamicState::kSampleMask:
            v.sample_mask = value;
            break;
        case DynamicState::kAlphaToCoverageEnable:
            v.alpha_to_coverage = value != 0;
            break;
        case DynamicState::kLineRasterizationMode:
            v.line_mode = VkLineRasterizationModeEXT(value);
            break;
        case DynamicState::kLineStippleEnable:
            v.line_stipple = value != 0;
            break;
        case DynamicState::kProvokingVertexMode:
            v.provoking_last = value == VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT;
            break;
        default:
            break;  // the other states have commands of their own
    }
}

std::string dynamic_refusal(DynamicMask mask, const DynamicValues& v, int samples) {
    if (mask & dynamic_bit(DynamicState::kLineStippleEnable) && v.line_stipple)
        return "stippledLineEnable VK_TRUE (vkCmdSetLineStippleEnableEXT) is not supported (features "
               "stippledRectangularLines, stippledBresenhamLines, stippledSmoothLines)";
    if (!(mask & dynamic_bit(DynamicState::kLineRasterizationMode))) return {};
    if (v.line_mode == VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT)
        return "lineRasterizationMode VK_LINE_RASTERIZATION_MODE_RECTANGULAR_SMOOTH_EXT (vkCmdSetLineRasterizationModeEXT) "
               "is not supported (feature smoothLines)";
    if (v.line_mode == VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT && samples > 1)
        return "lineRasterizationMode VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT (vkCmdSetLineRasterizationModeEXT) with "
               "rasterizationSamples " + std::to_string(samples) + " is not supported (lavapipe draws such lines single-sampled)";
    return {};
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
