#include "validation.hpp"

namespace tilevk::cts {

void ValidationLog::set_scope(const std::string& scope, const std::string& device) {
    std::lock_guard<std::mutex> lock(mutex_);
    scope_ = scope;
    device_ = device;
}

void ValidationLog::add_device(uint64_t device, uint64_t queue, const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    handles_[device] = name;
    handles_[queue] = name;
}

std::vector<ValidationMessage> ValidationLog::take() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<ValidationMessage> out;
    out.swap(pending_);
    return out;
}

std::map<std::string, int> ValidationLog::totals() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return totals_;
}

VkDebugUtilsMessengerCreateInfoEXT ValidationLog::messenger_info(ValidationLog* log) {
    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    // Warnings and errors of every type. INFO/VERBOSE are the loader's search log and the layer's banner, not
    // findings. PERFORMANCE-type warnings are counted too: without the opt-in best-practices setting the layer
    // emits very few, and each would be something to explain, not to hide.
    mci.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = on_message;
    mci.pUserData = log;
    return mci;
}

VKAPI_ATTR VkBool32 VKAPI_CALL ValidationLog::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                         VkDebugUtilsMessageTypeFlagsEXT,
                                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (data && user) static_cast<ValidationLog*>(user)->record(severity, *data);
    return VK_FALSE;  // never abort the call: the driver still runs it, as without the layer
}

void ValidationLog::record(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                           const VkDebugUtilsMessengerCallbackDataEXT& data) {
    std::lock_guard<std::mutex> lock(mutex_);
    ValidationMessage m;
    m.scope = scope_;
    m.device = device_;
    for (uint32_t i = 0; i < data.objectCount; ++i) {
        auto it = handles_.find(data.pObjects[i].objectHandle);
        if (it != handles_.end()) {
            m.device = it->second;
            break;
        }
    }
    if (m.device.empty()) m.device = "(instance)";
    m.id = data.pMessageIdName ? data.pMessageIdName : "";
    m.text = data.pMessage ? data.pMessage : "(no text)";
    m.error = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    ++totals_[m.device];
    pending_.push_back(std::move(m));
}

std::string format_message(const ValidationMessage& m, size_t max_text) {
    std::string text = m.text;
    if (max_text && text.size() > max_text) text = text.substr(0, max_text) + "...";
    return "[" + m.device + "] " + (m.error ? "error " : "warning ") + (m.id.empty() ? "" : m.id + ": ") + text;
}

}  // namespace tilevk::cts
