// Object lifetimes and queue behaviour on both drivers: allocation callbacks, fences, events, re-submission,
// secondary command buffers, vkCmdClearAttachments, and a Vulkan 1.3 application on the 1.0 driver.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>

#include "vk_harness.h"

namespace {

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::transition;

// Counts live allocations made through it.
struct CountingAllocator {
    std::mutex mutex;
    std::map<void*, size_t> live;
    size_t total = 0;
    VkAllocationCallbacks callbacks() {
        VkAllocationCallbacks a{};
        a.pUserData = this;
        a.pfnAllocation = [](void* u, size_t size, size_t align, VkSystemAllocationScope) -> void* {
            auto* self = static_cast<CountingAllocator*>(u);
            void* p = nullptr;
            if (posix_memalign(&p, align < sizeof(void*) ? sizeof(void*) : align, size) != 0) return nullptr;
            std::lock_guard<std::mutex> lock(self->mutex);
            self->live[p] = size;
            ++self->total;
            return p;
        };
        a.pfnReallocation = [](void*, void*, size_t, size_t, VkSystemAllocationScope) -> void* { return nullptr; };
        a.pfnFree = [](void* u, void* p) {
            if (p == nullptr) return;
            auto* self = static_cast<CountingAllocator*>(u);
            std::lock_guard<std::mutex> lock(self->mutex);
            self->live.erase(p);
            free(p);
        };
        return a;
    }
};

class Objects : public ::testing::TestWithParam<const char*> {
  protected:
    void SetUp() override {
        harness_ = std::make_unique<Harness>();
        ASSERT_TRUE(harness_->ok());
        VkPhysicalDevice pd = harness_->find_device(GetParam());
        ASSERT_NE(pd, VK_NULL_HANDLE) << GetParam();
        dev_ = std::make_unique<Device>(pd);
        ASSERT_TRUE(dev_->ok());
    }
    void TearDown() override {
        dev_.reset();
        EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
        harness_.reset();
    }
    std::unique_ptr<Harness> harness_;
    std::unique_ptr<Device> dev_;
};

TEST_P(Objects, AllocationCallbacksAreUsedAndBalanced) {
    CountingAllocator counter;
    VkAllocationCallbacks cb = counter.callbacks();
    VkDevice d = dev_->device();
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = 256;
    bci.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer buf;
    ASSERT_EQ(vkCreateBuffer(d, &bci, &cb, &buf), VK_SUCCESS);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    ASSERT_EQ(vkCreateFence(d, &fci, &cb, &fence), VK_SUCCESS);
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    VkCommandPool pool;
    ASSERT_EQ(vkCreateCommandPool(d, &pci, &cb, &pool), VK_SUCCESS);
    EXPECT_GE(counter.total, 3u) << "the driver must allocate its objects through the callbacks";
    vkDestroyCommandPool(d, pool, &cb);
    vkDestroyFence(d, fence, &cb);
    vkDestroyBuffer(d, buf, &cb);
    EXPECT_TRUE(counter.live.empty()) << counter.live.size() << " allocations leaked";
}

TEST_P(Objects, FencesAndEvents) {
    VkDevice d = dev_->device();
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence f;
    ASSERT_EQ(vkCreateFence(d, &fci, nullptr, &f), VK_SUCCESS);
    EXPECT_EQ(vkGetFenceStatus(d, f), VK_SUCCESS);
    EXPECT_EQ(vkResetFences(d, 1, &f), VK_SUCCESS);
    EXPECT_EQ(vkGetFenceStatus(d, f), VK_NOT_READY);
    EXPECT_EQ(vkWaitForFences(d, 1, &f, VK_TRUE, 1000), VK_TIMEOUT);  // 1 us: nothing will signal it
    vkDestroyFence(d, f, nullptr);

    VkEventCreateInfo eci{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
    VkEvent e1, e2;
    ASSERT_EQ(vkCreateEvent(d, &eci, nullptr, &e1), VK_SUCCESS);
    ASSERT_EQ(vkCreateEvent(d, &eci, nullptr, &e2), VK_SUCCESS);
    EXPECT_EQ(vkGetEventStatus(d, e1), VK_EVENT_RESET);
    EXPECT_EQ(vkSetEvent(d, e2), VK_SUCCESS);
    EXPECT_EQ(vkGetEventStatus(d, e2), VK_EVENT_SET);
    dev_->run([&](VkCommandBuffer cb) {
        vkCmdSetEvent(cb, e1, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdWaitEvents(cb, 1, &e1, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, nullptr, 0,
                        nullptr, 0, nullptr);
        vkCmdResetEvent(cb, e2, VK_PIPELINE_STAGE_TRANSFER_BIT);
    });
    EXPECT_EQ(vkGetEventStatus(d, e1), VK_EVENT_SET);
    EXPECT_EQ(vkGetEventStatus(d, e2), VK_EVENT_RESET);
    vkDestroyEvent(d, e1, nullptr);
    vkDestroyEvent(d, e2, nullptr);
}

// The same command buffer submitted twice runs twice; a secondary command buffer runs inside the primary.
TEST_P(Objects, ResubmitAndSecondary) {
    VkDevice d = dev_->device();
    Device::Buffer buf = dev_->make_buffer(64);
    std::memset(buf.map, 0, 64);
    VkQueue q;
    vkGetDeviceQueue(d, 0, 0, &q);
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    VkCommandPool pool;
    ASSERT_EQ(vkCreateCommandPool(d, &pci, nullptr, &pool), VK_SUCCESS);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_SECONDARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer sec, prim;
    ASSERT_EQ(vkAllocateCommandBuffers(d, &ai, &sec), VK_SUCCESS);
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ASSERT_EQ(vkAllocateCommandBuffers(d, &ai, &prim), VK_SUCCESS);
    VkCommandBufferInheritanceInfo inh{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.pInheritanceInfo = &inh;
    ASSERT_EQ(vkBeginCommandBuffer(sec, &bi), VK_SUCCESS);
    vkCmdCopyBuffer(sec, buf.buffer, buf.buffer, 1, std::array<VkBufferCopy, 1>{{{0, 32, 4}}}.data());
    ASSERT_EQ(vkEndCommandBuffer(sec), VK_SUCCESS);
    bi.pInheritanceInfo = nullptr;
    ASSERT_EQ(vkBeginCommandBuffer(prim, &bi), VK_SUCCESS);
    const uint32_t one = 1;
    vkCmdUpdateBuffer(prim, buf.buffer, 0, 4, &one);
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(prim, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, nullptr, 0,
                         nullptr);
    vkCmdExecuteCommands(prim, 1, &sec);
    ASSERT_EQ(vkEndCommandBuffer(prim), VK_SUCCESS);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &prim;
    ASSERT_EQ(vkQueueSubmit(q, 1, &si, VK_NULL_HANDLE), VK_SUCCESS);
    ASSERT_EQ(vkQueueWaitIdle(q), VK_SUCCESS);
    uint32_t got[16];
    std::memcpy(got, buf.map, 64);
    EXPECT_EQ(got[0], 1u);
    EXPECT_EQ(got[8], 1u);  // copied by the secondary
    // Change the source on the host and submit again: the copy reads the new value.
    got[0] = 0;
    std::memcpy(buf.map, &got[0], 4);
    ASSERT_EQ(vkQueueSubmit(q, 1, &si, VK_NULL_HANDLE), VK_SUCCESS);
    ASSERT_EQ(vkDeviceWaitIdle(d), VK_SUCCESS);
    std::memcpy(got, buf.map, 64);
    EXPECT_EQ(got[0], 1u);
    EXPECT_EQ(got[8], 1u);
    vkDestroyCommandPool(d, pool, nullptr);
    dev_->destroy(buf);
}

// Writes a LINEAR image through the mapped memory at vkGetImageSubresourceLayout's offsets and pitches, then
// reads it back with vkCmdCopyImageToBuffer: the reported layout must be the real one.
TEST_P(Objects, LinearImageSubresourceLayoutIsTheRealLayout) {
    VkDevice d = dev_->device();
    const uint32_t w = 7, h = 5;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = VK_FORMAT_R8G8B8A8_UNORM;
    ci.extent = {w, h, 1};
    ci.mipLevels = 1;
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_LINEAR;
    ci.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ci.initialLayout = VK_IMAGE_LAYOUT_PREINITIALIZED;
    VkImage img;
    ASSERT_EQ(vkCreateImage(d, &ci, nullptr, &img), VK_SUCCESS);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d, img, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(dev_->physical(), &mp);
    uint32_t type = 0;
    while (type < mp.memoryTypeCount &&
           !((req.memoryTypeBits & (1u << type)) &&
             (mp.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) &&
             (mp.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))) {
        ++type;
    }
    ASSERT_LT(type, mp.memoryTypeCount);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    VkDeviceMemory mem;
    ASSERT_EQ(vkAllocateMemory(d, &ai, nullptr, &mem), VK_SUCCESS);
    ASSERT_EQ(vkBindImageMemory(d, img, mem, 0), VK_SUCCESS);
    VkImageSubresource sub{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0};
    VkSubresourceLayout lay;
    vkGetImageSubresourceLayout(d, img, &sub, &lay);
    ASSERT_GE(lay.rowPitch, w * 4u);
    uint8_t* p = nullptr;
    ASSERT_EQ(vkMapMemory(d, mem, 0, VK_WHOLE_SIZE, 0, reinterpret_cast<void**>(&p)), VK_SUCCESS);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w * 4; ++x) p[lay.offset + y * lay.rowPitch + x] = uint8_t(y * 40 + x);
    vkUnmapMemory(d, mem);
    Device::Buffer buf = dev_->make_buffer(w * h * 4);
    dev_->run([&](VkCommandBuffer cb) {
        transition(cb, img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PREINITIALIZED,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy r{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
        vkCmdCopyImageToBuffer(cb, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.buffer, 1, &r);
    });
    const uint8_t* got = static_cast<const uint8_t*>(buf.map);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w * 4; ++x) ASSERT_EQ(got[y * w * 4 + x], uint8_t(y * 40 + x)) << x << "," << y;
    dev_->destroy(buf);
    vkDestroyImage(d, img, nullptr);
    vkFreeMemory(d, mem, nullptr);
}

INSTANTIATE_TEST_SUITE_P(BothDrivers, Objects, ::testing::Values("tilevk", "llvmpipe"));

// An application asking for Vulkan 1.3 still gets tilevk (a 1.2 driver accepts any apiVersion), and the
// loader's vkGetPhysicalDeviceProperties2 reaches it.
TEST(Versions, Vulkan13ApplicationSeesTilevk) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    VkInstance inst;
    ASSERT_EQ(vkCreateInstance(&ci, nullptr, &inst), VK_SUCCESS);
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(inst, &n, nullptr);
    std::vector<VkPhysicalDevice> pds(n);
    vkEnumeratePhysicalDevices(inst, &n, pds.data());
    bool found = false;
    for (VkPhysicalDevice pd : pds) {
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        if (std::strncmp(p2.properties.deviceName, "tilevk", 6) == 0) {
            found = true;
            EXPECT_EQ(VK_API_VERSION_MINOR(p2.properties.apiVersion), 3u);  // icd/meson.build icd_api_minor
        }
    }
    EXPECT_TRUE(found);
    vkDestroyInstance(inst, nullptr);
}

// Image parameters beyond what vkGetPhysicalDeviceImageFormatProperties reports (maxExtent = maxImageDimension2D,
// other image types, flags, sample counts) are invalid usage; tilevk refuses them with that query's code,
// VK_ERROR_FORMAT_NOT_SUPPORTED, as icd/README.md says (no validation layer: the calls are invalid on purpose).
TEST(Images, ParametersPastImageFormatPropertiesAreFormatNotSupported) {
    Harness h(false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    Device dev(pd);
    ASSERT_TRUE(dev.ok());
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    const uint32_t max2d = props.limits.maxImageDimension2D;
    auto create = [&](VkImageType type, uint32_t w, uint32_t hgt, VkImageCreateFlags flags,
                      VkSampleCountFlagBits samples) {
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = type;
        ci.format = VK_FORMAT_R8G8B8A8_UNORM;
        ci.extent = {w, hgt, 1};
        ci.mipLevels = 1;
        ci.arrayLayers = 1;
        ci.samples = samples;
        ci.tiling = VK_IMAGE_TILING_OPTIMAL;
        ci.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        ci.flags = flags;
        VkImage img = VK_NULL_HANDLE;
        const VkResult r = vkCreateImage(dev.device(), &ci, nullptr, &img);
        if (img != VK_NULL_HANDLE) vkDestroyImage(dev.device(), img, nullptr);
        return r;
    };
    EXPECT_EQ(create(VK_IMAGE_TYPE_2D, max2d, max2d, 0, VK_SAMPLE_COUNT_1_BIT), VK_SUCCESS);
    EXPECT_EQ(create(VK_IMAGE_TYPE_2D, max2d + 1, 16, 0, VK_SAMPLE_COUNT_1_BIT), VK_ERROR_FORMAT_NOT_SUPPORTED);
    EXPECT_EQ(create(VK_IMAGE_TYPE_2D, 16, max2d + 1, 0, VK_SAMPLE_COUNT_1_BIT), VK_ERROR_FORMAT_NOT_SUPPORTED);
    EXPECT_EQ(create(VK_IMAGE_TYPE_1D, 16, 1, 0, VK_SAMPLE_COUNT_1_BIT), VK_ERROR_FORMAT_NOT_SUPPORTED);
    EXPECT_EQ(create(VK_IMAGE_TYPE_3D, 16, 16, 0, VK_SAMPLE_COUNT_1_BIT), VK_SUCCESS);
    EXPECT_EQ(create(VK_IMAGE_TYPE_3D, 16, 16, 0, VK_SAMPLE_COUNT_4_BIT), VK_ERROR_FORMAT_NOT_SUPPORTED);
    // Sparse images are not supported (MUTABLE_FORMAT colour images are: api_breadth_mutable_format_test.cpp).
    EXPECT_EQ(create(VK_IMAGE_TYPE_2D, 16, 16, VK_IMAGE_CREATE_SPARSE_BINDING_BIT, VK_SAMPLE_COUNT_1_BIT),
              VK_ERROR_FORMAT_NOT_SUPPORTED);
    EXPECT_EQ(create(VK_IMAGE_TYPE_2D, 16, 16, 0, VK_SAMPLE_COUNT_8_BIT), VK_ERROR_FORMAT_NOT_SUPPORTED);
}

}  // namespace
