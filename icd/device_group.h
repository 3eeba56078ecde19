// VK_KHR_device_group on a one-device group (device_group.cpp).
#pragma once

#include <vulkan/vulkan.h>

namespace tilevk::icd {

// The area a render pass instance renders: VkDeviceGroupRenderPassBeginInfo's area for device 0 when the begin info
// chains one with a non-zero count (it then overrides renderArea, as the spec says), else renderArea.
VkRect2D render_area_of(const VkRenderPassBeginInfo& begin);
// The same for any begin info (VkRenderingInfo: vkCmdBeginRendering): `area` and its pNext `chain`; `command` names the
// command in the message.
VkRect2D render_area_of(const VkRect2D& area, const void* chain, const char* command);

}  // namespace tilevk::icd
