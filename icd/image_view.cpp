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
    // A 3D view of a 3D image, 2D and 2D-array views of 2D images, 1D and 1D-array views of 1D images. The others
    // (cube) are not implemented, nor 2D views of 3D images (that needs VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT,
    // which tilevk does not offer).
    bool made = false;
    switch (img->type) {
        case VK_IMAGE_TYPE_1D:
            made = ci->viewType == VK_IMAGE_VIEW_TYPE_1D || ci->viewType == VK_IMAGE_VIEW_TYPE_1D_ARRAY;
            break;
        case VK_IMAGE_TYPE_3D:
            made = ci->viewType == VK_IMAGE_VIEW_TYPE_3D;
            break;
        default:
            made = ci->viewType == VK_IMAGE_VIEW_TYPE_2D || ci->viewType == VK_IMAGE_VIEW_TYPE_2D_ARRAY;
            break;
    }
    if (!made) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateImageView: %s of a %s image is not implemented (1D and 1D-array views of 1D images, 2D "
                    "and 2D-array views of 2D images, 3D views of 3D images)",
                    vk_enum_name(ci->viewType), vk_enum_name(img->type));
    }
    const FormatInfo* f = find_format(ci->format);
    if (f == nullptr || !has_image_support(*f)) {
        return fail(VK_ERROR_FORMAT_NOT_SUPPORTED, "vkCreateImageView: %s is not supported", vk_enum_name(ci->format));
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
