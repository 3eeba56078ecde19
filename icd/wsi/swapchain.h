// VkSwapchainKHR (VK_KHR_swapchain). Swapchain images are ordinary tilevk images in device memory: the renderer draws
// into them in place like into any other image. Presenting hands an image to the swapchain's presentation thread,
// which at each refresh (FIFO: one image per refresh; MAILBOX: the newest at each refresh; IMMEDIATE: as soon as it
// arrives) copies it once into the window system's shared buffer (wsi/platform.h) and gives it back to acquire.
//
// vkQueueSubmit runs synchronously, so when vkQueuePresentKHR is called every submission made before it on the queue
// has finished: its wait semaphores are already satisfied and the image holds its final pixels. When
// vkAcquireNextImageKHR returns an image, the presentation thread has finished reading it, so the semaphore and the
// fence it is given are signalled at once.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "object.h"
#include "wsi/platform.h"

namespace tilevk::icd {

struct Device;
struct Image;
struct Fence;
struct Semaphore;

namespace wsi {

// One image being drawn while another waits for the next refresh; MAILBOX and deeper queues take more.
constexpr uint32_t kMinSwapchainImages = 2;
constexpr uint32_t kMaxSwapchainImages = 16;
// Everything a swapchain image can be used for: tilevk's colour formats are transfer sources and destinations,
// colour attachments, sampled images and input attachments (not storage images: the swapchain's B8G8R8A8 formats
// have no STORAGE_IMAGE feature, format/support.txt).
constexpr VkImageUsageFlags kSwapchainImageUsage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                                   VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
// The order lavapipe lists them in (FIFO_RELAXED is not offered).
constexpr VkPresentModeKHR kPresentModes[] = {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR,
                                              VK_PRESENT_MODE_FIFO_KHR};

// vkGetPhysicalDeviceSurfaceCapabilitiesKHR (surface.cpp).
VkResult surface_capabilities(VkSurfaceKHR surface, VkSurfaceCapabilitiesKHR* caps);

// The refresh interval FIFO and MAILBOX pace to: TILEVK_PRESENT_HZ (default 60 Hz; X11 offers tilevk no vertical
// blank to follow without a GPU driver, and a headless surface has none).
std::chrono::nanoseconds refresh_interval();

}  // namespace wsi

// VK_KHR_device_group with VK_KHR_swapchain: an image made with VkImageSwapchainCreateInfoKHR must have the
// swapchain's image parameters (checked at vkCreateImage), and VkBindImageMemorySwapchainInfoKHR binds it to the
// memory of one swapchain image, so both handles name the same texels.
VkResult check_swapchain_image(const VkImageCreateInfo& ci, const VkImageSwapchainCreateInfoKHR& link);
VkResult bind_swapchain_memory(Image* image, const VkBindImageMemorySwapchainInfoKHR& link);

struct Swapchain : NonDispatchableObject {
    using Handle = VkSwapchainKHR;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_SWAPCHAIN_KHR;

    Swapchain() : NonDispatchableObject(kType) {}
    ~Swapchain();  // shows the images still queued, stops the presentation thread, frees the images

    // Set up by vkCreateSwapchainKHR before start().
    Device* device = nullptr;
    VkExtent2D extent{};
    VkPresentModeKHR present_mode = VK_PRESENT_MODE_FIFO_KHR;
    uint32_t image_count = 0;
    // VK_KHR_swapchain_mutable_format: a MUTABLE_FORMAT swapchain's images are MUTABLE_FORMAT | EXTENDED_USAGE
    // images, as the extension says; an image bound to one (VkImageSwapchainCreateInfoKHR) must say the same.
    VkImageCreateFlags image_flags = 0;
    Image* images[wsi::kMaxSwapchainImages] = {};
    std::unique_ptr<wsi::PresentTarget> target;

    void start();  // every image available; starts the presentation thread
    // vkAcquireNextImageKHR's semantics (timeout 0 / finite / UINT64_MAX; VK_NOT_READY, VK_TIMEOUT, VK_SUBOPTIMAL_KHR,
    // VK_ERROR_OUT_OF_DATE_KHR once retired, VK_ERROR_SURFACE_LOST_KHR).
    VkResult acquire(uint64_t timeout, Semaphore* semaphore, Fence* fence, uint32_t* index);
    // Queues an acquired image for presentation (one swapchain's part of vkQueuePresentKHR).
    VkResult queue_present(uint32_t index);
    // Used as oldSwapchain: what is queued is shown now, then acquire and present report VK_ERROR_OUT_OF_DATE_KHR.
    void retire();

  private:
    enum class Slot : uint8_t { kAvailable, kAcquired, kQueued, kShowing };
    void run_presenter();
    void make_available(uint32_t index);  // with mutex_ held

    std::mutex mutex_;
    std::condition_variable acquire_cv_;    // an image became available, or the state changed
    std::condition_variable presenter_cv_;  // an image was queued, or the swapchain retires or stops
    Slot slots_[wsi::kMaxSwapchainImages] = {};
    std::deque<uint32_t> available_;  // in the order they became available: acquire takes the front
    std::deque<uint32_t> queued_;     // presented, not yet shown: FIFO order (MAILBOX: at most one)
    uint32_t acquired_count_ = 0;
    bool showing_ = false;     // the presentation thread is copying an image out
    bool suboptimal_ = false;  // the window no longer has the swapchain's size (seen at the last acquire)
    bool retired_ = false;
    bool stopping_ = false;
    VkResult status_ = VK_SUCCESS;  // VK_ERROR_SURFACE_LOST_KHR once the window is gone (sticky)
    std::thread presenter_;
};

}  // namespace tilevk::icd
