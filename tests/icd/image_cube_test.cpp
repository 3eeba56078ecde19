// Cube-compatible images and cube / cube-array views: what both drivers report (format properties with
// VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT, imageCubeArray, maxImageDimensionCube), and the creation rules tilevk checks
// (square, at least 6 layers; views of 6 layers or a multiple of 6 of a cube-compatible image). Sampling is
// compared with lavapipe by cts texture.cube.* and tested in tests/shader/texture_cube_test.cpp.
#include <gtest/gtest.h>

#include "vk_harness.h"

namespace {

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::TwoDriverSuite;

constexpr VkImageAspectFlags kColor = VK_IMAGE_ASPECT_COLOR_BIT;

VkImageCreateInfo cube_info(uint32_t w, uint32_t h, uint32_t layers, VkImageCreateFlags flags) {
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.flags = flags;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = VK_FORMAT_R8G8B8A8_UNORM;
    ci.extent = {w, h, 1};
    ci.mipLevels = 3;
    ci.arrayLayers = layers;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    return ci;
}

class ImageCube : public TwoDriverSuite {};

// Cube-compatible rows of vkGetPhysicalDeviceImageFormatProperties equal lavapipe's but for the layer count
// (lvp_formats.c: the 2D limits with one sample, also for attachment formats that have 4x as plain 2D images);
// imageCubeArray on both; maxImageDimensionCube is the 2D limit (lavapipe's 32768 is past its own maxExtent:
// icd/README.md "Limits").
TEST_F(ImageCube, FormatPropertiesFeatureAndLimit) {
    const VkFormat formats[] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32_SFLOAT,
                                VK_FORMAT_D32_SFLOAT, VK_FORMAT_B8G8R8A8_SRGB};
    const VkImageUsageFlags usages[] = {VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
    int supported = 0;
    for (VkFormat f : formats)
        for (VkImageUsageFlags u : usages) {
            VkImageFormatProperties t{}, l{};
            const VkImageCreateFlags cube = VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
            const VkResult rt = vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), f, VK_IMAGE_TYPE_2D,
                                                                         VK_IMAGE_TILING_OPTIMAL, u, cube, &t);
            const VkResult rl = vkGetPhysicalDeviceImageFormatProperties(lavapipe_->physical(), f, VK_IMAGE_TYPE_2D,
                                                                         VK_IMAGE_TILING_OPTIMAL, u, cube, &l);
            EXPECT_EQ(rt, rl) << "format " << f << " usage " << u;
            if (rt != VK_SUCCESS || rl != VK_SUCCESS) continue;
            ++supported;
            EXPECT_EQ(t.sampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
            EXPECT_EQ(t.sampleCounts, l.sampleCounts);
            EXPECT_EQ(t.maxExtent.width, l.maxExtent.width);
            EXPECT_EQ(t.maxExtent.height, l.maxExtent.height);
            EXPECT_EQ(t.maxMipLevels, l.maxMipLevels);
            EXPECT_EQ(t.maxArrayLayers, 256u);  // tilevk's layer limit for every 2D image (lavapipe: 2048)
        }
    EXPECT_GE(supported, 6);
    // a 3D image cannot be cube compatible
    VkImageFormatProperties p{};
    EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_TYPE_3D,
                                                       VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_USAGE_SAMPLED_BIT,
                                                       VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT, &p),
              VK_ERROR_FORMAT_NOT_SUPPORTED);
    VkPhysicalDeviceFeatures ft{}, fl{};
    vkGetPhysicalDeviceFeatures(tilevk_->physical(), &ft);
    vkGetPhysicalDeviceFeatures(lavapipe_->physical(), &fl);
    EXPECT_EQ(ft.imageCubeArray, VK_TRUE);
    EXPECT_EQ(ft.imageCubeArray, fl.imageCubeArray);
    VkPhysicalDeviceProperties pt;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &pt);
    EXPECT_EQ(pt.limits.maxImageDimensionCube, pt.limits.maxImageDimension2D);
}

// The rules, on tilevk alone (no validation layer: the refused calls are invalid on purpose).
TEST(ImageCubeRules, CreationAndViews) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    VkPhysicalDeviceFeatures features{};
    features.imageCubeArray = VK_TRUE;
    Device d(pd, &features);
    ASSERT_TRUE(d.ok());
    const VkImageCreateFlags cube = VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    VkImage img = VK_NULL_HANDLE;
    VkImageCreateInfo not_square = cube_info(8, 4, 6, cube);
    EXPECT_EQ(vkCreateImage(d.device(), &not_square, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);
    VkImageCreateInfo five = cube_info(8, 8, 5, cube);
    EXPECT_EQ(vkCreateImage(d.device(), &five, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);
    VkImageCreateInfo four_x = cube_info(8, 8, 6, cube);
    four_x.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    four_x.mipLevels = 1;
    four_x.samples = VK_SAMPLE_COUNT_4_BIT;
    EXPECT_EQ(vkCreateImage(d.device(), &four_x, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);

    Device::Image twelve = d.make_image(cube_info(8, 8, 12, cube));
    Device::Image plain = d.make_image(cube_info(8, 8, 6, 0));
    ASSERT_NE(twelve.image, VK_NULL_HANDLE);
    ASSERT_NE(plain.image, VK_NULL_HANDLE);
    struct View {
        VkImage image;
        VkImageViewType type;
        uint32_t base, count;
        VkResult want;
    };
    const View views[] = {
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE, 0, 6, VK_SUCCESS},
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE, 6, 6, VK_SUCCESS},
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 0, 12, VK_SUCCESS},
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 6, VK_REMAINING_ARRAY_LAYERS, VK_SUCCESS},
        {twelve.image, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 12, VK_SUCCESS},  // the layers as a 2D array
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE, 0, 12, VK_ERROR_FORMAT_NOT_SUPPORTED},
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 0, 8, VK_ERROR_FORMAT_NOT_SUPPORTED},
        {twelve.image, VK_IMAGE_VIEW_TYPE_CUBE_ARRAY, 4, VK_REMAINING_ARRAY_LAYERS, VK_ERROR_FORMAT_NOT_SUPPORTED},
        {plain.image, VK_IMAGE_VIEW_TYPE_CUBE, 0, 6, VK_ERROR_FORMAT_NOT_SUPPORTED},
    };
    for (const View& v : views) {
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = v.image;
        vci.viewType = v.type;
        vci.format = VK_FORMAT_R8G8B8A8_UNORM;
        vci.subresourceRange = {kColor, 0, VK_REMAINING_MIP_LEVELS, v.base, v.count};
        VkImageView view = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(d.device(), &vci, nullptr, &view), v.want)
            << "type " << v.type << " layers " << v.base << "+" << v.count;
        if (view != VK_NULL_HANDLE) vkDestroyImageView(d.device(), view, nullptr);
    }
    d.destroy(twelve);
    d.destroy(plain);
}

}  // namespace
