// VK_KHR_device_group (core in Vulkan 1.1) on tilevk's one-device groups (vkEnumeratePhysicalDeviceGroups,
// physical_device2.cpp): every device mask is 1 and every device index 0, so the group commands are the single-device
// commands they generalise — vkCmdDispatchBase is a dispatch from a base workgroup, a device render area is the
// render area. The window-system parts (present capabilities, present rectangles, vkAcquireNextImage2KHR, images
// bound to swapchain memory) live with the swapchain in wsi/.
#include "device_group.h"
#include "command_buffer.h"
#include "entrypoints.h"
#include "vk_names.h"

namespace tilevk::icd {

// The spec asks for two different devices of the group (VUID-vkGetDeviceGroupPeerMemoryFeatures-localDeviceIndex-
// 00691), which a one-device group does not have: no call is valid. It is reported and answered with no features,
// as lavapipe answers it.
VKAPI_ATTR void VKAPI_CALL tvk_GetDeviceGroupPeerMemoryFeatures(VkDevice, uint32_t heapIndex, uint32_t localDeviceIndex,
                                                                uint32_t remoteDeviceIndex,
                                                                VkPeerMemoryFeatureFlags* pPeerMemoryFeatures) {
    log_error(
        "vkGetDeviceGroupPeerMemoryFeatures: devices %u and %u, heap %u: the group has one device, so there is "
        "no peer memory",
        localDeviceIndex, remoteDeviceIndex, heapIndex);
    *pPeerMemoryFeatures = 0;
}

// Device 0 is the only device: a mask of 1 changes nothing; any other mask names devices that do not exist
// (VUID-vkCmdSetDeviceMask-deviceMask-00108) and is reported, leaving the commands to run on device 0.
VKAPI_ATTR void VKAPI_CALL tvk_CmdSetDeviceMask(VkCommandBuffer, uint32_t deviceMask) {
    if (deviceMask != 1)
        log_error("vkCmdSetDeviceMask: deviceMask 0x%x names devices the one-device group does not have", deviceMask);
}

// The workgroup IDs run from base to base + count (gl_WorkGroupID and gl_GlobalInvocationID include the base);
// execute_compute.cpp checks base + count against maxComputeWorkGroupCount when the dispatch runs.
VKAPI_ATTR void VKAPI_CALL tvk_CmdDispatchBase(VkCommandBuffer commandBuffer, uint32_t baseGroupX, uint32_t baseGroupY,
                                               uint32_t baseGroupZ, uint32_t groupCountX, uint32_t groupCountY,
                                               uint32_t groupCountZ) {
    if (auto* c = from_handle<CommandBuffer>(commandBuffer)->append<CmdDispatch>()) {
        c->base[0] = baseGroupX;
        c->base[1] = baseGroupY;
        c->base[2] = baseGroupZ;
        c->group_count[0] = groupCountX;
        c->group_count[1] = groupCountY;
        c->group_count[2] = groupCountZ;
    }
}

VkRect2D render_area_of(const VkRect2D& area, const void* chain, const char* command) {
    const auto* group =
        find_in_chain<VkDeviceGroupRenderPassBeginInfo>(chain, VK_STRUCTURE_TYPE_DEVICE_GROUP_RENDER_PASS_BEGIN_INFO);
    if (group == nullptr || group->deviceRenderAreaCount == 0) return area;
    if (group->deviceRenderAreaCount != 1)
        log_error("%s: VkDeviceGroupRenderPassBeginInfo has %u render areas for a one-device group; the first is used",
                  command, group->deviceRenderAreaCount);
    return group->pDeviceRenderAreas[0];
}

VkRect2D render_area_of(const VkRenderPassBeginInfo& begin) {
    return render_area_of(begin.renderArea, begin.pNext, "vkCmdBeginRenderPass");
}

}  // namespace tilevk::icd
