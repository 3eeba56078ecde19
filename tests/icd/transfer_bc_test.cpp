// Copies of BC-compressed images on both drivers (tilevk and lavapipe, validation on): buffer <-> image in 4x4 blocks
// (bufferRowLength / bufferImageHeight in texels, block offsets, levels that are not multiples of the block and end
// in a partial block), image <-> image between BC1 and the size-compatible R16G16B16A16_UINT (one 8-byte block is one
// texel), and BC1 -> BC1 at a partial edge block. The read-back bytes must equal lavapipe's AND the block moves
// computed here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "vk_harness.h"

namespace {

using tilevk::test::Device;
using tilevk::test::transition;
using tilevk::test::TwoDriverSuite;
using Bytes = std::vector<uint8_t>;

constexpr VkImageLayout kDst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
constexpr VkImageLayout kSrc = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
constexpr VkImageUsageFlags kXfer = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
constexpr VkFormat kBc1 = VK_FORMAT_BC1_RGBA_UNORM_BLOCK, kUint = VK_FORMAT_R16G16B16A16_UINT;

uint8_t pattern(size_t i) {
    return uint8_t(i * 7 + (i >> 8) * 13 + 1);
}

class TransferBc : public TwoDriverSuite {};

// Source image A: BC1 22x14, 3 levels (6x4, 3x2 and 2x1 blocks), uploaded from a buffer whose rows hold 7 blocks
// (bufferRowLength 28 texels) and whose level 0 has 5 block rows (bufferImageHeight 20). Read-back layout, blocks of
// 8 bytes, tightly packed: A level 0 (24), level 1 (6), level 2 (2), U (the 4x4 UINT image, 16 texels), B level 0
// (24), B level 2 (2).
TEST_F(TransferBc, BlockCopies) {
    constexpr uint32_t kRowBlocks = 7, kBlock = 8;
    const size_t n = 4096, out_bytes = (24 + 6 + 2 + 16 + 24 + 2) * kBlock;
    auto scenario = [&](Device& d) {
        Device::Buffer src = d.make_buffer(n), dst = d.make_buffer(out_bytes);
        for (size_t i = 0; i < n; ++i) static_cast<uint8_t*>(src.map)[i] = pattern(i);
        std::memset(dst.map, 0, out_bytes);
        Device::Image a = d.make_image(kBc1, 22, 14, 3, 1, VK_SAMPLE_COUNT_1_BIT, kXfer);
        Device::Image b = d.make_image(kBc1, 22, 14, 3, 1, VK_SAMPLE_COUNT_1_BIT, kXfer);
        Device::Image u = d.make_image(kUint, 4, 4, 1, 1, VK_SAMPLE_COUNT_1_BIT, kXfer);
        d.run([&](VkCommandBuffer cb) {
            for (VkImage i : {a.image, b.image, u.image})
                transition(cb, i, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
            // A: level 0 in two regions (texels 0-7, then 8-21 from the third block column), levels 1 and 2 whole
            const VkImageSubresourceLayers l0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                l1{VK_IMAGE_ASPECT_COLOR_BIT, 1, 0, 1}, l2{VK_IMAGE_ASPECT_COLOR_BIT, 2, 0, 1};
            const VkBufferImageCopy up[] = {{0, 28, 20, l0, {0, 0, 0}, {8, 14, 1}},
                                            {2 * kBlock, 28, 20, l0, {8, 0, 0}, {14, 14, 1}},
                                            {1024, 28, 0, l1, {0, 0, 0}, {11, 7, 1}},
                                            {2048, 0, 0, l2, {0, 0, 0}, {5, 3, 1}}};
            vkCmdCopyBufferToImage(cb, src.buffer, a.image, kDst, 4, up);
            // B and U from the buffer too, so every byte read back is defined
            const VkBufferImageCopy fill_b[] = {{3072, 0, 0, l0, {0, 0, 0}, {22, 14, 1}},
                                                {3072, 0, 0, l2, {0, 0, 0}, {5, 3, 1}}};
            vkCmdCopyBufferToImage(cb, src.buffer, b.image, kDst, 2, fill_b);
            const VkBufferImageCopy fill_u{3584, 0, 0, l0, {0, 0, 0}, {4, 4, 1}};
            vkCmdCopyBufferToImage(cb, src.buffer, u.image, kDst, 1, &fill_u);
            transition(cb, a.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kSrc);
            transition(cb, b.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kDst);
            transition(cb, u.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kDst);
            // A level 0 blocks (1..3, 1..2) -> U texels (1..3, 2..3): the extent counts A's texels
            const VkImageCopy to_u{l0, {4, 4, 0}, l0, {1, 2, 0}, {12, 8, 1}};
            vkCmdCopyImage(cb, a.image, kSrc, u.image, kDst, 1, &to_u);
            // A level 2 block (1, 0), a partial block of one texel column -> B level 2 block (1, 0)
            const VkImageCopy edge{l2, {4, 0, 0}, l2, {4, 0, 0}, {1, 3, 1}};
            vkCmdCopyImage(cb, a.image, kSrc, b.image, kDst, 1, &edge);
            transition(cb, u.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kSrc);
            // U texels (0..1, 0..1) -> B level 0 blocks (2..3, 1..2): the extent counts U's texels
            const VkImageCopy from_u{l0, {0, 0, 0}, l0, {8, 4, 0}, {2, 2, 1}};
            vkCmdCopyImage(cb, u.image, kSrc, b.image, kDst, 1, &from_u);
            transition(cb, b.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kSrc);
            const VkBufferImageCopy down[] = {{0, 0, 0, l0, {0, 0, 0}, {22, 14, 1}},
                                              {24 * kBlock, 0, 0, l1, {0, 0, 0}, {11, 7, 1}},
                                              {30 * kBlock, 0, 0, l2, {0, 0, 0}, {5, 3, 1}}};
            vkCmdCopyImageToBuffer(cb, a.image, kSrc, dst.buffer, 3, down);
            const VkBufferImageCopy down_u{32 * kBlock, 0, 0, l0, {0, 0, 0}, {4, 4, 1}};
            vkCmdCopyImageToBuffer(cb, u.image, kSrc, dst.buffer, 1, &down_u);
            const VkBufferImageCopy down_b[] = {{48 * kBlock, 0, 0, l0, {0, 0, 0}, {22, 14, 1}},
                                                {72 * kBlock, 0, 0, l2, {0, 0, 0}, {5, 3, 1}}};
            vkCmdCopyImageToBuffer(cb, b.image, kSrc, dst.buffer, 2, down_b);
        });
        const uint8_t* p = static_cast<const uint8_t*>(dst.map);
        Bytes out(p, p + out_bytes);
        d.destroy(a);
        d.destroy(b);
        d.destroy(u);
        d.destroy(src);
        d.destroy(dst);
        return out;
    };
    const Bytes t = scenario(*tilevk_), l = scenario(*lavapipe_);
    EXPECT_EQ(t, l) << "tilevk and lavapipe differ";
    // the block moves, from the source buffer
    auto block = [&](size_t at, Bytes& out, size_t to) {
        for (size_t i = 0; i < kBlock; ++i) out[to * kBlock + i] = pattern(at + i);
    };
    Bytes want(out_bytes, 0);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 6; ++x) block((y * kRowBlocks + x) * kBlock, want, y * 6 + x);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 3; ++x) block(1024 + (y * kRowBlocks + x) * kBlock, want, 24 + y * 3 + x);
    for (uint32_t x = 0; x < 2; ++x) block(2048 + x * kBlock, want, 30 + x);
    for (uint32_t i = 0; i < 16; ++i) block(3584 + i * kBlock, want, 32 + i);  // U as uploaded...
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 3; ++x) {  // ...then A's blocks (1..3, 1..2) at (1..3, 2..3)
            block(((1 + y) * kRowBlocks + 1 + x) * kBlock, want, 32 + (2 + y) * 4 + 1 + x);
        }
    for (uint32_t i = 0; i < 24; ++i) block(3072 + i * kBlock, want, 48 + i);  // B level 0 as uploaded...
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 2; ++x) {  // ...then U's uploaded texels (0..1, 0..1) at blocks (2..3, 1..2)
            block(3584 + (y * 4 + x) * kBlock, want, 48 + (1 + y) * 6 + 2 + x);
        }
    block(3072, want, 72);           // B level 2 block 0 as uploaded
    block(2048 + kBlock, want, 73);  // block 1 from A level 2
    EXPECT_EQ(t, want) << "block moves";
}

// What both drivers answer for BC1-BC5 and BC6H/BC7: BC1-BC5 images of the sizes above can be made (2D, both
// tilings); tilevk refuses BC6H/BC7 (not decoded yet), 3D and cube-compatible BC images (not tested), and never
// reports textureCompressionBC before all of BC1-BC7 work.
TEST_F(TransferBc, FormatQueries) {
    VkPhysicalDeviceFeatures feats{};
    vkGetPhysicalDeviceFeatures(tilevk_->physical(), &feats);
    EXPECT_FALSE(feats.textureCompressionBC);
    VkImageFormatProperties props{};
    for (VkFormat f = VK_FORMAT_BC1_RGB_UNORM_BLOCK; f <= VK_FORMAT_BC5_SNORM_BLOCK; f = VkFormat(f + 1)) {
        for (VkImageTiling tiling : {VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_TILING_LINEAR}) {
            EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), f, VK_IMAGE_TYPE_2D, tiling,
                                                               VK_IMAGE_USAGE_SAMPLED_BIT | kXfer, 0, &props),
                      VK_SUCCESS)
                << f;
        }
        EXPECT_EQ(
            vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), f, VK_IMAGE_TYPE_3D, VK_IMAGE_TILING_OPTIMAL,
                                                     VK_IMAGE_USAGE_SAMPLED_BIT, 0, &props),
            VK_ERROR_FORMAT_NOT_SUPPORTED)
            << f;
        EXPECT_EQ(
            vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), f, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0, &props),
            VK_ERROR_FORMAT_NOT_SUPPORTED)
            << f;
    }
    for (VkFormat f : {VK_FORMAT_BC6H_UFLOAT_BLOCK, VK_FORMAT_BC6H_SFLOAT_BLOCK, VK_FORMAT_BC7_UNORM_BLOCK,
                       VK_FORMAT_BC7_SRGB_BLOCK}) {
        VkFormatProperties fp{};
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &fp);
        EXPECT_EQ(fp.optimalTilingFeatures | fp.linearTilingFeatures | fp.bufferFeatures, 0u) << f;
    }
}

}  // namespace
