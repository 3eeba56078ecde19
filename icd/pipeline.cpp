#include "pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "descriptor_set_layout.h"
#include "device.h"
#include "entrypoints.h"
#include "physical_device.h"
#include "render_state.h"
#include "shader_module.h"

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

// Translates one create info; returns an empty string or the reason it is unsupported.
std::string build_pipeline(Device& dev, const VkGraphicsPipelineCreateInfo& ci, Pipeline& p) {
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
            return "only vertex and fragment stages are supported (stage bit " + std::to_string(st.stage) + ")";
        }
    }
    if (!p.vertex) return "no vertex shader";
    s.vertex = p.vertex.get();
    s.fragment = p.fragment.get();

    if (const VkPipelineDynamicStateCreateInfo* d = ci.pDynamicState)
        for (uint32_t i = 0; i < d->dynamicStateCount; ++i)
            if (d->pDynamicStates[i] <= VK_DYNAMIC_STATE_STENCIL_REFERENCE)
                p.dynamic |= dynamic_bit(d->pDynamicStates[i]);

    const VkPipelineVertexInputStateCreateInfo* vi = ci.pVertexInputState;
    for (uint32_t i = 0; vi && i < vi->vertexBindingDescriptionCount; ++i) {
        const VkVertexInputBindingDescription& b = vi->pVertexBindingDescriptions[i];
        if (b.binding >= s.bindings.size()) s.bindings.resize(b.binding + 1);
        s.bindings[b.binding].stride = b.stride;
        s.bindings[b.binding].rate = b.inputRate == VK_VERTEX_INPUT_RATE_INSTANCE ? rast::geometry::InputRate::kInstance
                                                                                  : rast::geometry::InputRate::kVertex;
    }
    for (uint32_t i = 0; vi && i < vi->vertexAttributeDescriptionCount; ++i) {
        const VkVertexInputAttributeDescription& a = vi->pVertexAttributeDescriptions[i];
        rast::geometry::VertexAttribDesc d;
        if (!vertex_format_of(a.format, &d.format))
            return "vertex attribute format " + std::to_string(a.format) + " is not supported";
        d.binding = a.binding;
        d.offset = a.offset;
        s.attribs.push_back(d);
        s.attrib_locations.push_back(a.location);
    }

    const VkPipelineInputAssemblyStateCreateInfo& ia = *ci.pInputAssemblyState;
    switch (ia.topology) {
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST:
            s.topology = rast::geometry::Topology::kTriangleList;
            break;
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP:
            s.topology = rast::geometry::Topology::kTriangleStrip;
            break;
        case VK_PRIMITIVE_TOPOLOGY_TRIANGLE_FAN:
            s.topology = rast::geometry::Topology::kTriangleFan;
            break;
        case VK_PRIMITIVE_TOPOLOGY_POINT_LIST:
            s.topology = rast::geometry::Topology::kPointList;
            break;
        case VK_PRIMITIVE_TOPOLOGY_LINE_LIST:
            s.topology = rast::geometry::Topology::kLineList;
            break;
        case VK_PRIMITIVE_TOPOLOGY_LINE_STRIP:
            s.topology = rast::geometry::Topology::kLineStrip;
            break;
        default:
            return "primitive topology " + std::to_string(ia.topology) + " (adjacency / patches) is not supported";
    }
    s.primitive_restart = ia.primitiveRestartEnable;

    const VkPipelineRasterizationStateCreateInfo& rs = *ci.pRasterizationState;
    p.rasterizer_discard = rs.rasterizerDiscardEnable;
    if (!p.rasterizer_discard) {
        if (rs.polygonMode > VK_POLYGON_MODE_POINT) return "polygon mode is not supported";
        s.polygon_mode = rs.polygonMode == VK_POLYGON_MODE_LINE    ? rast::render::PolygonMode::kLine
                         : rs.polygonMode == VK_POLYGON_MODE_POINT ? rast::render::PolygonMode::kPoint
                                                                   : rast::render::PolygonMode::kFill;
        s.cull = rast::CullMode(rs.cullMode & 3);
        s.front_ccw = rs.frontFace == VK_FRONT_FACE_COUNTER_CLOCKWISE;
        s.depth_clamp = rs.depthClampEnable;
        s.depth_bias_enable = rs.depthBiasEnable;
        s.depth_bias.constant_factor = rs.depthBiasConstantFactor;
        s.depth_bias.slope_factor = rs.depthBiasSlopeFactor;
        s.depth_bias.clamp = rs.depthBiasClamp;
        s.line_width = rs.lineWidth;

        if (const VkPipelineViewportStateCreateInfo* vp = ci.pViewportState) {
            if (vp->viewportCount > 1 || vp->scissorCount > 1) return "more than one viewport is not supported";
            if (vp->pViewports && !(p.dynamic & dynamic_bit(VK_DYNAMIC_STATE_VIEWPORT))) {
                const VkViewport& v = vp->pViewports[0];
                s.viewport = {v.x, v.y, v.width, v.height, v.minDepth, v.maxDepth};
            }
            if (vp->pScissors && !(p.dynamic & dynamic_bit(VK_DYNAMIC_STATE_SCISSOR))) {
                const VkRect2D& r = vp->pScissors[0];
                s.scissor = {r.offset.x, r.offset.y, int32_t(r.offset.x + int64_t(r.extent.width)),
                             int32_t(r.offset.y + int64_t(r.extent.height))};
            }
        }
        if (const VkPipelineMultisampleStateCreateInfo* ms = ci.pMultisampleState) {
            if (ms->rasterizationSamples != VK_SAMPLE_COUNT_1_BIT && ms->rasterizationSamples != VK_SAMPLE_COUNT_4_BIT)
                return "only 1 and 4 samples are supported";
            s.samples = int(ms->rasterizationSamples);
            if (ms->sampleShadingEnable && ms->minSampleShading > 0.0f)
                return "sample-rate shading (minSampleShading > 0) is not implemented";
            if (ms->alphaToOneEnable) return "alphaToOne is not implemented";
            if (ms->pSampleMask) s.sample_mask = ms->pSampleMask[0];
            s.alpha_to_coverage = ms->alphaToCoverageEnable;
        }
        if (const VkPipelineDepthStencilStateCreateInfo* ds = ci.pDepthStencilState) {
            if (ds->depthBoundsTestEnable) return "depth bounds test is not implemented";
            s.depth_stencil.depth_test = ds->depthTestEnable;
            s.depth_stencil.depth_write = ds->depthTestEnable && ds->depthWriteEnable;
            s.depth_stencil.depth_compare = fr::CompareOp(ds->depthCompareOp);
            s.depth_stencil.stencil_test = ds->stencilTestEnable;
            s.depth_stencil.front = stencil_face(ds->front);
            s.depth_stencil.back = stencil_face(ds->back);
        }
        if (const VkPipelineColorBlendStateCreateInfo* cb = ci.pColorBlendState) {
            if (cb->logicOpEnable) return "logic ops are not implemented";
            if (cb->attachmentCount > uint32_t(rast::render::kMaxColorTargets)) return "too many colour attachments";
            for (uint32_t i = 0; i < cb->attachmentCount; ++i) {
                const VkPipelineColorBlendAttachmentState& a = cb->pAttachments[i];
                fr::BlendAttachment& b = s.blend[i];
                b.blend_enable = a.blendEnable;
                if (a.colorBlendOp > VK_BLEND_OP_MAX || a.alphaBlendOp > VK_BLEND_OP_MAX)
                    return "blend op is not supported";
                // VkBlendFactor and VkBlendOp number their values as rast/fragment does.
                b.src_color = fr::BlendFactor(a.srcColorBlendFactor);
                b.dst_color = fr::BlendFactor(a.dstColorBlendFactor);
                b.color_op = fr::BlendOp(a.colorBlendOp);
                b.src_alpha = fr::BlendFactor(a.srcAlphaBlendFactor);
                b.dst_alpha = fr::BlendFactor(a.dstAlphaBlendFactor);
                b.alpha_op = fr::BlendOp(a.alphaBlendOp);
                b.write_mask = uint8_t(a.colorWriteMask & 0xf);
                if (a.blendEnable && !fr::blend_supported(b)) return "dual-source blend factors are not supported";
            }
            std::memcpy(s.blend_constants, cb->blendConstants, sizeof s.blend_constants);
        }
    }
    return {};
}

}  // namespace

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateGraphicsPipelines(VkDevice device, VkPipelineCache, uint32_t count,
                                                           const VkGraphicsPipelineCreateInfo* pCreateInfos,
                                                           const VkAllocationCallbacks* pAllocator,
                                                           VkPipeline* pPipelines) {
    Device* dev = from_handle<Device>(device);
    VkResult result = VK_SUCCESS;
    for (uint32_t i = 0; i < count; ++i) {
        pPipelines[i] = VK_NULL_HANDLE;
        const auto t0 = std::chrono::steady_clock::now();
        auto* p =
            create_object<Pipeline>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
        if (p == nullptr) {
            result = fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateGraphicsPipelines: out of host memory");
            continue;
        }
        const std::string why = build_pipeline(*dev, pCreateInfos[i], *p);
        if (!why.empty()) {
            destroy_object(p);
            // Vulkan 1.0 has no "unsupported" code for pipelines: the message says what is going on.
            result = fail(VK_ERROR_INITIALIZATION_FAILED, "vkCreateGraphicsPipelines: %s", why.c_str());
            continue;
        }
        p->create_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (std::getenv("TILEVK_LOG_PIPELINES"))
            std::fprintf(stderr,
                         "tilevk: graphics pipeline created in %.3f ms (%u shader programs built, %u from the cache)\n",
                         p->create_ms, p->programs_built, p->programs_cached);
        pPipelines[i] = to_handle(p);
    }
    return result;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateComputePipelines(VkDevice, VkPipelineCache, uint32_t count,
                                                          const VkComputePipelineCreateInfo*,
                                                          const VkAllocationCallbacks*, VkPipeline* pPipelines) {
    for (uint32_t i = 0; i < count; ++i) pPipelines[i] = VK_NULL_HANDLE;
    return fail(VK_ERROR_INITIALIZATION_FAILED,
                "vkCreateComputePipelines: tilevk has no compute queue and runs no compute shaders");
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyPipeline(VkDevice, VkPipeline pipeline, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Pipeline>(pipeline));
}

}  // namespace tilevk::icd
