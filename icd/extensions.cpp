#include "extensions.h"

#include <cstring>

#include "object.h"

namespace tilevk::icd {

VkResult enumerate_extensions(bool device, uint32_t* count, VkExtensionProperties* properties) {
    size_t n = 0;
    const ExtensionInfo* table = extensions(&n);
    uint32_t available = 0;
    for (size_t i = 0; i < n; ++i) available += table[i].device == device ? 1 : 0;
    if (properties == nullptr) {
        *count = available;
        return VK_SUCCESS;
    }
    uint32_t written = 0;
    for (size_t i = 0; i < n && written < *count; ++i) {
        if (table[i].device != device) continue;
        VkExtensionProperties& p = properties[written++];
        std::memset(&p, 0, sizeof p);
        std::strncpy(p.extensionName, table[i].name, VK_MAX_EXTENSION_NAME_SIZE - 1);
        p.specVersion = table[i].spec_version;
    }
    *count = written;
    return written < available ? VK_INCOMPLETE : VK_SUCCESS;
}

VkResult enable_extensions(const char* command, bool device, uint32_t name_count, const char* const* names,
                           ExtensionSet* enabled) {
    size_t n = 0;
    const ExtensionInfo* table = extensions(&n);
    for (uint32_t i = 0; i < name_count; ++i) {
        int id = find_extension(names[i]);
        if (id < 0 || table[id].device != device) {
            return fail(VK_ERROR_EXTENSION_NOT_PRESENT, "%s: %s extension '%s' is not supported by tilevk", command,
                        device ? "device" : "instance", names[i] != nullptr ? names[i] : "(null)");
        }
        enabled->set(size_t(id));
    }
    return VK_SUCCESS;
}

bool entry_point_enabled(const EntryPoint& e, uint32_t api_version, const ExtensionSet& instance_extensions,
                         const ExtensionSet* device_extensions) {
    // Versions compare by major.minor: an application's apiVersion carries a patch number the table does not.
    const uint32_t asked =
        VK_MAKE_API_VERSION(0, VK_API_VERSION_MAJOR(api_version), VK_API_VERSION_MINOR(api_version), 0);
    if (e.core_version != 0 && e.core_version <= asked) return true;
    size_t n = 0;
    const ExtensionInfo* table = extensions(&n);
    for (uint8_t i = 0; i < e.extension_count; ++i) {
        const size_t id = size_t(e.extensions[i]);
        if (!table[id].device) {
            if (instance_extensions.test(id)) return true;
        } else if (device_extensions == nullptr || device_extensions->test(id)) {
            return true;
        }
    }
    return false;
}

}  // namespace tilevk::icd
