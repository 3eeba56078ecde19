// The window systems tilevk presents to, behind one small interface: what a surface offers now, and where a
// swapchain's finished frames go. One file per window system (x11.cpp for xcb and Xlib, wayland.cpp, headless.cpp);
// surface.cpp dispatches on the VkIcdSurfaceBase::platform the loader-ICD interface puts at the start of a surface.
#pragma once
#include <vulkan/vk_icd.h>
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tilevk::icd::wsi {

// VkSurfaceCapabilitiesKHR::currentExtent when the swapchain decides the size (Wayland, headless).
constexpr uint32_t kExtentFromSwapchain = 0xFFFFFFFFu;

// What a surface offers right now, as its window system says.
struct SurfaceInfo {
    VkExtent2D current_extent{kExtentFromSwapchain, kExtentFromSwapchain};
    bool has_alpha = false;         // the window keeps alpha (a 32-bit X visual; Wayland's ARGB buffers)
    bool opaque_possible = true;    // the window can ignore alpha (every X visual without alpha; Wayland's XRGB)
    std::vector<VkFormat> formats;  // the swapchain formats whose bytes the window takes as they are, preferred first
};

// What one swapchain asks of its window.
struct TargetDesc {
    VkExtent2D extent;
    VkFormat format;
    VkCompositeAlphaFlagBitsKHR composite_alpha;
};

// The window system's side of one swapchain. present() runs on the swapchain's presentation thread only; check() on
// the thread that acquires (window-system libraries used here are thread-safe for that: libxcb, libwayland-client).
class PresentTarget {
  public:
    virtual ~PresentTarget() = default;
    // Copies one frame (the swapchain's extent and format, rows `pitch` bytes apart) into the window system's buffer
    // and shows it: VK_SUCCESS, or VK_ERROR_SURFACE_LOST_KHR when the window or the connection is gone.
    virtual VkResult present(const uint8_t* pixels, size_t pitch) = 0;
    // Whether the swapchain still fits the window: VK_SUCCESS, VK_SUBOPTIMAL_KHR (the window has another size; frames
    // are still shown, from the top-left corner, clipped) or VK_ERROR_SURFACE_LOST_KHR.
    virtual VkResult check() = 0;
};

// Per window system. query_*: VK_ERROR_SURFACE_LOST_KHR when the window or the connection is gone; VK_SUCCESS with no
// formats when the window cannot be presented to (an X visual that is not 8-bit TrueColor). create_*_target: the
// target, or an error code with a message on stderr.
VkResult query_x11(const VkIcdSurfaceBase* surface, SurfaceInfo* info);
VkResult create_x11_target(const VkIcdSurfaceBase* surface, const TargetDesc& desc,
                           std::unique_ptr<PresentTarget>* target);
// vkGetPhysicalDevice{Xcb,Xlib}PresentationSupportKHR: whether windows of `visual_id` can be presented to.
bool x11_presentation_supported(void* xcb_connection, uint32_t visual_id);
// The xcb connection under an Xlib Display (libX11-xcb's XGetXCBConnection), or nullptr without that library.
void* xcb_connection_of_xlib(void* display);
VkResult query_wayland(const VkIcdSurfaceBase* surface, SurfaceInfo* info);
VkResult create_wayland_target(const VkIcdSurfaceBase* surface, const TargetDesc& desc,
                               std::unique_ptr<PresentTarget>* target);
VkResult query_headless(SurfaceInfo* info);
std::unique_ptr<PresentTarget> create_headless_target();

// Dispatch on surface->platform (surface.cpp).
VkResult query_surface(VkSurfaceKHR surface, SurfaceInfo* info);
VkResult create_target(VkSurfaceKHR surface, const TargetDesc& desc, std::unique_ptr<PresentTarget>* target);

}  // namespace tilevk::icd::wsi
