#include "wsi/swapchain.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "device.h"
#include "entrypoints.h"
#include "formats.h"
#include "image.h"
#include "memory.h"
#include "physical_device.h"
#include "sync.h"
#include "vk_names.h"

namespace tilevk::icd {

namespace wsi {

std::chrono::nanoseconds refresh_interval() {
    static const std::chrono::nanoseconds interval = [] {
        double hz = 60.0;
        if (const char* v = getenv("TILEVK_PRESENT_HZ")) {
            const double asked = atof(v);
            if (asked >= 1.0 && asked <= 100000.0) {
                hz = asked;
            } else {
                log_error("TILEVK_PRESENT_HZ=%s is not a refresh rate in 1..100000; presenting at 60 Hz", v);
            }
        }
        return std::chrono::nanoseconds(int64_t(1e9 / hz));
    }();
    return interval;
}

}  // namespace wsi

namespace {

using Clock = std::chrono::steady_clock;

// A Vulkan timeout as a deadline that cannot overflow the clock (UINT64_MAX means "forever").
Clock::time_point deadline_after(uint64_t timeout_ns) {
    return Clock::now() + std::chrono::nanoseconds(std::min<uint64_t>(timeout_ns, uint64_t(1) << 62));
}

void free_image(Image* image) {
    if (image == nullptr) return;
    if (image->memory != nullptr) {
        free(image->memory->data);
        destroy_object(image->memory);
    }
    destroy_object(image);
}

// One swapchain image in its own device memory, laid out as every tilevk image is (image.h).
VkResult make_image(const VkAllocationCallbacks& a, const VkSwapchainCreateInfoKHR& ci, Image** out) {
    Image* img = create_object<Image>(a, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (img == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSwapchainKHR: out of host memory");
    img->format = find_format(ci.imageFormat);
    img->extent = {ci.imageExtent.width, ci.imageExtent.height, 1};
    img->usage = ci.imageUsage;
    img->mutable_format = (ci.flags & VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR) != 0;
    img->layout = compute_image_layout(*img->format, img->extent, 1, 1, 1);
    img->memory = create_object<DeviceMemory>(a, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    void* data = nullptr;
    if (img->memory == nullptr || posix_memalign(&data, kMemoryAlignment, size_t(img->layout.size)) != 0) {
        free_image(img);
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkCreateSwapchainKHR: cannot allocate a %ux%u image",
                    ci.imageExtent.width, ci.imageExtent.height);
    }
    memset(data, 0, size_t(img->layout.size));
    img->memory->data = static_cast<uint8_t*>(data);
    img->memory->size = img->layout.size;
    *out = img;
    return VK_SUCCESS;
}

// A mutable-format swapchain names the formats its images may be viewed as, imageFormat among them.
bool lists_image_format(const VkSwapchainCreateInfoKHR& ci) {
    const auto* list =
        find_in_chain<VkImageFormatListCreateInfo>(ci.pNext, VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO);
    return list != nullptr && std::find(list->pViewFormats, list->pViewFormats + list->viewFormatCount,
                                        ci.imageFormat) != list->pViewFormats + list->viewFormatCount;
}

// What vkCreateSwapchainKHR accepts beyond the valid-usage rules the validation layer checks: the surface's current
// formats, usages, alpha modes and tilevk's present modes. VK_ERROR_INITIALIZATION_FAILED with a message otherwise.
VkResult check_create_info(const VkSwapchainCreateInfoKHR& ci) {
    VkSurfaceCapabilitiesKHR caps;
    if (VkResult r = wsi::surface_capabilities(ci.surface, &caps); r != VK_SUCCESS) {
        return fail(r, "vkCreateSwapchainKHR: the surface is gone (%s)", vk_enum_name(r));
    }
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(ci.surface, &info); r != VK_SUCCESS) return r;
    const char* what = nullptr;
    if ((ci.flags & ~VkSwapchainCreateFlagsKHR(VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR)) != 0) {
        what = "flags other than VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR";
    } else if (ci.flags != 0 && !lists_image_format(ci)) {
        what =
            "VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR without a VkImageFormatListCreateInfo that lists imageFormat "
            "(VUID-VkSwapchainCreateInfoKHR-flags-03168)";
    } else if (std::find(info.formats.begin(), info.formats.end(), ci.imageFormat) == info.formats.end() ||
               ci.imageColorSpace != VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
        what = "a format or colour space the surface does not offer";
    } else if (ci.minImageCount > wsi::kMaxSwapchainImages) {
        what = "more images than maxImageCount";
    } else if (ci.imageExtent.width == 0 || ci.imageExtent.height == 0 || ci.imageExtent.width > kMaxImageDimension ||
               ci.imageExtent.height > kMaxImageDimension) {
        what = "an extent outside 1..16384";
    } else if (ci.imageArrayLayers != 1) {
        what = "imageArrayLayers other than 1";
    } else if ((ci.imageUsage & ~wsi::kSwapchainImageUsage) != 0 || ci.imageUsage == 0) {
        what = "an image usage outside supportedUsageFlags";
    } else if (ci.preTransform != VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR) {
        what = "a transform other than IDENTITY";
    } else if ((ci.compositeAlpha & caps.supportedCompositeAlpha) == 0) {
        what = "a composite alpha mode the surface does not support";
    } else if (std::find(std::begin(wsi::kPresentModes), std::end(wsi::kPresentModes), ci.presentMode) ==
               std::end(wsi::kPresentModes)) {
        what = "a present mode tilevk does not offer";
    }
    if (what != nullptr) {
        return fail(VK_ERROR_INITIALIZATION_FAILED, "vkCreateSwapchainKHR: %s (format %s, usage %s, present mode %s)",
                    what, vk_enum_name(ci.imageFormat), vk_flags_name<VkImageUsageFlagBits>(ci.imageUsage).c_str(),
                    vk_enum_name(ci.presentMode));
    }
    return VK_SUCCESS;
}

}  // namespace

// ---- the swapchain's state machine ------------------------------------------------------------------------------

void Swapchain::start() {
    for (uint32_t i = 0; i < image_count; ++i) available_.push_back(i);
    presenter_ = std::thread([this] { run_presenter(); });
}

Swapchain::~Swapchain() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    presenter_cv_.notify_all();
    if (presenter_.joinable()) presenter_.join();
    target.reset();  // detaches the window system's buffers
    for (uint32_t i = 0; i < image_count; ++i) free_image(images[i]);
}

void Swapchain::make_available(uint32_t index) {
    slots_[index] = Slot::kAvailable;
    available_.push_back(index);
}

// One frame per refresh for FIFO and MAILBOX, paced by a clock (the thread sleeps on a condition variable until the
// refresh or a new image; it never polls); IMMEDIATE shows each image as it arrives. A retiring or stopping swapchain
// shows what is still queued at once, in order: every FIFO present is shown, also the last ones before destruction.
void Swapchain::run_presenter() {
    const auto interval = wsi::refresh_interval();
    Clock::time_point next_refresh = Clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        presenter_cv_.wait(lock, [&] { return !queued_.empty() || stopping_; });
        if (queued_.empty()) break;  // stopping, nothing left to show
        if (present_mode != VK_PRESENT_MODE_IMMEDIATE_KHR) {
            presenter_cv_.wait_until(lock, next_refresh, [&] { return stopping_ || retired_; });
        }
        // The refresh this image is shown at: the next one is an interval later. After an idle display (nothing
        // queued for longer than an interval) the image is shown at once, as if a refresh were due.
        const Clock::time_point shown_at = std::max(next_refresh, Clock::now());
        const uint32_t index = queued_.front();
        queued_.pop_front();
        slots_[index] = Slot::kShowing;
        showing_ = true;
        const Image* img = images[index];
        lock.unlock();
        const VkResult r = target->present(img->texel(0, 0, 0, 0), size_t(img->layout.row_pitch[0]));
        lock.lock();
        showing_ = false;
        make_available(index);
        if (r < 0) status_ = r;
        acquire_cv_.notify_all();
        next_refresh = shown_at + interval;
    }
}

VkResult Swapchain::acquire(uint64_t timeout, Semaphore* semaphore, Fence* fence, uint32_t* index) {
    const VkResult fit = target->check();  // may ask the window system (a round trip on X11): outside the lock
    std::unique_lock<std::mutex> lock(mutex_);
    if (fit < 0 && status_ == VK_SUCCESS) status_ = fit;
    auto ready = [&] { return !available_.empty() || status_ < 0 || retired_; };
    if (!ready()) {
        if (timeout == 0) return VK_NOT_READY;
        const bool in_flight = !queued_.empty() || showing_;
        if (timeout == UINT64_MAX && !in_flight && acquired_count_ > image_count - wsi::kMinSwapchainImages) {
            // Only a present from another thread could free an image, and with this many images acquired the spec
            // forbids waiting forever for it: refuse instead of hanging.
            return fail(VK_NOT_READY,
                        "vkAcquireNextImageKHR: %u of %u images are acquired and none is being presented; an "
                        "infinite timeout would never return",
                        acquired_count_, image_count);
        }
        if (timeout == UINT64_MAX) {
            acquire_cv_.wait(lock, ready);
        } else if (!acquire_cv_.wait_until(lock, deadline_after(timeout), ready)) {
            return VK_TIMEOUT;
        }
    }
    if (status_ < 0) return status_;
    if (retired_) return VK_ERROR_OUT_OF_DATE_KHR;
    *index = available_.front();
    available_.pop_front();
    slots_[*index] = Slot::kAcquired;
    ++acquired_count_;
    suboptimal_ = fit == VK_SUBOPTIMAL_KHR;
    lock.unlock();
    if (semaphore != nullptr) semaphore->signaled = true;
    if (fence != nullptr) fence->signal();
    return fit == VK_SUBOPTIMAL_KHR ? VK_SUBOPTIMAL_KHR : VK_SUCCESS;
}

VkResult Swapchain::queue_present(uint32_t index) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (index >= image_count || slots_[index] != Slot::kAcquired) {
        return fail(VK_ERROR_OUT_OF_DATE_KHR, "vkQueuePresentKHR: image %u of the swapchain is not acquired", index);
    }
    --acquired_count_;
    if (status_ < 0 || retired_) {
        make_available(index);  // not shown: the window is gone, or a newer swapchain owns it
        acquire_cv_.notify_all();
        return status_ < 0 ? status_ : VK_ERROR_OUT_OF_DATE_KHR;
    }
    if (present_mode == VK_PRESENT_MODE_MAILBOX_KHR && !queued_.empty()) {
        make_available(queued_.front());  // replaced before it was shown
        queued_.pop_front();
        acquire_cv_.notify_all();
    }
    slots_[index] = Slot::kQueued;
    queued_.push_back(index);
    const VkResult fit = suboptimal_ ? VK_SUBOPTIMAL_KHR : VK_SUCCESS;
    lock.unlock();
    presenter_cv_.notify_all();
    return fit;
}

void Swapchain::retire() {
    std::unique_lock<std::mutex> lock(mutex_);
    retired_ = true;
    presenter_cv_.notify_all();
    acquire_cv_.notify_all();
    // The newer swapchain's frames must come after this one's: wait until what was queued has been shown.
    acquire_cv_.wait(lock, [&] { return queued_.empty() && !showing_; });
}

// ---- commands ---------------------------------------------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateSwapchainKHR(VkDevice device, const VkSwapchainCreateInfoKHR* ci,
                                                      const VkAllocationCallbacks* pAllocator,
                                                      VkSwapchainKHR* pSwapchain) {
    Device* dev = from_handle<Device>(device);
    // Retired even if creating the new one fails (vkCreateSwapchainKHR, "oldSwapchain").
    if (ci->oldSwapchain != VK_NULL_HANDLE) from_handle<Swapchain>(ci->oldSwapchain)->retire();
    if (VkResult r = check_create_info(*ci); r != VK_SUCCESS) return r;
    const VkAllocationCallbacks& a = pick_allocator(pAllocator, &dev->allocator);
    Swapchain* sc = create_object<Swapchain>(a, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (sc == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSwapchainKHR: out of host memory");
    sc->device = dev;
    sc->extent = ci->imageExtent;
    sc->present_mode = ci->presentMode;
    if ((ci->flags & VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR) != 0)
        sc->image_flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
    const wsi::TargetDesc desc{ci->imageExtent, ci->imageFormat, ci->compositeAlpha};
    VkResult r = wsi::create_target(ci->surface, desc, &sc->target);
    for (uint32_t i = 0; r == VK_SUCCESS && i < std::max(ci->minImageCount, wsi::kMinSwapchainImages); ++i) {
        r = make_image(a, *ci, &sc->images[i]);
        if (r == VK_SUCCESS) ++sc->image_count;
    }
    if (r != VK_SUCCESS) {
        destroy_object(sc);
        return r;
    }
    sc->start();
    *pSwapchain = to_handle(sc);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroySwapchainKHR(VkDevice, VkSwapchainKHR swapchain, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Swapchain>(swapchain));
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetSwapchainImagesKHR(VkDevice, VkSwapchainKHR swapchain, uint32_t* pCount,
                                                         VkImage* pImages) {
    Swapchain* sc = from_handle<Swapchain>(swapchain);
    if (pImages == nullptr) {
        *pCount = sc->image_count;
        return VK_SUCCESS;
    }
    const uint32_t n = std::min(*pCount, sc->image_count);
    for (uint32_t i = 0; i < n; ++i) pImages[i] = to_handle(sc->images[i]);
    *pCount = n;
    return n < sc->image_count ? VK_INCOMPLETE : VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_AcquireNextImageKHR(VkDevice device, VkSwapchainKHR swapchain, uint64_t timeout,
                                                       VkSemaphore semaphore, VkFence fence, uint32_t* pImageIndex) {
    if (from_handle<Device>(device)->lost) return VK_ERROR_DEVICE_LOST;
    return from_handle<Swapchain>(swapchain)->acquire(timeout, from_handle<Semaphore>(semaphore),
                                                      from_handle<Fence>(fence), pImageIndex);
}

// Presents once every submission made earlier on this queue has finished (batches the worker holds for a timeline
// value included: queue_scheduler.h), so the wait semaphores are satisfied and the images are final; the queue lock
// orders this call after one in flight. A VkPresentRegionsKHR (VK_KHR_incremental_present) is a hint that only those
// rectangles changed; presenting the whole image, as tilevk does, is what the extension allows when it is ignored.
VKAPI_ATTR VkResult VKAPI_CALL tvk_QueuePresentKHR(VkQueue queue, const VkPresentInfoKHR* pPresentInfo) {
    Queue* q = from_handle<Queue>(queue);
    q->scheduler->wait_idle();
    std::lock_guard<std::mutex> lock(q->submit_mutex);
    for (uint32_t i = 0; i < pPresentInfo->waitSemaphoreCount; ++i) {
        from_handle<Semaphore>(pPresentInfo->pWaitSemaphores[i])->signaled = false;
    }
    VkResult overall = VK_SUCCESS;
    for (uint32_t i = 0; i < pPresentInfo->swapchainCount; ++i) {
        Swapchain* sc = from_handle<Swapchain>(pPresentInfo->pSwapchains[i]);
        const VkResult r = q->device->lost ? VK_ERROR_DEVICE_LOST : sc->queue_present(pPresentInfo->pImageIndices[i]);
        if (pPresentInfo->pResults != nullptr) pPresentInfo->pResults[i] = r;
        if (r < 0 && overall >= 0) {
            overall = r;
        } else if (r == VK_SUBOPTIMAL_KHR && overall == VK_SUCCESS) {
            overall = r;
        }
    }
    return overall;
}

// ---- VK_KHR_device_group with VK_KHR_swapchain ------------------------------------------------------------------

VkResult check_swapchain_image(const VkImageCreateInfo& ci, const VkImageSwapchainCreateInfoKHR& link) {
    const Swapchain* sc = from_handle<Swapchain>(link.swapchain);
    const Image& image = *sc->images[0];
    if (ci.format == vk_format(*image.format) && ci.imageType == VK_IMAGE_TYPE_2D &&
        ci.extent.width == image.extent.width && ci.extent.height == image.extent.height && ci.extent.depth == 1 &&
        ci.mipLevels == 1 && ci.arrayLayers == 1 && ci.samples == VK_SAMPLE_COUNT_1_BIT &&
        ci.tiling == VK_IMAGE_TILING_OPTIMAL && ci.usage == image.usage && ci.flags == sc->image_flags)
        return VK_SUCCESS;
    return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                "vkCreateImage: VkImageSwapchainCreateInfoKHR names a swapchain of %ux%u %s images with usage %s, "
                "but the image is %ux%ux%u %s, %u levels, %u layers, %s, %s, usage %s, flags %s "
                "(VUID-VkImageSwapchainCreateInfoKHR-swapchain-00995)",
                image.extent.width, image.extent.height, vk_enum_name(vk_format(*image.format)),
                vk_flags_name<VkImageUsageFlagBits>(image.usage).c_str(), ci.extent.width, ci.extent.height,
                ci.extent.depth, vk_enum_name(ci.format), ci.mipLevels, ci.arrayLayers,
                vk_flags_name<VkSampleCountFlagBits>(ci.samples).c_str(), vk_enum_name(ci.tiling),
                vk_flags_name<VkImageUsageFlagBits>(ci.usage).c_str(),
                vk_flags_name<VkImageCreateFlagBits>(ci.flags).c_str());
}

VkResult bind_swapchain_memory(Image* image, const VkBindImageMemorySwapchainInfoKHR& link) {
    const Swapchain* sc = from_handle<Swapchain>(link.swapchain);
    if (link.imageIndex >= sc->image_count) {
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                    "vkBindImageMemory2: VkBindImageMemorySwapchainInfoKHR::imageIndex %u, but the swapchain has %u "
                    "images",
                    link.imageIndex, sc->image_count);
    }
    const Image& target = *sc->images[link.imageIndex];
    if (image->format != target.format || image->layout.size != target.layout.size ||
        image->extent.width != target.extent.width || image->extent.height != target.extent.height) {
        return fail(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                    "vkBindImageMemory2: a %ux%u %s image cannot use the memory of swapchain image %u (%ux%u %s); "
                    "create it with VkImageSwapchainCreateInfoKHR",
                    image->extent.width, image->extent.height, vk_enum_name(vk_format(*image->format)), link.imageIndex,
                    target.extent.width, target.extent.height, vk_enum_name(vk_format(*target.format)));
    }
    image->memory = target.memory;
    image->memory_offset = target.memory_offset;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetDeviceGroupPresentCapabilitiesKHR(VkDevice,
                                                                        VkDeviceGroupPresentCapabilitiesKHR* pCaps) {
    std::fill(std::begin(pCaps->presentMask), std::end(pCaps->presentMask), 0u);
    pCaps->presentMask[0] = 1;  // device 0 presents its own images
    pCaps->modes = VK_DEVICE_GROUP_PRESENT_MODE_LOCAL_BIT_KHR;
    return VK_SUCCESS;
}

// deviceMask can only be 1 (VUID-VkAcquireNextImageInfoKHR-deviceMask-01290): device 0 acquires.
VKAPI_ATTR VkResult VKAPI_CALL tvk_AcquireNextImage2KHR(VkDevice device, const VkAcquireNextImageInfoKHR* pInfo,
                                                        uint32_t* pImageIndex) {
    return tvk_AcquireNextImageKHR(device, pInfo->swapchain, pInfo->timeout, pInfo->semaphore, pInfo->fence,
                                   pImageIndex);
}

}  // namespace tilevk::icd
