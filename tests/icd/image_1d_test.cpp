// 1D images (VK_IMAGE_TYPE_1D) on both drivers: vkGetPhysicalDeviceImageFormatProperties for the usages tilevk
// offers (lavapipe's values), and copies, clears and blits of a 1D array image whose read-back bytes must equal
// lavapipe's (the copies also an expectation simulated here). The usages tilevk refuses for 1D (attachments,
// storage: not implemented), on tilevk alone. Sampling 1D images: cts texture.1d.*.
#include <gtest/gtest.h>

#include <cstring>

#include "image_nd.h"

namespace {

using namespace tilevk::test;  // the harness and image_nd.h

VkImageCreateInfo image_1d(uint32_t width, uint32_t levels, uint32_t layers, VkImageUsageFlags usage) {
    return image_info(VK_IMAGE_TYPE_1D, VK_FORMAT_R8G8B8A8_UNORM, {width, 1, 1}, levels, layers, usage);
}

class Image1D : public ImageNdSuite {};

// maxImageDimension1D and the 1D rows of the format query for transfer and sampled usage: lavapipe's answers
// (lvp_formats.c: the 2D width and level count, height and depth 1, one sample, no compressed formats); the array
// layers are tilevk's 2D limit.
TEST_F(Image1D, LimitsAndFormatPropertiesAsLavapipe) {
    VkPhysicalDeviceProperties pt, pl;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &pt);
    vkGetPhysicalDeviceProperties(lavapipe_->physical(), &pl);
    EXPECT_EQ(pt.limits.maxImageDimension1D, pl.limits.maxImageDimension1D);
    const VkFormat formats[] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8_UNORM,           VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_FORMAT_R32_SFLOAT,     VK_FORMAT_R32G32B32A32_UINT,  VK_FORMAT_B8G8R8A8_SRGB,
                                VK_FORMAT_D32_SFLOAT,     VK_FORMAT_BC1_RGB_UNORM_BLOCK};
    const VkImageUsageFlags usages[] = {kXfer, kXfer | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_USAGE_SAMPLED_BIT};
    const int supported = compare_format_rows(
        VK_IMAGE_TYPE_1D, formats, usages,
        [&](VkFormat f, VkImageUsageFlags, const VkImageFormatProperties& t, const VkImageFormatProperties&) {
            VkImageFormatProperties two_d{};
            EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), f, VK_IMAGE_TYPE_2D,
                                                               VK_IMAGE_TILING_OPTIMAL, kXfer, 0, &two_d),
                      VK_SUCCESS);
            EXPECT_EQ(t.maxExtent.width, pt.limits.maxImageDimension1D);
            EXPECT_EQ(t.maxExtent.height, 1u);
            EXPECT_EQ(t.maxExtent.depth, 1u);
            EXPECT_EQ(t.maxArrayLayers, two_d.maxArrayLayers);
        });
    EXPECT_GE(supported, 15);
    // not implemented for 1D (lavapipe offers them): rendering into a 1D view, image1D, input attachments
    const VkImageUsageFlags refused[] = {VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_USAGE_STORAGE_BIT,
                                         VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
    for (VkImageUsageFlags u : refused) {
        VkImageFormatProperties t{};
        EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), VK_FORMAT_R8G8B8A8_UNORM,
                                                           VK_IMAGE_TYPE_1D, VK_IMAGE_TILING_OPTIMAL, u, 0, &t),
                  VK_ERROR_FORMAT_NOT_SUPPORTED)
            << u;
    }
}

// Buffer -> 1D array (3 layers, padded layer stride through bufferImageHeight 1 and bufferRowLength), a clear of
// level 1, a 1D -> 1D copy across layers, 1D blits (scaled linear, mirrored nearest), read back whole.
TEST_F(Image1D, CopiesClearsAndBlits) {
    constexpr uint32_t W = 13, L = 3, kRow = 16;
    constexpr size_t a0 = 0, a1 = a0 + W * L * 4, b0 = a1 + 6 * L * 4, c0 = b0 + 9 * 2 * 4, total = c0 + 20 * 4;
    const uint8_t green[4] = {0, 255, 0, 255};
    const VkImageCreateInfo infos[3] = {image_1d(W, 2, L, kXfer | VK_IMAGE_USAGE_SAMPLED_BIT), image_1d(9, 1, 2, kXfer),
                                        image_1d(20, 1, 1, kXfer)};
    auto record = [&](VkCommandBuffer cb, const ImageTrio& im, VkBuffer up, VkBuffer down) {
        VkClearColorValue g{{0.0f, 1.0f, 0.0f, 1.0f}};
        VkImageSubresourceRange level1{kColor, 1, 1, 0, L}, all_b{kColor, 0, 1, 0, 2}, all_c{kColor, 0, 1, 0, 1};
        vkCmdClearColorImage(cb, im.a, kDst, &g, 1, &level1);
        vkCmdClearColorImage(cb, im.b, kDst, &g, 1, &all_b);
        vkCmdClearColorImage(cb, im.c, kDst, &g, 1, &all_c);
        VkBufferImageCopy whole{0, kRow, 1, {kColor, 0, 0, L}, {0, 0, 0}, {W, 1, 1}};
        vkCmdCopyBufferToImage(cb, up, im.a, kDst, 1, &whole);
        transition(cb, im.a, kColor, kDst, kSrc);
        VkImageCopy to_b{{kColor, 0, 1, 2}, {3, 0, 0}, {kColor, 0, 0, 2}, {1, 0, 0}, {7, 1, 1}};
        vkCmdCopyImage(cb, im.a, kSrc, im.b, kDst, 1, &to_b);
        VkImageBlit scaled{{kColor, 0, 2, 1}, {{1, 0, 0}, {12, 1, 1}}, {kColor, 0, 0, 1}, {{0, 0, 0}, {15, 1, 1}}};
        vkCmdBlitImage(cb, im.a, kSrc, im.c, kDst, 1, &scaled, VK_FILTER_LINEAR);
        VkImageBlit mirrored{{kColor, 0, 0, 1}, {{0, 0, 0}, {13, 1, 1}}, {kColor, 0, 0, 1}, {{20, 0, 0}, {16, 1, 1}}};
        vkCmdBlitImage(cb, im.a, kSrc, im.c, kDst, 1, &mirrored, VK_FILTER_NEAREST);
        transition(cb, im.b, kColor, kDst, kSrc);
        transition(cb, im.c, kColor, kDst, kSrc);
        VkBufferImageCopy downs[] = {{a0, 0, 0, {kColor, 0, 0, L}, {0, 0, 0}, {W, 1, 1}},
                                     {a1, 0, 0, {kColor, 1, 0, L}, {0, 0, 0}, {6, 1, 1}}};
        vkCmdCopyImageToBuffer(cb, im.a, kSrc, down, 2, downs);
        VkBufferImageCopy down_b{b0, 0, 0, {kColor, 0, 0, 2}, {0, 0, 0}, {9, 1, 1}};
        vkCmdCopyImageToBuffer(cb, im.b, kSrc, down, 1, &down_b);
        VkBufferImageCopy down_c{c0, 0, 0, {kColor, 0, 0, 1}, {0, 0, 0}, {20, 1, 1}};
        vkCmdCopyImageToBuffer(cb, im.c, kSrc, down, 1, &down_c);
    };
    auto scenario = [&](Device& d) { return image_nd_scenario(d, infos, kRow * L * 4, total, record); };
    const Bytes t = scenario(*tilevk_), l = scenario(*lavapipe_);
    ASSERT_EQ(t.size(), total);
    ASSERT_EQ(l.size(), total);
    for (size_t i = 0; i < total; ++i) {
        EXPECT_EQ(t[i], l[i]) << "byte " << i << " differs from lavapipe";
        if (t[i] != l[i]) break;
    }
    // The copies and clears, simulated (the blits are lavapipe's word only).
    Bytes want(c0);
    for (uint32_t layer = 0; layer < L; ++layer)
        for (uint32_t x = 0; x < W; ++x)
            for (uint32_t ch = 0; ch < 4; ++ch) want[(layer * W + x) * 4 + ch] = pattern((layer * kRow + x) * 4 + ch);
    for (size_t i = a1; i < b0; i += 4) std::memcpy(&want[i], green, 4);
    for (size_t i = b0; i < c0; i += 4) std::memcpy(&want[i], green, 4);
    for (uint32_t layer = 0; layer < 2; ++layer)
        for (uint32_t x = 0; x < 7; ++x)
            std::memcpy(&want[b0 + (layer * 9 + 1 + x) * 4], &want[((1 + layer) * W + 3 + x) * 4], 4);
    EXPECT_TRUE(Bytes(t.begin(), t.begin() + c0) == want) << "tilevk differs from the simulated copies";
}

// A 1D image's views: 1D and 1D_ARRAY are made; 2D views of it are refused with VK_ERROR_FEATURE_NOT_PRESENT.
TEST(Image1DRefusals, Views) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    Device d(pd);
    ASSERT_TRUE(d.ok());
    Device::Image img = d.make_image(image_1d(16, 2, 3, VK_IMAGE_USAGE_SAMPLED_BIT));
    ASSERT_NE(img.image, VK_NULL_HANDLE);
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = img.image;
    vci.format = VK_FORMAT_R8G8B8A8_UNORM;
    vci.subresourceRange = {kColor, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
    for (VkImageViewType t : {VK_IMAGE_VIEW_TYPE_1D, VK_IMAGE_VIEW_TYPE_1D_ARRAY}) {
        vci.viewType = t;
        VkImageView view = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(d.device(), &vci, nullptr, &view), VK_SUCCESS) << t;
        vkDestroyImageView(d.device(), view, nullptr);
    }
    for (VkImageViewType t : {VK_IMAGE_VIEW_TYPE_2D, VK_IMAGE_VIEW_TYPE_2D_ARRAY, VK_IMAGE_VIEW_TYPE_3D}) {
        vci.viewType = t;
        VkImageView view = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(d.device(), &vci, nullptr, &view), VK_ERROR_FEATURE_NOT_PRESENT) << t;
    }
    d.destroy(img);
}

}  // namespace
