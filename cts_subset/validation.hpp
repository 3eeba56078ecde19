// --validation: VK_LAYER_KHRONOS_validation on the runner's instance, and a VK_EXT_debug_utils messenger whose
// messages are attributed to the running case and device. A case that draws any message fails with its text.
#pragma once

#include <vulkan/vulkan.h>

#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace tilevk::cts {

struct ValidationMessage {
    std::string scope;   // the case name, or "(setup)" / "(teardown)"
    std::string device;  // the device the message is about (from its objects, else the side being recorded)
    std::string id;      // pMessageIdName, e.g. "VUID-vkCmdDraw-None-02699"
    std::string text;    // pMessage
    bool error = false;  // ERROR severity (else WARNING)
};

// Collects messages from the debug-utils callback. Thread-safe: the layer calls back on the thread making the API
// call, and the runner's watchdog thread never calls Vulkan.
class ValidationLog {
  public:
    // What the runner is doing now; messages with no recognisable device object go to `device`.
    void set_scope(const std::string& scope, const std::string& device);
    // Handles of a device's VkDevice and VkQueue, so messages naming them are attributed to it whatever the scope.
    void add_device(uint64_t device, uint64_t queue, const std::string& name);
    // Messages since the last take(), in order.
    std::vector<ValidationMessage> take();
    // Message count per device over the whole run.
    std::map<std::string, int> totals() const;

    // The severities and types the messenger asks for (see the README: errors and warnings of every type).
    static VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log);

  private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT types,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
    void record(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const VkDebugUtilsMessengerCallbackDataEXT& data);

    mutable std::mutex mutex_;
    std::string scope_ = "(setup)", device_;
    std::map<uint64_t, std::string> handles_;
    std::vector<ValidationMessage> pending_;
    std::map<std::string, int> totals_;
};

// One line per message: "[device] VUID: text" (the text shortened to `max_text` characters when > 0).
std::string format_message(const ValidationMessage& m, size_t max_text = 0);

}  // namespace tilevk::cts
