// VK_KHR_dynamic_rendering (suite ApiDynamicRendering): vkCmdBeginRenderingKHR / vkCmdEndRenderingKHR with pipelines
// made from VkPipelineRenderingCreateInfo and no render pass. Every scene runs on tilevk and lavapipe with the
// validation layer on and is compared byte for byte; on tilevk the same scene through a VkRenderPass (made with
// vkCreateRenderPass2, the resolves and view mask in it) must give the same bytes, since a dynamic render pass
// instance is translated into one (icd/dynamic_rendering.cpp). Refusals are checked on tilevk alone.
#include "api_breadth.h"
// After api_breadth.h (<cstdint>): the generated SPIR-V arrays include nothing themselves.
#include "ab_multiview_frag.h"
#include "ab_multiview_vert.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

const std::vector<const char*> kExtensions = {VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME};
constexpr VkFormat kC = VK_FORMAT_R8G8B8A8_UNORM;

// One attachment of a scene: its view and format, samples, load op and clear value, and where it resolves (or null).
struct Att {
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = kC;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR;
    VkClearValue clear{};
    VkImageView resolve = VK_NULL_HANDLE;
};

// What one render pass instance renders into: colour attachments, a depth/stencil attachment (view null: none),
// the view mask and the render area.
struct PassDesc {
    std::vector<Att> colours;
    Att ds;
    uint32_t view_mask = 0;
    VkRect2D area{{0, 0}, {32, 32}};
};

bool stencil_of(VkFormat f) {
    return has_stencil(f);
}
bool depth_of(VkFormat f) {
    return f != VK_FORMAT_S8_UINT;
}

// The same instance as a render pass made with vkCreateRenderPass2 (one subpass, the resolves in it).
VkRenderPass render_pass_of(Kit& k, const PassDesc& p, std::vector<VkImageView>& views) {
    std::vector<VkAttachmentDescription2> atts;
    std::vector<VkAttachmentReference2> colours, resolves;
    const auto add = [&](VkImageView v, VkFormat f, VkSampleCountFlagBits s, VkAttachmentLoadOp load,
                         VkImageLayout layout, VkImageAspectFlags aspect) {
        VkAttachmentDescription2 a{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
        a.format = f;
        a.samples = s;
        a.loadOp = a.stencilLoadOp = load;
        a.storeOp = a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
        a.initialLayout = load == VK_ATTACHMENT_LOAD_OP_LOAD ? layout : VK_IMAGE_LAYOUT_UNDEFINED;
        a.finalLayout = layout;
        atts.push_back(a);
        views.push_back(v);
        return VkAttachmentReference2{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, uint32_t(atts.size() - 1),
                                      layout, aspect};
    };
    const VkImageLayout cl = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        dl = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    for (const Att& c : p.colours) colours.push_back(add(c.view, c.format, c.samples, c.load, cl, 0));
    for (const Att& c : p.colours)
        if (c.resolve != VK_NULL_HANDLE)
            resolves.push_back(add(c.resolve, c.format, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE, cl, 0));
    VkSubpassDescription2 sub{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.viewMask = p.view_mask;
    sub.colorAttachmentCount = uint32_t(colours.size());
    sub.pColorAttachments = colours.data();
    sub.pResolveAttachments = resolves.empty() ? nullptr : resolves.data();
    VkAttachmentReference2 ds{}, ds_resolve{};
    VkSubpassDescriptionDepthStencilResolve dsr{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_DEPTH_STENCIL_RESOLVE};
    if (p.ds.view != VK_NULL_HANDLE) {
        ds = add(p.ds.view, p.ds.format, p.ds.samples, p.ds.load, dl, 0);
        sub.pDepthStencilAttachment = &ds;
        if (p.ds.resolve != VK_NULL_HANDLE) {
            ds_resolve = add(p.ds.resolve, p.ds.format, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE, dl, 0);
            dsr.depthResolveMode = depth_of(p.ds.format) ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_NONE;
            dsr.stencilResolveMode = stencil_of(p.ds.format) ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_NONE;
            dsr.pDepthStencilResolveAttachment = &ds_resolve;
            sub.pNext = &dsr;
        }
    }
    VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
    ci.attachmentCount = uint32_t(atts.size());
    ci.pAttachments = atts.data();
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    VkRenderPass rp = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateRenderPass2(k.d, &ci, nullptr, &rp), VK_SUCCESS);
    VkDevice d = k.d;
    k.undo(VK_OBJECT_TYPE_RENDER_PASS, rp, [d, rp] { vkDestroyRenderPass(d, rp, nullptr); });
    return rp;
}

VkRenderingAttachmentInfo rendering_att(const Att& a, VkImageLayout layout, VkResolveModeFlagBits mode) {
    VkRenderingAttachmentInfo r{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    r.imageView = a.view;
    r.imageLayout = layout;
    r.loadOp = a.load;
    r.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    r.clearValue = a.clear;
    if (a.resolve != VK_NULL_HANDLE) {
        r.resolveMode = mode;
        r.resolveImageView = a.resolve;
        r.resolveImageLayout = layout;
    }
    return r;
}

// Begins the instance `p` as dynamic rendering (flags: VkRenderingFlags) or, when `rp` is set, as that render pass.
class Instance {
  public:
    Instance(Kit& k, const PassDesc& p, bool dynamic) : k_(k), p_(p), dynamic_(dynamic) {
        if (!dynamic) {
            std::vector<VkImageView> views;
            rp_ = render_pass_of(k, p, views);
            fb_ = k.framebuffer(rp_, views, 32, 32, 1);
            for (const Att& c : p.colours) clears_.push_back(c.clear);
            for (const Att& c : p.colours)
                if (c.resolve != VK_NULL_HANDLE) clears_.push_back({});
            if (p.ds.view != VK_NULL_HANDLE) clears_.push_back(p.ds.clear);
        }
    }
    VkRenderPass render_pass() const { return rp_; }
    void begin(VkCommandBuffer c, VkRenderingFlags flags = 0) {
        if (!dynamic_) {
            VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
            bi.renderPass = rp_;
            bi.framebuffer = fb_;
            bi.renderArea = p_.area;
            bi.clearValueCount = uint32_t(clears_.size());
            bi.pClearValues = clears_.data();
            vkCmdBeginRenderPass(c, &bi,
                                 (flags & VK_RENDERING_CONTENTS_SECONDARY_COMMAND_BUFFERS_BIT)
                                     ? VK_SUBPASS_CONTENTS_SECONDARY_COMMAND_BUFFERS
                                     : VK_SUBPASS_CONTENTS_INLINE);
            return;
        }
        std::vector<VkRenderingAttachmentInfo> colours;
        for (const Att& a : p_.colours)
            colours.push_back(rendering_att(a, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_RESOLVE_MODE_AVERAGE_BIT));
        const VkRenderingAttachmentInfo ds =
            rendering_att(p_.ds, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_RESOLVE_MODE_SAMPLE_ZERO_BIT);
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.flags = flags;
        ri.renderArea = p_.area;
        ri.layerCount = p_.view_mask != 0 ? 0 : 1;
        ri.viewMask = p_.view_mask;
        ri.colorAttachmentCount = uint32_t(colours.size());
        ri.pColorAttachments = colours.data();
        const bool has_ds = p_.ds.view != VK_NULL_HANDLE;
        ri.pDepthAttachment = has_ds && depth_of(p_.ds.format) ? &ds : nullptr;
        ri.pStencilAttachment = has_ds && stencil_of(p_.ds.format) ? &ds : nullptr;
        device_proc<PFN_vkCmdBeginRenderingKHR>(k_, "vkCmdBeginRenderingKHR")(c, &ri);
    }
    void end(VkCommandBuffer c) {
        if (dynamic_)
            device_proc<PFN_vkCmdEndRenderingKHR>(k_, "vkCmdEndRenderingKHR")(c);
        else
            vkCmdEndRenderPass(c);
    }
    // The pipeline of `pp` for this instance: its render pass, or VkPipelineRenderingCreateInfo of its formats.
    VkPipeline pipeline(Pipe pp) {
        std::vector<VkFormat> formats;
        for (const Att& a : p_.colours) formats.push_back(a.format);
        VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
        ri.viewMask = p_.view_mask;
        ri.colorAttachmentCount = uint32_t(formats.size());
        ri.pColorAttachmentFormats = formats.data();
        const bool has_ds = p_.ds.view != VK_NULL_HANDLE;
        ri.depthAttachmentFormat = has_ds && depth_of(p_.ds.format) ? p_.ds.format : VK_FORMAT_UNDEFINED;
        ri.stencilAttachmentFormat = has_ds && stencil_of(p_.ds.format) ? p_.ds.format : VK_FORMAT_UNDEFINED;
        pp.color_count = uint32_t(formats.size());
        pp.samples = !p_.colours.empty() ? p_.colours[0].samples : p_.ds.samples;
        if (dynamic_)
            pp.pnext = &ri;
        else
            pp.rp = rp_;
        return k_.pipeline(pp);
    }
    // Secondary command buffers inside this instance: the inheritance of either kind.
    VkCommandBuffer secondary(const std::function<void(VkCommandBuffer)>& record) {
        VkCommandBuffer s = k_.command_buffer(VK_COMMAND_BUFFER_LEVEL_SECONDARY);
        std::vector<VkFormat> formats;
        for (const Att& a : p_.colours) formats.push_back(a.format);
        VkCommandBufferInheritanceRenderingInfo ri{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_RENDERING_INFO};
        ri.viewMask = p_.view_mask;
        ri.colorAttachmentCount = uint32_t(formats.size());
        ri.pColorAttachmentFormats = formats.data();
        ri.rasterizationSamples = !p_.colours.empty() ? p_.colours[0].samples : p_.ds.samples;
        const bool has_ds = p_.ds.view != VK_NULL_HANDLE;
        ri.depthAttachmentFormat = has_ds && depth_of(p_.ds.format) ? p_.ds.format : VK_FORMAT_UNDEFINED;
        ri.stencilAttachmentFormat = has_ds && stencil_of(p_.ds.format) ? p_.ds.format : VK_FORMAT_UNDEFINED;
        VkCommandBufferInheritanceInfo inh{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
        if (dynamic_)
            inh.pNext = &ri;
        else
            inh.renderPass = rp_;
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_RENDER_PASS_CONTINUE_BIT;
        bi.pInheritanceInfo = &inh;
        EXPECT_EQ(vkBeginCommandBuffer(s, &bi), VK_SUCCESS);
        record(s);
        EXPECT_EQ(vkEndCommandBuffer(s), VK_SUCCESS);
        return s;
    }

  private:
    Kit& k_;
    PassDesc p_;
    bool dynamic_;
    VkRenderPass rp_ = VK_NULL_HANDLE;
    VkFramebuffer fb_ = VK_NULL_HANDLE;
    std::vector<VkClearValue> clears_;
};

// A 32x32 image of `f` (`samples`, `layers`) used as an attachment and read back; its view.
struct Img {
    VkImage image;
    VkImageView view;
};
Img attachment_image(Kit& k, VkFormat f, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT, uint32_t layers = 1) {
    const bool depth = is_depth(f) || f == VK_FORMAT_S8_UINT;
    const VkImageUsageFlags usage =
        (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
        (samples == VK_SAMPLE_COUNT_1_BIT ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT : 0);
    Device::Image img = k.dev().make_image(f, 32, 32, 1, layers, samples, usage);
    EXPECT_NE(img.image, VK_NULL_HANDLE);
    k.undo(VK_OBJECT_TYPE_IMAGE, img.image, [&k, img]() mutable { k.dev().destroy(img); });
    const VkImageAspectFlags aspect =
        !depth ? VK_IMAGE_ASPECT_COLOR_BIT
               : (depth_of(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : 0) | (stencil_of(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    return {img.image, k.view(img.image, f, aspect, layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D, 0,
                              1, 0, layers)};
}

// Moves `img` to TRANSFER_SRC_OPTIMAL after rendering (every aspect of its format) for the read-back.
void to_transfer_src(VkCommandBuffer c, VkImage img, VkFormat f, VkImageLayout from, uint32_t layers = 1) {
    const bool depth = is_depth(f) || f == VK_FORMAT_S8_UINT;
    const VkImageAspectFlags aspect =
        !depth ? VK_IMAGE_ASPECT_COLOR_BIT
               : (depth_of(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : 0) | (stencil_of(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = from;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img;
    b.subresourceRange = {aspect, 0, 1, 0, layers};
    vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// Moves `img` from UNDEFINED to the attachment layout of its format (before the first instance).
void to_attachment(VkCommandBuffer c, VkImage img, VkFormat f, uint32_t layers = 1) {
    const bool depth = is_depth(f) || f == VK_FORMAT_S8_UINT;
    const VkImageAspectFlags aspect =
        !depth ? VK_IMAGE_ASPECT_COLOR_BIT
               : (depth_of(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : 0) | (stencil_of(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    transition(c, img, aspect, VK_IMAGE_LAYOUT_UNDEFINED,
               depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, 1,
               layers);
}

// Draws `vertices` (kBothTriangles by default: two triangles) with `pipe` in instance `in` of the primary `c`.
void draw_all(VkCommandBuffer c, VkPipeline pipe, const Device::Buffer& vb, uint32_t first, uint32_t count) {
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    bind_vertices(c, vb);
    vkCmdDraw(c, count, 1, first, 0);
}

// An alpha-blended pipeline of `in` with `ds` as its depth/stencil state.
VkPipeline blended(Instance& in, const VkPipelineDepthStencilStateCreateInfo* ds = nullptr) {
    Pipe pp;
    pp.blend = {alpha_over()};
    pp.ds = ds;
    return in.pipeline(pp);
}

// Colour of format `f` cleared, two blended triangles.
Bytes colour_scene(Kit& k, bool dynamic, VkFormat f) {
    Img c = attachment_image(k, f);
    PassDesc p;
    p.colours = {{c.view, f, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0.1f, 0.2f, 0.3f, 1)}};
    Instance in(k, p, dynamic);
    VkPipeline pipe = blended(in);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
        to_attachment(cb, c.image, f);
        in.begin(cb);
        draw_all(cb, pipe, vb, 0, 6);
        in.end(cb);
        to_transfer_src(cb, c.image, f, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    }),
              VK_SUCCESS);
    Bytes b = k.read(c.image, 32, 32, 4);
    const int red = f == VK_FORMAT_B8G8R8A8_UNORM ? 2 : 0;
    EXPECT_NEAR(px(b, 0, 31)[red], 25.5, 1.0);  // the clear where no triangle reaches
    EXPECT_NEAR(px(b, 0, 31)[2 - red], 76.5, 1.0);
    return b;
}

// Depth (and stencil) test against a cleared depth/stencil attachment: the triangles overlap at different depths,
// stencil (when the format has it) replaced with 0x33 where a triangle passes. Colour, depth and stencil read back.
Bytes depth_scene(Kit& k, bool dynamic, VkFormat f) {
    Img c = attachment_image(k, kC), d = attachment_image(k, f);
    PassDesc p;
    p.colours = {{c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0, 0, 0, 1)}};
    p.ds = {d.view, f, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_depth(0.75f, 0x5a)};
    Instance in(k, p, dynamic);
    VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
    if (stencil_of(f)) {
        ds.stencilTestEnable = VK_TRUE;
        ds.front = {
            VK_STENCIL_OP_KEEP, VK_STENCIL_OP_REPLACE, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_ALWAYS, 0xff, 0xff, 0x33};
        ds.back = ds.front;
    }
    VkPipeline pipe = blended(in, &ds);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
        to_attachment(cb, c.image, kC);
        to_attachment(cb, d.image, f);
        in.begin(cb);
        draw_all(cb, pipe, vb, 0, 6);
        in.end(cb);
        to_transfer_src(cb, c.image, kC, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        to_transfer_src(cb, d.image, f, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    }),
              VK_SUCCESS);
    Bytes out = k.read(c.image, 32, 32, 4);
    Bytes depth = k.read(d.image, 32, 32, texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT), VK_IMAGE_ASPECT_DEPTH_BIT);
    out.insert(out.end(), depth.begin(), depth.end());
    if (stencil_of(f)) {
        const Bytes st = k.read(d.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT);
        EXPECT_EQ(st[31 * 32], 0x5a);       // the clear at (0, 31)
        EXPECT_EQ(st[16 * 32 + 16], 0x33);  // a triangle in the middle
        out.insert(out.end(), st.begin(), st.end());
    }
    return out;
}

// 4x colour and depth/stencil of format D, resolved at the end of the instance (colour AVERAGE, depth and stencil
// SAMPLE_ZERO); the stencil, when D has it, replaced with 0x33 where a triangle passes.
Bytes msaa_scene(Kit& k, bool dynamic, VkFormat D) {
    Img c = attachment_image(k, kC, VK_SAMPLE_COUNT_4_BIT), r = attachment_image(k, kC);
    Img d = attachment_image(k, D, VK_SAMPLE_COUNT_4_BIT), dr = attachment_image(k, D);
    PassDesc p;
    p.colours = {
        {c.view, kC, VK_SAMPLE_COUNT_4_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0.1f, 0.2f, 0.3f, 1), r.view}};
    p.ds = {d.view, D, VK_SAMPLE_COUNT_4_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_depth(0.75f, 0x5a), dr.view};
    Instance in(k, p, dynamic);
    VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
    if (stencil_of(D)) {
        ds.stencilTestEnable = VK_TRUE;
        ds.front = {
            VK_STENCIL_OP_KEEP, VK_STENCIL_OP_REPLACE, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_ALWAYS, 0xff, 0xff, 0x33};
        ds.back = ds.front;
    }
    VkPipeline pipe = blended(in, &ds);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
        for (const Img& i : {c, r}) to_attachment(cb, i.image, kC);
        for (const Img& i : {d, dr}) to_attachment(cb, i.image, D);
        in.begin(cb);
        draw_all(cb, pipe, vb, 0, 6);
        in.end(cb);
        to_transfer_src(cb, r.image, kC, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        to_transfer_src(cb, dr.image, D, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    }),
              VK_SUCCESS);
    Bytes out = k.read(r.image, 32, 32, 4);
    EXPECT_NEAR(px(out, 0, 31)[0], 25.5, 1.0);  // resolved clear
    const Bytes depth = k.read(dr.image, 32, 32, texel_bytes(D, VK_IMAGE_ASPECT_DEPTH_BIT), VK_IMAGE_ASPECT_DEPTH_BIT);
    out.insert(out.end(), depth.begin(), depth.end());
    if (stencil_of(D)) {
        const Bytes st = k.read(dr.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT);
        EXPECT_EQ(st[31 * 32], 0x5a);       // resolved clear
        EXPECT_EQ(st[16 * 32 + 16], 0x33);  // a triangle's sample 0
        out.insert(out.end(), st.begin(), st.end());
    }
    return out;
}

// viewMask 0b11 into a two-layer image: clear, a draw, vkCmdClearAttachments, a second draw (each per view).
Bytes multiview_scene(Kit& k, bool dynamic) {
    Img c = attachment_image(k, kC, VK_SAMPLE_COUNT_1_BIT, 2);
    PassDesc p;
    p.colours = {{c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0.1f, 0.2f, 0.3f, 1)}};
    p.view_mask = 0b11;
    Instance in(k, p, dynamic);
    Pipe pp;
    pp.vs = SPV(ab_multiview_vert);
    pp.fs = SPV(ab_multiview_frag);
    pp.blend = {alpha_over()};
    VkPipeline pipe = in.pipeline(pp);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
        to_attachment(cb, c.image, kC, 2);
        in.begin(cb);
        draw_all(cb, pipe, vb, 0, 3);
        const VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 0.5f, 0, 1)};
        const VkClearRect rect{{{4, 20}, {10, 8}}, 0, 1};
        vkCmdClearAttachments(cb, 1, &ca, 1, &rect);
        vkCmdDraw(cb, 3, 1, 3, 0);
        in.end(cb);
        to_transfer_src(cb, c.image, kC, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, 2);
    }),
              VK_SUCCESS);
    const Bytes l0 = k.read(c.image, 32, 32, 4, VK_IMAGE_ASPECT_COLOR_BIT, 0, 0);
    const Bytes l1 = k.read(c.image, 32, 32, 4, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1);
    EXPECT_NE(l0, l1);  // gl_ViewIndex moves and colours the triangles
    for (const Bytes* l : {&l0, &l1}) {
        EXPECT_EQ(px(*l, 5, 21)[0], 255);  // vkCmdClearAttachments in both views
        EXPECT_EQ(px(*l, 5, 21)[1], 128);
    }
    return concat({l0, l1});
}

// Colour + D24S8: draw, vkCmdClearAttachments of colour and of depth/stencil, draw; inline or from two secondary
// command buffers (VkCommandBufferInheritanceRenderingInfo / the render pass) executed by the primary.
Bytes clear_attachments_scene(Kit& k, bool dynamic, bool secondaries) {
    const VkFormat D = VK_FORMAT_D24_UNORM_S8_UINT;
    Img c = attachment_image(k, kC), d = attachment_image(k, D);
    PassDesc p;
    p.colours = {{c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0.1f, 0.2f, 0.3f, 1)}};
    p.ds = {d.view, D, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_depth(0.75f, 7)};
    Instance in(k, p, dynamic);
    VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
    VkPipeline pipe = blended(in, &ds);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    const auto first = [&](VkCommandBuffer cb) {
        draw_all(cb, pipe, vb, 0, 3);
        const VkClearAttachment cas[2] = {
            {VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 0.5f, 0, 1)},
            {VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT, 0, clear_depth(0.05f, 0x44)}};
        const VkClearRect rects[2] = {{{{4, 20}, {10, 8}}, 0, 1}, {{{12, 6}, {9, 14}}, 0, 1}};
        vkCmdClearAttachments(cb, 2, cas, 2, rects);
    };
    const auto second = [&](VkCommandBuffer cb) { draw_all(cb, pipe, vb, 3, 3); };
    VkCommandBuffer sec[2] = {};
    if (secondaries) {
        sec[0] = in.secondary(first);
        sec[1] = in.secondary(second);
    }
    EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
        to_attachment(cb, c.image, kC);
        to_attachment(cb, d.image, D);
        if (secondaries) {
            in.begin(cb, VK_RENDERING_CONTENTS_SECONDARY_COMMAND_BUFFERS_BIT);
            vkCmdExecuteCommands(cb, 2, sec);
        } else {
            in.begin(cb);
            first(cb);
            second(cb);
        }
        in.end(cb);
        to_transfer_src(cb, c.image, kC, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        to_transfer_src(cb, d.image, D, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    }),
              VK_SUCCESS);
    Bytes out = k.read(c.image, 32, 32, 4);
    EXPECT_EQ(px(out, 5, 27)[0], 255);  // the colour clear rect, below the second triangle's reach
    const Bytes st = k.read(d.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT);
    EXPECT_EQ(st[7 * 32 + 13], 0x44);  // the depth/stencil clear rect
    const Bytes depth = k.read(d.image, 32, 32, 4, VK_IMAGE_ASPECT_DEPTH_BIT);
    return concat({out, st, depth});
}

// Three instances on one image: CLEAR + the first triangle; LOAD + the second triangle (the first stays); CLEAR of a
// partial render area (only that rectangle changes).
Bytes load_scene(Kit& k, bool dynamic) {
    Img c = attachment_image(k, kC);
    PassDesc clear, load, part;
    clear.colours = {
        {c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0.1f, 0.2f, 0.3f, 1)}};
    load.colours = {{c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_LOAD, {}}};
    part.colours = {{c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0, 1, 0, 1)}};
    part.area = {{20, 2}, {9, 5}};
    Instance i0(k, clear, dynamic), i1(k, load, dynamic), i2(k, part, dynamic);
    VkPipeline p0 = blended(i0), p1 = blended(i1);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
        to_attachment(cb, c.image, kC);
        i0.begin(cb);
        draw_all(cb, p0, vb, 0, 3);
        i0.end(cb);
        i1.begin(cb);
        draw_all(cb, p1, vb, 3, 3);
        i1.end(cb);
        i2.begin(cb);
        i2.end(cb);
        to_transfer_src(cb, c.image, kC, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    }),
              VK_SUCCESS);
    Bytes b = k.read(c.image, 32, 32, 4);
    EXPECT_EQ(px(b, 22, 4)[1], 255);  // the partial clear
    EXPECT_EQ(px(b, 22, 4)[0], 0);
    return b;
}

// 4x colour resolved into a 1x image by one render pass instance split in two: suspended at the end of the first
// command buffer and resumed in the second, both in one VkSubmitInfo; or the same draws in one instance.
Bytes suspend_scene(Kit& k, bool suspend) {
    Img c = attachment_image(k, kC, VK_SAMPLE_COUNT_4_BIT), r = attachment_image(k, kC);
    PassDesc p;
    p.colours = {
        {c.view, kC, VK_SAMPLE_COUNT_4_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(0.1f, 0.2f, 0.3f, 1), r.view}};
    Instance in(k, p, true);
    VkPipeline pipe = blended(in);
    Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    VkCommandBuffer cbs[2] = {k.command_buffer(), k.command_buffer()};
    const VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    for (VkCommandBuffer cb : cbs) EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);
    to_attachment(cbs[0], c.image, kC);
    to_attachment(cbs[0], r.image, kC);
    if (suspend) {
        in.begin(cbs[0], VK_RENDERING_SUSPENDING_BIT);
        draw_all(cbs[0], pipe, vb, 0, 3);
        in.end(cbs[0]);
        in.begin(cbs[1], VK_RENDERING_RESUMING_BIT);
        draw_all(cbs[1], pipe, vb, 3, 3);
        in.end(cbs[1]);
    } else {
        in.begin(cbs[0]);
        draw_all(cbs[0], pipe, vb, 0, 3);
        draw_all(cbs[0], pipe, vb, 3, 3);
        in.end(cbs[0]);
    }
    to_transfer_src(cbs[1], r.image, kC, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    for (VkCommandBuffer cb : cbs) EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 2;
    si.pCommandBuffers = cbs;
    EXPECT_EQ(vkQueueSubmit(k.queue, 1, &si, VK_NULL_HANDLE), VK_SUCCESS);
    EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_SUCCESS);
    return k.read(r.image, 32, 32, 4);
}

class ApiDynamicRendering : public ApiBreadth {
  protected:
    std::unique_ptr<DevicePair> devices() {
        dr_.dynamicRendering = VK_TRUE;
        dr_.pNext = &mv_;
        mv_.multiview = VK_TRUE;
        return device_pair(kExtensions, &dr_);
    }
    // The scene with dynamic rendering on both drivers (equal bytes), and on tilevk through a render pass (equal to
    // the dynamic one).
    void check(const std::function<Bytes(Kit&, bool)>& scene) {
        auto d = devices();
        const Bytes dyn = both_on(d->tilevk, d->lavapipe, [&](Kit& k) { return scene(k, true); });
        Kit k(d->tilevk);
        expect_same(scene(k, false), dyn, "the same scene through a VkRenderPass");
    }
    VkPhysicalDeviceDynamicRenderingFeatures dr_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    VkPhysicalDeviceMultiviewFeatures mv_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
};

TEST_F(ApiDynamicRendering, ClearAndBlendedDraw) {
    check([](Kit& k, bool dynamic) { return colour_scene(k, dynamic, kC); });
}

// One B8G8R8A8_UNORM attachment and no depth: lavapipe's linear rasterizer (rast/render/linear_mode.h
// lavapipe_linear_mode decides it from the translated subpass as for a render pass).
TEST_F(ApiDynamicRendering, ClearAndBlendedDrawBgra8LinearMode) {
    check([](Kit& k, bool dynamic) { return colour_scene(k, dynamic, VK_FORMAT_B8G8R8A8_UNORM); });
}

TEST_F(ApiDynamicRendering, DepthTestD32) {
    check([](Kit& k, bool dynamic) { return depth_scene(k, dynamic, VK_FORMAT_D32_SFLOAT); });
}

TEST_F(ApiDynamicRendering, DepthStencilTestD24S8) {
    check([](Kit& k, bool dynamic) { return depth_scene(k, dynamic, VK_FORMAT_D24_UNORM_S8_UINT); });
}

TEST_F(ApiDynamicRendering, Msaa4xColourAndDepthResolve) {
    check([](Kit& k, bool dynamic) { return msaa_scene(k, dynamic, VK_FORMAT_D32_SFLOAT); });
}

// Both VkRenderingAttachmentInfo structs resolve the one D24S8 view (SAMPLE_ZERO each).
TEST_F(ApiDynamicRendering, Msaa4xColourAndDepthStencilResolveD24S8) {
    check([](Kit& k, bool dynamic) { return msaa_scene(k, dynamic, VK_FORMAT_D24_UNORM_S8_UINT); });
}

TEST_F(ApiDynamicRendering, MultiviewViewMaskWithClearAttachments) {
    check(multiview_scene);
}

TEST_F(ApiDynamicRendering, ClearAttachmentsInline) {
    check([](Kit& k, bool dynamic) { return clear_attachments_scene(k, dynamic, false); });
}

TEST_F(ApiDynamicRendering, SecondaryCommandBuffersWithInheritance) {
    check([](Kit& k, bool dynamic) { return clear_attachments_scene(k, dynamic, true); });
}

TEST_F(ApiDynamicRendering, LoadOpLoadAcrossInstancesAndPartialRenderArea) {
    check(load_scene);
}

// Suspended in one command buffer, resumed in the next of the same submission: the clear applies once (at the
// first begin) and the resolve once (at the last end), so the result equals one instance with both draws.
TEST_F(ApiDynamicRendering, SuspendAndResumeAcrossCommandBuffers) {
    auto d = devices();
    const Bytes split = both_on(d->tilevk, d->lavapipe, [](Kit& k) { return suspend_scene(k, true); });
    Kit k(d->tilevk);
    expect_same(suspend_scene(k, false), split, "one instance with both draws");
}

// dynamicRendering is reported (VkPhysicalDeviceDynamicRenderingFeatures and the Vulkan 1.3 struct), as by
// lavapipe, and the extension is listed.
TEST_F(ApiDynamicRendering, FeatureAndExtensionReported) {
    for (VkPhysicalDevice pd : {tilevk_->physical(), lavapipe_->physical()}) {
        VkPhysicalDeviceDynamicRenderingFeatures dr{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &dr};
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        EXPECT_EQ(dr.dynamicRendering, VK_TRUE);
        uint32_t n = 0;
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> exts(n);
        vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
        EXPECT_TRUE(std::any_of(exts.begin(), exts.end(), [](const VkExtensionProperties& e) {
            return std::strcmp(e.extensionName, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME) == 0;
        }));
    }
}

// Invalid usage refused by name on tilevk (no validation layer): a pipeline without a render pass and
// vkCmdBeginRenderingKHR on a device without the dynamicRendering feature (the instance renders nothing: the image
// keeps its contents), a view mask without the multiview feature.
TEST_F(ApiDynamicRendering, RefusalsWithoutTheFeatures) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    VkPhysicalDeviceDynamicRenderingFeatures dr{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    for (bool feature : {false, true}) {
        dr.dynamicRendering = feature;
        Device dev(plain.find_device("tilevk"), nullptr, kExtensions, &dr);
        ASSERT_TRUE(dev.ok());
        Kit k(dev);
        Img c = attachment_image(k, kC, VK_SAMPLE_COUNT_1_BIT, 2);
        PassDesc p;
        p.colours = {{c.view, kC, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, clear_color(1, 1, 1, 1)}};
        p.view_mask = feature ? 0b11 : 0;  // multiview is not enabled
        Instance in(k, p, true);
        if (!feature) {
            StderrCapture capture;
            Pipe pp;
            VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
            pp.pnext = &ri;
            VkResult r = VK_SUCCESS;
            EXPECT_EQ(k.pipeline(pp, &r), VkPipeline(VK_NULL_HANDLE));
            EXPECT_EQ(r, VK_ERROR_INITIALIZATION_FAILED);
            EXPECT_NE(capture.text().find("VkPhysicalDeviceDynamicRenderingFeatures::dynamicRendering"),
                      std::string::npos)
                << capture.text();
        }
        StderrCapture capture;
        EXPECT_EQ(k.run([&](VkCommandBuffer cb) {
            const VkClearColorValue grey{{0.5f, 0.5f, 0.5f, 1}};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 2};
            vkCmdClearColorImage(cb, c.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &range);
            in.begin(cb);
            in.end(cb);
        }),
                  VK_SUCCESS);
        const std::string err = capture.text();
        EXPECT_NE(err.find(feature ? "VkPhysicalDeviceMultiviewFeatures::multiview"
                                   : "VkPhysicalDeviceDynamicRenderingFeatures::dynamicRendering"),
                  std::string::npos)
            << err;
        EXPECT_EQ(px(k.read(c.image, 32, 32, 4), 3, 3)[0], 128);  // not cleared: nothing rendered
    }
}

}  // namespace
}  // namespace tilevk::test::breadth
