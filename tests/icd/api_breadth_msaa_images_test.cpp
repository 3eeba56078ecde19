// 4x images beyond one render pass (suite ApiMsaaImages): their samples are stored as planes (icd/image.h), and every
// command that reads or writes a multisampled image must find sample s of pixel (x, y) of layer l where the renderer
// put it. One scene on tilevk and lavapipe (validation layer on), compared byte for byte: a 2-layer 4x RGBA8 image
// cleared with vkCmdClearColorImage, one layer rendered with edge pixels of mixed coverage, alpha blending and a 4x
// D24S8 depth test (a packed depth/stencil attachment goes through staging), copied with vkCmdCopyImage into another
// 4x image at an offset, rendered into again with LOAD over a partial render area (the stored depth decides the new
// coverage per sample) plus vkCmdClearAttachments, then resolved with vkCmdResolveImage at offsets, every layer.
#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

class ApiMsaaImages : public ApiBreadth {};

constexpr uint32_t kSize = 32;
constexpr VkFormat kColour = VK_FORMAT_R8G8B8A8_UNORM, kDepth = VK_FORMAT_D24_UNORM_S8_UINT;
constexpr VkImageLayout kDst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kSrc = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        kColourAtt = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        kDepthAtt = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

Device::Image ms_image(Kit& k, VkFormat f, uint32_t w, uint32_t h, uint32_t layers, VkImageUsageFlags usage) {
    Device::Image i = k.dev().make_image(f, w, h, 1, layers, VK_SAMPLE_COUNT_4_BIT, usage);
    EXPECT_NE(i.image, VK_NULL_HANDLE);
    k.undo(VK_OBJECT_TYPE_IMAGE, i.image, [&k, i]() mutable { k.dev().destroy(i); });
    return i;
}

// Every earlier write is visible to every later command (the test orders its commands, not stages).
void full_barrier(VkCommandBuffer c) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &mb, 0,
                         nullptr, 0, nullptr);
}

// Layers [layer, layer + count) of `img` from layout `from` to `to`, every earlier write made visible.
void layout(VkCommandBuffer c, VkImage img, VkImageAspectFlags aspects, VkImageLayout from, VkImageLayout to,
            uint32_t layer = 0, uint32_t count = VK_REMAINING_ARRAY_LAYERS) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = from == VK_IMAGE_LAYOUT_UNDEFINED ? 0 : VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img;
    b.subresourceRange = {aspects, 0, 1, layer, count};
    vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
}

// A 4x colour + 4x depth/stencil pass; `load`: LOAD both (else CLEAR), both stored. The colour attachment ends in
// TRANSFER_SRC_OPTIMAL (copied or resolved next).
VkRenderPass ms_pass(Kit& k, bool load) {
    const VkAttachmentLoadOp op = load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    VkAttachmentDescription c = attachment(kColour, op, VK_ATTACHMENT_STORE_OP_STORE, kSrc);
    VkAttachmentDescription d = attachment(kDepth, op, VK_ATTACHMENT_STORE_OP_STORE, kDepthAtt);
    c.samples = d.samples = VK_SAMPLE_COUNT_4_BIT;
    c.initialLayout = kColourAtt;
    d.initialLayout = kDepthAtt;
    static const VkAttachmentReference cref{0, kColourAtt}, dref{1, kDepthAtt};
    return k.render_pass({c, d}, {subpass(&cref, &dref)});
}

void begin_area(VkCommandBuffer c, VkRenderPass rp, VkFramebuffer fb, VkRect2D area) {
    const VkClearValue clears[2] = {clear_color(0.05f, 0.1f, 0.2f, 0.9f), clear_depth(0.45f, 0)};
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = rp;
    bi.framebuffer = fb;
    bi.renderArea = area;
    bi.clearValueCount = 2;
    bi.pClearValues = clears;
    vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
}

Bytes msaa_images_scene(Kit& k) {
    const VkImageUsageFlags colour_usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const Device::Image a = ms_image(k, kColour, kSize, kSize, 2, colour_usage),
                        b = ms_image(k, kColour, kSize, kSize, 1, colour_usage);
    const Device::Image z = ms_image(k, kDepth, kSize, kSize, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    const VkImageAspectFlags ds = VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    const VkImageUsageFlags one_usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const Device::Image r = k.image(kColour, kSize, kSize, one_usage, 1, 3);  // the three resolves, one per layer
    const VkRenderPass clear_rp = ms_pass(k, false), load_rp = ms_pass(k, true);
    const VkImageView zv = k.view(z.image, kDepth, ds);
    const VkFramebuffer fa = k.framebuffer(
        clear_rp, {k.view(a.image, kColour, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D, 0, 1, 1, 1), zv}, kSize,
        kSize);
    const VkFramebuffer fb =
        k.framebuffer(load_rp, {k.view(b.image, kColour, VK_IMAGE_ASPECT_COLOR_BIT), zv}, kSize, kSize);
    const VkPipelineDepthStencilStateCreateInfo dss = depth_state(VK_COMPARE_OP_LESS);
    Pipe p;
    p.rp = clear_rp;  // compatible with load_rp
    p.samples = VK_SAMPLE_COUNT_4_BIT;
    p.blend = {alpha_over()};
    p.ds = &dss;
    const VkPipeline pipe = k.pipeline(p);
    std::vector<Vertex> verts = kBothTriangles;
    for (const Vertex& t : {v(-0.65f, 0.5f, 0.3f, 0, 0.5f, 1, 0.7f), v(0.5f, 0.45f, 0.3f, 0.2f, 1, 0.1f, 0.7f),
                            v(-0.1f, -0.75f, 0.3f, 1, 0.3f, 0.6f, 0.7f)})
        verts.push_back(t);
    const Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    const Device::Buffer out = k.buffer(VkDeviceSize(kSize) * kSize * 4 * 3);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        const VkImageAspectFlags colour = VK_IMAGE_ASPECT_COLOR_BIT;
        for (VkImage img : {a.image, b.image, r.image}) layout(c, img, colour, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
        layout(c, z.image, ds, VK_IMAGE_LAYOUT_UNDEFINED, kDepthAtt);
        const VkImageSubresourceRange all{colour, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
        const VkClearColorValue grey{{0.3f, 0.6f, 0.9f, 0.5f}}, dark{{0.7f, 0.2f, 0.1f, 1.0f}};
        vkCmdClearColorImage(c, a.image, kDst, &grey, 1, &all);  // both layers; layer 1 is cleared again
        vkCmdClearColorImage(c, b.image, kDst, &dark, 1, &all);
        vkCmdClearColorImage(c, r.image, kDst, &dark, 1, &all);
        full_barrier(c);
        layout(c, a.image, colour, kDst, kSrc, 0, 1);
        layout(c, a.image, colour, kDst, kColourAtt, 1, 1);
        // Pass 1: layer 1 of `a`, the two triangles blended over the load clear, depth LESS against 0.45.
        begin_area(c, clear_rp, fa, {{0, 0}, {kSize, kSize}});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdDraw(c, 6, 1, 0, 0);
        vkCmdEndRenderPass(c);
        const VkImageCopy copy{{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 1},
                               {3, 5, 0},
                               {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                               {7, 2, 0},
                               {20, 17, 1}};
        vkCmdCopyImage(c, a.image, kSrc, b.image, kDst, 1, &copy);
        layout(c, b.image, colour, kDst, kColourAtt);
        // Pass 2: `b` loaded, over a partial area (x 5-24, y 3-24) that holds the whole third triangle (rendering
        // outside the area is undefined); it passes only where pass 1 left depth above 0.3.
        begin_area(c, load_rp, fb, {{5, 3}, {20, 22}});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdDraw(c, 3, 1, 6, 0);
        const VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, clear_color(1, 0.5f, 0, 1)};
        const VkClearRect rect{{{10, 10}, {4, 3}}, 0, 1};
        vkCmdClearAttachments(c, 1, &ca, 1, &rect);
        vkCmdEndRenderPass(c);
        const VkImageResolve from_b{{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                    {1, 1, 0},
                                    {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                    {0, 2, 0},
                                    {30, 29, 1}};
        const VkImageResolve from_a{{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 2},
                                    {0, 0, 0},
                                    {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 2},
                                    {0, 0, 0},
                                    {kSize, kSize, 1}};
        vkCmdResolveImage(c, b.image, kSrc, r.image, kDst, 1, &from_b);
        vkCmdResolveImage(c, a.image, kSrc, r.image, kDst, 1, &from_a);
        layout(c, r.image, colour, kDst, kSrc);
        const VkBufferImageCopy down{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 3}, {0, 0, 0}, {kSize, kSize, 1}};
        vkCmdCopyImageToBuffer(c, r.image, kSrc, out.buffer, 1, &down);
    }),
              VK_SUCCESS);
    Bytes bytes = Kit::bytes(out);
    // Checks that need no driver: layer 0 of `a` (resolve layer 1) is the vkCmdClearColorImage grey everywhere, and
    // the layers differ from each other (pass 1 and the copy reached the resolves).
    auto px = [&](uint32_t layer, uint32_t x, uint32_t y) -> const uint8_t* {
        return &bytes[((layer * kSize + y) * kSize + x) * 4];
    };
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) EXPECT_EQ(px(1, x, y)[1], 153) << x << "," << y;
    EXPECT_NE(std::memcmp(px(0, 0, 0), px(2, 0, 0), size_t(kSize) * kSize * 4), 0);
    return bytes;
}

TEST_F(ApiMsaaImages, CopyClearRenderAndResolveAgreeOnTheSampleLayout) {
    both(msaa_images_scene);
}

// The render pass's colour resolves run in the renderer's tiles (rast/render/targets.h TileResolve): a 4x target of
// 3x3 tiles (the last row and column partial) with two colour attachments, only the second resolved, over a
// render area that starts and ends inside tiles; the draws touch some tiles only, so tiles without primitives
// must resolve too, and pixels outside the area must keep the resolve image's own clear.
Bytes tile_resolve_scene(Kit& k) {
    constexpr uint32_t W = 150, H = 140;
    const VkImageUsageFlags ms_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    const Device::Image m0 = ms_image(k, kColour, W, H, 1, ms_usage), m1 = ms_image(k, kColour, W, H, 1, ms_usage);
    const Device::Image r = k.image(
        kColour, W, H,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    VkAttachmentDescription ms =
        attachment(kColour, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE, kColourAtt);
    ms.samples = VK_SAMPLE_COUNT_4_BIT;
    VkAttachmentDescription one = attachment(kColour, VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_STORE, kSrc);
    one.initialLayout = kColourAtt;
    const VkAttachmentReference cols[2] = {{0, kColourAtt}, {1, kColourAtt}};
    const VkAttachmentReference res[2] = {{VK_ATTACHMENT_UNUSED, kColourAtt}, {2, kColourAtt}};
    VkSubpassDescription sub = subpass(&cols[0]);
    sub.colorAttachmentCount = 2;
    sub.pResolveAttachments = res;
    const VkRenderPass rp = k.render_pass({ms, ms, one}, {sub});
    const VkFramebuffer fb = k.framebuffer(
        rp,
        {k.view(m0.image, kColour, VK_IMAGE_ASPECT_COLOR_BIT), k.view(m1.image, kColour, VK_IMAGE_ASPECT_COLOR_BIT),
         k.view(r.image, kColour, VK_IMAGE_ASPECT_COLOR_BIT)},
        W, H);
    Pipe p;
    p.fs = SPV(ab_mrt_frag);
    p.rp = rp;
    p.samples = VK_SAMPLE_COUNT_4_BIT;
    p.color_count = 2;
    p.width = W;
    p.height = H;
    p.blend = {alpha_over(), alpha_over()};
    const VkPipeline pipe = k.pipeline(p);
    // Two triangles inside the top-left and the middle tiles of the area only (NDC of 150x140 pixels).
    const std::vector<Vertex> verts = {
        v(-0.75f, -0.85f, 0, 1, 0.2f, 0.1f, 0.6f), v(-0.3f, -0.8f, 0, 0.1f, 1, 0.3f, 0.9f),
        v(-0.6f, -0.2f, 0, 0.3f, 0.4f, 1, 0.4f),   v(-0.1f, -0.05f, 0, 1, 1, 0, 0.7f),
        v(0.2f, 0.1f, 0, 0, 1, 1, 0.5f),           v(-0.05f, 0.3f, 0, 1, 0, 1, 0.8f)};
    const Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    const Device::Buffer out = k.buffer(VkDeviceSize(W) * H * 4);
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        layout(c, r.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDst);
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        const VkClearColorValue dark{{0.7f, 0.2f, 0.1f, 1.0f}};
        vkCmdClearColorImage(c, r.image, kDst, &dark, 1, &all);
        layout(c, r.image, VK_IMAGE_ASPECT_COLOR_BIT, kDst, kColourAtt);
        const VkClearValue clears[3] = {clear_color(0.1f, 0.3f, 0.5f, 1), clear_color(0.9f, 0.35f, 0.05f, 0.6f), {}};
        VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        bi.renderPass = rp;
        bi.framebuffer = fb;
        bi.renderArea = {{9, 5}, {131, 122}};
        bi.clearValueCount = 3;
        bi.pClearValues = clears;
        vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        bind_vertices(c, vb);
        vkCmdDraw(c, 6, 1, 0, 0);
        vkCmdEndRenderPass(c);
        full_barrier(c);
        const VkBufferImageCopy down{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {W, H, 1}};
        vkCmdCopyImageToBuffer(c, r.image, kSrc, out.buffer, 1, &down);
    }),
              VK_SUCCESS);
    Bytes bytes = Kit::bytes(out);
    auto px = [&](uint32_t x, uint32_t y) { return &bytes[(size_t(y) * W + x) * 4]; };
    EXPECT_EQ(px(3, 3)[0], 178);  // outside the area: the resolve image's clear (0.7)
    EXPECT_EQ(px(145, 135)[0], 178);
    EXPECT_EQ(px(130, 120)[0], 230);  // inside, in a tile without primitives: the second attachment's clear (0.9)
    return bytes;
}

TEST_F(ApiMsaaImages, TileResolvesCoverEveryTileOfTheRenderArea) {
    both(tile_resolve_scene);
}

}  // namespace
}  // namespace tilevk::test::breadth
