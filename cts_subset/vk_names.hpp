// Readable names for Vulkan values in failure reasons (formats, format-feature flags, results).
#pragma once

#include <vulkan/vulkan.h>

#include <string>

namespace tilevk::cts {

std::string format_name(VkFormat f);                       // "R8G8B8A8Unorm"
std::string format_features_name(VkFormatFeatureFlags f);  // "{ ColorAttachment | ColorAttachmentBlend }"
std::string result_name(VkResult r);                       // "ErrorInitializationFailed"

}  // namespace tilevk::cts
