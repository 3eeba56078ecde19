// VK_KHR_create_renderpass2 without views (suite ApiRenderPass2Subpasses; the multiview scenes are in
// api_breadth_multiview_test.cpp): the same scenes made with vkCreateRenderPass and vkCreateRenderPass2 (begun,
// advanced and ended with the 1.0 and the 2 commands) give the same bytes on each driver, and tilevk's equal
// lavapipe's (validation layer on). From branch rp2-with-renderpass2 (7dc2542).
#include "api_breadth.h"
#include "api_breadth_input_scene.h"

namespace tilevk::test::breadth {
namespace {

const std::vector<const char*> kExtensions = {VK_KHR_MULTIVIEW_EXTENSION_NAME, VK_KHR_MAINTENANCE_2_EXTENSION_NAME,
                                              VK_KHR_CREATE_RENDERPASS_2_EXTENSION_NAME};

struct Rp2 {
    explicit Rp2(VkDevice d)
        : create(reinterpret_cast<PFN_vkCreateRenderPass2KHR>(vkGetDeviceProcAddr(d, "vkCreateRenderPass2KHR"))),
          begin(reinterpret_cast<PFN_vkCmdBeginRenderPass2KHR>(vkGetDeviceProcAddr(d, "vkCmdBeginRenderPass2KHR"))),
          next(reinterpret_cast<PFN_vkCmdNextSubpass2KHR>(vkGetDeviceProcAddr(d, "vkCmdNextSubpass2KHR"))),
          end(reinterpret_cast<PFN_vkCmdEndRenderPass2KHR>(vkGetDeviceProcAddr(d, "vkCmdEndRenderPass2KHR"))) {}
    bool ok() const { return create && begin && next && end; }
    PFN_vkCreateRenderPass2KHR create;
    PFN_vkCmdBeginRenderPass2KHR begin;
    PFN_vkCmdNextSubpass2KHR next;
    PFN_vkCmdEndRenderPass2KHR end;
};

// A render pass as the 1.0 structs describe it, with the aspect of each input attachment (per subpass, per input).
struct PassDesc {
    std::vector<VkAttachmentDescription> atts;
    std::vector<VkSubpassDescription> subs;
    std::vector<VkSubpassDependency> deps;
    std::vector<std::vector<VkImageAspectFlags>> input_aspects;  // empty or one list per subpass
};

// The test's own translation of `p` into the 2-structs (the spec's equivalence), created with vkCreateRenderPass2.
VkRenderPass create_pass2(Kit& k, const PassDesc& p, VkResult* result = nullptr) {
    std::vector<VkAttachmentDescription2> atts;
    for (const VkAttachmentDescription& a : p.atts) {
        VkAttachmentDescription2 a2{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
        a2.flags = a.flags;
        a2.format = a.format;
        a2.samples = a.samples;
        a2.loadOp = a.loadOp;
        a2.storeOp = a.storeOp;
        a2.stencilLoadOp = a.stencilLoadOp;
        a2.stencilStoreOp = a.stencilStoreOp;
        a2.initialLayout = a.initialLayout;
        a2.finalLayout = a.finalLayout;
        atts.push_back(a2);
    }
    std::vector<std::vector<VkAttachmentReference2>> refs(p.subs.size() * 4);
    const auto refs2 = [](const VkAttachmentReference* r, uint32_t n, const std::vector<VkImageAspectFlags>* aspects,
                          std::vector<VkAttachmentReference2>& out) -> const VkAttachmentReference2* {
        if (r == nullptr) return nullptr;
        for (uint32_t i = 0; i < n; ++i) {
            VkAttachmentReference2 r2{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2};
            r2.attachment = r[i].attachment;
            r2.layout = r[i].layout;
            r2.aspectMask = aspects != nullptr ? (*aspects)[i] : 0;
            out.push_back(r2);
        }
        return out.data();
    };
    std::vector<VkSubpassDescription2> subs;
    for (size_t i = 0; i < p.subs.size(); ++i) {
        const VkSubpassDescription& s = p.subs[i];
        VkSubpassDescription2 s2{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2};
        s2.pipelineBindPoint = s.pipelineBindPoint;
        s2.inputAttachmentCount = s.inputAttachmentCount;
        s2.pInputAttachments = refs2(s.pInputAttachments, s.inputAttachmentCount,
                                     p.input_aspects.empty() ? nullptr : &p.input_aspects[i], refs[4 * i]);
        s2.colorAttachmentCount = s.colorAttachmentCount;
        s2.pColorAttachments = refs2(s.pColorAttachments, s.colorAttachmentCount, nullptr, refs[4 * i + 1]);
        s2.pResolveAttachments = refs2(s.pResolveAttachments, s.colorAttachmentCount, nullptr, refs[4 * i + 2]);
        s2.pDepthStencilAttachment = refs2(s.pDepthStencilAttachment, 1, nullptr, refs[4 * i + 3]);
        s2.preserveAttachmentCount = s.preserveAttachmentCount;
        s2.pPreserveAttachments = s.pPreserveAttachments;
        subs.push_back(s2);
    }
    std::vector<VkSubpassDependency2> deps;
    for (const VkSubpassDependency& d : p.deps) {
        VkSubpassDependency2 d2{VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2};
        d2.srcSubpass = d.srcSubpass;
        d2.dstSubpass = d.dstSubpass;
        d2.srcStageMask = d.srcStageMask;
        d2.dstStageMask = d.dstStageMask;
        d2.srcAccessMask = d.srcAccessMask;
        d2.dstAccessMask = d.dstAccessMask;
        d2.dependencyFlags = d.dependencyFlags;
        deps.push_back(d2);
    }
    VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
    ci.attachmentCount = uint32_t(atts.size());
    ci.pAttachments = atts.data();
    ci.subpassCount = uint32_t(subs.size());
    ci.pSubpasses = subs.data();
    ci.dependencyCount = uint32_t(deps.size());
    ci.pDependencies = deps.data();
    VkRenderPass rp = VK_NULL_HANDLE;
    const VkResult r = Rp2(k.d).create(k.d, &ci, nullptr, &rp);
    if (result != nullptr) {
        *result = r;
    } else {
        EXPECT_EQ(r, VK_SUCCESS);
    }
    if (rp != VK_NULL_HANDLE) {
        VkDevice d = k.d;
        k.undo(VK_OBJECT_TYPE_RENDER_PASS, rp, [d, rp] { vkDestroyRenderPass(d, rp, nullptr); });
    }
    return rp;
}

VkRenderPass create_pass(Kit& k, const PassDesc& p, bool v2) {
    return v2 ? create_pass2(k, p) : k.render_pass(p.atts, p.subs, p.deps);
}

// Begin / next subpass / end, in the 1.0 form (fns null) or the 2 form.
void begin(VkCommandBuffer c, const Rp2* fns, const VkRenderPassBeginInfo& bi) {
    if (fns == nullptr) {
        vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
        return;
    }
    VkSubpassBeginInfo sb{VK_STRUCTURE_TYPE_SUBPASS_BEGIN_INFO};
    sb.contents = VK_SUBPASS_CONTENTS_INLINE;
    fns->begin(c, &bi, &sb);
}
void next(VkCommandBuffer c, const Rp2* fns) {
    if (fns == nullptr) {
        vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_INLINE);
        return;
    }
    VkSubpassBeginInfo sb{VK_STRUCTURE_TYPE_SUBPASS_BEGIN_INFO};
    sb.contents = VK_SUBPASS_CONTENTS_INLINE;
    VkSubpassEndInfo se{VK_STRUCTURE_TYPE_SUBPASS_END_INFO};
    fns->next(c, &sb, &se);
}
void end(VkCommandBuffer c, const Rp2* fns) {
    if (fns == nullptr) {
        vkCmdEndRenderPass(c);
        return;
    }
    VkSubpassEndInfo se{VK_STRUCTURE_TYPE_SUBPASS_END_INFO};
    fns->end(c, &se);
}
VkRenderPassBeginInfo begin_info(VkRenderPass rp, VkFramebuffer fb, const std::vector<VkClearValue>& clears,
                                 const void* chain = nullptr) {
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.pNext = chain;
    bi.renderPass = rp;
    bi.framebuffer = fb;
    bi.renderArea = {{0, 0}, {32, 32}};
    bi.clearValueCount = uint32_t(clears.size());
    bi.pClearValues = clears.data();
    return bi;
}

class ApiRenderPass2Subpasses : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices() { return device_pair(kExtensions); }
};

// 4x RGBA8 cleared, drawn into, partly cleared again with vkCmdClearAttachments and drawn over, resolved into a 1x
// image at the end of the subpass; the pass made by the 1.0 or the 2 command (fns null or not).
Bytes msaa_scene(Kit& k, const Rp2* fns) {
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
    Device::Image ms =
        k.dev().make_image(C, 32, 32, 1, 1, VK_SAMPLE_COUNT_4_BIT,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT);
    EXPECT_NE(ms.image, VK_NULL_HANDLE);
    k.undo(VK_OBJECT_TYPE_IMAGE, ms.image, [&k, ms]() mutable { k.dev().destroy(ms); });
    Device::Image res = k.image(C, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    PassDesc p;
    VkAttachmentDescription a0 = attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    a0.samples = VK_SAMPLE_COUNT_4_BIT;
    p.atts = {a0, attachment(C, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE)};
    const VkAttachmentReference col{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
        resolve{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub = subpass(&col);
    sub.pResolveAttachments = &resolve;
    p.subs = {sub};
    p.deps = {{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0}};
    VkRenderPass rp = create_pass(k, p, fns != nullptr);
    VkFramebuffer fb = k.framebuffer(
        rp, {k.view(ms.image, C, VK_IMAGE_ASPECT_COLOR_BIT), k.view(res.image, C, VK_IMAGE_ASPECT_COLOR_BIT)}, 32, 32);
    Pipe pp;
    pp.rp = rp;
    pp.samples = VK_SAMPLE_COUNT_4_BIT;
    pp.blend = {alpha_over()};
    VkPipeline pipe = k.pipeline(pp);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin(c, fns, begin_info(rp, fb, {clear_color(0.1f, 0.2f, 0.3f, 1)}));
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdDraw(c, 3, 1, 0, 0);
        VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 0.5f, 0, 1)};
        VkClearRect rect{{{4, 20}, {10, 8}}, 0, 1};
        vkCmdClearAttachments(c, 1, &ca, 1, &rect);
        vkCmdDraw(c, 3, 1, 3, 0);
        end(c, fns);
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

TEST_F(ApiRenderPass2Subpasses, DrawClearResolveEqualsTheSamePassMadeWithVkCreateRenderPass) {
    auto dev = devices();
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        const Rp2 fns(k.d);
        EXPECT_TRUE(fns.ok());
        const Bytes one = msaa_scene(k, nullptr);
        const Bytes two = msaa_scene(k, &fns);
        expect_same(one, two, "vkCreateRenderPass vs vkCreateRenderPass2");
        return two;
    });
}

// Two subpasses: subpass 0 draws colour (RGBA8) and depth (D32); subpass 1 reads both as input attachments (aspect
// masks COLOR and DEPTH in the VkAttachmentReference2s) into an RGBA32F attachment; begun, advanced and ended with
// the 2 commands. Equal to the 1.0 pass with the 1.0 commands and to lavapipe.
Bytes input_scene(Kit& k, const Rp2* fns) {
    InputScene s(k);
    PassDesc p;
    p.atts = InputScene::attachments();
    p.subs = s.subpasses();
    p.input_aspects = {{}, {VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_DEPTH_BIT}};
    p.deps = {InputScene::dependency()};
    VkRenderPass rp = create_pass(k, p, fns != nullptr);
    VkFramebuffer fb = k.framebuffer(rp, s.views(), 32, 32);
    s.build(rp);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        begin(c, fns, begin_info(rp, fb, InputScene::clears()));
        s.draw_subpass0(c);
        next(c, fns);
        s.draw_subpass1(c);
        end(c, fns);
    }),
              VK_SUCCESS);
    return s.read_checked();
}

TEST_F(ApiRenderPass2Subpasses, InputAttachmentsWithAspectMasksAcrossNextSubpass2) {
    auto dev = devices();
    both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        const Rp2 fns(k.d);
        EXPECT_TRUE(fns.ok());
        const Bytes one = input_scene(k, nullptr);
        const Bytes two = input_scene(k, &fns);
        expect_same(one, two, "vkCreateRenderPass vs vkCreateRenderPass2");
        return two;
    });
}

}  // namespace
}  // namespace tilevk::test::breadth
