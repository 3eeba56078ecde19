// The library alone (no loader): dlopen() libvulkan_tilevk.so and check the three loader-interface exports.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <cstdio>
#include <set>
#include <string>

namespace {

using PFN_Negotiate = VkResult(VKAPI_PTR*)(uint32_t*);
using PFN_GetProc = PFN_vkVoidFunction(VKAPI_PTR*)(VkInstance, const char*);

class Exports : public ::testing::Test {
  protected:
    void SetUp() override {
        lib_ = dlopen(TILEVK_ICD_LIBRARY, RTLD_NOW | RTLD_LOCAL);
        ASSERT_NE(lib_, nullptr) << dlerror();
        negotiate_ = reinterpret_cast<PFN_Negotiate>(dlsym(lib_, "vk_icdNegotiateLoaderICDInterfaceVersion"));
        gipa_ = reinterpret_cast<PFN_GetProc>(dlsym(lib_, "vk_icdGetInstanceProcAddr"));
        gpdpa_ = reinterpret_cast<PFN_GetProc>(dlsym(lib_, "vk_icdGetPhysicalDeviceProcAddr"));
        ASSERT_NE(negotiate_, nullptr);
        ASSERT_NE(gipa_, nullptr);
        ASSERT_NE(gpdpa_, nullptr);
    }
    void TearDown() override {
        if (lib_ != nullptr) dlclose(lib_);
    }
    void* lib_ = nullptr;
    PFN_Negotiate negotiate_ = nullptr;
    PFN_GetProc gipa_ = nullptr;
    PFN_GetProc gpdpa_ = nullptr;
};

// tilevk needs loader interface 5 and speaks up to 7: below 5 -> VK_ERROR_INCOMPATIBLE_DRIVER, else min(v, 7).
TEST_F(Exports, NegotiatesInterfaceVersions) {
    struct Case {
        uint32_t loader;
        VkResult result;
        uint32_t agreed;
    };
    const Case cases[] = {{0, VK_ERROR_INCOMPATIBLE_DRIVER, 0},
                          {1, VK_ERROR_INCOMPATIBLE_DRIVER, 1},
                          {2, VK_ERROR_INCOMPATIBLE_DRIVER, 2},
                          {3, VK_ERROR_INCOMPATIBLE_DRIVER, 3},
                          {4, VK_ERROR_INCOMPATIBLE_DRIVER, 4},
                          {5, VK_SUCCESS, 5},
                          {6, VK_SUCCESS, 6},
                          {7, VK_SUCCESS, 7},
                          {8, VK_SUCCESS, 7},
                          {1000, VK_SUCCESS, 7}};
    for (const Case& c : cases) {
        uint32_t v = c.loader;
        EXPECT_EQ(negotiate_(&v), c.result) << "loader version " << c.loader;
        EXPECT_EQ(v, c.agreed) << "loader version " << c.loader;
    }
}

TEST_F(Exports, InstanceProcAddrWithoutInstance) {
    EXPECT_NE(gipa_(VK_NULL_HANDLE, "vkCreateInstance"), nullptr);
    EXPECT_NE(gipa_(VK_NULL_HANDLE, "vkEnumerateInstanceExtensionProperties"), nullptr);
    EXPECT_NE(gipa_(VK_NULL_HANDLE, "vkEnumerateInstanceLayerProperties"), nullptr);
    EXPECT_NE(gipa_(VK_NULL_HANDLE, "vkGetInstanceProcAddr"), nullptr);
    // Instance- and device-level commands need an instance.
    EXPECT_EQ(gipa_(VK_NULL_HANDLE, "vkEnumeratePhysicalDevices"), nullptr);
    EXPECT_EQ(gipa_(VK_NULL_HANDLE, "vkCreateDevice"), nullptr);
    EXPECT_EQ(gipa_(VK_NULL_HANDLE, "vkQueueSubmit"), nullptr);
}

TEST_F(Exports, UnknownAndExtensionNamesAreNull) {
    for (const char* name :
         {"", "vk", "vkNotACommand", "vkCreateInstanceX", "vkGetPhysicalDeviceMultisamplePropertiesEXT",
          "vkCreateSwapchainKHR", "vkCreateDebugUtilsMessengerEXT", "vk_icdGetInstanceProcAddr"}) {
        EXPECT_EQ(gipa_(VK_NULL_HANDLE, name), nullptr) << name;
        EXPECT_EQ(gpdpa_(VK_NULL_HANDLE, name), nullptr) << name;
    }
    // An exposed instance extension's command needs an instance (where the extension is enabled) through
    // vk_icdGetInstanceProcAddr; vk_icdGetPhysicalDeviceProcAddr, which the loader calls with no instance to learn
    // what the driver has, answers.
    EXPECT_EQ(gipa_(VK_NULL_HANDLE, "vkGetPhysicalDeviceProperties2KHR"), nullptr);
    EXPECT_NE(gpdpa_(VK_NULL_HANDLE, "vkGetPhysicalDeviceProperties2KHR"), nullptr);
}

// vk_icdGetPhysicalDeviceProcAddr answers only for commands whose first parameter is a VkPhysicalDevice.
TEST_F(Exports, PhysicalDeviceProcAddr) {
    for (const char* name : {"vkGetPhysicalDeviceProperties", "vkGetPhysicalDeviceFeatures", "vkCreateDevice",
                             "vkGetPhysicalDeviceFormatProperties", "vkEnumerateDeviceExtensionProperties"}) {
        EXPECT_NE(gpdpa_(VK_NULL_HANDLE, name), nullptr) << name;
    }
    for (const char* name : {"vkCreateInstance", "vkEnumeratePhysicalDevices", "vkDestroyInstance", "vkQueueSubmit",
                             "vkCreateBuffer", "vkCmdCopyBuffer", "vkGetDeviceProcAddr"}) {
        EXPECT_EQ(gpdpa_(VK_NULL_HANDLE, name), nullptr) << name;
    }
}

// Exactly three dynamic symbols are defined (besides linker-generated version nodes, if any).
TEST_F(Exports, OnlyTheLoaderInterfaceIsExported) {
    std::string cmd = std::string(TILEVK_NM) + " -D --defined-only " + TILEVK_ICD_LIBRARY;
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::set<std::string> symbols;
    char line[512];
    while (fgets(line, sizeof line, p) != nullptr) {
        char addr[64], type[8], name[400];
        if (sscanf(line, "%63s %7s %399s", addr, type, name) == 3 && std::string(type) != "A") symbols.insert(name);
    }
    ASSERT_EQ(pclose(p), 0) << cmd;
    const std::set<std::string> expected = {"vk_icdNegotiateLoaderICDInterfaceVersion", "vk_icdGetInstanceProcAddr",
                                            "vk_icdGetPhysicalDeviceProcAddr"};
    EXPECT_EQ(symbols, expected);
}

}  // namespace
