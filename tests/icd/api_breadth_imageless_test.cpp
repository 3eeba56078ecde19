// VK_KHR_imageless_framebuffer (suite ApiImagelessFramebuffer): render passes begun with vkCmdBeginRenderPass on an
// imageless framebuffer (the views given by VkRenderPassAttachmentBeginInfo) give the same bytes as the same pass on
// a framebuffer made with those views, on each driver, and tilevk's equal lavapipe's (validation layer on); what
// tilevk refuses fails by name, and an imageless pass begun without its views renders nothing without crashing.
#include "api_breadth.h"
#include "api_breadth_input_scene.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

// VK_KHR_imageless_framebuffer and what vk.xml makes it require.
const std::vector<const char*> kExtensions = {VK_KHR_MAINTENANCE_2_EXTENSION_NAME,
                                              VK_KHR_IMAGE_FORMAT_LIST_EXTENSION_NAME,
                                              VK_KHR_IMAGELESS_FRAMEBUFFER_EXTENSION_NAME};

// What VkFramebufferAttachmentImageInfo says of an attachment's image (32x32, one layer, no create flags).
struct AttachmentImage {
    VkFormat format;
    VkImageUsageFlags usage;
};

// A framebuffer of 32x32, one layer: made with `views`, or imageless (described by `images`), in which case the
// views are given at each begin.
struct Fb {
    VkFramebuffer fb = VK_NULL_HANDLE;
    bool imageless = false;
    std::vector<VkImageView> views;
};

Fb framebuffer(Kit& k, VkRenderPass rp, const std::vector<VkImageView>& views,
               const std::vector<AttachmentImage>& images, bool imageless) {
    if (!imageless) return {k.framebuffer(rp, views, 32, 32), false, views};
    std::vector<VkFramebufferAttachmentImageInfo> infos;
    for (const AttachmentImage& a : images) {
        VkFramebufferAttachmentImageInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_ATTACHMENT_IMAGE_INFO};
        info.usage = a.usage;
        info.width = info.height = 32;
        info.layerCount = 1;
        info.viewFormatCount = 1;
        info.pViewFormats = &a.format;
        infos.push_back(info);
    }
    VkFramebufferAttachmentsCreateInfo ai{VK_STRUCTURE_TYPE_FRAMEBUFFER_ATTACHMENTS_CREATE_INFO};
    ai.attachmentImageInfoCount = uint32_t(infos.size());
    ai.pAttachmentImageInfos = infos.data();
    VkFramebufferCreateInfo ci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    ci.pNext = &ai;
    ci.flags = VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT;
    ci.renderPass = rp;
    ci.attachmentCount = uint32_t(infos.size());
    ci.width = ci.height = 32;
    ci.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateFramebuffer(k.d, &ci, nullptr, &fb), VK_SUCCESS);
    VkDevice d = k.d;
    k.undo(VK_OBJECT_TYPE_FRAMEBUFFER, fb, [d, fb] { vkDestroyFramebuffer(d, fb, nullptr); });
    return {fb, true, views};
}

// vkCmdBeginRenderPass over the whole 32x32, chaining the views when the framebuffer is imageless.
void begin(VkCommandBuffer c, VkRenderPass rp, const Fb& fb, const std::vector<VkClearValue>& clears) {
    VkRenderPassAttachmentBeginInfo given{VK_STRUCTURE_TYPE_RENDER_PASS_ATTACHMENT_BEGIN_INFO};
    given.attachmentCount = uint32_t(fb.views.size());
    given.pAttachments = fb.views.data();
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.pNext = fb.imageless ? &given : nullptr;
    bi.renderPass = rp;
    bi.framebuffer = fb.fb;
    bi.renderArea = {{0, 0}, {32, 32}};
    bi.clearValueCount = uint32_t(clears.size());
    bi.pClearValues = clears.data();
    vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
}

class ApiImagelessFramebuffer : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices() {
        imageless_.imagelessFramebuffer = VK_TRUE;
        return device_pair(kExtensions, &imageless_);
    }
    // Runs `scene` with a framebuffer made with views and with an imageless one: equal on each driver, and
    // tilevk's equal lavapipe's.
    void imageless_equals_views(const std::function<Bytes(Kit&, bool)>& scene) {
        auto dev = devices();
        both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) {
            const Bytes with_views = scene(k, false);
            const Bytes imageless = scene(k, true);
            expect_same(with_views, imageless, "framebuffer with views vs imageless");
            return imageless;
        });
    }
    VkPhysicalDeviceImagelessFramebufferFeatures imageless_{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGELESS_FRAMEBUFFER_FEATURES};
};

// One imageless framebuffer used for two images, each given at its vkCmdBeginRenderPass, each cleared to its own
// colour and drawn into.
TEST_F(ApiImagelessFramebuffer, TakesItsViewsAtEachBegin) {
    auto dev = devices();
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
        const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        Device::Image img[2] = {k.image(C, 32, 32, usage), k.image(C, 32, 32, usage)};
        VkImageView views[2] = {k.view(img[0].image, C, VK_IMAGE_ASPECT_COLOR_BIT),
                                k.view(img[1].image, C, VK_IMAGE_ASPECT_COLOR_BIT)};
        VkRenderPass rp = k.render_pass({attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)},
                                        {subpass(&kColour0)});
        Fb fb = framebuffer(k, rp, {}, {{C, usage}}, true);
        Pipe pp;
        pp.rp = rp;
        VkPipeline pipe = k.pipeline(pp);
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            for (uint32_t i = 0; i < 2; ++i) {
                fb.views = {views[i]};
                begin(c, rp, fb, {clear_color(0.25f * float(i + 1), 0, 1, 1)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                bind_vertices(c, vb);
                vkCmdDraw(c, 3, 1, 3 * i, 0);
                vkCmdEndRenderPass(c);
            }
        }),
                  VK_SUCCESS);
        const Bytes a = k.read(img[0].image, 32, 32, 4), b = k.read(img[1].image, 32, 32, 4);
        // Each image has its own clear at the corner (31, 0) no triangle covers, and its own triangle.
        EXPECT_EQ(px(a, 31, 0)[0], 64);
        EXPECT_EQ(px(b, 31, 0)[0], 128);
        EXPECT_NE(a, b);
        return concat({a, b});
    });
}

// 4x RGBA8 cleared, drawn into, partly cleared again with vkCmdClearAttachments and drawn over, resolved into a 1x
// image at the end of the subpass: the load, draw, clear and resolve each find the views given at begin.
Bytes msaa_scene(Kit& k, bool imageless) {
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageUsageFlags ms_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                            res_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    Device::Image ms = k.dev().make_image(C, 32, 32, 1, 1, VK_SAMPLE_COUNT_4_BIT, ms_usage);
    EXPECT_NE(ms.image, VK_NULL_HANDLE);
    k.undo(VK_OBJECT_TYPE_IMAGE, ms.image, [&k, ms]() mutable { k.dev().destroy(ms); });
    Device::Image res = k.image(C, 32, 32, res_usage);
    VkAttachmentDescription a0 = attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    a0.samples = VK_SAMPLE_COUNT_4_BIT;
    const VkAttachmentReference col{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
        resolve{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub = subpass(&col);
    sub.pResolveAttachments = &resolve;
    VkRenderPass rp =
        k.render_pass({a0, attachment(C, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE)}, {sub},
                      {{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0}});
    const Fb fb = framebuffer(
        k, rp, {k.view(ms.image, C, VK_IMAGE_ASPECT_COLOR_BIT), k.view(res.image, C, VK_IMAGE_ASPECT_COLOR_BIT)},
        {{C, ms_usage}, {C, res_usage}}, imageless);
    Pipe pp;
    pp.rp = rp;
    pp.samples = VK_SAMPLE_COUNT_4_BIT;
    pp.blend = {alpha_over()};
    VkPipeline pipe = k.pipeline(pp);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin(c, rp, fb, {clear_color(0.1f, 0.2f, 0.3f, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdDraw(c, 3, 1, 0, 0);
        VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 0.5f, 0, 1)};
        VkClearRect rect{{{4, 20}, {10, 8}}, 0, 1};
        vkCmdClearAttachments(c, 1, &ca, 1, &rect);
        vkCmdDraw(c, 3, 1, 3, 0);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    Bytes out = k.read(res.image, 32, 32, 4);
    // Spot checks: the corner keeps the load clear (0.1, 0.3 in 8 bits, within a step), and (5, 21) the
    // vkCmdClearAttachments colour (no triangle there).
    EXPECT_NEAR(px(out, 0, 31)[0], 25.5, 1.0);
    EXPECT_NEAR(px(out, 0, 31)[2], 76.5, 1.0);
    EXPECT_EQ(px(out, 5, 21)[0], 255);
    EXPECT_EQ(px(out, 5, 21)[1], 128);
    return out;
}

TEST_F(ApiImagelessFramebuffer, MsaaDrawClearResolveEqualTheFramebufferWithViews) {
    imageless_equals_views(msaa_scene);
}

// Two subpasses: subpass 0 draws colour (RGBA8) with a depth test (D32); subpass 1 (vkCmdNextSubpass) reads both as
// input attachments into an RGBA32F attachment: the depth target and the later subpass find the views given at begin.
Bytes input_scene(Kit& k, bool imageless) {
    InputScene s(k);
    VkRenderPass rp = k.render_pass(InputScene::attachments(), s.subpasses(), {InputScene::dependency()});
    const Fb fb = framebuffer(k, rp, s.views(),
                              {{InputScene::kColour, InputScene::kColourUsage},
                               {InputScene::kDepth, InputScene::kDepthUsage},
                               {InputScene::kOut, InputScene::kOutUsage}},
                              imageless);
    s.build(rp);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin(c, rp, fb, InputScene::clears());
        s.draw_subpass0(c);
        vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_INLINE);
        s.draw_subpass1(c);
        vkCmdEndRenderPass(c);
    }),
              VK_SUCCESS);
    return s.read_checked();
}

TEST_F(ApiImagelessFramebuffer, DepthAndInputAttachmentsAcrossSubpassesEqualTheFramebufferWithViews) {
    imageless_equals_views(input_scene);
}

// tilevk alone, without the validation layer (these are errors it would report): an imageless framebuffer begun
// without its views (no VkRenderPassAttachmentBeginInfo, or one of the wrong count) renders nothing, and the same
// framebuffer with its view renders after; the flag without the feature, a view mask of VkRenderPassMultiviewCreateInfo
// (the multiview feature is not enabled on this device) and subpass flags are refused by name.
TEST_F(ApiImagelessFramebuffer, RefusalsAndInvalidUsage) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    VkPhysicalDeviceImagelessFramebufferFeatures feature{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGELESS_FRAMEBUFFER_FEATURES};
    feature.imagelessFramebuffer = VK_TRUE;
    Device dev(plain.find_device("tilevk"), nullptr, kExtensions, &feature);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const std::vector<VkAttachmentDescription> atts = {
        attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)};
    std::vector<VkSubpassDescription> subs = {subpass(&kColour0)};
    Device::Image img = k.image(C, 32, 32, usage);
    VkImageView view = k.view(img.image, C, VK_IMAGE_ASPECT_COLOR_BIT);
    VkRenderPass rp = k.render_pass(atts, subs);
    Fb fb = framebuffer(k, rp, {}, {{C, usage}}, true);
    Pipe pp;
    pp.rp = rp;
    VkPipeline pipe = k.pipeline(pp);
    Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    const auto pass = [&](VkCommandBuffer c) {
        begin(c, rp, fb, {clear_color(0, 1, 0, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdDraw(c, 3, 1, 0, 0);
        VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 1, 1, 1)};
        VkClearRect rect{{{0, 0}, {4, 4}}, 0, 1};
        vkCmdClearAttachments(c, 1, &ca, 1, &rect);
        vkCmdEndRenderPass(c);
    };
    // The image is cleared to grey, then the pass begun without VkRenderPassAttachmentBeginInfo (fb.imageless false
    // chains nothing), then with one giving no views: neither load op, draw nor clear writes it.
    for (const bool chained : {false, true}) {
        fb.imageless = chained;
        fb.views.clear();
        StderrCapture capture;
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            transition(c, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkClearColorValue cc{{0.5f, 0.5f, 0.5f, 0.5f}};
            VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(c, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &cc, 1, &range);
            pass(c);
            transition(c, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        }),
                  VK_SUCCESS);
        EXPECT_NE(capture.text().find("VkRenderPassAttachmentBeginInfo"), std::string::npos) << "chained " << chained;
        const Bytes untouched = k.read(img.image, 32, 32, 4);
        for (size_t i = 0; i < untouched.size(); ++i) ASSERT_EQ(untouched[i], 128) << "byte " << i << " " << chained;
    }
    fb.imageless = true;
    fb.views = {view};
    EXPECT_EQ(k.run([&](VkCommandBuffer c) { pass(c); }), VK_SUCCESS);
    const Bytes drawn = k.read(img.image, 32, 32, 4);
    EXPECT_EQ(px(drawn, 1, 1)[0], 255);   // vkCmdClearAttachments
    EXPECT_EQ(px(drawn, 31, 0)[1], 255);  // the load clear
    EXPECT_EQ(px(drawn, 31, 0)[0], 0);
    VkRenderPassCreateInfo rci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rci.attachmentCount = 1;
    rci.pAttachments = atts.data();
    rci.subpassCount = 1;
    rci.pSubpasses = subs.data();
    const auto refused = [&](const char* name) {
        VkRenderPass r = VK_NULL_HANDLE;
        StderrCapture capture;
        EXPECT_EQ(vkCreateRenderPass(k.d, &rci, nullptr, &r), VK_ERROR_FEATURE_NOT_PRESENT) << name;
        EXPECT_NE(capture.text().find(name), std::string::npos) << name;
        EXPECT_EQ(r, VkRenderPass(VK_NULL_HANDLE)) << name;
    };
    {
        const uint32_t masks[1] = {3};
        VkRenderPassMultiviewCreateInfo mv{VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO};
        mv.subpassCount = 1;
        mv.pViewMasks = masks;
        rci.pNext = &mv;
        refused("VkRenderPassMultiviewCreateInfo::pViewMasks[0]");
        rci.pNext = nullptr;
    }
    subs[0].flags = VK_SUBPASS_DESCRIPTION_PER_VIEW_ATTRIBUTES_BIT_NVX;
    refused("VK_SUBPASS_DESCRIPTION_PER_VIEW_ATTRIBUTES_BIT_NVX");
    subs[0].flags = 0;
    // Without the imagelessFramebuffer feature the flag is refused.
    Device plain_dev(plain.find_device("tilevk"), nullptr, kExtensions, nullptr);
    ASSERT_TRUE(plain_dev.ok());
    Kit k2(plain_dev);
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.flags = VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT;
    fci.renderPass = k2.render_pass(atts, subs);
    fci.attachmentCount = 1;
    fci.width = fci.height = 32;
    fci.layers = 1;
    VkFramebuffer refused_fb = VK_NULL_HANDLE;
    StderrCapture capture;
    EXPECT_EQ(vkCreateFramebuffer(k2.d, &fci, nullptr, &refused_fb), VK_ERROR_FEATURE_NOT_PRESENT);
    EXPECT_NE(capture.text().find("imagelessFramebuffer"), std::string::npos);
    EXPECT_EQ(refused_fb, VkFramebuffer(VK_NULL_HANDLE));
}

}  // namespace
}  // namespace tilevk::test::breadth
