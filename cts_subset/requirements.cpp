// What a scene needs from a device: features, format support, sample counts and limits.
#include "render.hpp"
#include "vk_names.hpp"

namespace tilevk::cts {
namespace {

bool uses_src1(VkBlendFactor f) {
    return f >= VK_BLEND_FACTOR_SRC1_COLOR && f <= VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA;
}

std::string check_format(const DeviceContext& c, VkFormat f, VkFormatFeatureFlags need, VkImageUsageFlags usage,
                         VkSampleCountFlagBits samples, const char* what) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(c.physical, f, &fp);
    if ((fp.optimalTilingFeatures & need) != need)
        return std::string(what) + " format " + format_name(f) + " lacks optimal-tiling features " +
               format_features_name(need & ~fp.optimalTilingFeatures);
    VkImageFormatProperties ip;
    if (vkGetPhysicalDeviceImageFormatProperties(c.physical, f, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage, 0,
                                                 &ip) != VK_SUCCESS)
        return std::string(what) + " format " + format_name(f) + " unsupported for image usage " +
               std::to_string(usage);
    if (!(ip.sampleCounts & samples))
        return std::string(what) + " format " + format_name(f) + " lacks " + std::to_string(samples) + " samples";
    return {};
}

}  // namespace

// VK_EXT_line_rasterization: the feature of the draw's lineRasterizationMode (DEFAULT: rectangularLines too, as
// the case asks for the struct).
std::string line_mode_unsupported(const DeviceContext& c, const Draw& d) {
    if (!d.line_mode) return {};
    const VkPhysicalDeviceLineRasterizationFeaturesEXT& l = c.line_rasterization;
    switch (*d.line_mode) {
        case VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT:
        case VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT:
            return l.rectangularLines ? "" : "VK_EXT_line_rasterization rectangularLines";
        case VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT:
            return l.bresenhamLines ? "" : "VK_EXT_line_rasterization bresenhamLines";
        default:
            return l.smoothLines ? "" : "VK_EXT_line_rasterization smoothLines";
    }
}

std::string unsupported(const DeviceContext& c, const Scene& s) {
    if (s.unsupported) {
        if (std::string why = s.unsupported(c); !why.empty()) return why;
    }
    const Target& t = s.target;
    const VkPhysicalDeviceFeatures& f = c.features;
    const VkPhysicalDeviceLimits& lim = c.props.limits;
    if (t.width > lim.maxImageDimension2D || t.height > lim.maxImageDimension2D)
        return "maxImageDimension2D " + std::to_string(lim.maxImageDimension2D);
    bool any_blend = false;
    for (const Draw& d : s.draws) any_blend |= d.blend.blendEnable == VK_TRUE;
    if (t.color != VK_FORMAT_UNDEFINED) {
        VkFormatFeatureFlags need = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT |
                                    (any_blend ? VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT : 0);
        auto e = check_format(c, t.color, need, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, t.samples, "colour");
        if (!e.empty()) return e;
    }
    if (t.depth != VK_FORMAT_UNDEFINED) {
        auto e = check_format(c, t.depth, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT,
                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, t.samples, "depth/stencil");
        if (!e.empty()) return e;
    }
    if (s.statistics != 0 && !f.pipelineStatisticsQuery) return "feature pipelineStatisticsQuery";
    if (s.queries != QueryMode::kNone && s.statistics == 0 && !f.occlusionQueryPrecise)
        return "feature occlusionQueryPrecise";
    for (const Draw& d : s.draws) {
        if (d.line_width != 1.0f && !f.wideLines) return "feature wideLines";
        if (d.line_width < lim.lineWidthRange[0] || d.line_width > lim.lineWidthRange[1])
            return "lineWidthRange excludes " + std::to_string(d.line_width);
        bool points = d.topology == VK_PRIMITIVE_TOPOLOGY_POINT_LIST || d.polygon_mode == VK_POLYGON_MODE_POINT;
        for (const Vertex& v : d.vertices) {
            if (!points) break;
            if (v.point_size != 1.0f && !f.largePoints) return "feature largePoints";
            if (v.point_size > lim.pointSizeRange[1]) return "pointSizeRange excludes " + std::to_string(v.point_size);
        }
        if (d.polygon_mode != VK_POLYGON_MODE_FILL && !f.fillModeNonSolid) return "feature fillModeNonSolid";
        if (d.logic_op && !f.logicOp) return "feature logicOp";
        if (d.dynamic &&
            !(c.extended_dynamic_state.extendedDynamicState && c.extended_dynamic_state2.extendedDynamicState2))
            return "VK_EXT_extended_dynamic_state(2) extendedDynamicState(2)";
        if (d.dynamic3 &&
            !(c.cmd.vertex_input && c.cmd.polygon_mode && c.cmd.depth_clamp && c.cmd.negative_one_to_one &&
              c.cmd.logic_op_enable && c.cmd.sample_mask && c.cmd.alpha_to_coverage && c.cmd.line_mode &&
              c.cmd.line_stipple && c.cmd.provoking_vertex && c.cmd.blend_enable && c.cmd.blend_equation &&
              c.cmd.write_mask && (c.cmd.depth_clip || !d.depth_clip_enable) && c.cmd.logic_op))
            return "VK_EXT_vertex_input_dynamic_state and the VK_EXT_extended_dynamic_state3 features it sets";
        // ... and what the pipeline of such a draw bakes (the opposite enables, LAST_VERTEX, BRESENHAM, [-w, w]).
        if (d.dynamic3 && !(f.logicOp && f.fillModeNonSolid && f.depthClamp && c.provoking_vertex.provokingVertexLast &&
                            c.line_rasterization.bresenhamLines && c.line_rasterization.rectangularLines &&
                            c.depth_clip_control.depthClipControl))
            return "features logicOp, fillModeNonSolid, depthClamp, provokingVertexLast, bresenhamLines, "
                   "rectangularLines, depthClipControl";
        if (d.dynamic && d.logic_op && !c.extended_dynamic_state2.extendedDynamicState2LogicOp)
            return "VK_EXT_extended_dynamic_state2 extendedDynamicState2LogicOp";
        if (d.color_write_enable && !c.color_write_enable.colorWriteEnable)
            return "VK_EXT_color_write_enable colorWriteEnable";
        if (!d.multi.empty() && !c.multi_draw.multiDraw) return "VK_EXT_multi_draw multiDraw";
        if (d.condition && !c.conditional_rendering.conditionalRendering)
            return "VK_EXT_conditional_rendering conditionalRendering";
        if (d.alpha_to_one && !f.alphaToOne) return "feature alphaToOne";
        if (d.min_sample_shading >= 0.0f && !f.sampleRateShading) return "feature sampleRateShading";
        if (d.viewport_count > 1 && !f.multiViewport) return "feature multiViewport";
        if (d.viewport_count > lim.maxViewports) return "maxViewports " + std::to_string(lim.maxViewports);
        if (d.negative_one_to_one && !c.depth_clip_control.depthClipControl)
            return "VK_EXT_depth_clip_control depthClipControl";
        if (d.index_type == VK_INDEX_TYPE_UINT8_EXT && !c.index_type_uint8.indexTypeUint8)
            return "VK_EXT_index_type_uint8 indexTypeUint8";
        const bool list = d.topology == VK_PRIMITIVE_TOPOLOGY_POINT_LIST ||
                          d.topology == VK_PRIMITIVE_TOPOLOGY_LINE_LIST ||
                          d.topology == VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        if (d.primitive_restart && list && !c.list_restart.primitiveTopologyListRestart)
            return "VK_EXT_primitive_topology_list_restart primitiveTopologyListRestart";
        if (d.viewport && d.viewport->height < 0 && !c.has_extension(VK_KHR_MAINTENANCE_1_EXTENSION_NAME))
            return "VK_KHR_maintenance1 (negative viewport height)";
        if (d.depth_clamp && !f.depthClamp) return "feature depthClamp";
        if (d.provoking_last && !c.provoking_vertex.provokingVertexLast)
            return "VK_EXT_provoking_vertex provokingVertexLast";
        if (d.depth_clip_enable && !c.depth_clip_enable.depthClipEnable)
            return "VK_EXT_depth_clip_enable depthClipEnable";
        if (std::string why = line_mode_unsupported(c, d); !why.empty()) return why;
        if (d.push_constants.size() * 4 > lim.maxPushConstantsSize) return "maxPushConstantsSize";
        if (d.color_format != VK_FORMAT_R32G32B32A32_SFLOAT) {
            VkFormatProperties fp;
            vkGetPhysicalDeviceFormatProperties(c.physical, d.color_format, &fp);
            if (!(fp.bufferFeatures & VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT))
                return std::string("vertex format ") + format_name(d.color_format) + " lacks VERTEX_BUFFER";
        }
        if (d.depth_bias && d.bias_clamp != 0.0f && !f.depthBiasClamp) return "feature depthBiasClamp";
        const auto& b = d.blend;
        if (b.blendEnable && !f.dualSrcBlend &&
            (uses_src1(b.srcColorBlendFactor) || uses_src1(b.dstColorBlendFactor) || uses_src1(b.srcAlphaBlendFactor) ||
             uses_src1(b.dstAlphaBlendFactor)))
            return "feature dualSrcBlend";
        if (d.texture) {
            VkFormatFeatureFlags need = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
            if (d.texture->mag == VK_FILTER_LINEAR || d.texture->min == VK_FILTER_LINEAR ||
                d.texture->mip_mode == VK_SAMPLER_MIPMAP_MODE_LINEAR)
                need |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
            if (d.texture->reduction != VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE) {
                if (!c.has_extension(VK_EXT_SAMPLER_FILTER_MINMAX_EXTENSION_NAME))
                    return "VK_EXT_sampler_filter_minmax";
                need |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_MINMAX_BIT;
            }
            if (d.texture->max_anisotropy > 0.0f && !f.samplerAnisotropy) return "feature samplerAnisotropy";
            if (d.texture->max_anisotropy > lim.maxSamplerAnisotropy)
                return "maxSamplerAnisotropy " + std::to_string(lim.maxSamplerAnisotropy);
            if (d.texture->non_seamless && !c.non_seamless_cube_map.nonSeamlessCubeMap)
                return "VK_EXT_non_seamless_cube_map nonSeamlessCubeMap";
            if (d.texture->custom_border && !c.custom_border_color.customBorderColors)
                return "VK_EXT_custom_border_color customBorderColors";
            const VkFormat tf = d.texture->format == VK_FORMAT_R8_UNORM ? VK_FORMAT_R8_UNORM : VK_FORMAT_R8G8B8A8_UNORM;
            auto e = check_format(c, tf, need, VK_IMAGE_USAGE_SAMPLED_BIT, VK_SAMPLE_COUNT_1_BIT, "texture");
            if (!e.empty()) return e;
            if (d.texture->wrap == VK_SAMPLER_ADDRESS_MODE_MIRROR_CLAMP_TO_EDGE &&
                !c.has_extension(VK_KHR_SAMPLER_MIRROR_CLAMP_TO_EDGE_EXTENSION_NAME))
                return "VK_KHR_sampler_mirror_clamp_to_edge";
        }
        if (d.viewport) {
            const VkViewport& v = *d.viewport;
            if (v.width > lim.maxViewportDimensions[0] || v.height > lim.maxViewportDimensions[1] ||
                v.x < lim.viewportBoundsRange[0] || v.x + v.width > lim.viewportBoundsRange[1] ||
                v.y < lim.viewportBoundsRange[0] || v.y + v.height > lim.viewportBoundsRange[1])
                return "viewport outside maxViewportDimensions/viewportBoundsRange";
        }
    }
    return {};
}

}  // namespace tilevk::cts
