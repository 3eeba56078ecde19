// Swapchains on X11 windows (xcb and Xlib surfaces) through the loader, run under xvfb-run by meson: what the window
// shows is read back with xcb_get_image and compared with the bytes rendered (tilevk through MIT-SHM and through
// PutImage, lavapipe too); a resized window makes acquire and present report VK_SUBOPTIMAL_KHR and the capabilities
// follow it; an unmapped (minimised) window takes presents without blocking; a destroyed window is
// VK_ERROR_SURFACE_LOST_KHR. Validation layer on, zero messages. gtest before Xlib: Xlib's macros (None, Bool, Status)
// would break gtest's templates.
#include <gtest/gtest.h>
// clang-format off
#define VK_USE_PLATFORM_XCB_KHR
#define VK_USE_PLATFORM_XLIB_KHR
#include <X11/Xlib-xcb.h>
#include <xcb/xcb.h>
// clang-format on

#include <chrono>
#include <cstdlib>
#include <cstring>

#include "vk_harness.h"

using namespace tilevk::test;
using Clock = std::chrono::steady_clock;

namespace {

struct XWindow {
    xcb_connection_t* c = nullptr;
    xcb_window_t window = 0;
    xcb_visualid_t visual = 0;
    Display* dpy = nullptr;  // set when the window was made through Xlib

    void sync() const { free(xcb_get_input_focus_reply(c, xcb_get_input_focus(c), nullptr)); }
    void resize(uint32_t w, uint32_t h) const {
        const uint32_t v[2] = {w, h};
        xcb_configure_window(c, window, XCB_CONFIG_WINDOW_WIDTH | XCB_CONFIG_WINDOW_HEIGHT, v);
        sync();
    }
    // The window's pixels as the X server has them (ZPixmap, 32 bits per pixel).
    std::vector<uint8_t> pixels(uint32_t w, uint32_t h) const {
        xcb_get_image_reply_t* r = xcb_get_image_reply(
            c, xcb_get_image(c, XCB_IMAGE_FORMAT_Z_PIXMAP, window, 0, 0, uint16_t(w), uint16_t(h), ~0u), nullptr);
        std::vector<uint8_t> out;
        if (r != nullptr) {
            const uint8_t* d = xcb_get_image_data(r);
            out.assign(d, d + xcb_get_image_data_length(r));
            free(r);
        }
        return out;
    }
};

XWindow xcb_window(uint16_t w, uint16_t h) {
    XWindow x;
    x.c = xcb_connect(nullptr, nullptr);
    if (xcb_connection_has_error(x.c)) return x;
    xcb_screen_t* s = xcb_setup_roots_iterator(xcb_get_setup(x.c)).data;
    x.window = xcb_generate_id(x.c);
    x.visual = s->root_visual;
    const uint32_t values[1] = {s->black_pixel};
    xcb_create_window(x.c, XCB_COPY_FROM_PARENT, x.window, s->root, 0, 0, w, h, 0, XCB_WINDOW_CLASS_INPUT_OUTPUT,
                      s->root_visual, XCB_CW_BACK_PIXEL, values);
    xcb_map_window(x.c, x.window);
    x.sync();
    return x;
}

XWindow xlib_window(uint16_t w, uint16_t h) {
    XWindow x;
    x.dpy = XOpenDisplay(nullptr);
    if (x.dpy == nullptr) return x;
    x.window = XCreateSimpleWindow(x.dpy, DefaultRootWindow(x.dpy), 0, 0, w, h, 0, 0, 0);
    XMapWindow(x.dpy, x.window);
    XSync(x.dpy, False);
    x.c = XGetXCBConnection(x.dpy);
    x.visual = XVisualIDFromVisual(DefaultVisual(x.dpy, DefaultScreen(x.dpy)));
    return x;
}

// The expected pixel of (x, y): every byte different across the image, alpha 255.
void pattern(uint32_t x, uint32_t y, uint8_t* bgra) {
    bgra[0] = uint8_t(x * 7 + y);
    bgra[1] = uint8_t(y * 5 + 3);
    bgra[2] = uint8_t(x ^ (y * 3));
    bgra[3] = 255;
}

class X11 {
  public:
    X11()
        : harness_(true, {VK_KHR_SURFACE_EXTENSION_NAME, VK_KHR_XCB_SURFACE_EXTENSION_NAME,
                          VK_KHR_XLIB_SURFACE_EXTENSION_NAME}) {}
    const Harness& harness() const { return harness_; }

    VkSurfaceKHR surface(const XWindow& w) {
        VkSurfaceKHR s = VK_NULL_HANDLE;
        if (w.dpy != nullptr) {
            VkXlibSurfaceCreateInfoKHR ci{VK_STRUCTURE_TYPE_XLIB_SURFACE_CREATE_INFO_KHR};
            ci.dpy = w.dpy;
            ci.window = w.window;
            EXPECT_EQ(vkCreateXlibSurfaceKHR(harness_.instance(), &ci, nullptr, &s), VK_SUCCESS);
        } else {
            VkXcbSurfaceCreateInfoKHR ci{VK_STRUCTURE_TYPE_XCB_SURFACE_CREATE_INFO_KHR};
            ci.connection = w.c;
            ci.window = w.window;
            EXPECT_EQ(vkCreateXcbSurfaceKHR(harness_.instance(), &ci, nullptr, &s), VK_SUCCESS);
        }
        return s;
    }

  private:
    Harness harness_;
};

// A swapchain with one helper: fill an acquired image with the pattern (a buffer copy) and present it.
class Chain {
  public:
    Chain(VkPhysicalDevice pd, VkSurfaceKHR surface, VkExtent2D extent, VkPresentModeKHR mode)
        : dev_(pd, nullptr, {VK_KHR_SWAPCHAIN_EXTENSION_NAME}), pd_(pd), surface_(surface), mode_(mode) {
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vkCreateFence(dev_.device(), &fci, nullptr, &fence_);
        recreate(extent);
    }
    // A swapchain of `extent` (the current one, if any, as its oldSwapchain, then destroyed).
    void recreate(VkExtent2D extent) {
        extent_ = extent;
        VkSurfaceCapabilitiesKHR caps{};
        vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd_, surface_, &caps);
        VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
        ci.surface = surface_;
        ci.minImageCount = caps.minImageCount;  // lavapipe: 3, tilevk: 2
        ci.imageFormat = VK_FORMAT_B8G8R8A8_UNORM;
        ci.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
        ci.imageExtent = extent;
        ci.imageArrayLayers = 1;
        ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        ci.preTransform = VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR;
        ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
        ci.presentMode = mode_;
        ci.clipped = VK_TRUE;
        ci.oldSwapchain = sc_;
        VkSwapchainKHR sc = VK_NULL_HANDLE;
        result_ = vkCreateSwapchainKHR(dev_.device(), &ci, nullptr, &sc);
        destroy_swapchain();
        sc_ = sc;
        if (result_ != VK_SUCCESS) return;
        uint32_t n = 0;
        vkGetSwapchainImagesKHR(dev_.device(), sc_, &n, nullptr);
        images_.resize(n);
        vkGetSwapchainImagesKHR(dev_.device(), sc_, &n, images_.data());
        if (staging_.buffer != VK_NULL_HANDLE) dev_.destroy(staging_);
        staging_ = dev_.make_buffer(VkDeviceSize(extent.width) * extent.height * 4);
        auto* p = static_cast<uint8_t*>(staging_.map);
        for (uint32_t y = 0; y < extent.height; ++y)
            for (uint32_t x = 0; x < extent.width; ++x) pattern(x, y, p + (size_t(y) * extent.width + x) * 4);
    }
    ~Chain() {
        if (!dev_.ok()) return;
        vkDeviceWaitIdle(dev_.device());
        destroy_swapchain();
        if (fence_ != VK_NULL_HANDLE) vkDestroyFence(dev_.device(), fence_, nullptr);
        if (staging_.buffer != VK_NULL_HANDLE) dev_.destroy(staging_);
    }
    VkResult created() const { return result_; }
    VkSwapchainKHR swapchain() const { return sc_; }
    void destroy_swapchain() {
        if (sc_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(dev_.device(), sc_, nullptr);
        sc_ = VK_NULL_HANDLE;
    }
    VkResult acquire(uint32_t* index) {
        vkResetFences(dev_.device(), 1, &fence_);
        VkResult r = vkAcquireNextImageKHR(dev_.device(), sc_, 2'000'000'000, VK_NULL_HANDLE, fence_, index);
        if (r >= 0) vkWaitForFences(dev_.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
        return r;
    }
    VkResult fill_and_present(uint32_t index) {
        VkResult r = dev_.run([&](VkCommandBuffer cb) {
            transition(cb, images_[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {extent_.width, extent_.height, 1};
            vkCmdCopyBufferToImage(cb, staging_.buffer, images_[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                   &region);
            transition(cb, images_[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        });
        if (r != VK_SUCCESS) return r;
        VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        pi.swapchainCount = 1;
        pi.pSwapchains = &sc_;
        pi.pImageIndices = &index;
        return vkQueuePresentKHR(dev_.queue(), &pi);
    }
    VkResult frame() {
        uint32_t index;
        VkResult r = acquire(&index);
        if (r < 0) return r;
        VkResult p = fill_and_present(index);
        return p != VK_SUCCESS ? p : r;
    }

  private:
    Device dev_;
    VkPhysicalDevice pd_;
    VkSurfaceKHR surface_;
    VkPresentModeKHR mode_;
    VkExtent2D extent_{};
    VkResult result_ = VK_ERROR_INITIALIZATION_FAILED;
    VkSwapchainKHR sc_ = VK_NULL_HANDLE;
    std::vector<VkImage> images_;
    Device::Buffer staging_;
    VkFence fence_ = VK_NULL_HANDLE;
};

// The window's bytes equal the pattern in blue, green, red (the X pixel's fourth byte is not part of a depth-24
// visual and is not compared).
void expect_window_shows_pattern(const XWindow& w, uint32_t width, uint32_t height, const char* what) {
    std::vector<uint8_t> px = w.pixels(width, height);
    ASSERT_EQ(px.size(), size_t(width) * height * 4) << what;
    int wrong = 0;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            uint8_t want[4];
            pattern(x, y, want);
            wrong += memcmp(&px[(size_t(y) * width + x) * 4], want, 3) != 0;
        }
    }
    EXPECT_EQ(wrong, 0) << what << ": pixels that differ from what was rendered";
}

#define EXPECT_ZERO_MESSAGES(x) EXPECT_EQ((x).harness().message_count(), 0) << (x).harness().message_report()

}  // namespace

TEST(X11, SurfaceReportsTheWindow) {
    X11 x;
    ASSERT_TRUE(x.harness().ok());
    XWindow w = xcb_window(96, 64);
    ASSERT_NE(w.window, 0u);
    VkPhysicalDevice pd = x.harness().find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    VkSurfaceKHR s = x.surface(w);
    EXPECT_TRUE(vkGetPhysicalDeviceXcbPresentationSupportKHR(pd, 0, w.c, w.visual));
    VkBool32 supported = VK_FALSE;
    EXPECT_EQ(vkGetPhysicalDeviceSurfaceSupportKHR(pd, 0, s, &supported), VK_SUCCESS);
    EXPECT_TRUE(supported);
    VkSurfaceCapabilitiesKHR caps;
    ASSERT_EQ(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, s, &caps), VK_SUCCESS);
    EXPECT_EQ(caps.currentExtent.width, 96u);
    EXPECT_EQ(caps.currentExtent.height, 64u);
    EXPECT_EQ(caps.minImageExtent.width, 96u);
    EXPECT_EQ(caps.maxImageExtent.height, 64u);
    EXPECT_EQ(caps.supportedCompositeAlpha,
              VkCompositeAlphaFlagsKHR(VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR | VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR));
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(pd, s, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> f(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(pd, s, &n, f.data());
    // Xvfb's TrueColor visual has red in bits 16-23: BGRA bytes; R8G8B8A8 would need red in the low byte.
    ASSERT_EQ(n, 2u);
    EXPECT_EQ(f[0].format, VK_FORMAT_B8G8R8A8_SRGB);
    EXPECT_EQ(f[1].format, VK_FORMAT_B8G8R8A8_UNORM);
    vkDestroySurfaceKHR(x.harness().instance(), s, nullptr);
    xcb_disconnect(w.c);
    EXPECT_ZERO_MESSAGES(x);
}

// The bytes rendered are the bytes the window shows: tilevk through MIT-SHM and through PutImage, lavapipe too, on
// xcb and Xlib surfaces.
TEST(X11, WindowShowsTheRenderedBytes) {
    X11 x;
    ASSERT_TRUE(x.harness().ok());
    struct Case {
        const char* device;
        const char* shm;
        bool xlib;
    };
    // (lavapipe on an Xlib surface under Xvfb sends a ShmCreatePixmap the server refuses, and Xlib's default error
    // handler ends the process: lavapipe is compared on xcb only.)
    for (Case c : {Case{"tilevk", "1", false}, Case{"tilevk", "0", false}, Case{"tilevk", "1", true},
                   Case{"tilevk", "0", true}, Case{"llvmpipe", "1", false}}) {
        const std::string what = std::string(c.device) + (c.xlib ? " Xlib" : " xcb") + " TILEVK_WSI_SHM=" + c.shm;
        setenv("TILEVK_WSI_SHM", c.shm, 1);
        XWindow w = c.xlib ? xlib_window(77, 45) : xcb_window(77, 45);
        ASSERT_NE(w.window, 0u) << what;
        VkPhysicalDevice pd = x.harness().find_device(c.device);
        ASSERT_NE(pd, VK_NULL_HANDLE) << what;
        VkSurfaceKHR s = x.surface(w);
        {
            Chain chain(pd, s, {77, 45}, VK_PRESENT_MODE_FIFO_KHR);
            ASSERT_EQ(chain.created(), VK_SUCCESS) << what;
            EXPECT_EQ(chain.frame(), VK_SUCCESS) << what;
            EXPECT_EQ(chain.frame(), VK_SUCCESS) << what;
            chain.destroy_swapchain();  // shows what is still queued
            w.sync();
            expect_window_shows_pattern(w, 77, 45, what.c_str());
        }
        vkDestroySurfaceKHR(x.harness().instance(), s, nullptr);
        if (w.dpy != nullptr) {
            XCloseDisplay(w.dpy);
        } else {
            xcb_disconnect(w.c);
        }
    }
    unsetenv("TILEVK_WSI_SHM");
    EXPECT_ZERO_MESSAGES(x);
}

// Resized: acquire and present say VK_SUBOPTIMAL_KHR (the frame is still shown, clipped), the capabilities give
// the new size, and a swapchain made for it is optimal again. Unmapped: presents go on without blocking.
TEST(X11, ResizedAndUnmappedWindows) {
    X11 x;
    ASSERT_TRUE(x.harness().ok());
    XWindow w = xcb_window(64, 40);
    VkPhysicalDevice pd = x.harness().find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    VkSurfaceKHR s = x.surface(w);
    {
        Chain chain(pd, s, {64, 40}, VK_PRESENT_MODE_MAILBOX_KHR);
        ASSERT_EQ(chain.created(), VK_SUCCESS);
        EXPECT_EQ(chain.frame(), VK_SUCCESS);
        w.resize(50, 30);
        uint32_t index;
        EXPECT_EQ(chain.acquire(&index), VK_SUBOPTIMAL_KHR);
        EXPECT_EQ(chain.fill_and_present(index), VK_SUBOPTIMAL_KHR);
        VkSurfaceCapabilitiesKHR caps;
        ASSERT_EQ(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, s, &caps), VK_SUCCESS);
        EXPECT_EQ(caps.currentExtent.width, 50u);
        EXPECT_EQ(caps.currentExtent.height, 30u);
        chain.recreate({50, 30});
        ASSERT_EQ(chain.created(), VK_SUCCESS);
        EXPECT_EQ(chain.frame(), VK_SUCCESS);
        chain.destroy_swapchain();
        w.sync();
        expect_window_shows_pattern(w, 50, 30, "resized");
        chain.recreate({50, 30});

        xcb_unmap_window(w.c, w.window);  // what a minimised window is to X
        w.sync();
        const auto t = Clock::now();
        for (int i = 0; i < 6; ++i) EXPECT_EQ(chain.frame(), VK_SUCCESS) << "frame " << i;
        EXPECT_LT(std::chrono::duration<double>(Clock::now() - t).count(), 5.0);
        xcb_map_window(w.c, w.window);
        w.sync();
        EXPECT_EQ(chain.frame(), VK_SUCCESS);
    }
    vkDestroySurfaceKHR(x.harness().instance(), s, nullptr);
    xcb_disconnect(w.c);
    EXPECT_ZERO_MESSAGES(x);
}

// The window destroyed under a swapchain (the application's bug, or another client's doing): acquire, present and
// the surface queries say VK_ERROR_SURFACE_LOST_KHR; nothing hangs or crashes; the swapchain can still be destroyed.
TEST(X11, DestroyedWindowIsSurfaceLost) {
    X11 x;
    ASSERT_TRUE(x.harness().ok());
    XWindow w = xcb_window(32, 32);
    VkPhysicalDevice pd = x.harness().find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    VkSurfaceKHR s = x.surface(w);
    {
        Chain chain(pd, s, {32, 32}, VK_PRESENT_MODE_FIFO_KHR);
        ASSERT_EQ(chain.created(), VK_SUCCESS);
        EXPECT_EQ(chain.frame(), VK_SUCCESS);
        uint32_t index;
        ASSERT_EQ(chain.acquire(&index), VK_SUCCESS);
        xcb_destroy_window(w.c, w.window);
        w.sync();
        const auto t = Clock::now();
        const VkResult presented = chain.fill_and_present(index);  // the presentation thread finds out later
        EXPECT_TRUE(presented == VK_SUCCESS || presented == VK_ERROR_SURFACE_LOST_KHR) << presented;
        EXPECT_EQ(chain.acquire(&index), VK_ERROR_SURFACE_LOST_KHR);
        EXPECT_EQ(chain.acquire(&index), VK_ERROR_SURFACE_LOST_KHR);
        EXPECT_LT(std::chrono::duration<double>(Clock::now() - t).count(), 5.0);
        VkSurfaceCapabilitiesKHR caps;
        EXPECT_EQ(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, s, &caps), VK_ERROR_SURFACE_LOST_KHR);
    }
    vkDestroySurfaceKHR(x.harness().instance(), s, nullptr);
    xcb_disconnect(w.c);
    EXPECT_ZERO_MESSAGES(x);
}
