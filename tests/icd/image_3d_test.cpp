// 3D images (VK_IMAGE_TYPE_3D) on both drivers: what vkGetPhysicalDeviceImageFormatProperties reports, and copies
// and clears with 3D offsets and extents, whose read-back bytes must equal lavapipe's AND an expectation simulated
// here on plain arrays. Refusals (views and parameters tilevk does not implement) on tilevk alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "image_nd.h"

namespace {

using namespace tilevk::test;  // the harness and image_nd.h

class Image3D : public ImageNdSuite {};

// maxImageDimension3D and the 3D rows of vkGetPhysicalDeviceImageFormatProperties: lavapipe's values (compared) and
// llvmpipe's constants (lp_limits.h: 16384 wide and high, 1 << LP_MAX_TEXTURE_3D_LEVELS = 4096 deep as lavapipe
// computes it; 15 levels; one layer; one sample).
TEST_F(Image3D, LimitsAndFormatPropertiesAsLavapipe) {
    VkPhysicalDeviceProperties pt, pl;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &pt);
    vkGetPhysicalDeviceProperties(lavapipe_->physical(), &pl);
    EXPECT_EQ(pt.limits.maxImageDimension3D, 4096u);
    EXPECT_EQ(pt.limits.maxImageDimension3D, pl.limits.maxImageDimension3D);
    const VkFormat formats[] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8_UNORM,          VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_FORMAT_R32_SFLOAT,     VK_FORMAT_R32G32B32A32_UINT, VK_FORMAT_B8G8R8A8_SRGB};
    const VkImageUsageFlags usages[] = {kXfer, kXfer | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT};
    const int supported = compare_format_rows(
        VK_IMAGE_TYPE_3D, formats, usages,
        [](VkFormat, VkImageUsageFlags, const VkImageFormatProperties& t, const VkImageFormatProperties& l) {
            EXPECT_EQ(t.maxExtent.width, 16384u);
            EXPECT_EQ(t.maxExtent.height, 16384u);
            EXPECT_EQ(t.maxExtent.depth, 4096u);
            EXPECT_EQ(t.maxMipLevels, 15u);
            EXPECT_EQ(t.maxArrayLayers, 1u);
            EXPECT_EQ(t.maxArrayLayers, l.maxArrayLayers);
        });
    EXPECT_GE(supported, 15);
}

// The simulated contents of a tightly packed RGBA8 box, texel (x, y, z) at ((z*h + y)*w + x)*4.
struct Box {
    uint32_t w, h, d;
    Bytes b;
    Box(uint32_t w_, uint32_t h_, uint32_t d_) : w(w_), h(h_), d(d_), b(size_t(w_) * h_ * d_ * 4, 0) {}
    uint8_t* at(uint32_t x, uint32_t y, uint32_t z) { return &b[((size_t(z) * h + y) * w + x) * 4]; }
    void fill(const uint8_t (&t)[4]) {
        for (size_t i = 0; i < b.size(); i += 4) std::memcpy(&b[i], t, 4);
    }
};

// Copies a box of texels between simulated images (src offset so, dst offset dO, extent e).
void copy_box(Box& src, VkOffset3D so, Box& dst, VkOffset3D dO, VkExtent3D e) {
    for (uint32_t z = 0; z < e.depth; ++z)
        for (uint32_t y = 0; y < e.height; ++y)
            for (uint32_t x = 0; x < e.width; ++x)
                std::memcpy(dst.at(dO.x + x, dO.y + y, dO.z + z), src.at(so.x + x, so.y + y, so.z + z), 4);
}

// Buffer -> 3D image (whole level, padded rows and slices; a sub-box of level 1), clears of a whole 3D image and a
// 3D level (every slice), 3D -> 3D copies with z offsets, 3D slices -> 2D array layers (VK_KHR_maintenance1), and
// 3D -> buffer read-backs of whole levels and of a sub-box.
TEST_F(Image3D, CopiesAndClearsWithDepth) {
    constexpr uint32_t W = 9, H = 5, D = 6, kRow = 10, kSlice = 6;  // level 0 and its buffer's padded rows/slices
    constexpr VkDeviceSize kUp = VkDeviceSize(kRow) * kSlice * D * 4, kUp1 = 2 * 2 * 2 * 4;
    const uint8_t magenta[4] = {255, 0, 255, 0}, black[4] = {0, 0, 0, 255};
    // Read-back layout: A level 0 | A level 1 (4x2x3) | B (7x4x5) | C (4x3, 3 layers) | A's sub-box (3x2x2 in 4x3
    // rows and slices).
    const size_t a0 = 0, a1 = a0 + W * H * D * 4, b0 = a1 + 4 * 2 * 3 * 4, c0 = b0 + 7 * 4 * 5 * 4,
                 s0 = c0 + 4 * 3 * 3 * 4, total = s0 + 4 * 3 * 2 * 4;
    const VkImageCreateInfo infos[3] = {image_info(VK_IMAGE_TYPE_3D, VK_FORMAT_R8G8B8A8_UNORM, {W, H, D}, 2, 1, kXfer),
                                        image_info(VK_IMAGE_TYPE_3D, VK_FORMAT_R8G8B8A8_UNORM, {7, 4, 5}, 1, 1, kXfer),
                                        image_info(VK_IMAGE_TYPE_2D, VK_FORMAT_R8G8B8A8_UNORM, {4, 3, 1}, 1, 3, kXfer)};
    auto record = [&](VkCommandBuffer cb, const ImageTrio& im, VkBuffer up, VkBuffer down) {
        VkClearColorValue m{{1.0f, 0.0f, 1.0f, 0.0f}}, k{{0.0f, 0.0f, 0.0f, 1.0f}};
        VkImageSubresourceRange level1{kColor, 1, 1, 0, 1}, all{kColor, 0, 1, 0, 1};
        vkCmdClearColorImage(cb, im.a, kDst, &m, 1, &level1);
        vkCmdClearColorImage(cb, im.b, kDst, &k, 1, &all);
        vkCmdClearColorImage(cb, im.c, kDst, &k, 1, &all);  // layer 0 only; layers 1, 2 get copies
        VkBufferImageCopy whole{0, kRow, kSlice, {kColor, 0, 0, 1}, {0, 0, 0}, {W, H, D}};
        VkBufferImageCopy part{kUp, 0, 0, {kColor, 1, 0, 1}, {1, 0, 1}, {2, 2, 2}};
        VkBufferImageCopy ups[] = {whole, part};
        vkCmdCopyBufferToImage(cb, up, im.a, kDst, 2, ups);
        transition(cb, im.a, kColor, kDst, kSrc);
        VkImageCopy to_b{{kColor, 0, 0, 1}, {1, 1, 2}, {kColor, 0, 0, 1}, {2, 0, 1}, {4, 3, 3}};
        vkCmdCopyImage(cb, im.a, kSrc, im.b, kDst, 1, &to_b);
        VkImageCopy to_c{{kColor, 0, 0, 1}, {5, 2, 3}, {kColor, 0, 1, 2}, {0, 0, 0}, {4, 3, 2}};
        vkCmdCopyImage(cb, im.a, kSrc, im.c, kDst, 1, &to_c);
        transition(cb, im.b, kColor, kDst, kSrc);
        transition(cb, im.c, kColor, kDst, kSrc);
        VkBufferImageCopy downs[] = {{a0, 0, 0, {kColor, 0, 0, 1}, {0, 0, 0}, {W, H, D}},
                                     {a1, 0, 0, {kColor, 1, 0, 1}, {0, 0, 0}, {4, 2, 3}},
                                     {s0, 4, 3, {kColor, 0, 0, 1}, {2, 1, 3}, {3, 2, 2}}};
        vkCmdCopyImageToBuffer(cb, im.a, kSrc, down, 3, downs);
        VkBufferImageCopy down_b{b0, 0, 0, {kColor, 0, 0, 1}, {0, 0, 0}, {7, 4, 5}};
        vkCmdCopyImageToBuffer(cb, im.b, kSrc, down, 1, &down_b);
        VkBufferImageCopy down_c{c0, 0, 0, {kColor, 0, 0, 3}, {0, 0, 0}, {4, 3, 1}};
        vkCmdCopyImageToBuffer(cb, im.c, kSrc, down, 1, &down_c);
    };
    auto scenario = [&](Device& d) { return image_nd_scenario(d, infos, kUp + kUp1, total, record); };
    const Bytes t = scenario(*tilevk_), l = scenario(*lavapipe_);
    ASSERT_EQ(t.size(), total);
    ASSERT_EQ(l.size(), total);
    EXPECT_TRUE(t == l) << "tilevk and lavapipe differ";

    // Expected, simulated.
    Box A0(W, H, D), A1(4, 2, 3), B(7, 4, 5), C(4, 3, 3), S(4, 3, 2);
    for (uint32_t z = 0; z < D; ++z)
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x)
                for (int ch = 0; ch < 4; ++ch)
                    A0.at(x, y, z)[ch] = pattern(((size_t(z) * kSlice + y) * kRow + x) * 4 + ch);
    A1.fill(magenta);
    for (uint32_t z = 0; z < 2; ++z)
        for (uint32_t y = 0; y < 2; ++y)
            for (uint32_t x = 0; x < 2; ++x)
                for (int ch = 0; ch < 4; ++ch)
                    A1.at(1 + x, y, 1 + z)[ch] = pattern(kUp + ((z * 2 + y) * 2 + x) * 4 + ch);
    B.fill(black);
    copy_box(A0, {1, 1, 2}, B, {2, 0, 1}, {4, 3, 3});
    std::memset(C.b.data(), 0xcd, C.b.size());  // layers 1 and 2 are copied over whole; layer 0 is cleared
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 0; x < 4; ++x) std::memcpy(C.at(x, y, 0), black, 4);
    copy_box(A0, {5, 2, 3}, C, {0, 0, 1}, {4, 3, 2});
    std::memset(S.b.data(), 0xcd, S.b.size());  // the buffer's padding texels are not written
    copy_box(A0, {2, 1, 3}, S, {0, 0, 0}, {3, 2, 2});
    Bytes want;
    for (const Box* x : {&A0, &A1, &B, &C}) want.insert(want.end(), x->b.begin(), x->b.end());
    // The sub-box's last slice ends after its last row's 3 texels: the rest of that 4x3 slice is untouched 0xcd
    // already, as in S.
    want.insert(want.end(), S.b.begin(), S.b.end());
    EXPECT_TRUE(t == want) << "tilevk differs from the simulated copies";
}

// What tilevk refuses about 3D images, with the query's VkResult (no validation layer: these calls are invalid or
// unsupported on purpose), and the 3D view it makes.
TEST(Image3DRefusals, ViewsAndParameters) {
    Harness h(/*validation=*/false);
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice pd = h.find_device("tilevk");
    ASSERT_NE(pd, VK_NULL_HANDLE);
    Device d(pd);
    ASSERT_TRUE(d.ok());
    VkImage img = VK_NULL_HANDLE;
    const VkFormat rgba8 = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkImageCreateInfo deep = image_info(VK_IMAGE_TYPE_3D, rgba8, {4, 4, 4097}, 1, 1, sampled);
    EXPECT_EQ(vkCreateImage(d.device(), &deep, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);
    VkImageCreateInfo layered = image_info(VK_IMAGE_TYPE_3D, rgba8, {4, 4, 4}, 1, 2, sampled);
    EXPECT_EQ(vkCreateImage(d.device(), &layered, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);
    VkImageCreateInfo msaa = image_info(VK_IMAGE_TYPE_3D, rgba8, {4, 4, 4}, 1, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    msaa.samples = VK_SAMPLE_COUNT_4_BIT;
    EXPECT_EQ(vkCreateImage(d.device(), &msaa, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);
    // image3D is not implemented (shader/README.md): no STORAGE usage on 3D images, where lavapipe has it; SAMPLED
    // (sampler3D) is offered.
    VkImageFormatProperties props{};
    EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(pd, rgba8, VK_IMAGE_TYPE_3D, VK_IMAGE_TILING_OPTIMAL,
                                                       VK_IMAGE_USAGE_STORAGE_BIT, 0, &props),
              VK_ERROR_FORMAT_NOT_SUPPORTED);
    EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(pd, rgba8, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                                       VK_IMAGE_USAGE_STORAGE_BIT, 0, &props),
              VK_SUCCESS);
    EXPECT_EQ(vkGetPhysicalDeviceImageFormatProperties(pd, rgba8, VK_IMAGE_TYPE_3D, VK_IMAGE_TILING_OPTIMAL, sampled, 0,
                                                       &props),
              VK_SUCCESS);
    VkImageCreateInfo storage = image_info(VK_IMAGE_TYPE_3D, rgba8, {4, 4, 4}, 1, 1, VK_IMAGE_USAGE_STORAGE_BIT);
    EXPECT_EQ(vkCreateImage(d.device(), &storage, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);
    VkImageCreateInfo compat = image_info(VK_IMAGE_TYPE_3D, rgba8, {4, 4, 4}, 1, 1, sampled);
    compat.flags = VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
    EXPECT_EQ(vkCreateImage(d.device(), &compat, nullptr, &img), VK_ERROR_FORMAT_NOT_SUPPORTED);

    // A 3D image: its memory holds every slice of every level; a 3D view is made, a 2D view is refused.
    Device::Image ok = d.make_image(image_info(VK_IMAGE_TYPE_3D, rgba8, {8, 4, 16}, 3, 1, sampled | kXfer));
    ASSERT_NE(ok.image, VK_NULL_HANDLE);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d.device(), ok.image, &req);
    EXPECT_GE(req.size, VkDeviceSize(8 * 4 * 16 + 4 * 2 * 8 + 2 * 1 * 4) * 4);
    VkSubresourceLayout sl;
    VkImageSubresource sub{kColor, 1, 0};
    vkGetImageSubresourceLayout(d.device(), ok.image, &sub, &sl);
    EXPECT_EQ(sl.rowPitch, 4u * 4);
    EXPECT_GE(sl.depthPitch, 4u * 4 * 2);
    EXPECT_EQ(sl.size, sl.depthPitch * 8);
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = ok.image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_3D;
    vci.format = rgba8;
    vci.subresourceRange = {kColor, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateImageView(d.device(), &vci, nullptr, &view), VK_SUCCESS);
    vkDestroyImageView(d.device(), view, nullptr);
    for (VkImageViewType t : {VK_IMAGE_VIEW_TYPE_2D, VK_IMAGE_VIEW_TYPE_2D_ARRAY, VK_IMAGE_VIEW_TYPE_CUBE}) {
        vci.viewType = t;
        view = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(d.device(), &vci, nullptr, &view), VK_ERROR_FEATURE_NOT_PRESENT) << t;
    }
    d.destroy(ok);
}

}  // namespace
