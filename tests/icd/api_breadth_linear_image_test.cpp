// LINEAR images with several levels and layers (suite ApiBreadth), as lavapipe allows them: the image format
// properties of both tilings agree, and an image of 3 levels x 2 layers written by the host through
// vkGetImageSubresourceLayout, then partly cleared and partly overwritten by a buffer copy, reads back the same on
// tilevk and lavapipe, by copies to a buffer and by the host through the layout again, every byte checked against the
// pattern computed here.
#include <cstring>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr uint32_t kSize = 8, kLevels = 3, kLayers = 2;
constexpr VkImageUsageFlags kUsage =
    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

uint32_t dim(uint32_t level) {
    return kSize >> level;
}

// The host's byte b of texel t in (level, layer).
uint8_t host_byte(uint32_t level, uint32_t layer, uint32_t t, uint32_t b) {
    return uint8_t(level * 64 + layer * 32 + t * 4 + b + 1);
}

// What every subresource holds at the end: the host's bytes, except (level 1, layer 1), cleared to (1, 0.5, 0, 1)
// — 255, 128, 0, 255 in UNORM8 — and (level 2, layer 0), copied from a buffer of bytes 200 + k.
std::vector<uint8_t> expected(uint32_t level, uint32_t layer) {
    const uint32_t n = dim(level) * dim(level);
    std::vector<uint8_t> v(n * 4);
    for (uint32_t t = 0; t < n; ++t)
        for (uint32_t b = 0; b < 4; ++b) {
            const uint8_t clear[4] = {255, 128, 0, 255};
            v[t * 4 + b] = level == 1 && layer == 1   ? clear[b]
                           : level == 2 && layer == 0 ? uint8_t(200 + t * 4 + b)
                                                      : host_byte(level, layer, t, b);
        }
    return v;
}

uint32_t host_memory_type(Kit& k, uint32_t bits) {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(k.dev().physical(), &mp);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (uint32_t t = 0; t < mp.memoryTypeCount; ++t)
        if ((bits >> t & 1) && (mp.memoryTypes[t].propertyFlags & host) == host) return t;
    ADD_FAILURE() << "no host-visible memory type";
    return 0;
}

// Copies (level, layer)'s rows between the mapped image and tight bytes, through the subresource's layout.
void host_rows(Kit& k, VkImage img, uint8_t* map, uint32_t level, uint32_t layer, uint8_t* tight, bool to_image) {
    const VkImageSubresource sr{VK_IMAGE_ASPECT_COLOR_BIT, level, layer};
    VkSubresourceLayout l;
    vkGetImageSubresourceLayout(k.d, img, &sr, &l);
    EXPECT_GE(l.rowPitch, dim(level) * 4u);
    for (uint32_t y = 0; y < dim(level); ++y) {
        uint8_t* row = map + l.offset + y * l.rowPitch;
        uint8_t* t = tight + y * dim(level) * 4;
        to_image ? std::memcpy(row, t, dim(level) * 4) : std::memcpy(t, row, dim(level) * 4);
    }
}

Bytes linear_levels_layers_scene(Kit& k) {
    const VkImageCreateInfo ici = image_info_2d(kFormat, kSize, kSize, kLevels, kLayers, VK_SAMPLE_COUNT_1_BIT, kUsage,
                                                VK_IMAGE_TILING_LINEAR, VK_IMAGE_LAYOUT_PREINITIALIZED);
    VkImage img = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateImage(k.d, &ici, nullptr, &img), VK_SUCCESS);
    if (img == VK_NULL_HANDLE) return {};
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(k.d, img, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = host_memory_type(k, req.memoryTypeBits);
    VkDeviceMemory mem = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateMemory(k.d, &ai, nullptr, &mem), VK_SUCCESS);
    EXPECT_EQ(vkBindImageMemory(k.d, img, mem, 0), VK_SUCCESS);
    void* mapped = nullptr;
    EXPECT_EQ(vkMapMemory(k.d, mem, 0, VK_WHOLE_SIZE, 0, &mapped), VK_SUCCESS);
    auto* map = static_cast<uint8_t*>(mapped);
    for (uint32_t level = 0; level < kLevels; ++level)
        for (uint32_t layer = 0; layer < kLayers; ++layer) {
            std::vector<uint8_t> t(dim(level) * dim(level) * 4);
            for (uint32_t i = 0; i < t.size(); ++i) t[i] = host_byte(level, layer, i / 4, i % 4);
            host_rows(k, img, map, level, layer, t.data(), true);
        }
    std::vector<uint8_t> src(dim(2) * dim(2) * 4);
    for (uint32_t i = 0; i < src.size(); ++i) src[i] = uint8_t(200 + i);
    Device::Buffer sb = k.buffer_of(src, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    Device::Buffer out = k.buffer(VkDeviceSize(kSize * kSize + dim(1) * dim(1) + dim(2) * dim(2)) * 4 * kLayers,
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PREINITIALIZED,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue red_half{{1.0f, 0.5f, 0.0f, 1.0f}};
        const VkImageSubresourceRange one{VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, 1, 1};
        vkCmdClearColorImage(c, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &red_half, 1, &one);
        VkBufferImageCopy r{};
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 2, 0, 1};
        r.imageExtent = {dim(2), dim(2), 1};
        vkCmdCopyBufferToImage(c, sb.buffer, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
        transition(c, img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkDeviceSize offset = 0;
        for (uint32_t level = 0; level < kLevels; ++level) {  // both layers of a level in one region
            VkBufferImageCopy o{};
            o.bufferOffset = offset;
            o.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, kLayers};
            o.imageExtent = {dim(level), dim(level), 1};
            vkCmdCopyImageToBuffer(c, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.buffer, 1, &o);
            offset += VkDeviceSize(dim(level) * dim(level)) * 4 * kLayers;
        }
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb, 0, nullptr, 0,
                             nullptr);
    }),
              VK_SUCCESS);
    Bytes bytes = Kit::bytes(out);
    for (uint32_t level = 0; level < kLevels; ++level)  // then the host's reads through the layout
        for (uint32_t layer = 0; layer < kLayers; ++layer) {
            std::vector<uint8_t> t(dim(level) * dim(level) * 4);
            host_rows(k, img, map, level, layer, t.data(), false);
            bytes.insert(bytes.end(), t.begin(), t.end());
        }
    vkUnmapMemory(k.d, mem);
    vkDestroyImage(k.d, img, nullptr);
    vkFreeMemory(k.d, mem, nullptr);
    return bytes;
}

}  // namespace

// Both tilings report the same levels and layers on tilevk (lavapipe's rule), within lavapipe's.
TEST_F(ApiBreadth, LinearImageLevelsAndLayersReportedAsOptimal) {
    for (VkImageUsageFlags usage : {kUsage, VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT),
                                    VkImageUsageFlags(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT)}) {
        VkImageFormatProperties lin{}, opt{}, lvp{};
        ASSERT_EQ(vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), kFormat, VK_IMAGE_TYPE_2D,
                                                           VK_IMAGE_TILING_LINEAR, usage, 0, &lin),
                  VK_SUCCESS);
        ASSERT_EQ(vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), kFormat, VK_IMAGE_TYPE_2D,
                                                           VK_IMAGE_TILING_OPTIMAL, usage, 0, &opt),
                  VK_SUCCESS);
        ASSERT_EQ(vkGetPhysicalDeviceImageFormatProperties(lavapipe_->physical(), kFormat, VK_IMAGE_TYPE_2D,
                                                           VK_IMAGE_TILING_LINEAR, usage, 0, &lvp),
                  VK_SUCCESS);
        EXPECT_EQ(lin.maxMipLevels, opt.maxMipLevels);
        EXPECT_EQ(lin.maxArrayLayers, opt.maxArrayLayers);
        EXPECT_GT(lin.maxMipLevels, 1u);
        EXPECT_GT(lin.maxArrayLayers, 1u);
        EXPECT_LE(lin.maxMipLevels, lvp.maxMipLevels);
        EXPECT_LE(lin.maxArrayLayers, lvp.maxArrayLayers);
    }
}

// The scene above on both drivers (bytes compared by `both`), and every byte as computed here.
TEST_F(ApiBreadth, LinearImageLevelsAndLayersAsLavapipe) {
    const Bytes got = both(linear_levels_layers_scene);
    std::vector<uint8_t> want;
    for (uint32_t level = 0; level < kLevels; ++level)  // the copies: level by level, layer by layer
        for (uint32_t layer = 0; layer < kLayers; ++layer) {
            const std::vector<uint8_t> e = expected(level, layer);
            want.insert(want.end(), e.begin(), e.end());
        }
    const std::vector<uint8_t> copies = want;
    want.insert(want.end(), copies.begin(), copies.end());  // the host's reads, in the same order
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < want.size(); ++i) ASSERT_EQ(int(got[i]), int(want[i])) << "byte " << i;
}

}  // namespace tilevk::test::breadth
