// VK_KHR_surface and the surface-creating extensions (xcb, Xlib, Wayland, headless), VK_KHR_get_surface_capabilities2.
// A VkSurfaceKHR is a pointer to the VkIcdSurface* struct of vk_icd.h for its platform. From loader interface 3 on
// the loader calls the driver's vkCreate*SurfaceKHR and hands the driver's handle to it, so tilevk allocates these
// structs itself; it never adds anything after them, so a surface the loader made (same struct) works just as well.
#define VK_USE_PLATFORM_XCB_KHR
#define VK_USE_PLATFORM_XLIB_KHR
#define VK_USE_PLATFORM_WAYLAND_KHR
#include <algorithm>

#include "entrypoints.h"
#include "instance.h"
#include "physical_device.h"
#include "vk_names.h"
#include "wsi/platform.h"
#include "wsi/swapchain.h"

namespace tilevk::icd {
namespace {

template <class IcdSurface, class Fill>
VkResult create_surface(VkInstance instance, const VkAllocationCallbacks* pAllocator, VkIcdWsiPlatform platform,
                        Fill fill, VkSurfaceKHR* pSurface) {
    const VkAllocationCallbacks& a = pick_allocator(pAllocator, &from_handle<Instance>(instance)->allocator);
    void* mem = host_alloc(a, sizeof(IcdSurface), alignof(IcdSurface), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (mem == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreate*SurfaceKHR: out of host memory");
    auto* s = new (mem) IcdSurface{};
    s->base.platform = platform;
    fill(s);
    *pSurface = reinterpret_cast<VkSurfaceKHR>(s);
    return VK_SUCCESS;
}

// Queue family 0 is tilevk's only one; it presents to every surface it can present to at all.
bool presenting_family(uint32_t family) {
    return family == 0;
}

template <class T>
VkResult write_array(const std::vector<T>& items, uint32_t* count, T* out) {
    if (out == nullptr) {
        *count = uint32_t(items.size());
        return VK_SUCCESS;
    }
    const uint32_t n = std::min(*count, uint32_t(items.size()));
    std::copy(items.begin(), items.begin() + n, out);
    *count = n;
    return n < items.size() ? VK_INCOMPLETE : VK_SUCCESS;
}

}  // namespace

namespace wsi {

VkResult query_surface(VkSurfaceKHR surface, SurfaceInfo* info) {
    const auto* base = reinterpret_cast<const VkIcdSurfaceBase*>(surface);
    switch (base->platform) {
        case VK_ICD_WSI_PLATFORM_XCB:
        case VK_ICD_WSI_PLATFORM_XLIB:
            return query_x11(base, info);
        case VK_ICD_WSI_PLATFORM_WAYLAND:
            return query_wayland(base, info);
        case VK_ICD_WSI_PLATFORM_HEADLESS:
            return query_headless(info);
        default:
            return fail(VK_ERROR_SURFACE_LOST_KHR,
                        "a surface of window-system platform %d: tilevk cannot present there", int(base->platform));
    }
}

VkResult create_target(VkSurfaceKHR surface, const TargetDesc& desc, std::unique_ptr<PresentTarget>* target) {
    const auto* base = reinterpret_cast<const VkIcdSurfaceBase*>(surface);
    switch (base->platform) {
        case VK_ICD_WSI_PLATFORM_XCB:
        case VK_ICD_WSI_PLATFORM_XLIB:
            return create_x11_target(base, desc, target);
        case VK_ICD_WSI_PLATFORM_WAYLAND:
            return create_wayland_target(base, desc, target);
        case VK_ICD_WSI_PLATFORM_HEADLESS:
            *target = create_headless_target();
            return VK_SUCCESS;
        default:
            return fail(VK_ERROR_SURFACE_LOST_KHR, "vkCreateSwapchainKHR: window-system platform %d is not supported",
                        int(base->platform));
    }
}

VkResult surface_capabilities(VkSurfaceKHR surface, VkSurfaceCapabilitiesKHR* caps) {
    SurfaceInfo info;
    if (VkResult r = query_surface(surface, &info); r != VK_SUCCESS) return r;
    *caps = {};
    caps->minImageCount = kMinSwapchainImages;
    caps->maxImageCount = kMaxSwapchainImages;
    caps->currentExtent = info.current_extent;
    if (info.current_extent.width == kExtentFromSwapchain) {
        caps->minImageExtent = {1, 1};
        caps->maxImageExtent = {kMaxImageDimension, kMaxImageDimension};
    } else {  // an X window: the swapchain must have the window's size
        caps->minImageExtent = caps->maxImageExtent = {std::min(info.current_extent.width, kMaxImageDimension),
                                                       std::min(info.current_extent.height, kMaxImageDimension)};
    }
    caps->maxImageArrayLayers = 1;
    caps->supportedTransforms = VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR;
    caps->currentTransform = VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR;
    caps->supportedCompositeAlpha = VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
    if (info.opaque_possible) caps->supportedCompositeAlpha |= VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (info.has_alpha) caps->supportedCompositeAlpha |= VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR;
    caps->supportedUsageFlags = kSwapchainImageUsage;
    return VK_SUCCESS;
}

}  // namespace wsi

// ---- creating and destroying surfaces --------------------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateXcbSurfaceKHR(VkInstance instance, const VkXcbSurfaceCreateInfoKHR* ci,
                                                       const VkAllocationCallbacks* pAllocator,
                                                       VkSurfaceKHR* pSurface) {
    return create_surface<VkIcdSurfaceXcb>(
        instance, pAllocator, VK_ICD_WSI_PLATFORM_XCB,
        [&](VkIcdSurfaceXcb* s) {
            s->connection = ci->connection;
            s->window = ci->window;
        },
        pSurface);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateXlibSurfaceKHR(VkInstance instance, const VkXlibSurfaceCreateInfoKHR* ci,
                                                        const VkAllocationCallbacks* pAllocator,
                                                        VkSurfaceKHR* pSurface) {
    return create_surface<VkIcdSurfaceXlib>(
        instance, pAllocator, VK_ICD_WSI_PLATFORM_XLIB,
        [&](VkIcdSurfaceXlib* s) {
            s->dpy = ci->dpy;
            s->window = ci->window;
        },
        pSurface);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateWaylandSurfaceKHR(VkInstance instance, const VkWaylandSurfaceCreateInfoKHR* ci,
                                                           const VkAllocationCallbacks* pAllocator,
                                                           VkSurfaceKHR* pSurface) {
    return create_surface<VkIcdSurfaceWayland>(
        instance, pAllocator, VK_ICD_WSI_PLATFORM_WAYLAND,
        [&](VkIcdSurfaceWayland* s) {
            s->display = ci->display;
            s->surface = ci->surface;
        },
        pSurface);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateHeadlessSurfaceEXT(VkInstance instance, const VkHeadlessSurfaceCreateInfoEXT*,
                                                            const VkAllocationCallbacks* pAllocator,
                                                            VkSurfaceKHR* pSurface) {
    return create_surface<VkIcdSurfaceHeadless>(
        instance, pAllocator, VK_ICD_WSI_PLATFORM_HEADLESS, [](VkIcdSurfaceHeadless*) {}, pSurface);
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroySurfaceKHR(VkInstance instance, VkSurfaceKHR surface,
                                                 const VkAllocationCallbacks* pAllocator) {
    if (surface == VK_NULL_HANDLE) return;
    host_free(pick_allocator(pAllocator, &from_handle<Instance>(instance)->allocator),
              reinterpret_cast<void*>(surface));
}

// ---- presentation support --------------------------------------------------------------------------------------

VKAPI_ATTR VkBool32 VKAPI_CALL tvk_GetPhysicalDeviceXcbPresentationSupportKHR(VkPhysicalDevice,
                                                                              uint32_t queueFamilyIndex,
                                                                              xcb_connection_t* connection,
                                                                              xcb_visualid_t visual_id) {
    return presenting_family(queueFamilyIndex) && wsi::x11_presentation_supported(connection, visual_id);
}

VKAPI_ATTR VkBool32 VKAPI_CALL tvk_GetPhysicalDeviceXlibPresentationSupportKHR(VkPhysicalDevice,
                                                                               uint32_t queueFamilyIndex, Display* dpy,
                                                                               VisualID visualID) {
    void* connection = wsi::xcb_connection_of_xlib(dpy);
    return presenting_family(queueFamilyIndex) && connection != nullptr &&
           wsi::x11_presentation_supported(connection, uint32_t(visualID));
}

VKAPI_ATTR VkBool32 VKAPI_CALL tvk_GetPhysicalDeviceWaylandPresentationSupportKHR(VkPhysicalDevice,
                                                                                  uint32_t queueFamilyIndex,
                                                                                  struct wl_display*) {
    // Any compositor: wl_shm and its ARGB8888/XRGB8888 formats are mandatory in the core Wayland protocol.
    return presenting_family(queueFamilyIndex);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceSurfaceSupportKHR(VkPhysicalDevice, uint32_t queueFamilyIndex,
                                                                      VkSurfaceKHR surface, VkBool32* pSupported) {
    *pSupported = VK_FALSE;
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(surface, &info); r != VK_SUCCESS) return r;
    *pSupported = presenting_family(queueFamilyIndex) && !info.formats.empty();
    return VK_SUCCESS;
}

// ---- what a surface offers -------------------------------------------------------------------------------------

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceSurfaceCapabilitiesKHR(VkPhysicalDevice, VkSurfaceKHR surface,
                                                                           VkSurfaceCapabilitiesKHR* pCaps) {
    return wsi::surface_capabilities(surface, pCaps);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceSurfaceCapabilities2KHR(
    VkPhysicalDevice, const VkPhysicalDeviceSurfaceInfo2KHR* pSurfaceInfo, VkSurfaceCapabilities2KHR* pCaps) {
    // VK_KHR_surface_protected_capabilities: tilevk has no protected memory (protectedMemory is VK_FALSE), so no
    // swapchain can be protected. Nothing else in either chain belongs to an extension tilevk exposes.
    for (auto* s = static_cast<VkBaseOutStructure*>(pCaps->pNext); s != nullptr; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_SURFACE_PROTECTED_CAPABILITIES_KHR)
            reinterpret_cast<VkSurfaceProtectedCapabilitiesKHR*>(s)->supportsProtected = VK_FALSE;
    }
    return wsi::surface_capabilities(pSurfaceInfo->surface, &pCaps->surfaceCapabilities);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceSurfaceFormatsKHR(VkPhysicalDevice, VkSurfaceKHR surface,
                                                                      uint32_t* pCount, VkSurfaceFormatKHR* pFormats) {
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(surface, &info); r != VK_SUCCESS) return r;
    std::vector<VkSurfaceFormatKHR> formats;
    for (VkFormat f : info.formats) formats.push_back({f, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR});
    return write_array(formats, pCount, pFormats);
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceSurfaceFormats2KHR(VkPhysicalDevice,
                                                                       const VkPhysicalDeviceSurfaceInfo2KHR* pInfo,
                                                                       uint32_t* pCount,
                                                                       VkSurfaceFormat2KHR* pFormats) {
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(pInfo->surface, &info); r != VK_SUCCESS) return r;
    if (pFormats == nullptr) {
        *pCount = uint32_t(info.formats.size());
        return VK_SUCCESS;
    }
    const uint32_t n = std::min(*pCount, uint32_t(info.formats.size()));
    for (uint32_t i = 0; i < n; ++i) pFormats[i].surfaceFormat = {info.formats[i], VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
    *pCount = n;
    return n < info.formats.size() ? VK_INCOMPLETE : VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDeviceSurfacePresentModesKHR(VkPhysicalDevice, VkSurfaceKHR surface,
                                                                           uint32_t* pCount, VkPresentModeKHR* pModes) {
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(surface, &info); r != VK_SUCCESS) return r;
    return write_array(std::vector<VkPresentModeKHR>(std::begin(wsi::kPresentModes), std::end(wsi::kPresentModes)),
                       pCount, pModes);
}

// ---- VK_KHR_device_group with VK_KHR_surface: a one-device group presents locally --------------------------------

VKAPI_ATTR VkResult VKAPI_CALL tvk_GetDeviceGroupSurfacePresentModesKHR(VkDevice, VkSurfaceKHR surface,
                                                                        VkDeviceGroupPresentModeFlagsKHR* pModes) {
    *pModes = 0;
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(surface, &info); r != VK_SUCCESS) return r;
    *pModes = VK_DEVICE_GROUP_PRESENT_MODE_LOCAL_BIT_KHR;
    return VK_SUCCESS;
}

// The whole surface: an X window's geometry, or (a surface whose size the swapchain sets: Wayland, headless) the
// "size unknown" rectangle of UINT32_MAX x UINT32_MAX that Mesa's window systems report too.
VKAPI_ATTR VkResult VKAPI_CALL tvk_GetPhysicalDevicePresentRectanglesKHR(VkPhysicalDevice, VkSurfaceKHR surface,
                                                                         uint32_t* pRectCount, VkRect2D* pRects) {
    wsi::SurfaceInfo info;
    if (VkResult r = wsi::query_surface(surface, &info); r != VK_SUCCESS) return r;
    const VkRect2D whole = info.current_extent.width == wsi::kExtentFromSwapchain
                               ? VkRect2D{{0, 0}, {UINT32_MAX, UINT32_MAX}}
                               : VkRect2D{{0, 0}, info.current_extent};
    return write_array(std::vector<VkRect2D>{whole}, pRectCount, pRects);
}

}  // namespace tilevk::icd
