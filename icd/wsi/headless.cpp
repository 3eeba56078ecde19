// VK_EXT_headless_surface: a surface with no window. Swapchains on it acquire, pace and present exactly as on a
// window (swapchain.cpp does all of that); the frame itself goes nowhere.
#include "wsi/platform.h"

namespace tilevk::icd::wsi {
namespace {

class HeadlessTarget final : public PresentTarget {
  public:
    VkResult present(const uint8_t*, size_t) override { return VK_SUCCESS; }
    VkResult check() override { return VK_SUCCESS; }
};

}  // namespace

// No window to match: the swapchain decides the extent; any of tilevk's 8-bit colour formats with any alpha.
VkResult query_headless(SurfaceInfo* info) {
    info->current_extent = {kExtentFromSwapchain, kExtentFromSwapchain};
    info->has_alpha = true;
    info->opaque_possible = true;
    info->formats = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB,
                     VK_FORMAT_R8G8B8A8_UNORM};
    return VK_SUCCESS;
}

std::unique_ptr<PresentTarget> create_headless_target() {
    return std::make_unique<HeadlessTarget>();
}

}  // namespace tilevk::icd::wsi
