#include "vk_names.hpp"

#include <vulkan/vulkan.hpp>
#include <vulkan/vulkan_to_string.hpp>

namespace tilevk::cts {

std::string format_name(VkFormat f) {
    return vk::to_string(static_cast<vk::Format>(f));
}
std::string format_features_name(VkFormatFeatureFlags f) {
    return vk::to_string(static_cast<vk::FormatFeatureFlags>(f));
}
std::string result_name(VkResult r) {
    return vk::to_string(static_cast<vk::Result>(r));
}

}  // namespace tilevk::cts
