#include "pipeline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "descriptor_set_layout.h"
#include "device.h"
#include "entrypoints.h"
#include "formats.h"
#include "physical_device.h"
#include "render_state.h"
#include "shader_module.h"
#include "vk_names.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreatePipelineCache(VkDevice device, const VkPipelineCacheCreateInfo*,
                                                       const VkAllocationCallbacks* pAllocator,
                                                       VkPipelineCache* pPipelineCache) {
    Device* dev = from_handle<Device>(device);
    auto* cache =
        create_object<PipelineCache>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (cache == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreatePipelineCache: out of host memory");
    *pPipelineCache = to_handle(cache);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPipelineCache(VkDevice, VkPipelineCache cache, const VkAllocationCallbacks*) {
    destroy_object(from_handle<PipelineCache>(cache));
}

// The cache holds nothing yet, so its data is just the header Vulkan requires (version one, 32 bytes).
VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPipelineCacheData(VkDevice device, VkPipelineCache, size_t* pDataSize,
                                                        void* pData) {
    constexpr size_t kHeaderSize = 16 + VK_UUID_SIZE;
    if (pData == nullptr) {
        *pDataSize = kHeaderSize;
        return VK_SUCCESS;
    }
    if (*pDataSize < kHeaderSize) {
        *pDataSize = 0;
        return VK_INCOMPLETE;
    }
    const VkPhysicalDeviceProperties& p = from_handle<Device>(device)->physical_device->properties;
    uint32_t header[4] = {uint32_t(kHeaderSize), VK_PIPELINE_CACHE_HEADER_VERSION_ONE, p.vendorID, p.deviceID};
    std::memcpy(pData, header, sizeof header);
    std::memcpy(static_cast<uint8_t*>(pData) + 16, p.pipelineCacheUUID, VK_UUID_SIZE);
    *pDataSize = kHeaderSize;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_MergePipelineCaches(VkDevice, VkPipelineCache, uint32_t, const VkPipelineCache*) {
    return VK_SUCCESS;
}

namespace {

using rast::render::PipelineState;
namespace fr = rast::fragment;

// Builds the program of one stage; false (with `why`) if shader/ refuses it.
bool make_program(Device& dev, const VkPipelineShaderStageCreateInfo& st, shader::Stage stage, Pipeline& p,
                  std::shared_ptr<const shader::Program>* out, std::string* why) {
    const ShaderModule* m = from_handle<ShaderModule>(st.module);
    shader::SpecConstants spec;
    if (const VkSpecializationInfo* si = st.pSpecializationInfo) {
        for (uint32_t i = 0; i < si->mapEntryCount; ++i) {
            const VkSpecializationMapEntry& e = si->pMapEntries[i];
            shader::SpecConstant c;
            c.id = e.constantID;
            c.words.assign((e.size + 3) / 4, 0u);
            if (e.offset + e.size <= si->dataSize && e.size <= 8)
                std::memcpy(c.words.data(), static_cast<const uint8_t*>(si->pData) + e.offset, e.size);
            spec.push_back(std::move(c));
        }
    }
    bool hit = false;
    shader::Result r = dev.programs.get_or_create(m->words, stage, st.pName ? st.pName : "main", spec, &hit);
    (hit ? p.programs_cached : p.programs_built) += 1;
    if (!r) {
        *why = r.error;
        return false;
    }
    *out = r.program;
    return true;
}

fr::StencilFace stencil_face(const VkStencilOpState& s) {
    fr::StencilFace f;
    f.fail_op = fr::StencilOp(s.failOp);
    f.pass_op = fr::StencilOp(s.passOp);
    f.depth_fail_op = fr::StencilOp(s.depthFailOp);
    f.compare_op = fr::CompareOp(s.compareOp);
    f.compare_mask = uint8_t(s.compareMask);
    f.write_mask = uint8_t(s.writeMask);
    f.reference = uint8_t(s.reference);
    return f;
}

// The shader stages (programs from the device's cache) and lavapipe's fragment UBO 0 size.
std::string translate_stages(Device& dev, const VkGraphicsPipelineCreateInfo& ci, Pipeline& p) {
    std::string why;
    PipelineState& s = p.state;
    // lavapipe's UBO 0 for the fragment stage (lvp_execute.c has_pcbuf, fill_ubo0): the layout's whole push-constant
    // size when any range names the fragment stage. llvmpipe's linear shading checks those floats.
    s.fragment_push_constant_bytes = 0;
    if (const PipelineLayout* layout = ci.layout ? from_handle<PipelineLayout>(ci.layout) : nullptr) {
        uint32_t size = 0, stages = 0;
        for (const VkPushConstantRange& r : layout->push_constants) {
            size = std::max(size, r.offset + r.size);
            stages |= r.stageFlags;
        }
        if (stages & VK_SHADER_STAGE_FRAGMENT_BIT) s.fragment_push_constant_bytes = size;
    }
    for (uint32_t i = 0; i < ci.stageCount; ++i) {
        const VkPipelineShaderStageCreateInfo& st = ci.pStages[i];
        if (st.stage == VK_SHADER_STAGE_VERTEX_BIT) {
            if (!make_program(dev, st, shader::Stage::Vertex, p, &p.vertex, &why)) return "vertex shader: " + why;
        } else if (st.stage == VK_SHADER_STAGE_FRAGMENT_BIT) {
            if (!make_program(dev, st, shader::Stage::Fragment, p, &p.fragment, &why)) return "fragment shader: " + why;
        } else {
            return std::string("only vertex and fragment stages are supported, not ") +
                   vk_flags_name<VkShaderStageFlagBits>(st.stage);
        }
    }
    if (!p.vertex) return "no vertex shader";
    const shader::ProgramInterface& vi = p.vertex->interface();
    if (vi.clip_distances + vi.cull_distances > uint32_t(shader::kMaxClipDistances))
        return "vertex shader: ClipDistance and CullDistance together exceed maxCombinedClipAndCullDistances (8)";
    // lavapipe interpolates them as fragment inputs; tilevk's fragment stage does not carry them (rast/README.md).
    if (p.fragment && (p.fragment->interface().builtins_read &
                       (shader::bit(shader::BuiltIn::ClipDistance) | shader::bit(shader::BuiltIn::CullDistance))))
        return "fragment shader: reading the built-in ClipDistance or CullDistance is not supported";
    s.vertex = p.vertex.get();
    s.fragment = p.fragment.get();
    return {};
}

bool is_dynamic(const Pipeline& p, DynamicState d) {
    return (p.dynamic & dynamic_bit(d)) != 0;
}

// Vertex bindings and attributes (formats with VERTEX_BUFFER support only), topology and restart. With
// VK_DYNAMIC_STATE_VERTEX_INPUT_EXT pVertexInputState is ignored: vkCmdSetVertexInputEXT sets it all.
std::string translate_vertex_input(const VkGraphicsPipelineCreateInfo& ci, bool dynamic_input, PipelineState& s) {
    const VkPipelineVertexInputStateCreateInfo* vi = dynamic_input ? nullptr : ci.pVertexInputState;
    for (uint32_t i = 0; vi && i < vi->vertexBindingDescriptionCount; ++i) {
        const VkVertexInputBindingDescription& b = vi->pVertexBindingDescriptions[i];
        if (b.binding >= s.bindings.size()) s.bindings.resize(b.binding + 1);
        s.bindings[b.binding].stride = b.stride;
        s.bindings[b.binding].rate = b.inputRate == VK_VERTEX_INPUT_RATE_INSTANCE ? rast::geometry::InputRate::kInstance
                                                                                  : rast::geometry::InputRate::kVertex;
    }
    // VK_EXT_vertex_attribute_divisor: divisors of instance-rate bindings (1 unless given).
    const auto* divisors = vi ? find_in_chain<VkPipelineVertexInputDivisorStateCreateInfoEXT>(
                                    vi->pNext, VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_DIVISOR_STATE_CREATE_INFO_EXT)
                              : nullptr;
    for (uint32_t i = 0; divisors && i < divisors->vertexBindingDivisorCount; ++i) {
        const VkVertexInputBindingDivisorDescriptionEXT& d = divisors->pVertexBindingDivisors[i];
        if (d.binding < s.bindings.size()) s.bindings[d.binding].divisor = d.divisor;
    }
    for (uint32_t i = 0; vi && i < vi->vertexAttributeDescriptionCount; ++i) {
        const VkVertexInputAttributeDescription& a = vi->pVertexAttributeDescriptions[i];
        rast::geometry::VertexAttribDesc d;
        const FormatInfo* vf = find_format(a.format);
        if (vf == nullptr || !(vf->buffer & format::kVertexBuffer))
            return std::string("vertex attribute format ") + vk_enum_name(a.format) + " is not supported";
        d.format = vf->id;
        d.binding = a.binding;
        d.offset = a.offset;
        s.attribs.push_back(d);
        s.attrib_locations.push_back(a.location);
    }
    const VkPipelineInputAssemblyStateCreateInfo& ia = *ci.pInputAssemblyState;
    // With a dynamic topology this is only its class; the draw's topology comes from vkCmdSetPrimitiveTopology.
    if (!topology_of(ia.topology, &s.topology))
        return std::string("primitive topology ") + vk_enum_name(ia.topology) + " is not supported";
    s.primitive_restart = ia.primitiveRestartEnable;

    return {};
}

// VK_EXT_line_rasterization: lavapipe's line_rectangular is every mode but BRESENHAM (DEFAULT and RECTANGULAR are
// one). Its smooth lines (draw's aaline stage rewrites the fragment shader) and stippled lines (draw's stipple
// stage) are not reproduced, and it rasterizes Bresenham lines single-sampled in a multisampled pass
// (lvp_pipeline.c disable_multisample), which tilevk does not model: refused by name.
// With the mode or the stipple enable dynamic, the struct's value is ignored (execute_draw.cpp refuses a dynamic
// BRESENHAM draw into a multisampled pass by name).
std::string translate_line_state(const VkGraphicsPipelineCreateInfo& ci, const Pipeline& p, PipelineState& s) {
    const auto* ls = find_in_chain<VkPipelineRasterizationLineStateCreateInfoEXT>(
        ci.pRasterizationState->pNext, VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT);
    if (ls == nullptr) return {};
    if (ls->stippledLineEnable && !is_dynamic(p, DynamicState::kLineStippleEnable))
        return "stippledLineEnable is not supported (features stippledRectangularLines, stippledBresenhamLines, "
               "stippledSmoothLines)";
    if (is_dynamic(p, DynamicState::kLineRasterizationMode)) return {};
    switch (ls->lineRasterizationMode) {
        case VK_LINE_RASTERIZATION_MODE_DEFAULT_EXT:
        case VK_LINE_RASTERIZATION_MODE_RECTANGULAR_EXT:
            s.line_mode = rast::geometry::LineMode::kRectangular;
            return {};
        case VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT: {
            const VkPipelineMultisampleStateCreateInfo* ms = ci.pMultisampleState;
            if (ms != nullptr && ms->rasterizationSamples != VK_SAMPLE_COUNT_1_BIT)
                return std::string(
                           "lineRasterizationMode VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT with "
                           "rasterizationSamples ") +
                       vk_flags_name<VkSampleCountFlagBits>(ms->rasterizationSamples) +
                       " is not supported (lavapipe draws such lines single-sampled)";
            s.line_mode = rast::geometry::LineMode::kBresenham;
            return {};
        }
        default:
            return std::string("lineRasterizationMode ") + vk_enum_name(ls->lineRasterizationMode) +
                   " is not supported (feature smoothLines)";
    }
}

// Rasterization state, the fixed viewport/scissor and depth clip control.
std::string translate_rasterization(const VkGraphicsPipelineCreateInfo& ci, Pipeline& p) {
    PipelineState& s = p.state;
    const VkPipelineRasterizationStateCreateInfo& rs = *ci.pRasterizationState;
    if (rs.polygonMode > VK_POLYGON_MODE_POINT && !is_dynamic(p, DynamicState::kPolygonMode))
        return std::string("polygon mode ") + vk_enum_name(rs.polygonMode) + " is not supported";
    s.polygon_mode = rs.polygonMode == VK_POLYGON_MODE_LINE    ? rast::render::PolygonMode::kLine
                     : rs.polygonMode == VK_POLYGON_MODE_POINT ? rast::render::PolygonMode::kPoint
                                                               : rast::render::PolygonMode::kFill;
    s.cull = rast::CullMode(rs.cullMode & 3);
    s.front_ccw = rs.frontFace == VK_FRONT_FACE_COUNTER_CLOCKWISE;
    s.depth_clamp = rs.depthClampEnable;
    // lavapipe's depth_clip_near/far: VK_EXT_depth_clip_enable's depthClipEnable when given, else
    // !depthClampEnable. depthClampEnable still clamps each fragment's z to the viewport's depth range either way.
    s.depth_clip = !rs.depthClampEnable;
    if (const auto* dc = find_in_chain<VkPipelineRasterizationDepthClipStateCreateInfoEXT>(
            rs.pNext, VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT)) {
        s.depth_clip = dc->depthClipEnable;
        p.statics.depth_clamp_sets_clip = false;
    }
    // VK_EXT_provoking_vertex: lavapipe's flatshade_first is FIRST_VERTEX, the default.
    if (const auto* pv = find_in_chain<VkPipelineRasterizationProvokingVertexStateCreateInfoEXT>(
            rs.pNext, VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_PROVOKING_VERTEX_STATE_CREATE_INFO_EXT)) {
        if (pv->provokingVertexMode > VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT)
            return "provokingVertexMode " + std::to_string(uint32_t(pv->provokingVertexMode)) +
                   " is not a VkProvokingVertexModeEXT";
        s.flatshade_first = pv->provokingVertexMode == VK_PROVOKING_VERTEX_MODE_FIRST_VERTEX_EXT;
    }
    s.depth_bias_enable = rs.depthBiasEnable;
    s.depth_bias.constant_factor = rs.depthBiasConstantFactor;
    s.depth_bias.slope_factor = rs.depthBiasSlopeFactor;
    s.depth_bias.clamp = rs.depthBiasClamp;
    s.line_width = rs.lineWidth;
    if (std::string why = translate_line_state(ci, p, s); !why.empty()) return why;
    if (const VkPipelineViewportStateCreateInfo* vp = ci.pViewportState) {
        // multiViewport: up to maxViewports are accepted; without a viewport-index output (no geometry stage,
        // no shaderOutputViewportIndex) every primitive uses viewport and scissor 0, as in lavapipe.
        const bool with_count = is_dynamic(p, DynamicState::kViewportWithCount);
        if ((!with_count && vp->viewportCount > kMaxViewports) ||
            (!is_dynamic(p, DynamicState::kScissorWithCount) && vp->scissorCount > kMaxViewports))
            return "viewportCount/scissorCount exceeds maxViewports";
        for (auto* e = static_cast<const VkBaseInStructure*>(vp->pNext); e != nullptr; e = e->pNext)
            if (e->sType == VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_DEPTH_CLIP_CONTROL_CREATE_INFO_EXT)
                s.clip_halfz =
                    !reinterpret_cast<const VkPipelineViewportDepthClipControlCreateInfoEXT*>(e)->negativeOneToOne;
        if (vp->pViewports && vp->viewportCount > 0 && !is_dynamic(p, DynamicState::kViewport) && !with_count) {
            const VkViewport& v = vp->pViewports[0];
            s.viewport = {v.x, v.y, v.width, v.height, v.minDepth, v.maxDepth};
        }
        if (vp->pScissors && vp->scissorCount > 0 && !is_dynamic(p, DynamicState::kScissor) &&
            !is_dynamic(p, DynamicState::kScissorWithCount)) {
            const VkRect2D& r = vp->pScissors[0];
            s.scissor = {r.offset.x, r.offset.y, int32_t(r.offset.x + int64_t(r.extent.width)),
                         int32_t(r.offset.y + int64_t(r.extent.height))};
        }
    }
    return {};
}

// lavapipe's min_samples > 1 (docs/lavapipe-rules.md §3): lvp_execute.c update_samples takes
// ceil(samples * minSampleShading) with sampleShadingEnable, and every sample once that exceeds 1 (so at 4x a
// minSampleShading above 0.25); a fragment shader that reads SampleId or SamplePosition or has a Sample-decorated
// input (nir's uses_sample_shading, lvp_pipeline.c force_min_sample) forces every sample too. At 1x llvmpipe's
// variant key leaves min_samples at 1 (lp_state_fs.c, key->multisample).
bool per_sample_shading(const VkPipelineMultisampleStateCreateInfo& ms, const shader::Program* fs) {
    if (ms.rasterizationSamples == VK_SAMPLE_COUNT_1_BIT) return false;
    if (ms.sampleShadingEnable && std::ceil(float(ms.rasterizationSamples) * ms.minSampleShading) > 1.0f) return true;
    if (!fs) return false;
    const shader::ProgramInterface& i = fs->interface();
    if (i.builtins_read & (shader::bit(shader::BuiltIn::SampleId) | shader::bit(shader::BuiltIn::SamplePosition)))
        return true;
    for (const shader::IoVariable& v : i.inputs)
        if (v.sample) return true;
    return false;
}

// Sample count, sample mask, alpha to coverage and to one; depth and stencil tests.
std::string translate_multisample_depth(const VkGraphicsPipelineCreateInfo& ci, Pipeline& p) {
    PipelineState& s = p.state;
    if (const VkPipelineMultisampleStateCreateInfo* ms = ci.pMultisampleState) {
        if (ms->rasterizationSamples != VK_SAMPLE_COUNT_1_BIT && ms->rasterizationSamples != VK_SAMPLE_COUNT_4_BIT)
            return std::string("rasterizationSamples ") +
                   vk_flags_name<VkSampleCountFlagBits>(ms->rasterizationSamples) +
                   " is not supported (VK_SAMPLE_COUNT_1_BIT or VK_SAMPLE_COUNT_4_BIT)";
        s.samples = int(ms->rasterizationSamples);
        s.per_sample = per_sample_shading(*ms, p.fragment.get());
        s.alpha_to_one = ms->alphaToOneEnable;
        if (ms->pSampleMask) s.sample_mask = ms->pSampleMask[0];
        s.alpha_to_coverage = ms->alphaToCoverageEnable;
    }
    if (const VkPipelineDepthStencilStateCreateInfo* ds = ci.pDepthStencilState) {
        if (ds->depthBoundsTestEnable && !is_dynamic(p, DynamicState::kDepthBoundsTestEnable))
            return "depthBoundsTestEnable (feature depthBounds) is not supported";
        p.statics.depth_test = ds->depthTestEnable;
        p.statics.depth_write = ds->depthWriteEnable;
        s.depth_stencil.depth_test = ds->depthTestEnable;
        s.depth_stencil.depth_write = ds->depthTestEnable && ds->depthWriteEnable;
        s.depth_stencil.depth_compare = fr::CompareOp(ds->depthCompareOp);
        s.depth_stencil.stencil_test = ds->stencilTestEnable;
        s.depth_stencil.front = stencil_face(ds->front);
        s.depth_stencil.back = stencil_face(ds->back);
    }
    return {};
}

// Per-attachment blend state, the logic op and the blend constants.
// A dynamic blend equation (extended dynamic state 3) replaces the ops and factors here, which are then not checked.
std::string translate_blend(const VkGraphicsPipelineCreateInfo& ci, Pipeline& p) {
    PipelineState& s = p.state;
    const bool dynamic_equation = is_dynamic(p, DynamicState::kColorBlendEquation);
    const VkPipelineColorBlendStateCreateInfo* cb = ci.pColorBlendState;
    if (!cb) return {};
    if (cb->logicOpEnable && cb->logicOp > VK_LOGIC_OP_SET)
        return std::string("logic op ") + vk_enum_name(cb->logicOp) + " is not supported";
    if (cb->attachmentCount > uint32_t(rast::render::kMaxColorTargets))
        return "attachmentCount exceeds maxColorAttachments";
    for (uint32_t i = 0; i < cb->attachmentCount; ++i) {
        const VkPipelineColorBlendAttachmentState& a = cb->pAttachments[i];
        fr::BlendAttachment& b = s.blend[i];
        b.blend_enable = a.blendEnable;
        b.write_mask = uint8_t(a.colorWriteMask & 0xf);
        b.logic_op_enable = cb->logicOpEnable;  // VkLogicOp numbers its values as rast/fragment does
        b.logic_op = fr::LogicOp(cb->logicOp);
        if (dynamic_equation) continue;
        if (a.colorBlendOp > VK_BLEND_OP_MAX || a.alphaBlendOp > VK_BLEND_OP_MAX)
            return std::string("blend op ") +
                   vk_enum_name(a.colorBlendOp > VK_BLEND_OP_MAX ? a.colorBlendOp : a.alphaBlendOp) +
                   " is not supported";
        // VkBlendFactor and VkBlendOp number their values as rast/fragment does.
        b.src_color = fr::BlendFactor(a.srcColorBlendFactor);
        b.dst_color = fr::BlendFactor(a.dstColorBlendFactor);
        b.color_op = fr::BlendOp(a.colorBlendOp);
        b.src_alpha = fr::BlendFactor(a.srcAlphaBlendFactor);
        b.dst_alpha = fr::BlendFactor(a.dstAlphaBlendFactor);
        b.alpha_op = fr::BlendOp(a.alphaBlendOp);
        for (VkBlendFactor f :
             {a.srcColorBlendFactor, a.dstColorBlendFactor, a.srcAlphaBlendFactor, a.dstAlphaBlendFactor})
            if (uint32_t(f) > uint32_t(VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA))
                return "blend factor " + std::to_string(uint32_t(f)) + " is not a VkBlendFactor";
        // The second source is colour output Location 0, Index 1, which only attachment 0 can blend with
        // (maxFragmentDualSrcAttachments 1, as lavapipe: llvmpipe looks for SRC1 factors on its first target only).
        if (i > 0 && fr::uses_second_source(b))
            return "pColorBlendAttachments[" + std::to_string(i) +
                   "] uses a dual-source blend factor (VK_BLEND_FACTOR_SRC1_*): maxFragmentDualSrcAttachments is 1";
    }
    std::memcpy(s.blend_constants, cb->blendConstants, sizeof s.blend_constants);
    // VK_EXT_color_write_enable, static: attachments whose enable is not VK_TRUE write nothing (with the state
    // dynamic the struct is ignored and apply_dynamic_state does the same at each draw).
    const auto* cw = find_in_chain<VkPipelineColorWriteCreateInfoEXT>(
        cb->pNext, VK_STRUCTURE_TYPE_PIPELINE_COLOR_WRITE_CREATE_INFO_EXT);
    if (cw != nullptr && !is_dynamic(p, DynamicState::kColorWriteEnable)) {
        uint32_t enables = ~0u;
        for (uint32_t i = 0; i < cw->attachmentCount && i < 32; ++i)
            if (cw->pColorWriteEnables[i] != VK_TRUE) enables &= ~(1u << i);
        p.statics.color_write_enables = enables;
        disable_color_writes(enables, s);
    }
    return {};
}

// Translates one create info; returns an empty string or the reason it is unsupported.
std::string build_pipeline(Device& dev, const VkGraphicsPipelineCreateInfo& ci, Pipeline& p) {
    // Without a render pass the pipeline is for dynamic rendering (VkPipelineRenderingCreateInfo, or none: no
    // attachments). Nothing of the pass is kept either way: draws take the attachments of the instance they run in.
    if (ci.renderPass == VK_NULL_HANDLE && !dev.enabled_features.core.v13.dynamicRendering)
        return "renderPass is VK_NULL_HANDLE, which needs the dynamicRendering feature "
               "(VkPhysicalDeviceDynamicRenderingFeatures::dynamicRendering), not enabled";
    if (std::string why = translate_stages(dev, ci, p); !why.empty()) return why;
    if (std::string why = dynamic_mask_of(ci.pDynamicState, &p.dynamic); !why.empty()) return why;
    if (std::string why = translate_vertex_input(ci, is_dynamic(p, DynamicState::kVertexInput), p.state); !why.empty())
        return why;
    const bool discard = ci.pRasterizationState->rasterizerDiscardEnable;
    p.statics.rasterizer_discard = discard;
    // A pipeline that discards everything needs no more state, unless the discard can be switched off per draw.
    if (discard && !is_dynamic(p, DynamicState::kRasterizerDiscardEnable)) return {};
    if (std::string why = translate_rasterization(ci, p); !why.empty()) return why;
    if (std::string why = translate_multisample_depth(ci, p); !why.empty()) return why;
    // VK_EXT_depth_range_unrestricted enabled on the device: D32F depth (also of D32_SFLOAT_S8_UINT) is not clamped
    // to [0, 1], as lavapipe's unclamped_fragment_depth_values (lvp_execute.c) for every draw of such a device.
    p.state.depth_stencil.unrestricted_depth = dev.enabled_extensions[size_t(Ext::EXT_depth_range_unrestricted)];
    return translate_blend(ci, p);
}

// VK_EXT_pipeline_creation_feedback: the pipeline's creation time. Per-stage feedback is left invalid (flags 0):
// shader programs are built inside the pipeline's time and may come from the device's program cache.
void write_creation_feedback(const void* chain, uint64_t nanoseconds) {
    for (auto* s = static_cast<const VkBaseInStructure*>(chain); s != nullptr; s = s->pNext) {
        if (s->sType != VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO) continue;
        const auto* f = reinterpret_cast<const VkPipelineCreationFeedbackCreateInfo*>(s);
        f->pPipelineCreationFeedback->flags = VK_PIPELINE_CREATION_FEEDBACK_VALID_BIT;
        f->pPipelineCreationFeedback->duration = nanoseconds;
        for (uint32_t i = 0; i < f->pipelineStageCreationFeedbackCount; ++i)
            f->pPipelineStageCreationFeedbacks[i] = {0, 0};
    }
}

// What vkCreateGraphicsPipelines and vkCreateComputePipelines share: each create info in turn through `build` (the
// kind's own work; a message when the pipeline is refused), creation feedback, and `log` (the kind's
// TILEVK_LOG_PIPELINES line).
template <class CreateInfo, class Build, class Log>
VkResult create_pipelines(Device* dev, const char* entry, uint32_t count, const CreateInfo* pCreateInfos,
                          const VkAllocationCallbacks* pAllocator, VkPipeline* pPipelines, Build build, Log log) {
    VkResult result = VK_SUCCESS;
    for (uint32_t i = 0; i < count; ++i) pPipelines[i] = VK_NULL_HANDLE;
    for (uint32_t i = 0; i < count; ++i) {
        const CreateInfo& ci = pCreateInfos[i];
        const bool early_return = (ci.flags & VK_PIPELINE_CREATE_EARLY_RETURN_ON_FAILURE_BIT) != 0;
        // Pipeline creation cache control: every tilevk pipeline is built when created (the program cache is the
        // device's own, not the application's VkPipelineCache), so a pipeline that must not compile fails, as
        // lavapipe's does.
        if (ci.flags & VK_PIPELINE_CREATE_FAIL_ON_PIPELINE_COMPILE_REQUIRED_BIT) {
            result = VK_PIPELINE_COMPILE_REQUIRED;
            if (early_return) break;
            continue;
        }
        const auto t0 = std::chrono::steady_clock::now();
        auto* p =
            create_object<Pipeline>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
        if (p == nullptr) {
            result = fail(VK_ERROR_OUT_OF_HOST_MEMORY, "%s: out of host memory", entry);
            if (early_return) break;
            continue;
        }
        const std::string why = build(*dev, ci, *p);
        if (!why.empty()) {
            destroy_object(p);
            // Vulkan 1.0 has no "unsupported" code for pipelines: the message says what is going on.
            result = fail(VK_ERROR_INITIALIZATION_FAILED, "%s: %s", entry, why.c_str());
            if (early_return) break;
            continue;
        }
        const auto elapsed = std::chrono::steady_clock::now() - t0;
        p->create_ms = std::chrono::duration<double, std::milli>(elapsed).count();
        write_creation_feedback(ci.pNext,
                                uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count()));
        if (std::getenv("TILEVK_LOG_PIPELINES")) log(*p);
        pPipelines[i] = to_handle(p);
    }
    return result;
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateGraphicsPipelines(VkDevice device, VkPipelineCache, uint32_t count,
                                                           const VkGraphicsPipelineCreateInfo* pCreateInfos,
                                                           const VkAllocationCallbacks* pAllocator,
                                                           VkPipeline* pPipelines) {
    return create_pipelines(from_handle<Device>(device), "vkCreateGraphicsPipelines", count, pCreateInfos, pAllocator,
                            pPipelines, build_pipeline, [](const Pipeline& p) {
                                std::fprintf(stderr,
                                             "tilevk: graphics pipeline created in %.3f ms (%u shader programs built, "
                                             "%u from the cache)\n",
                                             p.create_ms, p.programs_built, p.programs_cached);
                            });
}

namespace {

// VK_EXT_subgroup_size_control: every subgroup has shader::kSubgroupSize lanes (minSubgroupSize = maxSubgroupSize),
// so ALLOW_VARYING_SUBGROUP_SIZE changes nothing and a required size can only be that one. Subgroup k of a
// workgroup is its invocations 8k .. 8k + 7 (shader/README.md "Subgroups"), so a local size x that is a multiple of 8
// (what REQUIRE_FULL_SUBGROUPS asks of the application, VUID-VkPipelineShaderStageCreateInfo-flags-02758/02759)
// makes every subgroup full. Other values are invalid usage, refused by name rather than run differently.
std::string check_subgroup_size(const VkPipelineShaderStageCreateInfo& stage, uint32_t size_x) {
    for (auto* s = static_cast<const VkBaseInStructure*>(stage.pNext); s != nullptr; s = s->pNext) {
        if (s->sType != VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_REQUIRED_SUBGROUP_SIZE_CREATE_INFO) continue;
        const uint32_t want =
            reinterpret_cast<const VkPipelineShaderStageRequiredSubgroupSizeCreateInfo*>(s)->requiredSubgroupSize;
        if (want != shader::kSubgroupSize)
            return "VkPipelineShaderStageRequiredSubgroupSizeCreateInfo::requiredSubgroupSize " + std::to_string(want) +
                   " is not tilevk's one subgroup size " + std::to_string(shader::kSubgroupSize);
    }
    if ((stage.flags & VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT) != 0 &&
        size_x % shader::kSubgroupSize != 0)
        return "VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT with local size x = " +
               std::to_string(size_x) + ", not a multiple of the subgroup size " +
               std::to_string(shader::kSubgroupSize);
    return {};
}

// The compute stage's program, checked against the limits tilevk reports (physical_device.h): a local size or
// Workgroup memory past them is refused here, naming the limit, rather than run.
std::string build_compute_pipeline(Device& dev, const VkComputePipelineCreateInfo& ci, Pipeline& p) {
    if (ci.stage.stage != VK_SHADER_STAGE_COMPUTE_BIT)
        return std::string("the stage of a compute pipeline must be VK_SHADER_STAGE_COMPUTE_BIT, not ") +
               vk_flags_name<VkShaderStageFlagBits>(ci.stage.stage);
    std::string why;
    if (!make_program(dev, ci.stage, shader::Stage::Compute, p, &p.compute, &why)) return "compute shader: " + why;
    const std::array<uint32_t, 3>& size = p.compute->interface().local_size;
    static const char* const kAxis[3] = {"x", "y", "z"};
    uint64_t invocations = 1;
    for (int i = 0; i < 3; ++i) {
        if (size[i] == 0 || size[i] > kMaxComputeWorkGroupSize)
            return "compute shader: local size " + std::string(kAxis[i]) + " = " + std::to_string(size[i]) +
                   " is outside 1..VkPhysicalDeviceLimits::maxComputeWorkGroupSize[" + std::to_string(i) +
                   "] = " + std::to_string(kMaxComputeWorkGroupSize);
        invocations *= size[i];
    }
    if (invocations > kMaxComputeWorkGroupInvocations)
        return "compute shader: local size " + std::to_string(size[0]) + "x" + std::to_string(size[1]) + "x" +
               std::to_string(size[2]) + " = " + std::to_string(invocations) +
               " invocations is more than VkPhysicalDeviceLimits::maxComputeWorkGroupInvocations = " +
               std::to_string(kMaxComputeWorkGroupInvocations);
    const uint32_t shared = p.compute->interface().shared_memory_bytes;
    if (shared > kMaxComputeSharedMemorySize)
        return "compute shader: its Workgroup variables need " + std::to_string(shared) +
               " bytes, more than VkPhysicalDeviceLimits::maxComputeSharedMemorySize = " +
               std::to_string(kMaxComputeSharedMemorySize);
    if (std::string bad = check_subgroup_size(ci.stage, size[0]); !bad.empty()) return "compute shader: " + bad;
    return {};
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateComputePipelines(VkDevice device, VkPipelineCache, uint32_t count,
                                                          const VkComputePipelineCreateInfo* pCreateInfos,
                                                          const VkAllocationCallbacks* pAllocator,
                                                          VkPipeline* pPipelines) {
    return create_pipelines(from_handle<Device>(device), "vkCreateComputePipelines", count, pCreateInfos, pAllocator,
                            pPipelines, build_compute_pipeline, [](const Pipeline& p) {
                                std::fprintf(stderr, "tilevk: compute pipeline created in %.3f ms (%s)\n", p.create_ms,
                                             p.programs_built != 0 ? "program built" : "program from the cache");
                            });
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPipeline(VkDevice, VkPipeline pipeline, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Pipeline>(pipeline));
}

}  // namespace tilevk::icd
