#include "image.h"

#include "device.h"
#include "entrypoints.h"
#include "physical_device.h"

namespace tilevk::icd {

constexpr VkDeviceSize kLevelAlignment = 64;

ImageLayout compute_image_layout(const FormatInfo& f, VkExtent3D extent, uint32_t levels, uint32_t layers,
                                 uint32_t samples) {
    ImageLayout l;
    VkDeviceSize offset = 0;
    for (uint32_t level = 0; level < levels; ++level) {
        VkDeviceSize w = extent.width >> level ? extent.width >> level : 1;
        VkDeviceSize h = extent.height >> level ? extent.height >> level : 1;
        offset = (offset + kLevelAlignment - 1) & ~(kLevelAlignment - 1);
        l.level_offset[level] = offset;
        l.row_pitch[level] = w * samples * f.texel_bytes;
        l.layer_pitch[level] = l.row_pitch[level] * h;
        offset += l.layer_pitch[level] * layers;
    }
    l.size = (offset + kLevelAlignment - 1) & ~(kLevelAlignment - 1);
    return l;
}

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateImage(VkDevice device, const VkImageCreateInfo* ci,
                                               const VkAllocationCallbacks* pAllocator, VkImage* pImage) {
    Device* dev = from_handle<Device>(device);
    const FormatInfo* f = find_format(ci->format);
    if (f == nullptr || f->aspects == 0) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED, "vkCreateImage: format %d is not supported for images",
                    int(ci->format));
    }
    if (ci->imageType != VK_IMAGE_TYPE_2D || ci->extent.depth != 1) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateImage: only 2D images are implemented (type %d)",
                    int(ci->imageType));
    }
    if (ci->flags != 0) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateImage: image create flags 0x%x are not supported",
                    ci->flags);
    }
    if (ci->samples != VK_SAMPLE_COUNT_1_BIT && ci->samples != VK_SAMPLE_COUNT_4_BIT) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateImage: %u samples (only 1 and 4)", unsigned(ci->samples));
    }
    // Anything vkGetPhysicalDeviceImageFormatProperties refuses (usage, tiling) is refused here too.
    VkImageFormatProperties props;
    if (tvk_GetPhysicalDeviceImageFormatProperties(to_handle(dev->physical_device), ci->format, ci->imageType,
                                                   ci->tiling, ci->usage, ci->flags, &props) != VK_SUCCESS ||
        ci->mipLevels > props.maxMipLevels || ci->arrayLayers > props.maxArrayLayers ||
        (ci->samples & props.sampleCounts) == 0) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                    "vkCreateImage: format %d, tiling %d, usage 0x%x, %u levels, %u layers, %u samples unsupported",
                    int(ci->format), int(ci->tiling), ci->usage, ci->mipLevels, ci->arrayLayers, unsigned(ci->samples));
    }
    if (ci->samples != VK_SAMPLE_COUNT_1_BIT && (!format_supports_msaa(*f) || ci->tiling != VK_IMAGE_TILING_OPTIMAL)) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateImage: format %d cannot be multisampled in tilevk",
                    int(ci->format));
    }
    if (ci->extent.width == 0 || ci->extent.height == 0 || ci->extent.width > kMaxImageDimension ||
        ci->extent.height > kMaxImageDimension || ci->mipLevels == 0 || ci->mipLevels > kMaxMipLevels ||
        ci->arrayLayers == 0 || ci->arrayLayers > kMaxArrayLayers) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateImage: extent %ux%u, %u levels, %u layers out of range",
                    ci->extent.width, ci->extent.height, ci->mipLevels, ci->arrayLayers);
    }
    Image* img = create_object<Image>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (img == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateImage: out of host memory");
    img->format = f;
    img->extent = ci->extent;
    img->mip_levels = ci->mipLevels;
    img->array_layers = ci->arrayLayers;
    img->samples = ci->samples;
    img->tiling = ci->tiling;
    img->usage = ci->usage;
    img->layout = compute_image_layout(*f, ci->extent, ci->mipLevels, ci->arrayLayers, ci->samples);
    *pImage = to_handle(img);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyImage(VkDevice, VkImage image, const VkAllocationCallbacks*) {
    destroy_object(from_handle<Image>(image));
}

VKAPI_ATTR void VKAPI_CALL tvk_GetImageMemoryRequirements(VkDevice, VkImage image, VkMemoryRequirements* pReqs) {
    Image* img = from_handle<Image>(image);
    pReqs->size = img->layout.size;
    pReqs->alignment = kLevelAlignment;
    pReqs->memoryTypeBits = 1;
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
    if (img->format->pack == PackKind::kD32FS8 || img->format->pack == PackKind::kD24S8) {
        pLayout->offset += aspect_offset(*img->format, pSub->aspectMask);  // interleaved depth/stencil texels
    }
    pLayout->size = l.layer_pitch[level];
    pLayout->rowPitch = l.row_pitch[level];
    pLayout->arrayPitch = l.layer_pitch[level];
    pLayout->depthPitch = l.layer_pitch[level];
}

}  // namespace tilevk::icd
