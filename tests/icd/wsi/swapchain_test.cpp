// Swapchains on headless surfaces (VK_EXT_headless_surface) through the loader, on tilevk, with the validation layer
// (zero messages) except where invalid usage is the point: what the surface reports, acquire/present order for FIFO,
// MAILBOX and IMMEDIATE, pacing (FIFO and MAILBOX: one image per refresh, without spinning), timeouts 0 / finite /
// UINT64_MAX, fences and semaphores, retired (out-of-date) swapchains, destruction with images queued or acquired,
// presenting from another thread, and VK_KHR_device_group's swapchain commands and images bound to swapchain memory.
// The refresh rate is TILEVK_PRESENT_HZ=5 (meson.build): 200 ms per refresh, so that the sequences below fit inside one
// refresh even on a loaded machine.
#include <gtest/gtest.h>
#include <time.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <map>
#include <mutex>
#include <thread>

#include "../stderr_capture.h"
#include "vk_harness.h"
#include "vk_pipeline.h"

using namespace tilevk::test;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kRefreshSeconds = 0.2;  // TILEVK_PRESENT_HZ=5
constexpr VkExtent2D kExtent = {64, 48};
constexpr VkFormat kFormat = VK_FORMAT_B8G8R8A8_UNORM;

double seconds_since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

double cpu_seconds() {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// An instance with the surface extensions, tilevk's device with VK_KHR_swapchain, a headless surface, and a frame
// helper that clears an acquired image and hands it to vkQueuePresentKHR the way an application does.
class Headless {
  public:
    explicit Headless(bool validation = true,
                      const std::vector<const char*>& device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME},
                      const char* instance_extension = nullptr)
        : harness_(validation, instance_extensions(instance_extension)) {
        if (!harness_.ok()) return;
        pd_ = harness_.find_device("tilevk");
        if (pd_ == VK_NULL_HANDLE) return;
        dev_ = std::make_unique<Device>(pd_, nullptr, device_extensions);
        auto create = reinterpret_cast<PFN_vkCreateHeadlessSurfaceEXT>(
            vkGetInstanceProcAddr(harness_.instance(), "vkCreateHeadlessSurfaceEXT"));
        VkHeadlessSurfaceCreateInfoEXT ci{VK_STRUCTURE_TYPE_HEADLESS_SURFACE_CREATE_INFO_EXT};
        if (create == nullptr || create(harness_.instance(), &ci, nullptr, &surface_) != VK_SUCCESS) return;
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vkCreateFence(device(), &fci, nullptr, &fence_);
        vkCreateFence(device(), &fci, nullptr, &submit_fence_);
    }
    ~Headless() {
        if (dev_ && dev_->ok()) {
            vkDeviceWaitIdle(device());
            for (VkSwapchainKHR sc : swapchains_) vkDestroySwapchainKHR(device(), sc, nullptr);
            for (auto& [sc, cbs] : command_buffers_) {
                vkFreeCommandBuffers(device(), dev_->pool(), uint32_t(cbs.size()), cbs.data());
            }
            for (VkSemaphore s : semaphores_) vkDestroySemaphore(device(), s, nullptr);
            vkDestroyFence(device(), fence_, nullptr);
            vkDestroyFence(device(), submit_fence_, nullptr);
        }
        dev_.reset();
        if (surface_ != VK_NULL_HANDLE) vkDestroySurfaceKHR(harness_.instance(), surface_, nullptr);
    }
    bool ok() const { return surface_ != VK_NULL_HANDLE && dev_ && dev_->ok() && fence_ != VK_NULL_HANDLE; }
    VkDevice device() const { return dev_->device(); }
    VkPhysicalDevice physical() const { return pd_; }
    VkSurfaceKHR surface() const { return surface_; }
    Device& device_object() const { return *dev_; }
    VkFence fence() const { return fence_; }
    VkQueue queue() const { return dev_->queue(); }
    const Harness& harness() const { return harness_; }

    VkSwapchainCreateInfoKHR create_info(VkPresentModeKHR mode, uint32_t images) const {
        VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
        ci.surface = surface_;
        ci.minImageCount = images;
        ci.imageFormat = kFormat;
        ci.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
        ci.imageExtent = kExtent;
        ci.imageArrayLayers = 1;
        ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
        ci.preTransform = VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR;
        ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
        ci.presentMode = mode;
        ci.clipped = VK_TRUE;
        return ci;
    }
    VkSwapchainKHR make(VkPresentModeKHR mode, uint32_t images, VkSwapchainKHR old = VK_NULL_HANDLE) {
        VkSwapchainCreateInfoKHR ci = create_info(mode, images);
        ci.oldSwapchain = old;
        VkSwapchainKHR sc = VK_NULL_HANDLE;
        if (vkCreateSwapchainKHR(device(), &ci, nullptr, &sc) != VK_SUCCESS) return VK_NULL_HANDLE;
        swapchains_.push_back(sc);
        record(sc);
        return sc;
    }
    void destroy(VkSwapchainKHR sc) {
        vkDestroySwapchainKHR(device(), sc, nullptr);
        std::erase(swapchains_, sc);
    }
    std::vector<VkImage> images(VkSwapchainKHR sc) const {
        uint32_t n = 0;
        vkGetSwapchainImagesKHR(device(), sc, &n, nullptr);
        std::vector<VkImage> v(n);
        vkGetSwapchainImagesKHR(device(), sc, &n, v.data());
        return v;
    }
    // vkAcquireNextImageKHR with this object's fence, waited for when the acquire succeeded.
    VkResult acquire(VkSwapchainKHR sc, uint64_t timeout, uint32_t* index) {
        vkResetFences(device(), 1, &fence_);
        VkResult r = vkAcquireNextImageKHR(device(), sc, timeout, VK_NULL_HANDLE, fence_, index);
        if (r == VK_SUCCESS || r == VK_SUBOPTIMAL_KHR) {
            EXPECT_EQ(vkWaitForFences(device(), 1, &fence_, VK_TRUE, 0), VK_SUCCESS);
        }
        return r;
    }
    // Clears the image (its command buffer, recorded at creation) and presents it, the render semaphore between.
    VkResult frame(VkSwapchainKHR sc, uint32_t index, VkSemaphore acquired = VK_NULL_HANDLE,
                   const void* present_chain = nullptr) {
        VkSemaphore rendered = render_semaphore(sc, index);
        VkPipelineStageFlags stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.waitSemaphoreCount = acquired != VK_NULL_HANDLE ? 1 : 0;
        si.pWaitSemaphores = &acquired;
        si.pWaitDstStageMask = &stage;
        si.commandBufferCount = 1;
        si.pCommandBuffers = &command_buffers_[sc][index];
        si.signalSemaphoreCount = 1;
        si.pSignalSemaphores = &rendered;
        // With a fence waited for, so that the validation layer knows the command buffer is free again.
        vkResetFences(device(), 1, &submit_fence_);
        if (VkResult r = vkQueueSubmit(queue(), 1, &si, submit_fence_); r != VK_SUCCESS) return r;
        if (VkResult r = vkWaitForFences(device(), 1, &submit_fence_, VK_TRUE, UINT64_MAX); r != VK_SUCCESS) return r;
        return present(sc, index, rendered, nullptr, present_chain);
    }
    VkResult present(VkSwapchainKHR sc, uint32_t index, VkSemaphore wait, VkResult* result = nullptr,
                     const void* chain = nullptr) {
        VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR, chain};
        pi.waitSemaphoreCount = wait != VK_NULL_HANDLE ? 1 : 0;
        pi.pWaitSemaphores = &wait;
        pi.swapchainCount = 1;
        pi.pSwapchains = &sc;
        pi.pImageIndices = &index;
        pi.pResults = result;
        return vkQueuePresentKHR(queue(), &pi);
    }
    VkSemaphore semaphore() {
        VkSemaphoreCreateInfo ci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore s;
        vkCreateSemaphore(device(), &ci, nullptr, &s);
        semaphores_.push_back(s);
        return s;
    }

  private:
    static std::vector<const char*> instance_extensions(const char* extra) {
        std::vector<const char*> v{VK_KHR_SURFACE_EXTENSION_NAME, VK_EXT_HEADLESS_SURFACE_EXTENSION_NAME,
                                   VK_KHR_GET_SURFACE_CAPABILITIES_2_EXTENSION_NAME};
        if (extra != nullptr) v.push_back(extra);
        return v;
    }
    // One semaphore per image: re-signalled only after the image came back from presentation.
    VkSemaphore render_semaphore(VkSwapchainKHR sc, uint32_t index) {
        auto& v = render_semaphores_[sc];
        while (v.size() <= index) v.push_back(semaphore());
        return v[index];
    }
    void record(VkSwapchainKHR sc) {
        std::vector<VkImage> imgs = images(sc);
        std::vector<VkCommandBuffer> cbs(imgs.size());
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = dev_->pool();
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = uint32_t(cbs.size());
        vkAllocateCommandBuffers(device(), &ai, cbs.data());
        for (size_t i = 0; i < imgs.size(); ++i) {
            VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            vkBeginCommandBuffer(cbs[i], &bi);
            transition(cbs[i], imgs[i], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkClearColorValue c{{0.25f * float(i), 0.5f, 1.0f, 1.0f}};
            VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cbs[i], imgs[i], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1, &range);
            transition(cbs[i], imgs[i], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
            vkEndCommandBuffer(cbs[i]);
        }
        command_buffers_[sc] = cbs;
    }

    Harness harness_;
    VkPhysicalDevice pd_ = VK_NULL_HANDLE;
    std::unique_ptr<Device> dev_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkFence submit_fence_ = VK_NULL_HANDLE;
    std::vector<VkSwapchainKHR> swapchains_;
    std::map<VkSwapchainKHR, std::vector<VkCommandBuffer>> command_buffers_;
    std::map<VkSwapchainKHR, std::vector<VkSemaphore>> render_semaphores_;
    std::vector<VkSemaphore> semaphores_;
};

#define REQUIRE_OK(h)                                                                                    \
    ASSERT_TRUE((h).ok()) << "no tilevk device with a headless surface";                                 \
    struct ZeroMessages {                                                                                \
        const Headless& hh;                                                                              \
        ~ZeroMessages() { EXPECT_EQ(hh.harness().message_count(), 0) << hh.harness().message_report(); } \
    } zero_messages_ {                                                                                   \
        h                                                                                                \
    }

}  // namespace

TEST(Swapchain, HeadlessSurfaceReportsWhatSwapchainsAccept) {
    Headless h;
    REQUIRE_OK(h);
    VkBool32 supported = VK_FALSE;
    ASSERT_EQ(vkGetPhysicalDeviceSurfaceSupportKHR(h.physical(), 0, h.surface(), &supported), VK_SUCCESS);
    EXPECT_TRUE(supported);
    VkSurfaceCapabilitiesKHR caps;
    ASSERT_EQ(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(h.physical(), h.surface(), &caps), VK_SUCCESS);
    EXPECT_EQ(caps.minImageCount, 2u);
    EXPECT_EQ(caps.maxImageCount, 16u);
    EXPECT_EQ(caps.currentExtent.width, 0xFFFFFFFFu);  // the swapchain decides
    EXPECT_EQ(caps.maxImageExtent.width, 16384u);
    EXPECT_EQ(caps.maxImageArrayLayers, 1u);
    EXPECT_EQ(caps.supportedUsageFlags & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    EXPECT_EQ(caps.supportedUsageFlags & VK_IMAGE_USAGE_STORAGE_BIT, 0u);
    EXPECT_EQ(caps.supportedTransforms, VkSurfaceTransformFlagsKHR(VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR));

    auto caps2_fn = reinterpret_cast<PFN_vkGetPhysicalDeviceSurfaceCapabilities2KHR>(
        vkGetInstanceProcAddr(h.harness().instance(), "vkGetPhysicalDeviceSurfaceCapabilities2KHR"));
    ASSERT_NE(caps2_fn, nullptr);
    VkPhysicalDeviceSurfaceInfo2KHR info{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SURFACE_INFO_2_KHR};
    info.surface = h.surface();
    VkSurfaceCapabilities2KHR caps2{VK_STRUCTURE_TYPE_SURFACE_CAPABILITIES_2_KHR};
    ASSERT_EQ(caps2_fn(h.physical(), &info, &caps2), VK_SUCCESS);
    EXPECT_EQ(memcmp(&caps2.surfaceCapabilities, &caps, sizeof caps), 0);

    uint32_t n = 0;
    ASSERT_EQ(vkGetPhysicalDeviceSurfaceFormatsKHR(h.physical(), h.surface(), &n, nullptr), VK_SUCCESS);
    std::vector<VkSurfaceFormatKHR> formats(n);
    ASSERT_EQ(vkGetPhysicalDeviceSurfaceFormatsKHR(h.physical(), h.surface(), &n, formats.data()), VK_SUCCESS);
    ASSERT_EQ(n, 4u);
    EXPECT_EQ(formats[0].format, VK_FORMAT_B8G8R8A8_SRGB);
    EXPECT_EQ(formats[1].format, VK_FORMAT_B8G8R8A8_UNORM);
    EXPECT_EQ(formats[2].format, VK_FORMAT_R8G8B8A8_SRGB);
    EXPECT_EQ(formats[3].format, VK_FORMAT_R8G8B8A8_UNORM);
    uint32_t two = 2;
    EXPECT_EQ(vkGetPhysicalDeviceSurfaceFormatsKHR(h.physical(), h.surface(), &two, formats.data()), VK_INCOMPLETE);
    EXPECT_EQ(two, 2u);
    auto formats2_fn = reinterpret_cast<PFN_vkGetPhysicalDeviceSurfaceFormats2KHR>(
        vkGetInstanceProcAddr(h.harness().instance(), "vkGetPhysicalDeviceSurfaceFormats2KHR"));
    ASSERT_NE(formats2_fn, nullptr);
    std::vector<VkSurfaceFormat2KHR> formats2(4, {VK_STRUCTURE_TYPE_SURFACE_FORMAT_2_KHR});
    n = 4;
    ASSERT_EQ(formats2_fn(h.physical(), &info, &n, formats2.data()), VK_SUCCESS);
    for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(formats2[i].surfaceFormat.format, formats[i].format);

    ASSERT_EQ(vkGetPhysicalDeviceSurfacePresentModesKHR(h.physical(), h.surface(), &n, nullptr), VK_SUCCESS);
    std::vector<VkPresentModeKHR> modes(n);
    ASSERT_EQ(vkGetPhysicalDeviceSurfacePresentModesKHR(h.physical(), h.surface(), &n, modes.data()), VK_SUCCESS);
    EXPECT_EQ(modes, (std::vector<VkPresentModeKHR>{VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR,
                                                    VK_PRESENT_MODE_FIFO_KHR}));

    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 3);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    EXPECT_EQ(h.images(sc).size(), 3u);
    uint32_t one = 1;
    VkImage first;
    EXPECT_EQ(vkGetSwapchainImagesKHR(h.device(), sc, &one, &first), VK_INCOMPLETE);
}

// VK_KHR_surface_protected_capabilities: tilevk has no protected memory, so no surface supports protected
// swapchains (the struct is written, whatever the application left in it).
TEST(Swapchain, NoSurfaceSupportsProtectedSwapchains) {
    Headless h(true, {VK_KHR_SWAPCHAIN_EXTENSION_NAME}, VK_KHR_SURFACE_PROTECTED_CAPABILITIES_EXTENSION_NAME);
    REQUIRE_OK(h);
    auto caps2_fn = reinterpret_cast<PFN_vkGetPhysicalDeviceSurfaceCapabilities2KHR>(
        vkGetInstanceProcAddr(h.harness().instance(), "vkGetPhysicalDeviceSurfaceCapabilities2KHR"));
    ASSERT_NE(caps2_fn, nullptr);
    VkPhysicalDeviceSurfaceInfo2KHR info{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SURFACE_INFO_2_KHR};
    info.surface = h.surface();
    VkSurfaceProtectedCapabilitiesKHR prot{VK_STRUCTURE_TYPE_SURFACE_PROTECTED_CAPABILITIES_KHR};
    prot.supportsProtected = VK_TRUE;
    VkSurfaceCapabilities2KHR caps2{VK_STRUCTURE_TYPE_SURFACE_CAPABILITIES_2_KHR, &prot};
    ASSERT_EQ(caps2_fn(h.physical(), &info, &caps2), VK_SUCCESS);
    EXPECT_EQ(prot.supportsProtected, VK_FALSE);
    EXPECT_EQ(caps2.surfaceCapabilities.minImageCount, 2u);
}

// VK_KHR_incremental_present: a present naming the changed rectangles is accepted and presents the image (the
// regions are a hint; tilevk presents the whole image), with zero validation messages.
TEST(Swapchain, IncrementalPresentRegionsAreAccepted) {
    Headless h(true, {VK_KHR_SWAPCHAIN_EXTENSION_NAME, VK_KHR_INCREMENTAL_PRESENT_EXTENSION_NAME});
    REQUIRE_OK(h);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_IMMEDIATE_KHR, 3);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    uint32_t a = 0;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &a), VK_SUCCESS);
    const VkRectLayerKHR rect{{8, 4}, {16, 8}, 0};
    const VkPresentRegionKHR region{1, &rect};
    const VkPresentRegionsKHR regions{VK_STRUCTURE_TYPE_PRESENT_REGIONS_KHR, nullptr, 1, &region};
    ASSERT_EQ(h.frame(sc, a, VK_NULL_HANDLE, &regions), VK_SUCCESS);
    ASSERT_EQ(vkQueueWaitIdle(h.queue()), VK_SUCCESS);
    uint32_t next = 0;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &next), VK_SUCCESS);
}

// Clears `image` through a view of `view_format` to (0.5, 0.25, 0.75, 1) in a render pass and returns its bytes.
std::vector<uint8_t> clear_through_view(Device& dev, VkImage image, VkFormat view_format) {
    VkAttachmentDescription a{};
    a.format = view_format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    SingleAttachmentPass pass(dev.device(), image, a, VK_IMAGE_ASPECT_COLOR_BIT, kExtent.width, kExtent.height);
    Device::Buffer out = dev.make_buffer(VkDeviceSize(kExtent.width) * kExtent.height * 4);
    EXPECT_EQ(dev.run([&](VkCommandBuffer c) {
        VkClearValue clear{};
        clear.color = {{0.5f, 0.25f, 0.75f, 1.0f}};
        VkRenderPassBeginInfo rb{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rb.renderPass = pass.pass;
        rb.framebuffer = pass.framebuffer;
        rb.renderArea = {{0, 0}, kExtent};
        rb.clearValueCount = 1;
        rb.pClearValues = &clear;
        vkCmdBeginRenderPass(c, &rb, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdEndRenderPass(c);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {kExtent.width, kExtent.height, 1};
        vkCmdCopyImageToBuffer(c, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.buffer, 1, &region);
    }),
              VK_SUCCESS);
    std::vector<uint8_t> bytes(static_cast<uint8_t*>(out.map), static_cast<uint8_t*>(out.map) + out.size);
    dev.destroy(out);
    pass.destroy(dev.device());
    return bytes;
}

// VK_KHR_swapchain_mutable_format: a swapchain made with MUTABLE_FORMAT and a format list takes views of the listed
// formats — an sRGB view over B8G8R8A8_UNORM images writes the sRGB encoding, the same bytes as an ordinary
// B8G8R8A8_SRGB image cleared the same way; without the format list creation is refused by name.
TEST(Swapchain, MutableFormatImagesTakeViewsOfTheListedFormats) {
    Headless h(true, {VK_KHR_SWAPCHAIN_EXTENSION_NAME, VK_KHR_MAINTENANCE_2_EXTENSION_NAME,
                      VK_KHR_IMAGE_FORMAT_LIST_EXTENSION_NAME, VK_KHR_SWAPCHAIN_MUTABLE_FORMAT_EXTENSION_NAME});
    REQUIRE_OK(h);
    const VkFormat formats[2] = {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB};
    VkImageFormatListCreateInfo list{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO, nullptr, 2, formats};
    VkSwapchainCreateInfoKHR ci = h.create_info(VK_PRESENT_MODE_IMMEDIATE_KHR, 2);
    ci.pNext = &list;
    ci.flags = VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR;
    ci.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    VkSwapchainKHR sc = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateSwapchainKHR(h.device(), &ci, nullptr, &sc), VK_SUCCESS);
    uint32_t index = 0;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &index), VK_SUCCESS);
    const std::vector<VkImage> images = h.images(sc);
    const std::vector<uint8_t> through_srgb = clear_through_view(h.device_object(), images[index], formats[1]);
    Device::Image plain = h.device_object().make_image(
        VK_FORMAT_B8G8R8A8_SRGB, kExtent.width, kExtent.height, 1, 1, VK_SAMPLE_COUNT_1_BIT,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    const std::vector<uint8_t> reference = clear_through_view(h.device_object(), plain.image, formats[1]);
    h.device_object().destroy(plain);
    EXPECT_EQ(through_srgb, reference);
    EXPECT_GE(through_srgb[2], 180);  // red 0.5 encoded as sRGB (0.735 * 255), not UNORM's 128
    vkDestroySwapchainKHR(h.device(), sc, nullptr);
}

TEST(Swapchain, MutableFormatWithoutAFormatListIsRefused) {
    Headless h(false, {VK_KHR_SWAPCHAIN_EXTENSION_NAME, VK_KHR_MAINTENANCE_2_EXTENSION_NAME,
                       VK_KHR_IMAGE_FORMAT_LIST_EXTENSION_NAME, VK_KHR_SWAPCHAIN_MUTABLE_FORMAT_EXTENSION_NAME});
    ASSERT_TRUE(h.ok());
    VkSwapchainCreateInfoKHR ci = h.create_info(VK_PRESENT_MODE_IMMEDIATE_KHR, 2);
    ci.flags = VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR;
    VkSwapchainKHR sc = VK_NULL_HANDLE;
    StderrCapture err;
    EXPECT_EQ(vkCreateSwapchainKHR(h.device(), &ci, nullptr, &sc), VK_ERROR_INITIALIZATION_FAILED);
    EXPECT_NE(err.text().find("VUID-VkSwapchainCreateInfoKHR-flags-03168"), std::string::npos);
    EXPECT_EQ(sc, VK_NULL_HANDLE);
}

// FIFO: images come back in the order they were presented, one per refresh. The first present is shown at once
// (no refresh has passed yet), the next ones 200 ms apart; acquire with timeout 0 / 50 ms reports NOT_READY /
// TIMEOUT meanwhile, UINT64_MAX waits for the refresh.
TEST(Swapchain, FifoReturnsImagesInPresentationOrderOnePerRefresh) {
    Headless h;
    REQUIRE_OK(h);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 3);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    uint32_t a, b, c, d;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &a), VK_SUCCESS);
    const auto shown_a = Clock::now();
    ASSERT_EQ(h.frame(sc, a), VK_SUCCESS);  // shown at once: the first refresh is due
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &b), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, b), VK_SUCCESS);  // waits for the next refresh
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &c), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, c), VK_SUCCESS);
    EXPECT_EQ(a, 0u);
    EXPECT_EQ(b, 1u);
    EXPECT_EQ(c, 2u);
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &d), VK_SUCCESS);  // a came back after it was shown
    EXPECT_EQ(d, a);
    uint32_t none;
    EXPECT_EQ(h.acquire(sc, 0, &none), VK_NOT_READY);
    const auto t = Clock::now();
    EXPECT_EQ(h.acquire(sc, 50'000'000, &none), VK_TIMEOUT);
    EXPECT_GE(seconds_since(t), 0.05);
    ASSERT_LT(seconds_since(shown_a), kRefreshSeconds) << "the machine is too slow for this test's timing";
    uint32_t e;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &e), VK_SUCCESS);  // b, shown at the second refresh
    EXPECT_EQ(e, b);
    EXPECT_GE(seconds_since(shown_a), kRefreshSeconds * 0.95);
    ASSERT_EQ(h.frame(sc, d), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, e), VK_SUCCESS);
    uint32_t f;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &f), VK_SUCCESS);
    EXPECT_EQ(f, c);
}

// MAILBOX: a present replaces the image waiting for the refresh, which becomes available at once.
TEST(Swapchain, MailboxReplacesTheWaitingImage) {
    Headless h;
    REQUIRE_OK(h);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_MAILBOX_KHR, 3);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    uint32_t a, b, c, x, y, none;
    const auto start = Clock::now();
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &a), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, a), VK_SUCCESS);  // shown at once
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &b), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, b), VK_SUCCESS);  // waits for the next refresh ...
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &c), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, c), VK_SUCCESS);  // ... and is replaced by c
    ASSERT_EQ(h.acquire(sc, 0, &x), VK_SUCCESS);
    ASSERT_EQ(h.acquire(sc, 0, &y), VK_SUCCESS);
    EXPECT_EQ(x, a);
    EXPECT_EQ(y, b);
    EXPECT_EQ(h.acquire(sc, 0, &none), VK_NOT_READY);  // c waits for the refresh
    ASSERT_LT(seconds_since(start), kRefreshSeconds) << "the machine is too slow for this test's timing";
    ASSERT_EQ(h.frame(sc, x), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, y), VK_SUCCESS);
}

// IMMEDIATE: every present is shown as it arrives, so images come straight back, well inside one refresh.
TEST(Swapchain, ImmediateShowsEachPresentAtOnce) {
    Headless h;
    REQUIRE_OK(h);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_IMMEDIATE_KHR, 2);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    const auto start = Clock::now();
    for (int i = 0; i < 20; ++i) {
        uint32_t index;
        ASSERT_EQ(h.acquire(sc, 1'000'000'000, &index), VK_SUCCESS) << "frame " << i;
        ASSERT_EQ(h.frame(sc, index), VK_SUCCESS);
    }
    EXPECT_LT(seconds_since(start), 10 * kRefreshSeconds);  // FIFO would need 19 refreshes
}

// FIFO paces an application that renders as fast as it can to the refresh rate, and the waits sleep.
TEST(Swapchain, FifoPacesWithoutSpinning) {
    Headless h;
    REQUIRE_OK(h);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 2);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    const auto start = Clock::now();
    const double cpu0 = cpu_seconds();
    constexpr int kFrames = 8;
    for (int i = 0; i < kFrames; ++i) {
        uint32_t index;
        ASSERT_EQ(h.acquire(sc, UINT64_MAX, &index), VK_SUCCESS);
        ASSERT_EQ(h.frame(sc, index), VK_SUCCESS);
    }
    const double wall = seconds_since(start), cpu = cpu_seconds() - cpu0;
    // Frame 0 is shown at once and frame k at refresh k; acquire k waits for frame k-2's image: the last acquire
    // returns at refresh kFrames-3.
    EXPECT_GE(wall, (kFrames - 3) * kRefreshSeconds * 0.95);
    EXPECT_LT(cpu, 0.25 * wall) << "cpu " << cpu << " s in " << wall << " s";
}

TEST(Swapchain, FencesAndSemaphoresOfAcquire) {
    Headless h;
    REQUIRE_OK(h);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 2);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    VkSemaphore acquired = h.semaphore();
    uint32_t index;
    ASSERT_EQ(vkAcquireNextImageKHR(h.device(), sc, UINT64_MAX, acquired, VK_NULL_HANDLE, &index), VK_SUCCESS);
    ASSERT_EQ(h.frame(sc, index, acquired), VK_SUCCESS);       // the submission waits on the acquire semaphore
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &index), VK_SUCCESS);  // the fence: signalled when acquire returns
    ASSERT_EQ(h.frame(sc, index), VK_SUCCESS);
    ASSERT_EQ(vkQueueWaitIdle(h.queue()), VK_SUCCESS);
}

// A swapchain passed as oldSwapchain is retired: presenting an image acquired from it before reports OUT_OF_DATE
// (acquiring from it is invalid usage: InvalidUsageIsRefusedWithoutHanging); the new swapchain works, and destroying
// the old one leaves the new one alone.
TEST(Swapchain, RetiredSwapchainIsOutOfDate) {
    Headless h;
    REQUIRE_OK(h);
    VkSwapchainKHR old_sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 3);
    ASSERT_NE(old_sc, VK_NULL_HANDLE);
    uint32_t kept, index;
    ASSERT_EQ(h.acquire(old_sc, UINT64_MAX, &index), VK_SUCCESS);
    ASSERT_EQ(h.frame(old_sc, index), VK_SUCCESS);
    ASSERT_EQ(h.acquire(old_sc, UINT64_MAX, &kept), VK_SUCCESS);
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 3, old_sc);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    EXPECT_EQ(h.frame(old_sc, kept), VK_ERROR_OUT_OF_DATE_KHR);
    ASSERT_EQ(vkQueueWaitIdle(h.queue()), VK_SUCCESS);
    h.destroy(old_sc);
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &index), VK_SUCCESS);
    EXPECT_EQ(h.frame(sc, index), VK_SUCCESS);
}

// Destroying a swapchain while images are queued for later refreshes, or acquired, neither hangs nor crashes: the
// queued images are shown and the presentation thread stops.
TEST(Swapchain, DestroyWithImagesInFlight) {
    Headless h;
    REQUIRE_OK(h);
    for (VkPresentModeKHR mode : {VK_PRESENT_MODE_FIFO_KHR, VK_PRESENT_MODE_MAILBOX_KHR}) {
        VkSwapchainKHR sc = h.make(mode, 4);
        ASSERT_NE(sc, VK_NULL_HANDLE);
        uint32_t index;
        for (int i = 0; i < 3; ++i) {
            ASSERT_EQ(h.acquire(sc, UINT64_MAX, &index), VK_SUCCESS);
            ASSERT_EQ(h.frame(sc, index), VK_SUCCESS);
        }
        ASSERT_EQ(h.acquire(sc, UINT64_MAX, &index), VK_SUCCESS);  // one acquired, never presented
        ASSERT_EQ(vkQueueWaitIdle(h.queue()), VK_SUCCESS);
        const auto t = Clock::now();
        h.destroy(sc);
        EXPECT_LT(seconds_since(t), kRefreshSeconds) << "destroy waited for refreshes";
    }
}

// The spec allows vkQueuePresentKHR from any thread, the queue externally synchronized: one thread acquires and
// renders, another presents (a mutex is the external synchronization of the queue). With `overlap`, the acquiring
// thread goes on while the other presents; without it, it waits for each vkQueuePresentKHR to return (the validation
// layer records a present only when the call returns, and an IMMEDIATE image can be acquired again before that).
void present_from_another_thread(Headless& h, bool overlap) {
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_IMMEDIATE_KHR, 3);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    std::mutex queue_mutex, handoff;
    std::condition_variable cv;
    std::vector<uint32_t> to_present;
    bool done = false;
    int presented = 0;
    std::vector<VkResult> results;
    std::thread presenter([&] {
        for (;;) {
            std::unique_lock<std::mutex> l(handoff);
            cv.wait(l, [&] { return done || !to_present.empty(); });
            if (to_present.empty()) return;
            const uint32_t index = to_present.front();
            to_present.erase(to_present.begin());
            l.unlock();
            VkResult r;
            {
                std::lock_guard<std::mutex> q(queue_mutex);
                r = h.frame(sc, index);
            }
            l.lock();
            results.push_back(r);
            ++presented;
            cv.notify_all();
        }
    });
    for (int i = 0; i < 12; ++i) {
        uint32_t index;
        ASSERT_EQ(h.acquire(sc, 2'000'000'000, &index), VK_SUCCESS) << "frame " << i;
        std::unique_lock<std::mutex> l(handoff);
        to_present.push_back(index);
        cv.notify_all();
        if (!overlap) cv.wait(l, [&] { return presented == i + 1; });
    }
    {
        std::lock_guard<std::mutex> l(handoff);
        done = true;
        cv.notify_all();
    }
    presenter.join();
    ASSERT_EQ(results.size(), 12u);
    for (VkResult r : results) EXPECT_EQ(r, VK_SUCCESS);
    EXPECT_EQ(vkQueueWaitIdle(h.queue()), VK_SUCCESS);
}

TEST(Swapchain, PresentFromAnotherThread) {
    Headless h;
    REQUIRE_OK(h);
    present_from_another_thread(h, /*overlap=*/false);
}

TEST(Swapchain, PresentFromAnotherThreadWhileAcquiring) {
    Headless h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    present_from_another_thread(h, /*overlap=*/true);
}

// Invalid usage the validation layer reports (so without it): tilevk refuses instead of hanging or crashing.
TEST(Swapchain, InvalidUsageIsRefusedWithoutHanging) {
    Headless h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkSwapchainCreateInfoKHR ci = h.create_info(VK_PRESENT_MODE_FIFO_RELAXED_KHR, 2);
    VkSwapchainKHR sc = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateSwapchainKHR(h.device(), &ci, nullptr, &sc), VK_ERROR_INITIALIZATION_FAILED);
    ci = h.create_info(VK_PRESENT_MODE_FIFO_KHR, 2);
    ci.imageFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    EXPECT_EQ(vkCreateSwapchainKHR(h.device(), &ci, nullptr, &sc), VK_ERROR_INITIALIZATION_FAILED);
    ci = h.create_info(VK_PRESENT_MODE_FIFO_KHR, 2);
    ci.imageUsage |= VK_IMAGE_USAGE_STORAGE_BIT;
    EXPECT_EQ(vkCreateSwapchainKHR(h.device(), &ci, nullptr, &sc), VK_ERROR_INITIALIZATION_FAILED);
    ci = h.create_info(VK_PRESENT_MODE_FIFO_KHR, 17);
    EXPECT_EQ(vkCreateSwapchainKHR(h.device(), &ci, nullptr, &sc), VK_ERROR_INITIALIZATION_FAILED);

    sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 2);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    uint32_t a, b, c;
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &a), VK_SUCCESS);
    ASSERT_EQ(h.acquire(sc, UINT64_MAX, &b), VK_SUCCESS);
    // Both acquired, nothing presented: waiting forever could never end.
    const auto t = Clock::now();
    EXPECT_EQ(h.acquire(sc, UINT64_MAX, &c), VK_NOT_READY);
    EXPECT_LT(seconds_since(t), 1.0);
    EXPECT_EQ(h.present(sc, 7, VK_NULL_HANDLE), VK_ERROR_OUT_OF_DATE_KHR);  // no such image
    EXPECT_EQ(h.present(sc, a, VK_NULL_HANDLE), VK_SUCCESS);
    EXPECT_EQ(h.present(sc, a, VK_NULL_HANDLE), VK_ERROR_OUT_OF_DATE_KHR);  // presented twice

    VkSwapchainKHR newer = h.make(VK_PRESENT_MODE_FIFO_KHR, 2, sc);  // sc is retired: nothing more to acquire
    ASSERT_NE(newer, VK_NULL_HANDLE);
    EXPECT_EQ(h.acquire(sc, 0, &c), VK_ERROR_OUT_OF_DATE_KHR);
    EXPECT_EQ(h.acquire(sc, UINT64_MAX, &c), VK_ERROR_OUT_OF_DATE_KHR);
}

// VK_KHR_device_group with a swapchain on tilevk's one-device group: device 0 presents locally, the present rectangle
// is the whole surface ("size unknown" on a headless surface), vkAcquireNextImage2KHR acquires, and an image made
// with VkImageSwapchainCreateInfoKHR and bound with VkBindImageMemorySwapchainInfoKHR shares the texels of that
// swapchain image. An image whose parameters differ from the swapchain's is refused by name.
TEST(Swapchain, DeviceGroupImagesBoundToSwapchainMemory) {
    Headless h(true, {VK_KHR_SWAPCHAIN_EXTENSION_NAME, VK_KHR_DEVICE_GROUP_EXTENSION_NAME,
                      VK_KHR_BIND_MEMORY_2_EXTENSION_NAME});
    REQUIRE_OK(h);
    const VkDevice d = h.device();
    auto caps_fn = reinterpret_cast<PFN_vkGetDeviceGroupPresentCapabilitiesKHR>(
        vkGetDeviceProcAddr(d, "vkGetDeviceGroupPresentCapabilitiesKHR"));
    auto modes_fn = reinterpret_cast<PFN_vkGetDeviceGroupSurfacePresentModesKHR>(
        vkGetDeviceProcAddr(d, "vkGetDeviceGroupSurfacePresentModesKHR"));
    auto rects_fn = reinterpret_cast<PFN_vkGetPhysicalDevicePresentRectanglesKHR>(
        vkGetInstanceProcAddr(h.harness().instance(), "vkGetPhysicalDevicePresentRectanglesKHR"));
    auto acquire2 = reinterpret_cast<PFN_vkAcquireNextImage2KHR>(vkGetDeviceProcAddr(d, "vkAcquireNextImage2KHR"));
    auto bind2 = reinterpret_cast<PFN_vkBindImageMemory2KHR>(vkGetDeviceProcAddr(d, "vkBindImageMemory2KHR"));
    ASSERT_TRUE(caps_fn && modes_fn && rects_fn && acquire2 && bind2);
    VkDeviceGroupPresentCapabilitiesKHR caps{VK_STRUCTURE_TYPE_DEVICE_GROUP_PRESENT_CAPABILITIES_KHR};
    ASSERT_EQ(caps_fn(d, &caps), VK_SUCCESS);
    EXPECT_EQ(caps.presentMask[0], 1u);
    EXPECT_EQ(caps.presentMask[1], 0u);
    EXPECT_EQ(caps.modes, VkDeviceGroupPresentModeFlagsKHR(VK_DEVICE_GROUP_PRESENT_MODE_LOCAL_BIT_KHR));
    VkDeviceGroupPresentModeFlagsKHR modes = 0;
    ASSERT_EQ(modes_fn(d, h.surface(), &modes), VK_SUCCESS);
    EXPECT_EQ(modes, VkDeviceGroupPresentModeFlagsKHR(VK_DEVICE_GROUP_PRESENT_MODE_LOCAL_BIT_KHR));
    uint32_t n = 0;
    ASSERT_EQ(rects_fn(h.physical(), h.surface(), &n, nullptr), VK_SUCCESS);
    ASSERT_EQ(n, 1u);
    VkRect2D rect{};
    ASSERT_EQ(rects_fn(h.physical(), h.surface(), &n, &rect), VK_SUCCESS);
    EXPECT_EQ(rect.offset.x, 0);
    EXPECT_EQ(rect.extent.width, UINT32_MAX);
    EXPECT_EQ(rect.extent.height, UINT32_MAX);

    VkSwapchainCreateInfoKHR sci = h.create_info(VK_PRESENT_MODE_FIFO_KHR, 3);
    sci.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // read back below
    VkSwapchainKHR sc = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateSwapchainKHR(d, &sci, nullptr, &sc), VK_SUCCESS);
    const std::vector<VkImage> images = h.images(sc);
    VkImageSwapchainCreateInfoKHR link{VK_STRUCTURE_TYPE_IMAGE_SWAPCHAIN_CREATE_INFO_KHR};
    link.swapchain = sc;
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.pNext = &link;
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = kFormat;
    ici.extent = {kExtent.width, kExtent.height, 1};
    ici.mipLevels = ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = sci.imageUsage;
    VkImage alias = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateImage(d, &ici, nullptr, &alias), VK_SUCCESS);
    VkBindImageMemorySwapchainInfoKHR bind_sc{VK_STRUCTURE_TYPE_BIND_IMAGE_MEMORY_SWAPCHAIN_INFO_KHR};
    bind_sc.swapchain = sc;
    bind_sc.imageIndex = 1;
    VkBindImageMemoryInfo bind{VK_STRUCTURE_TYPE_BIND_IMAGE_MEMORY_INFO};
    bind.pNext = &bind_sc;
    bind.image = alias;
    ASSERT_EQ(bind2(d, 1, &bind), VK_SUCCESS);

    // Clear the alias, read swapchain image 1 (their shared texels) into a host-visible buffer.
    Device::Buffer out = h.device_object().make_buffer(VkDeviceSize(kExtent.width) * kExtent.height * 4,
                                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = h.device_object().pool();
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(d, &ai, &cb), VK_SUCCESS);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cb, &bi);
    transition(cb, alias, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    const VkClearColorValue colour = {{1.0f, 0.0f, 51.0f / 255.0f, 1.0f}};
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cb, alias, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1, &all);
    transition(cb, images[1], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {kExtent.width, kExtent.height, 1};
    vkCmdCopyImageToBuffer(cb, images[1], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.buffer, 1, &region);
    vkEndCommandBuffer(cb);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    ASSERT_EQ(vkQueueSubmit(h.queue(), 1, &si, VK_NULL_HANDLE), VK_SUCCESS);
    ASSERT_EQ(vkQueueWaitIdle(h.queue()), VK_SUCCESS);
    const auto* texels = static_cast<const uint8_t*>(out.map);
    size_t wrong = 0;
    for (uint32_t i = 0; i < kExtent.width * kExtent.height; ++i) {
        const uint8_t want[4] = {51, 0, 255, 255};  // B, G, R, A
        wrong += memcmp(texels + 4 * i, want, 4) != 0;
    }
    EXPECT_EQ(wrong, 0u) << "texels of swapchain image 1 that are not the colour its alias was cleared to";
    vkFreeCommandBuffers(d, h.device_object().pool(), 1, &cb);
    h.device_object().destroy(out);

    VkAcquireNextImageInfoKHR acquire{VK_STRUCTURE_TYPE_ACQUIRE_NEXT_IMAGE_INFO_KHR};
    acquire.swapchain = sc;
    acquire.timeout = UINT64_MAX;
    acquire.fence = h.fence();
    acquire.deviceMask = 1;
    vkResetFences(d, 1, &acquire.fence);
    uint32_t index = UINT32_MAX;
    EXPECT_EQ(acquire2(d, &acquire, &index), VK_SUCCESS);
    EXPECT_LT(index, uint32_t(images.size()));
    EXPECT_EQ(vkWaitForFences(d, 1, &acquire.fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
    vkDestroyImage(d, alias, nullptr);
    vkDestroySwapchainKHR(d, sc, nullptr);
}

TEST(Swapchain, DeviceGroupImageOfOtherParametersIsRefused) {
    Headless h(false, {VK_KHR_SWAPCHAIN_EXTENSION_NAME, VK_KHR_DEVICE_GROUP_EXTENSION_NAME});
    ASSERT_TRUE(h.ok());
    VkSwapchainKHR sc = h.make(VK_PRESENT_MODE_FIFO_KHR, 2);
    ASSERT_NE(sc, VK_NULL_HANDLE);
    VkImageSwapchainCreateInfoKHR link{VK_STRUCTURE_TYPE_IMAGE_SWAPCHAIN_CREATE_INFO_KHR};
    link.swapchain = sc;
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.pNext = &link;
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = kFormat;
    ici.extent = {kExtent.width + 1, kExtent.height, 1};  // not the swapchain's extent
    ici.mipLevels = ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = h.create_info(VK_PRESENT_MODE_FIFO_KHR, 2).imageUsage;
    VkImage alias = VK_NULL_HANDLE;
    StderrCapture capture;
    EXPECT_NE(vkCreateImage(h.device(), &ici, nullptr, &alias), VK_SUCCESS);
    const std::string err = capture.text();
    EXPECT_EQ(alias, VK_NULL_HANDLE);
    EXPECT_NE(err.find("VkImageSwapchainCreateInfoKHR"), std::string::npos) << err;
}
