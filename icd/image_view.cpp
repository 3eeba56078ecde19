#include "image_view.h"

#include "render_state.h"

#include "device.h"
#include "entrypoints.h"
#include "vk_names.h"

namespace tilevk::icd {

VKAPI_ATTR VkResult VKAPI_CALL tvk_CreateImageView(VkDevice device, const VkImageViewCreateInfo* ci,
                                                   const VkAllocationCallbacks* pAllocator, VkImageView* pView) {
    Device* dev = from_handle<Device>(device);
    Image* img = from_handle<Image>(ci->image);
    // 1D and 1D-array views of 1D images, 3D views of 3D images, 2D, 2D-array, cube and cube-array views of 2D images
    // (cube views: of cube-compatible images, 6 layers or a multiple of 6). 2D views of 3D images are not made
    // (that needs VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT, which tilevk does not offer).
    const bool view_cube = ci->viewType == VK_IMAGE_VIEW_TYPE_CUBE || ci->viewType == VK_IMAGE_VIEW_TYPE_CUBE_ARRAY;
    bool made = false;
    switch (img->type) {
        case VK_IMAGE_TYPE_1D:
            made = ci->viewType == VK_IMAGE_VIEW_TYPE_1D || ci->viewType == VK_IMAGE_VIEW_TYPE_1D_ARRAY;
            break;
        case VK_IMAGE_TYPE_3D:
            made = ci->viewType == VK_IMAGE_VIEW_TYPE_3D;
            break;
        default:
            made = ci->viewType == VK_IMAGE_VIEW_TYPE_2D || ci->viewType == VK_IMAGE_VIEW_TYPE_2D_ARRAY || view_cube;
            break;
    }
    if (!made) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateImageView: %s of a %s image is not implemented (1D and 1D-array views of 1D images, 2D, "
                    "2D-array, cube and cube-array views of 2D images, 3D views of 3D images)",
                    vk_enum_name(ci->viewType), vk_enum_name(img->type));
    }
    if (view_cube) {
        const uint32_t layers = ci->subresourceRange.layerCount == VK_REMAINING_ARRAY_LAYERS
                                    ? img->array_layers - ci->subresourceRange.baseArrayLayer
                                    : ci->subresourceRange.layerCount;
        const bool count_ok = ci->viewType == VK_IMAGE_VIEW_TYPE_CUBE ? layers == 6 : layers % 6 == 0 && layers > 0;
        if (!img->cube_compatible || !count_ok) {
            return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                        "vkCreateImageView: %s needs an image created with VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT and "
                        "6 layers (a multiple of 6 for VK_IMAGE_VIEW_TYPE_CUBE_ARRAY); got %s, %u layers",
                        vk_enum_name(ci->viewType),
                        img->cube_compatible ? "a cube-compatible image" : "an image without the flag", layers);
        }
    }
    const FormatInfo* f = find_format(ci->format);
    if (f == nullptr || !has_image_support(*f)) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED, "vkCreateImageView: %s is not supported", vk_enum_name(ci->format));
    }
    // Another format reinterprets the image's bytes: only for a MUTABLE_FORMAT image and a colour format of the same
    // texel size (the size-compatible classes; VUID-VkImageViewCreateInfo-image-01761/01762). Every path that reads
    // or writes through a view uses the view's format; copies and blits use the image's.
    if (f != img->format) {
        const bool colour =
            f->aspects == VK_IMAGE_ASPECT_COLOR_BIT && img->format->aspects == VK_IMAGE_ASPECT_COLOR_BIT;
        if (!img->mutable_format || !colour || f->bytes != img->format->bytes ||
            f->layout == format::Layout::kCompressed || img->format->layout == format::Layout::kCompressed) {
            return fail(VK_ERROR_FORMAT_NOT_SUPPORTED,
                        "vkCreateImageView: a %s view of a %s image%s: tilevk views an image as another format only "
                        "when the image has VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT and both are uncompressed colour "
                        "formats of one texel size (VUID-VkImageViewCreateInfo-image-01761)",
                        vk_enum_name(ci->format), vk_enum_name(vk_format(*img->format)),
                        img->mutable_format ? "" : " without VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT");
        }
    }
    ImageView* view =
        create_object<ImageView>(pick_allocator(pAllocator, &dev->allocator), VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (view == nullptr) return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateImageView: out of host memory");
    view->image = img;
    view->format = f;
    view->view_type = ci->viewType;
    view->components = ci->components;
    view->range = ci->subresourceRange;
    if (view->range.levelCount == VK_REMAINING_MIP_LEVELS) {
        view->range.levelCount = img->mip_levels - view->range.baseMipLevel;
    }
    if (view->range.layerCount == VK_REMAINING_ARRAY_LAYERS) {
        view->range.layerCount = img->array_layers - view->range.baseArrayLayer;
    }
    if (img->memory != nullptr) {  // bound already (Vulkan requires it for a non-sparse image)
        view->sampled_ok = shader_view_of(*view, &view->sampled);
        view->sampled_memory = img->memory;
    }
    *pView = to_handle(view);
    return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL tvk_DestroyImageView(VkDevice, VkImageView imageView, const VkAllocationCallbacks*) {
    destroy_object(from_handle<ImageView>(imageView));
}

}  // namespace tilevk::icd
