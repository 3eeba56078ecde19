// Images made with VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT (suite ApiMutableFormat), on tilevk and lavapipe with the
// validation layer on: an R8G8B8A8_UNORM image rendered through an sRGB view (load-op clear, blended draw) and read
// back through both views, byte for byte equal between the drivers; and the views tilevk refuses.
#include "api_breadth.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

using ApiMutableFormat = ApiBreadth;

constexpr uint32_t kSize = 16;
constexpr VkFormat kViewFormats[2] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB};

Device::Image mutable_image(Kit& k, VkImageUsageFlags usage) {
    VkImageFormatListCreateInfo list{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO, nullptr, 2, kViewFormats};
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, &list};
    ci.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = kViewFormats[0];
    ci.extent = {kSize, kSize, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.usage = usage;
    Device::Image img = k.dev().make_image(ci);
    EXPECT_NE(img.image, VK_NULL_HANDLE);
    k.undo(VK_OBJECT_TYPE_IMAGE, img.image, [&k, img]() mutable { k.dev().destroy(img); });
    return img;
}

// Samples `img` through a view of `f` at the pixel centres of a float target; returns the target's bytes.
Bytes sample_through(Kit& k, VkImage img, VkFormat f) {
    Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, kSize, kSize);
    const auto [dsl, layout, set] = sampler_set(k);
    VkDescriptorImageInfo ii{k.sampler(), k.view(img, f, VK_IMAGE_ASPECT_COLOR_BIT),
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
    VkPipeline pipe = k.pipeline(fullscreen_pipe(SPV(ab_sample_frag), tg, layout));
    EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
    return k.read(tg.image.image, kSize, kSize, 16);
}

// Rendered through the sRGB view: the clear and the blend work in linear light and store the sRGB encoding; the
// stored bytes, and what the UNORM and sRGB views read back, are lavapipe's. The sRGB bytes also differ from what a
// plain UNORM target stores (the view's format is not ignored).
TEST_F(ApiMutableFormat, RenderThroughAnSrgbViewAndSampleThroughBoth) {
    Bytes unorm_target;
    const Bytes all = both([&](Kit& k) {
        Target plain = target(k, VK_FORMAT_R8G8B8A8_UNORM, kSize, kSize);
        Pipe p;
        p.rp = plain.rp;
        p.width = p.height = kSize;
        p.blend = {alpha_over()};
        VkPipeline plain_pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kTriangle2, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        const auto draw = [&](VkCommandBuffer c, VkRenderPass rp, VkFramebuffer fb, VkPipeline pipe) {
            begin_pass(c, rp, fb, kSize, kSize, {clear_color(0.5f, 0.25f, 0.75f, 0.6f)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        };
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw(c, plain.rp, plain.fb, plain_pipe); }), VK_SUCCESS);
        unorm_target = k.read(plain.image.image, kSize, kSize, 4);

        Device::Image img = mutable_image(
            k, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        VkRenderPass rp =
            k.render_pass({attachment(kViewFormats[1], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)},
                          {subpass(&kColour0)});
        VkFramebuffer fb =
            k.framebuffer(rp, {k.view(img.image, kViewFormats[1], VK_IMAGE_ASPECT_COLOR_BIT)}, kSize, kSize);
        p.rp = rp;
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw(c, rp, fb, pipe); }), VK_SUCCESS);
        Bytes stored = k.read(img.image, kSize, kSize, 4);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            transition(c, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }),
                  VK_SUCCESS);
        return concat(
            {stored, sample_through(k, img.image, kViewFormats[0]), sample_through(k, img.image, kViewFormats[1])});
    });
    ASSERT_EQ(all.size(), kSize * kSize * (4 + 16 + 16));
    // Pixel (0, 0) holds the clear only: red 0.5 is 128 in UNORM and its sRGB encoding (0.735 * 255) through the view.
    EXPECT_EQ(unorm_target[0], 128);
    EXPECT_GE(all[0], 186);
    EXPECT_LE(all[0], 189);
    EXPECT_NE(Bytes(all.begin(), all.begin() + kSize * kSize * 4), unorm_target);
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

// A view of another format needs VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT and a colour format of the same texel size;
// tilevk refuses the rest by name instead of reinterpreting bytes it cannot. Invalid usage on purpose: no layer.
TEST(MutableFormatRefusals, ViewsOfOtherFormatsNeedTheFlagAndOneTexelSize) {
    Harness h(false);
    ASSERT_TRUE(h.instance() != VK_NULL_HANDLE);
    Device dev(h.find_device("tilevk"));
    ASSERT_TRUE(dev.ok());
    const auto try_view = [&](VkImage img, VkFormat f) {
        VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        ci.image = img;
        ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        ci.format = f;
        ci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        StderrCapture err;
        const VkResult r = vkCreateImageView(dev.device(), &ci, nullptr, &v);
        const std::string text = err.text();
        if (v != VK_NULL_HANDLE) vkDestroyImageView(dev.device(), v, nullptr);
        if (r != VK_SUCCESS) {
            EXPECT_NE(text.find("VUID-VkImageViewCreateInfo-image-01761"), std::string::npos) << text;
        }
        return r;
    };
    Device::Image fixed =
        dev.make_image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, 1, 1, VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_USAGE_SAMPLED_BIT);
    EXPECT_EQ(try_view(fixed.image, VK_FORMAT_R8G8B8A8_UNORM), VK_SUCCESS);
    EXPECT_EQ(try_view(fixed.image, VK_FORMAT_R8G8B8A8_SRGB), VK_ERROR_FORMAT_NOT_SUPPORTED);
    dev.destroy(fixed);
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = VK_FORMAT_R8G8B8A8_UNORM;
    ci.extent = {4, 4, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    Device::Image mut = dev.make_image(ci);
    ASSERT_NE(mut.image, VK_NULL_HANDLE);
    EXPECT_EQ(try_view(mut.image, VK_FORMAT_R8G8B8A8_SRGB), VK_SUCCESS);
    EXPECT_EQ(try_view(mut.image, VK_FORMAT_R32_UINT), VK_SUCCESS);  // one 4-byte size class
    EXPECT_EQ(try_view(mut.image, VK_FORMAT_R16G16B16A16_UNORM), VK_ERROR_FORMAT_NOT_SUPPORTED);
    dev.destroy(mut);
}

}  // namespace
}  // namespace tilevk::test::breadth
