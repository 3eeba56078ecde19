// Shared by the tests of images that are not plain 2D (image_1d_test.cpp, image_3d_test.cpp): the create info,
// the upload pattern, and the comparison of vkGetPhysicalDeviceImageFormatProperties rows with lavapipe's.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <vector>

#include "vk_harness.h"

namespace tilevk::test {

inline constexpr VkImageLayout kDst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
inline constexpr VkImageLayout kSrc = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
inline constexpr VkImageUsageFlags kXfer = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
inline constexpr VkImageAspectFlags kColor = VK_IMAGE_ASPECT_COLOR_BIT;

// An optimally tiled, single-sampled, exclusive image starting UNDEFINED.
inline VkImageCreateInfo image_info(VkImageType type, VkFormat format, VkExtent3D extent, uint32_t levels,
                                    uint32_t layers, VkImageUsageFlags usage) {
    return {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
            .imageType = type,
            .format = format,
            .extent = extent,
            .mipLevels = levels,
            .arrayLayers = layers,
            .samples = VK_SAMPLE_COUNT_1_BIT,
            .tiling = VK_IMAGE_TILING_OPTIMAL,
            .usage = usage,
            .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
}

// Upload bytes: no period of 256, so a texel copied from the wrong place shows.
inline uint8_t pattern(size_t i) {
    return uint8_t(i * 7 + (i >> 8) * 13 + 1);
}

using Bytes = std::vector<uint8_t>;

// The three images of a transfer scenario, as `image_nd_scenario` hands them to the recording.
struct ImageTrio {
    VkImage a, b, c;
};
using TrioRecorder = std::function<void(VkCommandBuffer, const ImageTrio&, VkBuffer up, VkBuffer down)>;

// On `d`: images made from `infos` and moved to TRANSFER_DST_OPTIMAL, an upload buffer of `up_bytes` holding
// pattern(i), a read-back buffer of `total` bytes preset to 0xcd; `record` adds the work to the same command
// buffer. Returns the read-back, or nothing when an image could not be made (a failed expectation).
inline Bytes image_nd_scenario(Device& d, const VkImageCreateInfo (&infos)[3], size_t up_bytes, size_t total,
                               const TrioRecorder& record) {
    Device::Buffer up = d.make_buffer(up_bytes), down = d.make_buffer(total);
    for (size_t i = 0; i < up_bytes; ++i) static_cast<uint8_t*>(up.map)[i] = pattern(i);
    std::memset(down.map, 0xcd, total);
    Device::Image images[3] = {d.make_image(infos[0]), d.make_image(infos[1]), d.make_image(infos[2])};
    bool made = true;
    for (const Device::Image& i : images) {
        EXPECT_NE(i.image, VK_NULL_HANDLE);
        made = made && i.image != VK_NULL_HANDLE;
    }
    Bytes out;
    if (made) {
        d.run([&](VkCommandBuffer cb) {
            for (const Device::Image& i : images) transition(cb, i.image, kColor, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
            record(cb, {images[0].image, images[1].image, images[2].image}, up.buffer, down.buffer);
        });
        const uint8_t* p = static_cast<const uint8_t*>(down.map);
        out.assign(p, p + total);
    }
    for (Device::Image& i : images) d.destroy(i);
    d.destroy(up);
    d.destroy(down);
    return out;
}

// Fixture of the limits-vs-lavapipe tests: both drivers' format query rows for one image type.
class ImageNdSuite : public TwoDriverSuite {
  protected:
    // Called with each (format, usage) row both drivers support: tilevk's and lavapipe's properties.
    using RowCheck = std::function<void(VkFormat, VkImageUsageFlags, const VkImageFormatProperties& tilevk,
                                        const VkImageFormatProperties& lavapipe)>;

    // Queries every format with every usage (optimal tiling, no flags) on both drivers: the VkResults must be
    // equal, and where both succeed, the extent, level count and sample counts (single sample) must be lavapipe's
    // before `check` sees the row. Returns how many rows both support.
    static int compare_format_rows(VkImageType type, std::span<const VkFormat> formats,
                                   std::span<const VkImageUsageFlags> usages, const RowCheck& check) {
        int supported = 0;
        for (VkFormat f : formats)
            for (VkImageUsageFlags u : usages) {
                VkImageFormatProperties t{}, l{};
                const VkResult rt = vkGetPhysicalDeviceImageFormatProperties(tilevk_->physical(), f, type,
                                                                             VK_IMAGE_TILING_OPTIMAL, u, 0, &t);
                const VkResult rl = vkGetPhysicalDeviceImageFormatProperties(lavapipe_->physical(), f, type,
                                                                             VK_IMAGE_TILING_OPTIMAL, u, 0, &l);
                EXPECT_EQ(rt, rl) << "format " << f << " usage " << u;
                if (rt != VK_SUCCESS || rl != VK_SUCCESS) continue;
                ++supported;
                EXPECT_EQ(t.maxExtent.width, l.maxExtent.width);
                EXPECT_EQ(t.maxExtent.height, l.maxExtent.height);
                EXPECT_EQ(t.maxExtent.depth, l.maxExtent.depth);
                EXPECT_EQ(t.maxMipLevels, l.maxMipLevels);
                EXPECT_EQ(t.sampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
                EXPECT_EQ(t.sampleCounts, l.sampleCounts);
                check(f, u, t, l);
            }
        return supported;
    }
};

}  // namespace tilevk::test
