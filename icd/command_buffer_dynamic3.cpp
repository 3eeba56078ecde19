// vkCmdSetVertexInputEXT (VK_EXT_vertex_input_dynamic_state) and the vkCmdSet* of extended dynamic state 3
// (VK_EXT_extended_dynamic_state3) that do more than record one value: the sample mask and the per-attachment
// states. Each records the value it sets; execution applies it where the bound pipeline declared the state dynamic
// (dynamic_state.cpp). The one-value commands, and the refusals of the members tilevk reports VK_FALSE, are lines
// of dynamic_commands.txt.
#include <algorithm>

#include "command_buffer.h"
#include "dynamic_commands.h"
#include "entrypoints.h"
#include "formats.h"
#include "object.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

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

// Only sample mask word 0 exists (at most 4 samples); a null mask is every sample, as lavapipe reads it.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetSampleMaskEXT(VkCommandBuffer commandBuffer, VkSampleCountFlagBits,
                                                   const VkSampleMask* pSampleMask) {
    record_dynamic_value(commandBuffer, DynamicState::kSampleMask, pSampleMask ? pSampleMask[0] : ~0u);
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

}  // namespace tilevk::icd
