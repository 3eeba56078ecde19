// Test harness for the loader-level ICD tests: an instance with VK_LAYER_KHRONOS_validation and a debug-utils
// messenger that counts every message, and small helpers to make buffers/images and run one command buffer.
#pragma once
#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tilevk::test {

struct Messages {
    std::atomic<int> count{0};
    std::vector<std::string> texts;  // for the failure report
};

class Harness {
  public:
    // Creates the instance (Vulkan 1.2 unless `api_version` says otherwise, validation + debug utils). ok() tells
    // whether it worked, including the messenger: without it the layer would print to stdout and message_count()
    // would stay 0. `extensions`: instance extensions to enable besides VK_EXT_debug_utils.
    explicit Harness(bool validation = true, const std::vector<const char*>& extensions = {},
                     uint32_t api_version = VK_API_VERSION_1_2);
    ~Harness();
    bool ok() const { return instance_ != VK_NULL_HANDLE && messenger_ != VK_NULL_HANDLE; }
    VkInstance instance() const { return instance_; }
    int message_count() const { return messages_.count.load(); }
    std::string message_report() const;
    std::vector<VkPhysicalDevice> physical_devices() const;
    // The device whose name starts with `prefix`, or VK_NULL_HANDLE.
    VkPhysicalDevice find_device(const char* prefix) const;

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    Messages messages_;
};

// A logical device with its queue, a command pool, and helpers.
class Device {
  public:
    // `features`: what to enable (none when null); `extensions`: device extensions to enable; `chain`: the
    // VkDeviceCreateInfo pNext chain (feature structs).
    explicit Device(VkPhysicalDevice pd, const VkPhysicalDeviceFeatures* features = nullptr,
                    const std::vector<const char*>& extensions = {}, const void* chain = nullptr);
    ~Device();
    VkDevice device() const { return device_; }
    VkPhysicalDevice physical() const { return pd_; }
    VkQueue queue() const { return queue_; }
    VkCommandPool pool() const { return pool_; }
    bool ok() const { return device_ != VK_NULL_HANDLE; }

    struct Buffer {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        void* map = nullptr;
        VkDeviceSize size = 0;
    };
    struct Image {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
    };
    // TRANSFER_SRC|DST (| extra_usage), host visible and coherent, mapped; with SHADER_DEVICE_ADDRESS in
    // extra_usage, its memory is allocated with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT.
    Buffer make_buffer(VkDeviceSize size, VkBufferUsageFlags extra_usage = 0);
    void destroy(Buffer& b);
    Image make_image(VkFormat format, uint32_t width, uint32_t height, uint32_t levels, uint32_t layers,
                     VkSampleCountFlagBits samples, VkImageUsageFlags usage);
    // Any image (3D, other flags): made from `ci`, bound to fresh memory. Empty when vkCreateImage fails.
    Image make_image(const VkImageCreateInfo& ci);
    void destroy(Image& i);
    // Records with `record`, submits with a fence and waits. Returns the submission's result, else the wait's.
    VkResult run(const std::function<void(VkCommandBuffer)>& record);
    // The first memory type in `bits` with all of `flags`, or ~0u.
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;

  private:
    VkPhysicalDevice pd_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
};

// Fixture base of the suites that run the same work on both drivers: one validation-enabled instance and a device
// on tilevk and on lavapipe, shared by the suite (made in SetUpTestSuite, so a missing driver fails every test of
// it); every test must leave zero validation messages.
class TwoDriverSuite : public ::testing::Test {
  protected:
    static void SetUpTestSuite();
    static void TearDownTestSuite();
    void TearDown() override;
    static std::unique_ptr<Harness> harness_;
    static std::unique_ptr<Device> tilevk_, lavapipe_;
};

// A 2D image's create info (exclusive sharing), for Device::make_image or an image bound by hand.
VkImageCreateInfo image_info_2d(VkFormat format, uint32_t width, uint32_t height, uint32_t levels, uint32_t layers,
                                VkSampleCountFlagBits samples, VkImageUsageFlags usage,
                                VkImageTiling tiling = VK_IMAGE_TILING_OPTIMAL,
                                VkImageLayout initial_layout = VK_IMAGE_LAYOUT_UNDEFINED);

// Whole-image layout transition (UNDEFINED or anything -> `to`), for the validation layer's benefit.
void transition(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspects, VkImageLayout from, VkImageLayout to,
                uint32_t levels = VK_REMAINING_MIP_LEVELS, uint32_t layers = VK_REMAINING_ARRAY_LAYERS);

}  // namespace tilevk::test
