// VkImage with tilevk's one plain linear layout, used for both OPTIMAL and LINEAR tiling:
//   level-major; inside a level, array layers one after another (a 3D image's depth slices take the place of its
//   layers: slice z of a level is stored, addressed and copied as layer z); inside a layer, one plane per sample
//   (sample 0 first, `sample_pitch` bytes each); inside a plane, rows of `row_pitch` bytes; inside a row, pixels.
//   Texel (x, y, layer, level, sample) is at  level_offset[level] + layer*layer_pitch[level]
//                                              + sample*sample_pitch[level] + y*row_pitch[level] + x*texel_bytes.
// Block-compressed formats (BC) store whole 4x4 blocks in place of texels: rows of ceil(width/4) blocks, ceil(height/4)
// rows, a partial last block included; `texel` then takes block coordinates and `texel_bytes` is the block size.
// Levels start on 64-byte boundaries; rows are packed (no row padding). Sample planes are the renderer's own target
// layout (rast/render/targets.h), so a multisampled attachment is rendered in place, with no staging copy in or out
// (and no second copy of its memory); single-sampled images have one plane, the plain row layout. No API call shows
// a multisampled image's layout (such images are OPTIMAL only and never copied to or from buffers or host memory).
#pragma once
#include "formats.h"
#include "memory.h"
#include "physical_device.h"

namespace tilevk::icd {

struct ImageLayout {
    VkDeviceSize level_offset[kMaxMipLevels] = {};
    VkDeviceSize row_pitch[kMaxMipLevels] = {};
    VkDeviceSize sample_pitch[kMaxMipLevels] = {};  // row_pitch * height, padded at 4x (image.cpp sample_plane_pitch)
    VkDeviceSize layer_pitch[kMaxMipLevels] = {};   // sample_pitch * samples (a 3D image: the depth pitch)
    VkDeviceSize size = 0;
};

struct Image : NonDispatchableObject {
    using Handle = VkImage;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_IMAGE;
    Image() : NonDispatchableObject(kType) {}

    const FormatInfo* format = nullptr;
    VkImageType type = VK_IMAGE_TYPE_2D;
    VkExtent3D extent{};
    uint32_t mip_levels = 1;
    uint32_t array_layers = 1;
    uint32_t samples = 1;
    VkImageTiling tiling = VK_IMAGE_TILING_OPTIMAL;
    VkImageUsageFlags usage = 0;
    bool cube_compatible = false;  // VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT: cube and cube-array views allowed
    bool mutable_format = false;   // VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT: views of other same-sized colour formats
    ImageLayout layout;
    DeviceMemory* memory = nullptr;
    VkDeviceSize memory_offset = 0;

    uint32_t level_width(uint32_t level) const { return extent.width >> level ? extent.width >> level : 1; }
    uint32_t level_height(uint32_t level) const { return extent.height >> level ? extent.height >> level : 1; }
    uint32_t level_depth(uint32_t level) const { return extent.depth >> level ? extent.depth >> level : 1; }
    // The layers of a level as they are stored: a 3D image's depth slices, else its array layers.
    uint32_t level_layers(uint32_t level) const { return type == VK_IMAGE_TYPE_3D ? level_depth(level) : array_layers; }
    // A level's size in blocks (in texels for uncompressed formats, whose blocks are one texel).
    uint32_t level_blocks_w(uint32_t level) const {
        return (level_width(level) + format->block_width - 1) / format->block_width;
    }
    uint32_t level_blocks_h(uint32_t level) const {
        return (level_height(level) + format->block_height - 1) / format->block_height;
    }
    // Address of sample 0 of texel (x, y) of a subresource (block (x, y) of a compressed format).
    uint8_t* texel(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
        return memory->data + memory_offset + layout.level_offset[level] + layer * layout.layer_pitch[level] +
               y * layout.row_pitch[level] + VkDeviceSize(x) * format->bytes;
    }
    // Bytes from sample s of a texel to sample s+1 of the same texel.
    VkDeviceSize sample_pitch(uint32_t level) const { return layout.sample_pitch[level]; }
};

// Computes the layout described above.
ImageLayout compute_image_layout(const FormatInfo& f, VkExtent3D extent, uint32_t levels, uint32_t layers,
                                 uint32_t samples);
// The memory requirements of an image of this layout (vkGetImageMemoryRequirements and, without an image,
// vkGetDeviceImageMemoryRequirements: the one home of both answers).
VkMemoryRequirements image_requirements(const ImageLayout& layout);

struct Device;
// What vkCreateImage checks before it makes an image (and vkGetDeviceImageMemoryRequirements before it answers): the
// format's image support and every parameter against vkGetPhysicalDeviceImageFormatProperties. On success *format is
// the format's row; otherwise VK_ERROR_FORMAT_NOT_SUPPORTED and a stderr line starting with `command`.
VkResult check_image_create_info(const Device& dev, const VkImageCreateInfo* ci, const char* command,
                                 const FormatInfo** format);

}  // namespace tilevk::icd
