// API breadth (api_breadth.h): command buffers (secondaries, resets, re-recording), render passes (subpasses,
// preserve and input attachments, unused references, clears) and dynamic state, on tilevk and lavapipe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "api_breadth.h"
#include "api_breadth_input_scene.h"

namespace tilevk::test::breadth {
namespace {

// ---- Command buffers -------------------------------------------------------------------------------------------

// Two secondaries inside a render pass (RENDER_PASS_CONTINUE, dynamic viewport/scissor set inside each), one
// outside (fill + update), executed from one primary; then the primary is reset, re-recorded and resubmitted.
TEST_F(ApiBreadth, SecondaryCommandBuffersInsideAndOutsideRenderPass) {
    const Bytes b = both([](Kit& k) {
        Target t = target(k);
        Pipe p;
        p.rp = t.rp;
        p.dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb1 = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb2 = k.buffer_of(kTriangle2, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer out = k.buffer(32 * 32 * 4 + 144);  // image, then 128 filled and 16 updated bytes
        VkCommandBufferInheritanceInfo inh{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
        inh.renderPass = t.rp;
        inh.subpass = 0;
        inh.framebuffer = t.fb;
        VkCommandBuffer sec[3];
        for (int i = 0; i < 3; ++i) {
            sec[i] = k.command_buffer(VK_COMMAND_BUFFER_LEVEL_SECONDARY);
            VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            bi.flags = i < 2 ? VK_COMMAND_BUFFER_USAGE_RENDER_PASS_CONTINUE_BIT : 0;
            VkCommandBufferInheritanceInfo none{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
            bi.pInheritanceInfo = i < 2 ? &inh : &none;
            EXPECT_EQ(vkBeginCommandBuffer(sec[i], &bi), VK_SUCCESS);
            if (i < 2) {
                vkCmdBindPipeline(sec[i], VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                VkViewport vp = i == 0 ? VkViewport{0, 0, 32, 32, 0, 1} : VkViewport{4, 2, 24, 28, 0, 1};
                VkRect2D sc = i == 0 ? VkRect2D{{0, 0}, {32, 32}} : VkRect2D{{3, 5}, {20, 17}};
                vkCmdSetViewport(sec[i], 0, 1, &vp);
                vkCmdSetScissor(sec[i], 0, 1, &sc);
                VkDeviceSize zero = 0;
                vkCmdBindVertexBuffers(sec[i], 0, 1, i == 0 ? &vb1.buffer : &vb2.buffer, &zero);
                vkCmdDraw(sec[i], 3, 1, 0, 0);
            } else {
                vkCmdFillBuffer(sec[i], out.buffer, 32 * 32 * 4, 128, 0xA5C3E1F0u);
                const uint32_t words[4] = {1, 2, 0xDEADBEEF, 4};
                vkCmdUpdateBuffer(sec[i], out.buffer, 32 * 32 * 4 + 128, sizeof words, words);
            }
            EXPECT_EQ(vkEndCommandBuffer(sec[i]), VK_SUCCESS);
        }
        VkCommandBuffer prim = k.command_buffer();
        auto record = [&](bool with_secondaries) {
            VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            EXPECT_EQ(vkBeginCommandBuffer(prim, &bi), VK_SUCCESS);
            begin_pass(prim, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)},
                       with_secondaries ? VK_SUBPASS_CONTENTS_SECONDARY_COMMAND_BUFFERS : VK_SUBPASS_CONTENTS_INLINE);
            if (with_secondaries) vkCmdExecuteCommands(prim, 2, sec);
            vkCmdEndRenderPass(prim);
            VkBufferImageCopy r{};
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            r.imageExtent = {32, 32, 1};
            vkCmdCopyImageToBuffer(prim, t.image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.buffer, 1, &r);
            if (with_secondaries) vkCmdExecuteCommands(prim, 1, &sec[2]);
            EXPECT_EQ(vkEndCommandBuffer(prim), VK_SUCCESS);
        };
        record(true);
        EXPECT_EQ(k.submit(prim), VK_SUCCESS);
        Bytes first = Kit::bytes(out);
        // Submitted again (no ONE_TIME_SUBMIT): the same work runs again, after the host scribbled over the result.
        std::memset(out.map, 0x77, out.size);
        EXPECT_EQ(k.submit(prim), VK_SUCCESS);
        Bytes second = Kit::bytes(out);
        EXPECT_EQ(first, second);
        // Reset and re-recorded without the secondaries: only the clear remains; the tail keeps the host's bytes.
        std::memset(out.map, 0x77, out.size);
        EXPECT_EQ(vkResetCommandBuffer(prim, 0), VK_SUCCESS);
        record(false);
        EXPECT_EQ(k.submit(prim), VK_SUCCESS);
        Bytes third = Kit::bytes(out);
        EXPECT_EQ(third[32 * 32 * 4], 0x77);
        EXPECT_EQ(px(third, 10, 12)[2], 64);
        return concat({first, third});
    });
    EXPECT_EQ(px(b, 31, 0)[2], 64);   // outside both triangles
    EXPECT_NE(px(b, 10, 12)[2], 64);  // first secondary's triangle
    EXPECT_EQ(b[32 * 32 * 4], 0xF0);  // fill (little-endian word)
    EXPECT_EQ(b[32 * 32 * 4 + 136], 0xEF);
}

// vkResetCommandPool resets every command buffer of the pool; a ONE_TIME_SUBMIT buffer re-recorded runs its new
// content.
TEST_F(ApiBreadth, CommandPoolResetAndReRecord) {
    both([](Kit& k) {
        Device::Buffer out = k.buffer(64);
        VkCommandBuffer cb = k.command_buffer();
        for (uint32_t round = 0; round < 3; ++round) {
            if (round == 2) {
                EXPECT_EQ(vkResetCommandPool(k.d, k.pool, 0), VK_SUCCESS);
            }
            VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
            EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);  // implicit reset (pool allows it)
            vkCmdFillBuffer(cb, out.buffer, 16 * round, 16, 0x01010101u * (round + 1));
            EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
            EXPECT_EQ(k.submit(cb), VK_SUCCESS);
        }
        const Bytes b = Kit::bytes(out);
        EXPECT_EQ(b[0], 1);
        EXPECT_EQ(b[16], 2);
        EXPECT_EQ(b[32], 3);
        EXPECT_EQ(b[48], 0);
        return b;
    });
}

// ---- Render passes ---------------------------------------------------------------------------------------------

// Three subpasses over five attachments of four formats: MRT into RGBA8 + R32F (subpass 0, preserving the rest),
// MRT into RGBA16F (loaded, pre-cleared outside the pass) + BGRA8 (DONT_CARE, fully covered) (subpass 1), then a
// blended draw over the RGBA8 written in subpass 0 (subpass 2). Attachment 4 is storeOp DONT_CARE.
TEST_F(ApiBreadth, SubpassesPreserveAndMixedFormatAttachments) {
    VkPhysicalDeviceFeatures features{};
    features.independentBlend = VK_TRUE;
    Device tdev(tilevk_->physical(), &features), ldev(lavapipe_->physical(), &features);
    ASSERT_TRUE(tdev.ok() && ldev.ok());
    const VkFormat fmts[5] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT,
                              VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM};
    const uint32_t texel[5] = {4, 4, 8, 4, 4};
    both_on(tdev, ldev, [&](Kit& k) {
        std::vector<Device::Image> imgs;
        std::vector<VkImageView> views;
        for (VkFormat f : fmts) {
            imgs.push_back(k.image(f, 32, 32,
                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                       VK_IMAGE_USAGE_TRANSFER_DST_BIT));
            views.push_back(k.view(imgs.back().image, f, VK_IMAGE_ASPECT_COLOR_BIT));
        }
        std::vector<VkAttachmentDescription> atts = {
            attachment(fmts[0], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE),
            attachment(fmts[1], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE),
            attachment(fmts[2], VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_STORE),
            attachment(fmts[3], VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE),
            attachment(fmts[4], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                       VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)};
        const VkImageLayout CA = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        VkAttachmentReference s0[3] = {{0, CA}, {1, CA}, {4, CA}}, s1[2] = {{2, CA}, {3, CA}}, s2[1] = {{0, CA}};
        uint32_t keep0[2] = {2, 3}, keep1[2] = {0, 1}, keep2[2] = {1, 2};
        std::vector<VkSubpassDescription> subs(3);
        for (auto& s : subs) s.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subs[0].colorAttachmentCount = 3;
        subs[0].pColorAttachments = s0;
        subs[0].preserveAttachmentCount = 2;
        subs[0].pPreserveAttachments = keep0;
        subs[1].colorAttachmentCount = 2;
        subs[1].pColorAttachments = s1;
        subs[1].preserveAttachmentCount = 2;
        subs[1].pPreserveAttachments = keep1;
        subs[2].colorAttachmentCount = 1;
        subs[2].pColorAttachments = s2;
        subs[2].preserveAttachmentCount = 2;
        subs[2].pPreserveAttachments = keep2;
        std::vector<VkSubpassDependency> deps;
        for (uint32_t i = 0; i < 2; ++i)
            deps.push_back({i, i + 1, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                            VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0});
        VkRenderPass rp = k.render_pass(atts, subs, deps);
        VkFramebuffer fb = k.framebuffer(rp, views, 32, 32);
        Pipe p0;
        p0.fs = SPV(ab_mrt_frag);
        p0.rp = rp;
        p0.color_count = 3;
        p0.blend = {opaque(), opaque(), opaque()};
        p0.blend[2].colorWriteMask = 0;  // the third attachment is written by no output
        VkPipeline pipe0 = k.pipeline(p0);
        Pipe p1 = p0;
        p1.subpass = 1;
        p1.color_count = 2;
        p1.blend = {alpha_over(), opaque()};
        VkPipeline pipe1 = k.pipeline(p1);
        Pipe p1full;
        p1full.vs = SPV(ab_fullscreen_vert);
        p1full.fs = SPV(ab_mrt_frag);
        p1full.bindings = {};
        p1full.attrs = {};
        p1full.rp = rp;
        p1full.subpass = 1;
        p1full.color_count = 2;
        p1full.blend = {opaque(), opaque()};
        p1full.blend[0].colorWriteMask = 0;  // only the DONT_CARE attachment gets the full-screen triangle
        VkPipeline pipe1full = k.pipeline(p1full);
        Pipe p2;
        p2.rp = rp;
        p2.subpass = 2;
        p2.blend = {alpha_over()};
        VkPipeline pipe2 = k.pipeline(p2);
        Device::Buffer vb1 = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb2 = k.buffer_of(kTriangle2, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            transition(c, imgs[2].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkClearColorValue cc{{0.3f, 0.6f, 0.9f, 0.5f}};
            VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(c, imgs[2].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &cc, 1, &range);
            transition(c, imgs[2].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            begin_pass(c, rp, fb, 32, 32,
                       {clear_color(0, 0, 0.25f, 1), clear_color(-2.5f, 0, 0, 0), clear_color(0, 0, 0, 0),
                        clear_color(0, 0, 0, 0), clear_color(1, 1, 1, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe0);
            bind_vertices(c, vb1);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_INLINE);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe1full);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe1);
            bind_vertices(c, vb2);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_INLINE);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe2);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes all;
        for (int i = 0; i < 4; ++i) {
            Bytes b = k.read(imgs[i].image, 32, 32, texel[i]);
            if (i == 0) {
                EXPECT_EQ(px(b, 31, 31)[2], 64);  // outside both triangles: the clear
                EXPECT_NE(px(b, 8, 6)[2], 64);    // inside the first triangle: drawn
            }
            all.insert(all.end(), b.begin(), b.end());
        }
        return all;
    });
}

// Input attachments: subpass 0 draws colour (RGBA8) and depth (D32); subpass 1 reads both with subpassLoad at
// each pixel into an RGBA32F attachment.
TEST_F(ApiBreadth, InputAttachmentsReadThePreviousSubpass) {
    both([](Kit& k) {
        InputScene s(k);
        VkRenderPass rp = k.render_pass(InputScene::attachments(), s.subpasses(), {InputScene::dependency()});
        VkFramebuffer fb = k.framebuffer(rp, s.views(), 32, 32);
        s.build(rp);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 32, 32, InputScene::clears());
            s.draw_subpass0(c);
            vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_INLINE);
            s.draw_subpass1(c);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        return s.read_checked();
    });
}

// A subpass whose first colour reference is VK_ATTACHMENT_UNUSED (the shader's output 0 goes nowhere, output 1
// to the attachment), recorded in secondary command buffers across vkCmdNextSubpass, with vkCmdClearAttachments
// inside a secondary.
TEST_F(ApiBreadth, UnusedAttachmentReferenceAndSecondaryClears) {
    VkPhysicalDeviceFeatures features{};
    features.independentBlend = VK_TRUE;
    Device tdev(tilevk_->physical(), &features), ldev(lavapipe_->physical(), &features);
    ASSERT_TRUE(tdev.ok() && ldev.ok());
    both_on(tdev, ldev, [](Kit& k) {
        const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
        Device::Image img = k.image(C, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        const VkImageLayout CA = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        VkAttachmentReference refs0[2] = {{VK_ATTACHMENT_UNUSED, CA}, {0, CA}}, refs1[1] = {{0, CA}};
        std::vector<VkSubpassDescription> subs(2);
        subs[0].pipelineBindPoint = subs[1].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subs[0].colorAttachmentCount = 2;
        subs[0].pColorAttachments = refs0;
        subs[1].colorAttachmentCount = 1;
        subs[1].pColorAttachments = refs1;
        VkSubpassDependency dep{0,
                                1,
                                VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                0};
        VkRenderPass rp =
            k.render_pass({attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)}, subs, {dep});
        VkFramebuffer fb = k.framebuffer(rp, {k.view(img.image, C, VK_IMAGE_ASPECT_COLOR_BIT)}, 32, 32);
        Pipe p0;
        p0.fs = SPV(ab_mrt_frag);
        p0.rp = rp;
        p0.color_count = 2;
        VkPipeline pipe0 = k.pipeline(p0);
        Pipe p1;
        p1.rp = rp;
        p1.subpass = 1;
        p1.blend = {alpha_over()};
        VkPipeline pipe1 = k.pipeline(p1);
        Device::Buffer vb1 = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb2 = k.buffer_of(kTriangle2, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        VkCommandBuffer sec[2];
        for (uint32_t i = 0; i < 2; ++i) {
            sec[i] = k.command_buffer(VK_COMMAND_BUFFER_LEVEL_SECONDARY);
            VkCommandBufferInheritanceInfo inh{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
            inh.renderPass = rp;
            inh.subpass = i;
            inh.framebuffer = i == 0 ? VK_NULL_HANDLE : fb;  // the framebuffer is optional
            VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            // The second is executed twice in one primary: SIMULTANEOUS_USE.
            bi.flags =
                VK_COMMAND_BUFFER_USAGE_RENDER_PASS_CONTINUE_BIT |
                (i == 1 ? VK_COMMAND_BUFFER_USAGE_SIMULTANEOUS_USE_BIT : VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT);
            bi.pInheritanceInfo = &inh;
            EXPECT_EQ(vkBeginCommandBuffer(sec[i], &bi), VK_SUCCESS);
            VkDeviceSize zero = 0;
            vkCmdBindPipeline(sec[i], VK_PIPELINE_BIND_POINT_GRAPHICS, i == 0 ? pipe0 : pipe1);
            vkCmdBindVertexBuffers(sec[i], 0, 1, i == 0 ? &vb1.buffer : &vb2.buffer, &zero);
            vkCmdDraw(sec[i], 3, 1, 0, 0);
            if (i == 1) {
                VkClearAttachment ca{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
                ca.clearValue.color = {{0.2f, 0.9f, 0.4f, 1.0f}};
                VkClearRect r{{{5, 20}, {14, 6}}, 0, 1};
                vkCmdClearAttachments(sec[i], 1, &ca, 1, &r);
            }
            EXPECT_EQ(vkEndCommandBuffer(sec[i]), VK_SUCCESS);
        }
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1)}, VK_SUBPASS_CONTENTS_SECONDARY_COMMAND_BUFFERS);
            vkCmdExecuteCommands(c, 1, &sec[0]);
            vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_SECONDARY_COMMAND_BUFFERS);
            const VkCommandBuffer twice[2] = {sec[1], sec[1]};  // blended twice: visible
            vkCmdExecuteCommands(c, 2, twice);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(img.image, 32, 32, 4);
        EXPECT_EQ(px(b, 6, 21)[1], 230);  // the secondary's clear rectangle
        return b;
    });
}

// vkCmdClearAttachments: several partial rectangles, colour and depth, on both layers of a 2-layer framebuffer,
// between draws (the second draw is depth-tested against the partly cleared depth).
TEST_F(ApiBreadth, ClearAttachmentsRectsAndLayers) {
    both([](Kit& k) {
        Device::Image col = k.image(VK_FORMAT_R8G8B8A8_UNORM, 32, 32,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, 1, 2);
        Device::Image dep =
            k.image(VK_FORMAT_D32_SFLOAT, 32, 32,
                    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, 1, 2);
        VkRenderPass rp = colour_depth_pass(k, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT);
        VkFramebuffer fb = k.framebuffer(rp,
                                         {k.view(col.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT,
                                                 VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0, 2),
                                          k.view(dep.image, VK_FORMAT_D32_SFLOAT, VK_IMAGE_ASPECT_DEPTH_BIT,
                                                 VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, 1, 0, 2)},
                                         32, 32, 2);
        const VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
        Pipe p;
        p.rp = rp;
        p.ds = &ds;
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb1 = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb2 = k.buffer_of(kTriangle2, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(1.0f)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb1);
            vkCmdDraw(c, 3, 1, 0, 0);
            VkClearAttachment ca[2] = {{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}}, {VK_IMAGE_ASPECT_DEPTH_BIT, 0, {}}};
            ca[0].clearValue.color = {{0.5f, 1.0f, 0.0f, 1.0f}};
            ca[1].clearValue.depthStencil = {0.05f, 0};
            VkClearRect rects[3] = {{{{2, 3}, {9, 7}}, 0, 1}, {{{20, 1}, {5, 30}}, 0, 2}, {{{7, 18}, {13, 4}}, 1, 1}};
            vkCmdClearAttachments(c, 1, &ca[0], 3, rects);
            VkClearRect drect{{{12, 10}, {10, 10}}, 0, 1};
            vkCmdClearAttachments(c, 1, &ca[1], 1, &drect);
            bind_vertices(c, vb2);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes l0 = k.read(col.image, 32, 32, 4, VK_IMAGE_ASPECT_COLOR_BIT, 0, 0);
        Bytes l1 = k.read(col.image, 32, 32, 4, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1);
        EXPECT_EQ(px(l0, 4, 5)[0], 128);    // first rect (over the triangle)
        EXPECT_EQ(px(l1, 22, 20)[1], 255);  // second rect reaches layer 1
        EXPECT_EQ(px(l1, 10, 19)[1], 255);  // third rect is on layer 1 only
        EXPECT_EQ(px(l1, 2, 2)[2], 64);     // layer 1 elsewhere: the render pass clear
        Bytes d0 = k.read(dep.image, 32, 32, 4, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0);
        return concat({l0, l1, d0});
    });
}

// ---- Dynamic state ---------------------------------------------------------------------------------------------

// Every dynamic state of Vulkan 1.0, set before the pipeline is bound (it must survive the bind), then changed
// after it for a second draw: viewport, scissor, line width (wide lines), depth bias, blend constants, stencil
// compare mask / write mask / reference.
TEST_F(ApiBreadth, DynamicStateBeforeAndAfterBind) {
    VkPhysicalDeviceFeatures features{};
    features.wideLines = VK_TRUE;
    features.depthBiasClamp = VK_TRUE;
    Device tdev(tilevk_->physical(), &features), ldev(lavapipe_->physical(), &features);
    ASSERT_TRUE(tdev.ok() && ldev.ok());
    both_on(tdev, ldev, [](Kit& k) {
        const auto [col, dep, rp, fb] = depth_target(k, VK_FORMAT_D32_SFLOAT_S8_UINT);
        VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS_OR_EQUAL);
        ds.stencilTestEnable = VK_TRUE;
        ds.front = ds.back = {
            VK_STENCIL_OP_KEEP, VK_STENCIL_OP_INCREMENT_AND_WRAP, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_EQUAL, 0, 0, 0};
        const VkPipelineColorBlendAttachmentState bl =
            blend_add(VK_BLEND_FACTOR_CONSTANT_COLOR, VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR,
                      VK_BLEND_FACTOR_CONSTANT_ALPHA, VK_BLEND_FACTOR_ZERO);
        Pipe p;
        p.rp = rp;
        p.ds = &ds;
        p.depth_bias = true;
        p.blend = {bl};
        p.dynamic = {VK_DYNAMIC_STATE_VIEWPORT,           VK_DYNAMIC_STATE_SCISSOR,
                     VK_DYNAMIC_STATE_LINE_WIDTH,         VK_DYNAMIC_STATE_DEPTH_BIAS,
                     VK_DYNAMIC_STATE_BLEND_CONSTANTS,    VK_DYNAMIC_STATE_STENCIL_COMPARE_MASK,
                     VK_DYNAMIC_STATE_STENCIL_WRITE_MASK, VK_DYNAMIC_STATE_STENCIL_REFERENCE};
        VkPipeline tri = k.pipeline(p);
        p.topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        VkPipeline lines = k.pipeline(p);
        std::vector<Vertex> verts = kBothTriangles;
        verts.push_back(v(-0.9f, 0.8f, 0.0f, 1, 1, 1));
        verts.push_back(v(0.9f, -0.3f, 0.0f, 1, 0.5f, 0));
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(0.5f, 3)});
            // Before the bind.
            VkViewport vp{1, 2, 29, 27, 0, 1};
            VkRect2D sc{{2, 1}, {27, 29}};
            vkCmdSetViewport(c, 0, 1, &vp);
            vkCmdSetScissor(c, 0, 1, &sc);
            vkCmdSetLineWidth(c, 3.0f);
            vkCmdSetDepthBias(c, -0.25f * 16777216.0f / 65536.0f, 0.0f, -0.5f);
            const float bc[4] = {0.25f, 0.5f, 0.75f, 0.6f};
            vkCmdSetBlendConstants(c, bc);
            vkCmdSetStencilCompareMask(c, VK_STENCIL_FACE_FRONT_AND_BACK, 0x3);
            vkCmdSetStencilWriteMask(c, VK_STENCIL_FACE_FRONT_AND_BACK, 0xff);
            vkCmdSetStencilReference(c, VK_STENCIL_FACE_FRONT_AND_BACK, 0x7);  // 7&3 == 3&3: passes
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, tri);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            // After the bind: new values for the second triangle.
            VkViewport vp2{0, 0, 32, 32, 0, 1};
            VkRect2D sc2{{0, 0}, {24, 32}};
            vkCmdSetViewport(c, 0, 1, &vp2);
            vkCmdSetScissor(c, 0, 1, &sc2);
            vkCmdSetDepthBias(c, 0.0f, 0.0f, 0.0f);
            const float bc2[4] = {1.0f, 0.25f, 0.0f, 1.0f};
            vkCmdSetBlendConstants(c, bc2);
            vkCmdSetStencilCompareMask(c, VK_STENCIL_FACE_FRONT_AND_BACK, 0xff);
            vkCmdSetStencilReference(c, VK_STENCIL_FACE_FRONT_AND_BACK, 3);  // only where stencil is 3
            vkCmdSetStencilWriteMask(c, VK_STENCIL_FACE_FRONT_AND_BACK, 0x0c);
            vkCmdDraw(c, 3, 1, 3, 0);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, lines);
            vkCmdSetStencilReference(c, VK_STENCIL_FACE_FRONT_AND_BACK, 4);
            vkCmdSetStencilCompareMask(c, VK_STENCIL_FACE_FRONT_AND_BACK, 0x4);
            vkCmdDraw(c, 2, 1, 6, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes c0 = k.read(col.image, 32, 32, 4);
        Bytes d0 = k.read(dep.image, 32, 32, 4, VK_IMAGE_ASPECT_DEPTH_BIT);
        Bytes s0 = k.read(dep.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT);
        EXPECT_EQ(px(c0, 0, 31)[2], 64);  // outside the first scissor
        return concat({c0, d0, s0});
    });
}

// Two-sided stencil with different front and back state (static ops, per-face dynamic reference and masks), both
// windings drawn, on D24_UNORM_S8_UINT; and a reversed-depth viewport (minDepth 1, maxDepth 0, compare GREATER,
// cleared to 0) as reversed-Z renderers use it.
TEST_F(ApiBreadth, PerFaceStencilAndReversedDepthRange) {
    both([](Kit& k) {
        const auto [col, dep, rp, fb] = depth_target(k, VK_FORMAT_D24_UNORM_S8_UINT);
        VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_GREATER);
        ds.stencilTestEnable = VK_TRUE;
        ds.front = {VK_STENCIL_OP_ZERO,
                    VK_STENCIL_OP_INCREMENT_AND_CLAMP,
                    VK_STENCIL_OP_KEEP,
                    VK_COMPARE_OP_GREATER_OR_EQUAL,
                    0,
                    0,
                    0};
        ds.back = {VK_STENCIL_OP_KEEP,
                   VK_STENCIL_OP_INVERT,
                   VK_STENCIL_OP_DECREMENT_AND_WRAP,
                   VK_COMPARE_OP_NOT_EQUAL,
                   0,
                   0,
                   0};
        Pipe p;
        p.rp = rp;
        p.ds = &ds;
        p.dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_STENCIL_COMPARE_MASK,
                     VK_DYNAMIC_STATE_STENCIL_WRITE_MASK, VK_DYNAMIC_STATE_STENCIL_REFERENCE};
        VkPipeline pipe = k.pipeline(p);
        // kTriangle is counter-clockwise in framebuffer space, its reversed copy clockwise: one front, one back.
        std::vector<Vertex> verts = kTriangle;
        verts.insert(verts.end(), kTriangle2.rbegin(), kTriangle2.rend());
        verts.insert(verts.end(), kTriangle2.begin(), kTriangle2.end());
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(0.0f, 0x35)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            VkViewport vp{0, 0, 32, 32, 1.0f, 0.0f};  // reversed depth range
            vkCmdSetViewport(c, 0, 1, &vp);
            vkCmdSetStencilReference(c, VK_STENCIL_FACE_FRONT_BIT, 0x40);
            vkCmdSetStencilReference(c, VK_STENCIL_FACE_BACK_BIT, 0x35);
            vkCmdSetStencilCompareMask(c, VK_STENCIL_FACE_FRONT_BIT, 0xf0);
            vkCmdSetStencilCompareMask(c, VK_STENCIL_FACE_BACK_BIT, 0x0f);
            vkCmdSetStencilWriteMask(c, VK_STENCIL_FACE_FRONT_BIT, 0xff);
            vkCmdSetStencilWriteMask(c, VK_STENCIL_FACE_BACK_BIT, 0x3c);
            bind_vertices(c, vb);
            vkCmdDraw(c, 6, 1, 0, 0);
            vkCmdSetStencilReference(c, VK_STENCIL_FACE_BACK_BIT, 0x30);
            vkCmdDraw(c, 3, 1, 6, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes c0 = k.read(col.image, 32, 32, 4);
        EXPECT_EQ(px(c0, 31, 31)[2], 64);
        return concat({c0, k.read(dep.image, 32, 32, 4, VK_IMAGE_ASPECT_DEPTH_BIT),
                       k.read(dep.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT)});
    });
}

}  // namespace
}  // namespace tilevk::test::breadth
