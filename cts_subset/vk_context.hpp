// The runner's Vulkan side: one instance, and a "device context" per side (ours and the reference).
// Both sides may live on the same physical device (lavapipe vs lavapipe) as two separate VkDevices.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace tilevk::cts {

class ValidationLog;

// Any failing Vulkan call becomes this error; its text is the reason a case fails.
struct VkError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
void vk_check(VkResult r, const char* what);

struct DeviceContext {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties props{};
    VkPhysicalDeviceFeatures features{};
    VkPhysicalDeviceMemoryProperties memory{};
    std::string name;

    // The index of a memory type allowed by `bits` that has all of `flags`; throws if there is none.
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;
};

class Instance {
  public:
    // With a log, VK_LAYER_KHRONOS_validation is enabled and a debug-utils messenger feeds the log (also during
    // vkCreateInstance/vkDestroyInstance).
    explicit Instance(ValidationLog* validation = nullptr);
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    std::vector<std::string> device_names() const;
    // Opens a logical device on the first physical device whose name contains `substring` (or starts with it when
    // `prefix`); returns false with a reason if none matches or creation fails.
    bool open(const std::string& substring, bool prefix, DeviceContext& out, std::string& reason) const;
    static void close(DeviceContext& ctx);

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    std::vector<VkPhysicalDevice> physicals_;
};

}  // namespace tilevk::cts
