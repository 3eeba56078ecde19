// vkCmdSetVertexInputEXT (VK_EXT_vertex_input_dynamic_state) and the vkCmdSet* of extended dynamic state 3
// (VK_EXT_extended_dynamic_state3). Each records the value it sets; execution applies it where the bound pipeline
// declared the state dynamic (dynamic_state.cpp). The commands of the members tilevk reports VK_FALSE
// (device_features.cpp) are invalid to call; they log and record nothing.
#include <algorithm>

#include "command_buffer.h"
#include "entrypoints.h"
#include "formats.h"
#include "object.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

void set(VkCommandBuffer commandBuffer, DynamicState state, uint32_t value) {
    if (auto* c = from_handle<CommandBuffer>(commandBuffer)->append<CmdSetDynamic>()) {
        c->state = state;
        c->value = value;
    }
}

// kColorBlendEnable and kColorWriteMask: one 32-bit value per attachment.
void set_attachments(VkCommandBuffer commandBuffer, DynamicState state, uint32_t first, uint32_t count,
                     const uint32_t* values, const VkColorBlendEquationEXT* equations) {
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    if (auto* c = cb->append<CmdSetAttachmentDynamic>()) {
        c->state = state;
        c->first = first;
        c->count = count;
        c->values = values ? cb->copy(values, count) : nullptr;
        c->equations = equations ? cb->copy(equations, count) : nullptr;
    }
}

void unsupported(const char* command, const char* feature) {
    log_error("%s: %s is not supported (VK_FALSE); ignored", command, feature);
}

}  // namespace

// The attributes keep their order; a binding number past maxVertexInputBindings or a format without
// VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT is invalid usage, logged and left out rather than read wrongly.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetVertexInputEXT(VkCommandBuffer commandBuffer, uint32_t vertexBindingDescriptionCount,
                                                   const VkVertexInputBindingDescription2EXT* pVertexBindingDescriptions,
                                                   uint32_t vertexAttributeDescriptionCount,
                                                   const VkVertexInputAttributeDescription2EXT* pVertexAttributeDescriptions) {
    VertexInputValues v;
    for (uint32_t i = 0; i < vertexBindingDescriptionCount; ++i) {
        const VkVertexInputBindingDescription2EXT& b = pVertexBindingDescriptions[i];
        if (b.binding >= VertexInputValues::kMax) {
            log_error("vkCmdSetVertexInputEXT: binding %u is not below maxVertexInputBindings (%u); left out",
                      b.binding, VertexInputValues::kMax);
            continue;
        }
        v.binding_count = std::max(v.binding_count, b.binding + 1);
        // A vertex-rate binding's divisor is never read (lavapipe's instance_divisor 0).
        v.bindings[b.binding] = {b.stride, b.inputRate == VK_VERTEX_INPUT_RATE_INSTANCE, b.divisor};
    }
    for (uint32_t i = 0; i < vertexAttributeDescriptionCount; ++i) {
        const VkVertexInputAttributeDescription2EXT& a = pVertexAttributeDescriptions[i];
        const FormatInfo* f = find_format(a.format);
        if (f == nullptr || !(f->buffer & format::kVertexBuffer) || a.binding >= VertexInputValues::kMax ||
            v.attribute_count == VertexInputValues::kMax) {
            log_error("vkCmdSetVertexInputEXT: attribute at location %u (format %s, binding %u) is not supported; "
                      "left out",
                      a.location, vk_enum_name(a.format), a.binding);
            continue;
        }
        v.attributes[v.attribute_count++] = {a.location, a.binding, a.offset, a.format};
    }
    CommandBuffer* cb = from_handle<CommandBuffer>(commandBuffer);
    if (auto* c = cb->append<CmdSetVertexInput>()) c->values = cb->copy(&v, 1);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetPolygonModeEXT(VkCommandBuffer commandBuffer, VkPolygonMode polygonMode) {
    set(commandBuffer, DynamicState::kPolygonMode, uint32_t(polygonMode));
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetDepthClampEnableEXT(VkCommandBuffer commandBuffer, VkBool32 depthClampEnable) {
    set(commandBuffer, DynamicState::kDepthClampEnable, depthClampEnable);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetDepthClipEnableEXT(VkCommandBuffer commandBuffer, VkBool32 depthClipEnable) {
    set(commandBuffer, DynamicState::kDepthClipEnable, depthClipEnable);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetDepthClipNegativeOneToOneEXT(VkCommandBuffer commandBuffer,
                                                                VkBool32 negativeOneToOne) {
    set(commandBuffer, DynamicState::kDepthClipNegativeOneToOne, negativeOneToOne);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetLogicOpEnableEXT(VkCommandBuffer commandBuffer, VkBool32 logicOpEnable) {
    set(commandBuffer, DynamicState::kLogicOpEnable, logicOpEnable);
}

// Only sample mask word 0 exists (at most 4 samples); a null mask is every sample, as lavapipe reads it.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetSampleMaskEXT(VkCommandBuffer commandBuffer, VkSampleCountFlagBits,
                                                   const VkSampleMask* pSampleMask) {
    set(commandBuffer, DynamicState::kSampleMask, pSampleMask ? pSampleMask[0] : ~0u);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetAlphaToCoverageEnableEXT(VkCommandBuffer commandBuffer,
                                                              VkBool32 alphaToCoverageEnable) {
    set(commandBuffer, DynamicState::kAlphaToCoverageEnable, alphaToCoverageEnable);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetLineRasterizationModeEXT(VkCommandBuffer commandBuffer,
                                                              VkLineRasterizationModeEXT lineRasterizationMode) {
    set(commandBuffer, DynamicState::kLineRasterizationMode, uint32_t(lineRasterizationMode));
}

// The stippled* features are VK_FALSE, so VK_FALSE is the only valid value; it is recorded all the same.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetLineStippleEnableEXT(VkCommandBuffer commandBuffer,
                                                          VkBool32 stippledLineEnable) {
    set(commandBuffer, DynamicState::kLineStippleEnable, stippledLineEnable);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetProvokingVertexModeEXT(VkCommandBuffer commandBuffer,
                                                            VkProvokingVertexModeEXT provokingVertexMode) {
    set(commandBuffer, DynamicState::kProvokingVertexMode, uint32_t(provokingVertexMode));
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetColorBlendEnableEXT(VkCommandBuffer commandBuffer, uint32_t firstAttachment,
                                                         uint32_t attachmentCount,
                                                         const VkBool32* pColorBlendEnables) {
    set_attachments(commandBuffer, DynamicState::kColorBlendEnable, firstAttachment, attachmentCount,
                    pColorBlendEnables, nullptr);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetColorBlendEquationEXT(VkCommandBuffer commandBuffer, uint32_t firstAttachment,
                                                           uint32_t attachmentCount,
                                                           const VkColorBlendEquationEXT* pColorBlendEquations) {
    set_attachments(commandBuffer, DynamicState::kColorBlendEquation, firstAttachment, attachmentCount, nullptr,
                    pColorBlendEquations);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetColorWriteMaskEXT(VkCommandBuffer commandBuffer, uint32_t firstAttachment,
                                                       uint32_t attachmentCount,
                                                       const VkColorComponentFlags* pColorWriteMasks) {
    set_attachments(commandBuffer, DynamicState::kColorWriteMask, firstAttachment, attachmentCount, pColorWriteMasks,
                    nullptr);
}

// The members tilevk reports VK_FALSE (device_features.cpp says why).
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetAlphaToOneEnableEXT(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetAlphaToOneEnableEXT", "extendedDynamicState3AlphaToOneEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetTessellationDomainOriginEXT(VkCommandBuffer, VkTessellationDomainOrigin) {
    unsupported("vkCmdSetTessellationDomainOriginEXT", "extendedDynamicState3TessellationDomainOrigin");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetRasterizationSamplesEXT(VkCommandBuffer, VkSampleCountFlagBits) {
    unsupported("vkCmdSetRasterizationSamplesEXT", "extendedDynamicState3RasterizationSamples");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetRasterizationStreamEXT(VkCommandBuffer, uint32_t) {
    unsupported("vkCmdSetRasterizationStreamEXT", "extendedDynamicState3RasterizationStream");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetConservativeRasterizationModeEXT(VkCommandBuffer,
                                                                      VkConservativeRasterizationModeEXT) {
    unsupported("vkCmdSetConservativeRasterizationModeEXT", "extendedDynamicState3ConservativeRasterizationMode");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetExtraPrimitiveOverestimationSizeEXT(VkCommandBuffer, float) {
    unsupported("vkCmdSetExtraPrimitiveOverestimationSizeEXT", "extendedDynamicState3ExtraPrimitiveOverestimationSize");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetSampleLocationsEnableEXT(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetSampleLocationsEnableEXT", "extendedDynamicState3SampleLocationsEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetColorBlendAdvancedEXT(VkCommandBuffer, uint32_t, uint32_t,
                                                           const VkColorBlendAdvancedEXT*) {
    unsupported("vkCmdSetColorBlendAdvancedEXT", "extendedDynamicState3ColorBlendAdvanced");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetViewportWScalingEnableNV(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetViewportWScalingEnableNV", "extendedDynamicState3ViewportWScalingEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetViewportSwizzleNV(VkCommandBuffer, uint32_t, uint32_t,
                                                       const VkViewportSwizzleNV*) {
    unsupported("vkCmdSetViewportSwizzleNV", "extendedDynamicState3ViewportSwizzle");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetCoverageToColorEnableNV(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetCoverageToColorEnableNV", "extendedDynamicState3CoverageToColorEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetCoverageToColorLocationNV(VkCommandBuffer, uint32_t) {
    unsupported("vkCmdSetCoverageToColorLocationNV", "extendedDynamicState3CoverageToColorLocation");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetCoverageModulationModeNV(VkCommandBuffer, VkCoverageModulationModeNV) {
    unsupported("vkCmdSetCoverageModulationModeNV", "extendedDynamicState3CoverageModulationMode");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetCoverageModulationTableEnableNV(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetCoverageModulationTableEnableNV", "extendedDynamicState3CoverageModulationTableEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetCoverageModulationTableNV(VkCommandBuffer, uint32_t, const float*) {
    unsupported("vkCmdSetCoverageModulationTableNV", "extendedDynamicState3CoverageModulationTable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetShadingRateImageEnableNV(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetShadingRateImageEnableNV", "extendedDynamicState3ShadingRateImageEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetRepresentativeFragmentTestEnableNV(VkCommandBuffer, VkBool32) {
    unsupported("vkCmdSetRepresentativeFragmentTestEnableNV", "extendedDynamicState3RepresentativeFragmentTestEnable");
}
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetCoverageReductionModeNV(VkCommandBuffer, VkCoverageReductionModeNV) {
    unsupported("vkCmdSetCoverageReductionModeNV", "extendedDynamicState3CoverageReductionMode");
}

}  // namespace tilevk::icd
