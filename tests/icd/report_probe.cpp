// icd_report_probe: what tilevk reports through the Vulkan API, checked against what it accepts, printed as JSON for
// tests/icd/vulkaninfo_test.py to compare with vulkaninfo's text and -j output.
//   - every member of every feature struct of vk.xml (vk_names.cpp is compiled in), read with
//     vkGetPhysicalDeviceFeatures2 and then requested alone from vkCreateDevice: accepted exactly when reported
//   - every device extension, enabled alone and all together at vkCreateDevice
//   - apiVersion, device name and type, a set of limits, queue families, and the features of every named VkFormat.
// Exit status 1 (with the reasons on stderr) when a report and the driver's behaviour disagree.
#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "vk_names.h"

namespace {

using tilevk::icd::feature_structs;
using tilevk::icd::features10;
using tilevk::icd::FeatureStruct;
using tilevk::icd::vk_enum_name;
using tilevk::icd::vk_flags_name;

int g_mismatches = 0;

void mismatch(const std::string& what) {
    std::fprintf(stderr, "icd_report_probe: MISMATCH: %s\n", what.c_str());
    ++g_mismatches;
}

std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

VkBool32 member(const void* s, size_t offset) {
    VkBool32 v;
    std::memcpy(&v, static_cast<const char*>(s) + offset, sizeof v);
    return v;
}

struct Probe {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice pd = VK_NULL_HANDLE;
    PFN_vkGetPhysicalDeviceFeatures2KHR features2 = nullptr;

    VkResult create_device(const void* chain, const std::vector<const char*>& extensions) {
        float prio = 1.0f;
        VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        q.queueCount = 1;
        q.pQueuePriorities = &prio;
        VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        ci.pNext = chain;
        ci.queueCreateInfoCount = 1;
        ci.pQueueCreateInfos = &q;
        ci.enabledExtensionCount = uint32_t(extensions.size());
        ci.ppEnabledExtensionNames = extensions.data();
        VkDevice dev = VK_NULL_HANDLE;
        const VkResult r = vkCreateDevice(pd, &ci, nullptr, &dev);
        if (r == VK_SUCCESS) vkDestroyDevice(dev, nullptr);
        return r;
    }

    // {"Struct": {"member": bool}} for VkPhysicalDeviceFeatures and every feature struct; each member checked.
    std::string features() {
        std::string out = "{";
        auto one = [&](const FeatureStruct& fs, const void* reported, bool core10) {
            out += (out.size() > 1 ? ", " : "") + quote(fs.name) + ": {";
            for (uint32_t m = 0; m < fs.count; ++m) {
                const bool yes = member(reported, fs.offsets[m]) != VK_FALSE;
                out += (m ? ", " : "") + quote(fs.members[m]) + (yes ? ": true" : ": false");
                std::vector<unsigned char> want(fs.size, 0);
                VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
                void* target = core10 ? static_cast<void*>(&f2.features) : want.data();
                if (!core10) std::memcpy(want.data(), &fs.s_type, sizeof fs.s_type);
                const VkBool32 on = VK_TRUE;
                std::memcpy(static_cast<char*>(target) + fs.offsets[m], &on, sizeof on);
                const VkResult r = create_device(core10 ? static_cast<const void*>(&f2) : want.data(), {});
                if ((r == VK_SUCCESS) != yes)
                    mismatch(std::string(fs.name) + "::" + fs.members[m] + " reported " + (yes ? "true" : "false") +
                             " but vkCreateDevice returned " + vk_enum_name(r));
            }
            out += "}";
        };
        VkPhysicalDeviceFeatures f10;
        vkGetPhysicalDeviceFeatures(pd, &f10);
        one(features10(), &f10, true);
        size_t n = 0;
        const FeatureStruct* all = feature_structs(&n);
        for (size_t i = 0; i < n; ++i) {
            std::vector<unsigned char> s(all[i].size, 0);
            std::memcpy(s.data(), &all[i].s_type, sizeof all[i].s_type);
            VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
            f2.pNext = s.data();
            features2(pd, &f2);
            one(all[i], s.data(), false);
        }
        return out + "}";
    }

    std::string extensions() {
        uint32_t n = 0;
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> e(n);
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, e.data());
        std::vector<const char*> names;
        for (const VkExtensionProperties& x : e) names.push_back(x.extensionName);
        std::string out = "{";
        for (uint32_t i = 0; i < n; ++i) {
            out += (i ? ", " : "") + quote(e[i].extensionName) + ": " + std::to_string(e[i].specVersion);
            // Enabled alone, and all together (what an extension requires is among them): both must work.
            const VkResult alone = create_device(nullptr, {e[i].extensionName});
            if (alone != VK_SUCCESS) mismatch(std::string(e[i].extensionName) + " alone: " + vk_enum_name(alone));
        }
        if (n > 0 && create_device(nullptr, names) != VK_SUCCESS) mismatch("all device extensions together refused");
        return out + "}";
    }

    std::string formats() {
        std::string out = "{";
        auto add = [&](VkFormat f) {
            const char* name = vk_enum_name(f);
            if (std::strncmp(name, "VK_FORMAT_", 10) != 0) return;  // not a format of this header
            VkFormatProperties p;
            vkGetPhysicalDeviceFormatProperties(pd, f, &p);
            if (p.linearTilingFeatures == 0 && p.optimalTilingFeatures == 0 && p.bufferFeatures == 0) return;
            auto bits = [](VkFormatFeatureFlags m) {
                return quote(m ? vk_flags_name<VkFormatFeatureFlagBits>(m) : std::string());
            };
            out += (out.size() > 1 ? ", " : "") + quote(name) +
                   ": {\"linearTilingFeatures\": " + bits(p.linearTilingFeatures) +
                   ", \"optimalTilingFeatures\": " + bits(p.optimalTilingFeatures) +
                   ", \"bufferFeatures\": " + bits(p.bufferFeatures) + "}";
        };
        for (int v = 1; v < 1000; ++v) add(VkFormat(v));
        // Extension formats: 1000000000 + (extension number - 1) * 1000 + offset.
        for (int ext = 1; ext < 600; ++ext)
            for (int off = 0; off < 64; ++off) add(VkFormat(1000000000 + (ext - 1) * 1000 + off));
        return out + "}";
    }

    std::string properties() {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        const VkPhysicalDeviceLimits& l = p.limits;
        std::map<std::string, std::string> v = {
            {"apiVersion", std::to_string(p.apiVersion)},
            {"deviceName", quote(p.deviceName)},
            {"deviceType", quote(vk_enum_name(p.deviceType))},
            {"maxBoundDescriptorSets", std::to_string(l.maxBoundDescriptorSets)},
            {"maxColorAttachments", std::to_string(l.maxColorAttachments)},
            {"maxFragmentOutputAttachments", std::to_string(l.maxFragmentOutputAttachments)},
            {"maxFragmentDualSrcAttachments", std::to_string(l.maxFragmentDualSrcAttachments)},
            {"maxViewports", std::to_string(l.maxViewports)},
            {"maxSamplerAnisotropy", std::to_string(int(l.maxSamplerAnisotropy))},
            {"maxImageDimension2D", std::to_string(l.maxImageDimension2D)},
            {"maxPushConstantsSize", std::to_string(l.maxPushConstantsSize)},
            {"strictLines", l.strictLines ? "true" : "false"},
        };
        std::string out = "{";
        for (const auto& [k, x] : v) out += (out.size() > 1 ? ", " : "") + quote(k) + ": " + x;
        return out + "}";
    }

    std::string queue_families() {
        uint32_t n = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
        std::vector<VkQueueFamilyProperties> q(n);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, q.data());
        std::string out = "[";
        for (uint32_t i = 0; i < n; ++i)
            out += std::string(i ? ", " : "") +
                   "{\"queueFlags\": " + quote(vk_flags_name<VkQueueFlagBits>(q[i].queueFlags)) +
                   ", \"queueCount\": " + std::to_string(q[i].queueCount) +
                   ", \"timestampValidBits\": " + std::to_string(q[i].timestampValidBits) + "}";
        return out + "]";
    }
};

}  // namespace

int main() {
    Probe p;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    const char* ext = VK_KHR_GET_PHYSICAL_DEVICE_PROPERTIES_2_EXTENSION_NAME;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = &ext;
    if (vkCreateInstance(&ci, nullptr, &p.instance) != VK_SUCCESS) {
        std::fprintf(stderr, "icd_report_probe: vkCreateInstance failed\n");
        return 2;
    }
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(p.instance, &n, nullptr);
    std::vector<VkPhysicalDevice> pds(n);
    vkEnumeratePhysicalDevices(p.instance, &n, pds.data());
    for (VkPhysicalDevice pd : pds) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(pd, &props);
        if (std::strncmp(props.deviceName, "tilevk", 6) == 0) p.pd = pd;
    }
    p.features2 = reinterpret_cast<PFN_vkGetPhysicalDeviceFeatures2KHR>(
        vkGetInstanceProcAddr(p.instance, "vkGetPhysicalDeviceFeatures2KHR"));
    if (p.pd == VK_NULL_HANDLE || p.features2 == nullptr) {
        std::fprintf(stderr, "icd_report_probe: no tilevk device, or no vkGetPhysicalDeviceFeatures2KHR\n");
        return 2;
    }
    // stderr carries the driver's refusal lines while features are checked; the JSON goes to stdout.
    std::printf(
        "{\"properties\": %s,\n \"extensions\": %s,\n \"queueFamilies\": %s,\n \"formats\": %s,\n \"features\": %s}\n",
        p.properties().c_str(), p.extensions().c_str(), p.queue_families().c_str(), p.formats().c_str(),
        p.features().c_str());
    vkDestroyInstance(p.instance, nullptr);
    return g_mismatches == 0 ? 0 : 1;
}
