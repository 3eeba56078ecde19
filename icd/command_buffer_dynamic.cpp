// The vkCmdSet* of extended dynamic state 1 and 2 (VK_EXT_extended_dynamic_state[2], core in Vulkan 1.3) that do
// more than record one value, and the two helpers of the one-value commands that dynamic_commands.txt lists (their
// definitions are generated). Each records the value it sets; execution applies it where the bound pipeline declared
// the state dynamic (dynamic_state.cpp). vkCmdBindVertexBuffers2 is with the other binds (command_buffer.cpp).
#include "command_buffer.h"
#include "dynamic_commands.h"
#include "entrypoints.h"
#include "object.h"

namespace tilevk::icd {

void record_dynamic_value(VkCommandBuffer commandBuffer, DynamicState state, uint32_t value) {
    if (auto* c = from_handle<CommandBuffer>(commandBuffer)->append<CmdSetDynamic>()) {
        c->state = state;
        c->value = value;
    }
}

void refuse_dynamic_command(const char* command, const char* feature) {
    log_error("%s: %s is not supported (VK_FALSE); ignored", command, feature);
}

// The WithCount forms set the viewports / scissors exactly as vkCmdSetViewport/vkCmdSetScissor from index 0 do.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetViewportWithCount(VkCommandBuffer commandBuffer, uint32_t viewportCount,
                                                       const VkViewport* pViewports) {
    tvk_CmdSetViewport(commandBuffer, 0, viewportCount, pViewports);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetScissorWithCount(VkCommandBuffer commandBuffer, uint32_t scissorCount,
                                                      const VkRect2D* pScissors) {
    tvk_CmdSetScissor(commandBuffer, 0, scissorCount, pScissors);
}

VKAPI_ATTR void VKAPI_CALL tvk_CmdSetStencilOp(VkCommandBuffer commandBuffer, VkStencilFaceFlags faceMask,
                                               VkStencilOp failOp, VkStencilOp passOp, VkStencilOp depthFailOp,
                                               VkCompareOp compareOp) {
    if (auto* c = from_handle<CommandBuffer>(commandBuffer)->append<CmdSetStencilOp>()) {
        c->faces = faceMask;
        c->ops.failOp = failOp;
        c->ops.passOp = passOp;
        c->ops.depthFailOp = depthFailOp;
        c->ops.compareOp = compareOp;
    }
}

// VK_EXT_color_write_enable: one bit per attachment (at most maxColorAttachments, 8); a value other than VK_TRUE
// disables, as lavapipe's handle_set_color_write_enable reads it.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetColorWriteEnableEXT(VkCommandBuffer commandBuffer, uint32_t attachmentCount,
                                                         const VkBool32* pColorWriteEnables) {
    uint32_t enables = ~0u;
    for (uint32_t i = 0; i < attachmentCount && i < 32; ++i)
        if (pColorWriteEnables[i] != VK_TRUE) enables &= ~(1u << i);
    record_dynamic_value(commandBuffer, DynamicState::kColorWriteEnable, enables);
}
// VK_EXT_line_rasterization: no tilevk pipeline stipples its lines (stippledLineEnable and the dynamic state
// VK_DYNAMIC_STATE_LINE_STIPPLE_EXT are refused at pipeline creation), so the factor and pattern are never read.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetLineStippleEXT(VkCommandBuffer, uint32_t, uint16_t) {}

// extendedDynamicState2PatchControlPoints is VK_FALSE (no tessellation): calling this is invalid usage, and there
// is no patch to control.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetPatchControlPointsEXT(VkCommandBuffer, uint32_t) {
    log_error(
        "vkCmdSetPatchControlPointsEXT: tilevk has no tessellation (extendedDynamicState2PatchControlPoints "
        "is not supported); ignored");
}

}  // namespace tilevk::icd
