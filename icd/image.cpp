#include "image.h"

#include "device.h"
#include "entrypoints.h"
#include "physical_device.h"
#include "vk_names.h"
#include "wsi/swapchain.h"

namespace tilevk::icd {

constexpr VkDeviceSize kLevelAlignment = 64;

// The bytes from one sample plane to the next. Planes a multiple of 4 KiB apart (1920x1080 RGBA8 is) put a pixel's
// four samples at one page offset: the fragment stage's and the resolve's four streams then collide in the same L1
// sets and stall on 4K aliasing of loads behind stores. Past a 4 KiB boundary, planes start 1088 B (17 lines) apart
// in the page, so the four samples take four distinct offsets.
static VkDeviceSize sample_plane_pitch(VkDeviceSize plane_bytes, uint32_t samples) {
    if (samples <= 1) return plane_bytes;
    constexpr VkDeviceSize kPage = 4096, kStagger = 17 * 64;
    return (plane_bytes + kPage - 1) / kPage * kPage + kStagger;
}

ImageLayout compute_image_layout(const FormatInfo& f, VkExtent3D extent, uint32_t levels, uint32_t layers,
                                 uint32_t samples) {
    ImageLayout l;
    VkDeviceSize offset = 0;
    for (uint32_t level = 0; level < levels; ++level) {
        // block-compressed levels are stored as rows of whole blocks (a partial last block included)
        const VkDeviceSize tw = extent.width >> level ? extent.width >> level : 1;
        const VkDeviceSize th = extent.height >> level ? extent.height >> level : 1;
        const VkDeviceSize w = (tw + f.block_width - 1) / f.block_width, h = (th + f.block_height - 1) / f.block_height;
        VkDeviceSize d = extent.depth >> level ? extent.depth >> level : 1;  // 3D: slices stored as layers (image.h)
        offset = (offset + kLevelAlignment - 1) & ~(kLevelAlignment - 1);
        l.level_offset[level] = offset;
        l.row_pitch[level] = w * f.bytes;
        l.sample_pitch[level] = sample_plane_pitch(l.row_pitch[level] * h, samples);
        l.layer_pitch[level] = l.sample_pitch[level] * samples;
        offset += l.layer_pitch[level] * layers * d;
    }
    l.size = (offset + kLevelAlignment - 1) & ~(kLevelAlignment - 1);
    return l;
}

VkResult check_image_create_info(const Device& dev, const VkImageCreateInfo* ci, const char* command,
                                 const FormatInfo** format) {
    const FormatInfo* f = find_format(ci->format);
    if (f == nullptr || !has_image_support(*f)) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED, "%s: %s is not supported for images", command,
                    vk_enum_name(ci->format));
    }
    // The spec bounds an image's parameters by what vkGetPhysicalDeviceImageFormatProperties reports for them
    // (VUID-VkImageCreateInfo-imageCreateMaxMipLevels-02251, -extent-02252/02253, -samples-02258,
    // -arrayLayers-02256, -imageCreateImageFormatPropertiesList-02251...): whatever that query refuses, or any value
    // past its maxExtent/maxMipLevels/maxArrayLayers/sampleCounts (maxImageDimension2D included), is refused here
    // with the query's own code, VK_ERROR_FORMAT_NOT_SUPPORTED (vkCreateImage has no code of its own for invalid
    // parameters; this beats a half-working image).
    // VK_EXT_separate_stencil_usage: the stencil aspect's usage must be supported too (tilevk's format support is
    // per format, so the image must allow the union of both usages, as vkGetPhysicalDeviceImageFormatProperties2
    // checks it).
    const auto* stencil =
        find_in_chain<VkImageStencilUsageCreateInfo>(ci->pNext, VK_STRUCTURE_TYPE_IMAGE_STENCIL_USAGE_CREATE_INFO);
    const VkImageUsageFlags usage = ci->usage | (stencil != nullptr ? stencil->stencilUsage : 0);
    VkImageFormatProperties props{};
    const VkResult supported = tvk_GetPhysicalDeviceImageFormatProperties(
        to_handle(dev.physical_device), ci->format, ci->imageType, ci->tiling, usage, ci->flags, &props);
    if (supported != VK_SUCCESS || ci->extent.width == 0 || ci->extent.height == 0 || ci->extent.depth == 0 ||
        ci->extent.width > props.maxExtent.width || ci->extent.height > props.maxExtent.height ||
        ci->extent.depth > props.maxExtent.depth || ci->mipLevels == 0 || ci->mipLevels > props.maxMipLevels ||
        ci->arrayLayers == 0 || ci->arrayLayers > props.maxArrayLayers || (ci->samples & props.sampleCounts) == 0) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                    "%s: %s, %s, %s, usage %s, flags %s, extent %ux%ux%u, %u levels, "
                    "%u layers, %s: not supported (vkGetPhysicalDeviceImageFormatProperties: %s; maxExtent "
                    "%ux%ux%u, %u levels, %u layers, sample counts %s)",
                    command, vk_enum_name(ci->imageType), vk_enum_name(ci->format), vk_enum_name(ci->tiling),
                    vk_flags_name<VkImageUsageFlagBits>(usage).c_str(),
                    vk_flags_name<VkImageCreateFlagBits>(ci->flags).c_str(), ci->extent.width, ci->extent.height,
                    ci->extent.depth, ci->mipLevels, ci->arrayLayers,
                    vk_flags_name<VkSampleCountFlagBits>(ci->samples).c_str(),
                    supported == VK_SUCCESS ? "supported" : "VK_ERROR_FORMAT_NOT_SUPPORTED", props.maxExtent.width,
                    props.maxExtent.height, props.maxExtent.depth, props.maxMipLevels, props.maxArrayLayers,
                    vk_flags_name<VkSampleCountFlagBits>(props.sampleCounts).c_str());
    }
    // A cube-compatible image holds whole square faces (VUID-VkImageCreateInfo-flags-08865/08866).
    if ((ci->flags & VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT) &&
        (ci->extent.width != ci->extent.height || ci->arrayLayers < 6)) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                    "%s: VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT needs a square extent and at least 6 array layers "
                    "(got %ux%u, %u layers)",
                    command, ci->extent.width, ci->extent.height, ci->arrayLayers);
    }
    *format = f;
    return VK_SUCCESS;
}

VkMemoryRequirements image_requirements(const ImageLayout& layout) {
    return {layout.size, kLevelAlignment, 1};
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateImage(VkDevice device, const VkImageCreateInfo* ci,
                                               const VkAllocationCallbacks* pAllocator, VkImage* pImage) {
    Device* dev = from_handle<Device>(device);
    const FormatInfo* f = nullptr;
    if (VkResult r = check_image_create_info(*dev, ci, "vkCreateImage", &f); r != VK_SUCCESS) return r;
    if (const auto* swapchain =
            find_in_chain<VkImageSwapchainCreateInfoKHR>(ci->pNext, VK_STRUCTURE_TYPE_IMAGE_SWAPCHAIN_CREATE_INFO_KHR);
        swapchain != nullptr && swapchain->swapchain != VK_NULL_HANDLE) {
        if (VkResult r = check_swapchain_image(*ci, *swapchain); r != VK_SUCCESS) return r;
    }
    Image* img = create_object<Image>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (img == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateImage: out of host memory");
    img->format = f;
    img->type = ci->imageType;
    img->extent = ci->extent;
    img->mip_levels = ci->mipLevels;
    img->array_layers = ci->arrayLayers;
    img->samples = ci->samples;
    img->tiling = ci->tiling;
    img->usage = ci->usage;
    img->cube_compatible = (ci->flags & VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT) != 0;
    img->mutable_format = (ci->flags & VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT) != 0;
    img->layout = compute_image_layout(*f, ci->extent, ci->mipLevels, ci->arrayLayers, ci->samples);
    *pImage = to_handle(img);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyImage(VkDevice, VkImage image, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Image>(image));
}

VKAPI_ATTR void VKAPI_CALL tvk_GetImageMemoryRequirements(VkDevice, VkImage image, VkMemoryRequirements* pReqs) {
    *pReqs = image_requirements(from_handle<Image>(image)->layout);
}

VKAPI_ATTR void VKAPI_CALL tvk_GetImageSparseMemoryRequirements(VkDevice, VkImage, uint32_t* pCount,
                                                                VkSparseImageMemoryRequirements*) {
    *pCount = 0;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_BindImageMemory(VkDevice, VkImage image, VkDeviceMemory memory,
                                                   VkDeviceSize memoryOffset) {
    Image* img = from_handle<Image>(image);
    img->memory = from_handle<DeviceMemory>(memory);
    img->memory_offset = memoryOffset;
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_GetImageSubresourceLayout(VkDevice, VkImage image, const VkImageSubresource* pSub,
                                                         VkSubresourceLayout* pLayout) {
    Image* img = from_handle<Image>(image);
    const ImageLayout& l = img->layout;
    const uint32_t level = pSub->mipLevel;
    pLayout->offset = l.level_offset[level] + VkDeviceSize(pSub->arrayLayer) * l.layer_pitch[level];
    if (has_depth_and_stencil(*img->format)) {
        pLayout->offset += aspect_offset(*img->format, pSub->aspectMask);  // interleaved depth/stencil texels
    }
    pLayout->size = l.layer_pitch[level] * (img->type == VK_IMAGE_TYPE_3D ? img->level_depth(level) : 1);
    pLayout->rowPitch = l.row_pitch[level];
    pLayout->arrayPitch = l.layer_pitch[level];
    pLayout->depthPitch = l.layer_pitch[level];
}

}  // namespace tilevk::icd
