// Present overhead per 1920x1080 frame through the Vulkan API (the loader, both drivers in one run): a loop of
// vkAcquireNextImageKHR + vkQueuePresentKHR with nothing rendered, IMMEDIATE, two images, so that each iteration
// waits for the previous frame to be out of the swapchain: the time per iteration is what presenting one frame costs
// (tilevk: the copy into the MIT-SHM segment or the PutImage requests, the X server's copy, the round trip;
// lavapipe: its PutImage path). A headless tilevk surface gives the swapchain's own cost without a window.
// "CPU" is the whole process (the presentation thread included; the X server not).
// Needs an X server of at least 1920x1080 (-noreset: the benchmarks connect one after another):
//   xvfb-run -a -s "-screen 0 1920x1080x24 -noreset" build/bench/wsi/present_bench
#include <benchmark/benchmark.h>
#define VK_USE_PLATFORM_XCB_KHR
#include <vulkan/vulkan.h>
#include <xcb/xcb.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr VkExtent2D kExtent = {1920, 1080};

struct Window {
    xcb_connection_t* c = nullptr;
    xcb_window_t w = 0;
};

Window make_window() {
    Window x;
    x.c = xcb_connect(nullptr, nullptr);
    if (xcb_connection_has_error(x.c)) return {};
    xcb_screen_t* s = xcb_setup_roots_iterator(xcb_get_setup(x.c)).data;
    x.w = xcb_generate_id(x.c);
    xcb_create_window(x.c, XCB_COPY_FROM_PARENT, x.w, s->root, 0, 0, kExtent.width, kExtent.height, 0,
                      XCB_WINDOW_CLASS_INPUT_OUTPUT, s->root_visual, 0, nullptr);
    xcb_map_window(x.c, x.w);
    free(xcb_get_input_focus_reply(x.c, xcb_get_input_focus(x.c), nullptr));
    return x;
}

struct Setup {
    VkInstance instance = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    Window window;
    std::string error;

    Setup(const char* device_prefix, bool headless) {
        const char* exts[] = {VK_KHR_SURFACE_EXTENSION_NAME,
                              headless ? VK_EXT_HEADLESS_SURFACE_EXTENSION_NAME : VK_KHR_XCB_SURFACE_EXTENSION_NAME};
        VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ici.enabledExtensionCount = 2;
        ici.ppEnabledExtensionNames = exts;
        if (vkCreateInstance(&ici, nullptr, &instance) != VK_SUCCESS) {
            error = "vkCreateInstance";
            return;
        }
        uint32_t n = 0;
        vkEnumeratePhysicalDevices(instance, &n, nullptr);
        std::vector<VkPhysicalDevice> pds(n);
        vkEnumeratePhysicalDevices(instance, &n, pds.data());
        VkPhysicalDevice pd = VK_NULL_HANDLE;
        for (VkPhysicalDevice p : pds) {
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(p, &props);
            if (strncmp(props.deviceName, device_prefix, strlen(device_prefix)) == 0) pd = p;
        }
        if (pd == VK_NULL_HANDLE) {
            error = std::string("no device ") + device_prefix;
            return;
        }
        if (headless) {
            auto create = reinterpret_cast<PFN_vkCreateHeadlessSurfaceEXT>(
                vkGetInstanceProcAddr(instance, "vkCreateHeadlessSurfaceEXT"));
            VkHeadlessSurfaceCreateInfoEXT ci{VK_STRUCTURE_TYPE_HEADLESS_SURFACE_CREATE_INFO_EXT};
            if (create == nullptr || create(instance, &ci, nullptr, &surface) != VK_SUCCESS) error = "headless";
        } else {
            window = make_window();
            VkXcbSurfaceCreateInfoKHR ci{VK_STRUCTURE_TYPE_XCB_SURFACE_CREATE_INFO_KHR};
            ci.connection = window.c;
            ci.window = window.w;
            if (window.c == nullptr || vkCreateXcbSurfaceKHR(instance, &ci, nullptr, &surface) != VK_SUCCESS) {
                error = "no X server (run under xvfb-run)";
            }
        }
        if (!error.empty()) return;
        float prio = 1.0f;
        VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        q.queueCount = 1;
        q.pQueuePriorities = &prio;
        const char* dev_ext = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &q;
        dci.enabledExtensionCount = 1;
        dci.ppEnabledExtensionNames = &dev_ext;
        if (vkCreateDevice(pd, &dci, nullptr, &device) != VK_SUCCESS) {
            error = "vkCreateDevice";
            return;
        }
        vkGetDeviceQueue(device, 0, 0, &queue);
        VkSurfaceCapabilitiesKHR caps;
        vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface, &caps);
        VkSwapchainCreateInfoKHR sci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
        sci.surface = surface;
        sci.minImageCount = caps.minImageCount;
        sci.imageFormat = VK_FORMAT_B8G8R8A8_UNORM;
        sci.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
        sci.imageExtent = kExtent;
        sci.imageArrayLayers = 1;
        sci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        sci.preTransform = VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR;
        sci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
        sci.presentMode = VK_PRESENT_MODE_IMMEDIATE_KHR;
        sci.clipped = VK_TRUE;
        if (vkCreateSwapchainKHR(device, &sci, nullptr, &swapchain) != VK_SUCCESS) error = "vkCreateSwapchainKHR";
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vkCreateFence(device, &fci, nullptr, &fence);
    }
    ~Setup() {
        if (device != VK_NULL_HANDLE) {
            vkDeviceWaitIdle(device);
            if (swapchain != VK_NULL_HANDLE) vkDestroySwapchainKHR(device, swapchain, nullptr);
            vkDestroyFence(device, fence, nullptr);
            vkDestroyDevice(device, nullptr);
        }
        if (surface != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance, surface, nullptr);
        if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
        if (window.c != nullptr) xcb_disconnect(window.c);
    }

    bool frame() {
        uint32_t index;
        vkResetFences(device, 1, &fence);
        VkResult r;
        // lavapipe's software path answers VK_NOT_READY whatever the timeout while no image is free: ask again.
        while ((r = vkAcquireNextImageKHR(device, swapchain, UINT64_MAX, VK_NULL_HANDLE, fence, &index)) ==
               VK_NOT_READY) {
        }
        if (r < 0) {
            fprintf(stderr, "vkAcquireNextImageKHR: %d\n", int(r));
            return false;
        }
        vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
        VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        pi.swapchainCount = 1;
        pi.pSwapchains = &swapchain;
        pi.pImageIndices = &index;
        return vkQueuePresentKHR(queue, &pi) >= 0;
    }
};

void BM_Present(benchmark::State& state, const char* device, bool headless, const char* shm) {
    setenv("TILEVK_WSI_SHM", shm, 1);
    Setup s(device, headless);
    if (!s.error.empty()) {
        state.SkipWithError(s.error.c_str());
        return;
    }
    for (int i = 0; i < 3; ++i) s.frame();  // warm up
    for (auto _ : state) {
        if (!s.frame()) {
            state.SkipWithError("acquire or present failed");
            break;
        }
    }
    state.SetItemsProcessed(state.iterations());
}

}  // namespace

// Alternating drivers, in one process; per iteration = one 1080p frame presented.
BENCHMARK_CAPTURE(BM_Present, lavapipe_xcb, "llvmpipe", false, "1")
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Present, tilevk_xcb_shm, "tilevk", false, "1")
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Present, tilevk_xcb_putimage, "tilevk", false, "0")
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Present, tilevk_headless, "tilevk", true, "1")
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
