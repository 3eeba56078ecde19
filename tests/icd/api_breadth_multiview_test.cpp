// VK_KHR_multiview (suite ApiMultiview): render passes with view masks draw every view into its own layer of a 2D
// array image, gl_ViewIndex telling the shaders which (vertex and fragment stage); load-op clears,
// vkCmdClearAttachments and resolves cover the views of the mask and leave the other layers alone. Every layer is
// compared byte for byte with lavapipe (validation layer on); refusals are checked on tilevk alone.
#include "api_breadth.h"
// After api_breadth.h (<cstdint>): the generated SPIR-V arrays include nothing themselves.
#include "ab_multiview_frag.h"
#include "ab_multiview_vert.h"

namespace tilevk::test::breadth {
namespace {

const std::vector<const char*> kExtensions = {VK_KHR_MULTIVIEW_EXTENSION_NAME};
// VK_KHR_create_renderpass2 and what vk.xml makes it require.
const std::vector<const char*> kExtensions2 = {VK_KHR_MULTIVIEW_EXTENSION_NAME, VK_KHR_MAINTENANCE_2_EXTENSION_NAME,
                                               VK_KHR_CREATE_RENDERPASS_2_EXTENSION_NAME};

// One multiview scene: a colour attachment of `layers` layers (4x and resolved into a 1x image when `msaa`), a pass
// whose one subpass renders the views of `mask`, a draw of `instances` instances, optionally a vkCmdClearAttachments
// and a second draw.
struct Scene {
    uint32_t mask = 0b11;
    uint32_t layers = 2;
    bool msaa = false;
    uint32_t instances = 1;
    bool clear_attachments = false;
    bool separate_instances = false;  // one vkCmdDraw per instance (firstInstance i) instead of one instanced draw
    // VK_KHR_create_renderpass2: the pass made with vkCreateRenderPass2KHR (viewMask in VkSubpassDescription2, aspect
    // masks in VkAttachmentReference2) and run with vkCmdBeginRenderPass2KHR / vkCmdEndRenderPass2KHR.
    bool rp2 = false;
};

// The pass of multiview_pass in its VK_KHR_create_renderpass2 form.
VkRenderPass multiview_pass2(Kit& k, const std::vector<VkAttachmentDescription>& atts, const VkSubpassDescription& sub,
                             const VkSubpassDependency& dep, uint32_t mask) {
    std::vector<VkAttachmentDescription2> atts2;
    for (const VkAttachmentDescription& a : atts) {
        VkAttachmentDescription2 a2{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
        a2.format = a.format;
        a2.samples = a.samples;
        a2.loadOp = a.loadOp;
        a2.storeOp = a.storeOp;
        a2.stencilLoadOp = a.stencilLoadOp;
        a2.stencilStoreOp = a.stencilStoreOp;
        a2.initialLayout = a.initialLayout;
        a2.finalLayout = a.finalLayout;
        atts2.push_back(a2);
    }
    const auto ref2 = [](const VkAttachmentReference& r) {
        return VkAttachmentReference2{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, r.attachment, r.layout,
                                      VK_IMAGE_ASPECT_COLOR_BIT};
    };
    const VkAttachmentReference2 col = ref2(sub.pColorAttachments[0]);
    const VkAttachmentReference2 res = sub.pResolveAttachments != nullptr ? ref2(sub.pResolveAttachments[0]) : col;
    VkSubpassDescription2 sub2{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2};
    sub2.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub2.viewMask = mask;
    sub2.colorAttachmentCount = 1;
    sub2.pColorAttachments = &col;
    sub2.pResolveAttachments = sub.pResolveAttachments != nullptr ? &res : nullptr;
    VkSubpassDependency2 dep2{VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2};
    dep2.srcSubpass = dep.srcSubpass;
    dep2.dstSubpass = dep.dstSubpass;
    dep2.srcStageMask = dep.srcStageMask;
    dep2.dstStageMask = dep.dstStageMask;
    dep2.srcAccessMask = dep.srcAccessMask;
    dep2.dstAccessMask = dep.dstAccessMask;
    VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
    ci.attachmentCount = uint32_t(atts2.size());
    ci.pAttachments = atts2.data();
    ci.subpassCount = 1;
    ci.pSubpasses = &sub2;
    ci.dependencyCount = 1;
    ci.pDependencies = &dep2;
    ci.correlatedViewMaskCount = 1;  // a hint: accepted
    ci.pCorrelatedViewMasks = &mask;
    VkRenderPass rp = VK_NULL_HANDLE;
    EXPECT_EQ(device_proc<PFN_vkCreateRenderPass2KHR>(k, "vkCreateRenderPass2KHR")(k.d, &ci, nullptr, &rp), VK_SUCCESS);
    if (rp != VK_NULL_HANDLE) {
        VkDevice d = k.d;
        k.undo(VK_OBJECT_TYPE_RENDER_PASS, rp, [d, rp] { vkDestroyRenderPass(d, rp, nullptr); });
    }
    return rp;
}

constexpr VkFormat kC = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkClearColorValue kPrefill{{0.5f, 0.5f, 0.5f, 1.0f}};

VkRenderPass multiview_pass(Kit& k, const Scene& s, const uint32_t* mask, VkResult expect = VK_SUCCESS) {
    std::vector<VkAttachmentDescription> atts;
    VkAttachmentDescription out = attachment(kC, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
    out.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;  // pre-filled: the layers outside the mask keep it
    const VkAttachmentReference col{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
        resolve{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub = subpass(&col);
    if (s.msaa) {
        VkAttachmentDescription ms = attachment(kC, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        ms.samples = VK_SAMPLE_COUNT_4_BIT;
        out.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        atts = {ms, out};
        sub.pResolveAttachments = &resolve;
    } else {
        atts = {out};
    }
    const VkSubpassDependency dep{VK_SUBPASS_EXTERNAL,
                                  0,
                                  VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                  VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                  VK_ACCESS_TRANSFER_WRITE_BIT,
                                  VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT,
                                  0};
    if (s.rp2) return multiview_pass2(k, atts, sub, dep, *mask);
    VkRenderPassMultiviewCreateInfo mv{VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO};
    mv.subpassCount = 1;
    mv.pViewMasks = mask;
    mv.correlationMaskCount = 1;  // a hint: accepted
    mv.pCorrelationMasks = mask;
    VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    ci.pNext = &mv;
    ci.attachmentCount = uint32_t(atts.size());
    ci.pAttachments = atts.data();
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    ci.dependencyCount = 1;
    ci.pDependencies = &dep;
    VkRenderPass rp = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateRenderPass(k.d, &ci, nullptr, &rp), expect);
    if (rp != VK_NULL_HANDLE) {
        VkDevice d = k.d;
        k.undo(VK_OBJECT_TYPE_RENDER_PASS, rp, [d, rp] { vkDestroyRenderPass(d, rp, nullptr); });
    }
    return rp;
}

// Renders the scene and returns every layer of the (resolved) image, layer after layer.
Bytes multiview_scene(Kit& k, const Scene& s) {
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Device::Image out = k.image(kC, 32, 32, usage, 1, s.layers);
    std::vector<VkImageView> views;
    if (s.msaa) {
        Device::Image ms =
            k.dev().make_image(kC, 32, 32, 1, s.layers, VK_SAMPLE_COUNT_4_BIT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        EXPECT_NE(ms.image, VK_NULL_HANDLE);
        k.undo(VK_OBJECT_TYPE_IMAGE, ms.image, [&k, ms]() mutable { k.dev().destroy(ms); });
        views.push_back(
            k.view(ms.image, kC, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0, s.layers));
    }
    views.push_back(k.view(out.image, kC, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0, s.layers));
    VkRenderPass rp = multiview_pass(k, s, &s.mask);
    VkFramebuffer fb = k.framebuffer(rp, views, 32, 32, 1);  // multiview: one framebuffer layer
    Pipe pp;
    pp.vs = SPV(ab_multiview_vert);
    pp.fs = SPV(ab_multiview_frag);
    pp.rp = rp;
    pp.samples = s.msaa ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
    pp.blend = {alpha_over()};
    VkPipeline pipe = k.pipeline(pp);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, out.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, s.layers};
        vkCmdClearColorImage(c, out.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &kPrefill, 1, &range);
        std::vector<VkClearValue> clears(views.size(), clear_color(0.1f, 0.2f, 0.3f, 1));
        if (s.rp2) {
            VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
            bi.renderPass = rp;
            bi.framebuffer = fb;
            bi.renderArea = {{0, 0}, {32, 32}};
            bi.clearValueCount = uint32_t(clears.size());
            bi.pClearValues = clears.data();
            const VkSubpassBeginInfo sbi{VK_STRUCTURE_TYPE_SUBPASS_BEGIN_INFO, nullptr, VK_SUBPASS_CONTENTS_INLINE};
            device_proc<PFN_vkCmdBeginRenderPass2KHR>(k, "vkCmdBeginRenderPass2KHR")(c, &bi, &sbi);
        } else {
            begin_pass(c, rp, fb, 32, 32, clears);
        }
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        if (s.separate_instances) {
            for (uint32_t i = 0; i < s.instances; ++i) vkCmdDraw(c, 3, 1, 0, i);
        } else {
            vkCmdDraw(c, 3, s.instances, 0, 0);
        }
        if (s.clear_attachments) {
            const VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 0.5f, 0, 1)};
            const VkClearRect rect{{{4, 20}, {10, 8}}, 0, 1};
            vkCmdClearAttachments(c, 1, &ca, 1, &rect);
            vkCmdDraw(c, 3, 1, 3, 0);
        }
        if (s.rp2) {
            const VkSubpassEndInfo sei{VK_STRUCTURE_TYPE_SUBPASS_END_INFO};
            device_proc<PFN_vkCmdEndRenderPass2KHR>(k, "vkCmdEndRenderPass2KHR")(c, &sei);
        } else {
            vkCmdEndRenderPass(c);
        }
    }),
              VK_SUCCESS);
    std::vector<Bytes> layers;
    for (uint32_t l = 0; l < s.layers; ++l)
        layers.push_back(k.read(out.image, 32, 32, 4, VK_IMAGE_ASPECT_COLOR_BIT, 0, l));
    // Independent checks: a layer outside the mask keeps the pre-fill everywhere; a view's layer has the load clear
    // in the corner (0, 31) no triangle reaches (0.1 and 0.3 in 8 bits), the vkCmdClearAttachments colour at (5, 21)
    // when cleared, and differs from every other view's layer (gl_ViewIndex moves and colours the triangles).
    for (uint32_t l = 0; l < s.layers; ++l) {
        if (!(s.mask >> l & 1)) {
            for (size_t i = 0; i < layers[l].size(); ++i)
                if (layers[l][i] != (i % 4 == 3 ? 255 : 128)) {
                    ADD_FAILURE() << "layer " << l << " (not a view) written at byte " << i;
                    break;
                }
            continue;
        }
        EXPECT_NEAR(px(layers[l], 0, 31)[0], 25.5, 1.0) << "layer " << l;
        EXPECT_NEAR(px(layers[l], 0, 31)[2], 76.5, 1.0) << "layer " << l;
        if (s.clear_attachments) {
            EXPECT_EQ(px(layers[l], 5, 21)[0], 255) << "layer " << l;
            EXPECT_EQ(px(layers[l], 5, 21)[1], 128) << "layer " << l;
        }
        for (uint32_t o = 0; o < l; ++o)
            if (s.mask >> o & 1) {
                EXPECT_NE(layers[l], layers[o]) << "views " << o << " and " << l;
            }
    }
    Bytes all;
    for (const Bytes& b : layers) all.insert(all.end(), b.begin(), b.end());
    return all;
}

class ApiMultiview : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices() {
        multiview_.multiview = VK_TRUE;
        return device_pair(kExtensions, &multiview_);
    }
    void equals_lavapipe(const Scene& s) {
        auto dev = devices();
        both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return multiview_scene(k, s); });
    }
    VkPhysicalDeviceMultiviewFeatures multiview_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
};

TEST_F(ApiMultiview, TwoViewsWithLoadClearAndClearAttachments) {
    Scene s;
    s.clear_attachments = true;
    equals_lavapipe(s);
}

// Views 0 and 2 of three layers: layer 1 is neither cleared, drawn nor cleared by vkCmdClearAttachments.
TEST_F(ApiMultiview, NonContiguousViewMaskLeavesTheOtherLayerAlone) {
    Scene s;
    s.mask = 0b101;
    s.layers = 3;
    s.clear_attachments = true;
    equals_lavapipe(s);
}

// 4x, two views, draw + vkCmdClearAttachments + draw, resolved per view at the end of the subpass.
TEST_F(ApiMultiview, MsaaViewsResolveIntoTheirLayers) {
    Scene s;
    s.msaa = true;
    s.clear_attachments = true;
    equals_lavapipe(s);
}

// Named difference: lavapipe 22.3 resolves every layer of the attachment views, views of the mask or not (with mask
// 0b110 it writes layer 0 from the 4x image's never-rendered layer 0). tilevk resolves the views of the mask, as the
// spec says; on tilevk alone, layer 0 keeps its pre-fill (multiview_scene checks it) and layers 1, 2 are the views.
TEST_F(ApiMultiview, MsaaResolveCoversOnlyTheViewsOfTheMask) {
    auto dev = devices();
    Kit k(dev->tilevk);
    Scene s;
    s.msaa = true;
    s.mask = 0b110;
    s.layers = 3;
    s.clear_attachments = true;
    multiview_scene(k, s);
}

// Three views of four layers, one draw each, equal to lavapipe; then instances (gl_InstanceIndex with gl_ViewIndex):
// on tilevk an instanced draw of 3 instances equals three draws with firstInstance 0, 1, 2 in every view.
// Instanced draws in two or more views differ from lavapipe 22.3; EachViewEqualsItsOwnSingleViewPass shows that
// lavapipe is the one that is wrong there.
TEST_F(ApiMultiview, InstancedDrawInEveryView) {
    Scene s;
    s.mask = 0b111;
    s.layers = 4;
    auto dev = devices();
    both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return multiview_scene(k, s); });
    Kit k(dev->tilevk);
    s.instances = 3;
    s.separate_instances = true;
    const Bytes separate = multiview_scene(k, s);
    s.separate_instances = false;
    const Bytes instanced = multiview_scene(k, s);
    expect_same(instanced, separate, "instanced vs one draw per instance");
}

// Named difference, analysed: with two or more views and two or more draws in a row, lavapipe 22.3's layer of a
// view changes with the other views of the mask (layer 1 of mask 0b11 differs from layer 1 of mask 0b10 in ~800
// bytes at triangle edges, layer 0 of 0b11 from 0b01 in ~700), though a view renders the same draws with the same
// gl_ViewIndex in both. The spec renders each view as if on its own, so that layer must not depend on the mask:
// here tilevk's layer of each view of a two-view pass equals its layer from a pass of that view alone, and those
// single-view passes equal lavapipe's byte for byte.
TEST_F(ApiMultiview, EachViewEqualsItsOwnSingleViewPass) {
    auto dev = devices();
    Scene s;
    s.instances = 2;
    s.separate_instances = true;
    std::vector<Bytes> single;
    for (uint32_t mask : {0b01u, 0b10u}) {
        s.mask = mask;
        single.push_back(both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return multiview_scene(k, s); }));
    }
    Kit k(dev->tilevk);
    s.mask = 0b11;
    const Bytes both = multiview_scene(k, s);
    const size_t layer = both.size() / 2;
    for (size_t v = 0; v < 2; ++v)
        expect_same(Bytes(both.begin() + v * layer, both.begin() + (v + 1) * layer),
                    Bytes(single[v].begin() + v * layer, single[v].begin() + (v + 1) * layer),
                    v == 0 ? "view 0 of mask 0b11 vs mask 0b01" : "view 1 of mask 0b11 vs mask 0b10");
}

// The feature and the limits, as lavapipe reports them.
TEST_F(ApiMultiview, FeatureAndPropertiesEqualLavapipe) {
    for (Device* d : {tilevk_.get(), lavapipe_.get()}) {
        VkPhysicalDeviceMultiviewFeatures f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f};
        auto get_features = reinterpret_cast<PFN_vkGetPhysicalDeviceFeatures2KHR>(
            vkGetInstanceProcAddr(harness_->instance(), "vkGetPhysicalDeviceFeatures2KHR"));
        ASSERT_NE(get_features, nullptr);
        get_features(d->physical(), &f2);
        EXPECT_EQ(f.multiview, VK_TRUE);
        EXPECT_EQ(f.multiviewGeometryShader, d == tilevk_.get() ? VK_FALSE : f.multiviewGeometryShader);
        EXPECT_EQ(f.multiviewTessellationShader, d == tilevk_.get() ? VK_FALSE : f.multiviewTessellationShader);
        VkPhysicalDeviceMultiviewProperties p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_PROPERTIES};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p};
        auto get_props = reinterpret_cast<PFN_vkGetPhysicalDeviceProperties2KHR>(
            vkGetInstanceProcAddr(harness_->instance(), "vkGetPhysicalDeviceProperties2KHR"));
        ASSERT_NE(get_props, nullptr);
        get_props(d->physical(), &p2);
        EXPECT_EQ(p.maxMultiviewViewCount, 6u);
        EXPECT_EQ(p.maxMultiviewInstanceIndex, 0x7fffffffu);
    }
}

// tilevk alone, without the validation layer (these are errors it would report): view masks without the multiview
// feature enabled, and a view at maxMultiviewViewCount, are refused by name.
TEST_F(ApiMultiview, Refusals) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    const Scene s;
    const auto refused = [&](Device& dev, uint32_t mask, const char* name) {
        Kit k(dev);
        testing::internal::CaptureStderr();
        EXPECT_EQ(multiview_pass(k, s, &mask, VK_ERROR_FEATURE_NOT_PRESENT), VkRenderPass(VK_NULL_HANDLE)) << name;
        EXPECT_NE(testing::internal::GetCapturedStderr().find(name), std::string::npos) << name;
    };
    {
        Device without(plain.find_device("tilevk"), nullptr, kExtensions, nullptr);
        ASSERT_TRUE(without.ok());
        refused(without, 0b11, "multiview feature");
    }
    VkPhysicalDeviceMultiviewFeatures f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
    f.multiview = VK_TRUE;
    Device with(plain.find_device("tilevk"), nullptr, kExtensions, &f);
    ASSERT_TRUE(with.ok());
    refused(with, 1u << 6, "maxMultiviewViewCount");
    refused(with, 0b1000001, "maxMultiviewViewCount");
    Kit k(with);
    const uint32_t ok = 1u << 5;
    EXPECT_NE(multiview_pass(k, s, &ok), VkRenderPass(VK_NULL_HANDLE));
    {  // an input attachment in a multiview subpass (it would read layer ViewIndex)
        VkAttachmentDescription a{};
        a.format = VK_FORMAT_R8G8B8A8_UNORM, a.samples = VK_SAMPLE_COUNT_1_BIT;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD, a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE, a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.initialLayout = a.finalLayout = VK_IMAGE_LAYOUT_GENERAL;
        const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_GENERAL};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.inputAttachmentCount = 1, sub.pInputAttachments = &ref;
        sub.colorAttachmentCount = 1, sub.pColorAttachments = &ref;
        const uint32_t mask = 0b11;
        VkRenderPassMultiviewCreateInfo mv{VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO};
        mv.subpassCount = 1, mv.pViewMasks = &mask;
        VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO, &mv};
        ci.attachmentCount = 1, ci.pAttachments = &a, ci.subpassCount = 1, ci.pSubpasses = &sub;
        VkRenderPass rp = VK_NULL_HANDLE;
        testing::internal::CaptureStderr();
        EXPECT_EQ(vkCreateRenderPass(with.device(), &ci, nullptr, &rp), VK_ERROR_FEATURE_NOT_PRESENT);
        EXPECT_NE(testing::internal::GetCapturedStderr().find("input attachments in a multiview subpass"),
                  std::string::npos);
        EXPECT_EQ(rp, VkRenderPass(VK_NULL_HANDLE));
    }
}

// VK_KHR_create_renderpass2 (suite ApiRenderPass2): the multiview scenes made with vkCreateRenderPass2KHR and run with
// vkCmdBeginRenderPass2KHR / vkCmdEndRenderPass2KHR equal the same scenes in the 1.0 form on each driver, and
// tilevk's equal lavapipe's (validation layer on).
class ApiRenderPass2 : public ApiBreadth {
  protected:
    void rp2_equals_rp1(Scene s) {
        VkPhysicalDeviceMultiviewFeatures mv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
        mv.multiview = VK_TRUE;
        Device tilevk(tilevk_->physical(), nullptr, kExtensions2, &mv),
            lavapipe(lavapipe_->physical(), nullptr, kExtensions2, &mv);
        ASSERT_TRUE(tilevk.ok() && lavapipe.ok());
        both_on(tilevk, lavapipe, [&](Kit& k) {
            s.rp2 = false;
            const Bytes one = multiview_scene(k, s);
            s.rp2 = true;
            const Bytes two = multiview_scene(k, s);
            expect_same(one, two, "vkCreateRenderPass vs vkCreateRenderPass2");
            return two;
        });
    }
};

TEST_F(ApiRenderPass2, TwoViewsWithLoadClearAndClearAttachments) {
    Scene s;
    s.clear_attachments = true;
    rp2_equals_rp1(s);
}

TEST_F(ApiRenderPass2, NonContiguousViewMask) {
    Scene s;
    s.mask = 0b101;
    s.layers = 3;
    s.clear_attachments = true;
    rp2_equals_rp1(s);
}

TEST_F(ApiRenderPass2, MsaaViewsResolve) {
    Scene s;
    s.msaa = true;
    s.clear_attachments = true;
    rp2_equals_rp1(s);
}

// tilevk alone, without the validation layer: VkFragmentShadingRateAttachmentInfoKHR (VK_KHR_fragment_shading_rate,
// not offered) is refused by name, and a viewMask without the multiview feature enabled like the 1.0 form's (the
// depth/stencil resolve refusals are in api_breadth_ds_resolve_test.cpp).
TEST_F(ApiRenderPass2, Refusals) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"), nullptr, kExtensions2, nullptr);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    VkAttachmentDescription2 att{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
    att.format = kC;
    att.samples = VK_SAMPLE_COUNT_1_BIT;
    att.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    const VkAttachmentReference2 col{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, 0,
                                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT};
    VkSubpassDescription2 sub{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &col;
    VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
    ci.attachmentCount = 1;
    ci.pAttachments = &att;
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    auto create = device_proc<PFN_vkCreateRenderPass2KHR>(k, "vkCreateRenderPass2KHR");
    const auto refused = [&](const char* name) {
        VkRenderPass r = VK_NULL_HANDLE;
        testing::internal::CaptureStderr();
        EXPECT_EQ(create(k.d, &ci, nullptr, &r), VK_ERROR_FEATURE_NOT_PRESENT) << name;
        EXPECT_NE(testing::internal::GetCapturedStderr().find(name), std::string::npos) << name;
        EXPECT_EQ(r, VkRenderPass(VK_NULL_HANDLE)) << name;
    };
    VkFragmentShadingRateAttachmentInfoKHR fsr{VK_STRUCTURE_TYPE_FRAGMENT_SHADING_RATE_ATTACHMENT_INFO_KHR};
    sub.pNext = &fsr;
    refused("VK_STRUCTURE_TYPE_FRAGMENT_SHADING_RATE_ATTACHMENT_INFO_KHR");
    sub.pNext = nullptr;
    sub.viewMask = 0b11;
    refused("multiview feature");
    sub.viewMask = 0;
    VkRenderPass rp = VK_NULL_HANDLE;
    EXPECT_EQ(create(k.d, &ci, nullptr, &rp), VK_SUCCESS);
    vkDestroyRenderPass(k.d, rp, nullptr);
}

}  // namespace
}  // namespace tilevk::test::breadth
