// The two bodies of the vkCmdSet* that dynamic_commands.txt lists: gen/gen_entrypoints.py writes those functions
// into entrypoints.cpp, which includes this header alone (it defines the window-system platform macros, under which
// Xlib's `None` would break the heavier headers). Defined in command_buffer_dynamic.cpp.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

#include "dynamic_state.h"

namespace tilevk::icd {

// Records `value` for `state` in the command buffer; execution applies it where the bound pipeline declared the
// state dynamic.
void record_dynamic_value(VkCommandBuffer commandBuffer, DynamicState state, uint32_t value);
// Logs the call of `command`, whose `feature` tilevk reports VK_FALSE (so calling it is invalid); records nothing.
void refuse_dynamic_command(const char* command, const char* feature);

}  // namespace tilevk::icd
