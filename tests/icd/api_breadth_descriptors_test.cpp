// API breadth (api_breadth.h): push constants, specialization constants, limits, descriptor sets and arrays,
// textures and views, MSAA resolves, depth sampling, rendering into levels/layers, texel buffers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

// ---- Push constants and descriptors ----------------------------------------------------------------------------

// Push constants in both stages at different offsets, updated in pieces between draws.
TEST_F(ApiBreadth, PushConstantsBothStagesWithOffsets) {
    both([](Kit& k) {
        Target t = target(k);
        VkPipelineLayout layout =
            k.pipeline_layout({}, {{VK_SHADER_STAGE_VERTEX_BIT, 0, 16}, {VK_SHADER_STAGE_FRAGMENT_BIT, 16, 32}});
        Pipe p;
        p.vs = SPV(ab_push_vert);
        p.fs = SPV(ab_push_frag);
        p.rp = t.rp;
        p.layout = layout;
        VkPipeline pipe = k.pipeline(p);
        p.blend = {alpha_over()};
        VkPipeline blended = k.pipeline(p);  // same layout: the pushed values stay valid across the switch
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            // Pushed before the pipeline is bound.
            const float off[4] = {0.1f, -0.05f, 0, 0}, frag[8] = {1, 0.5f, 0.25f, 1, 0, 0.1f, 0.2f, 0};
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, 16, off);
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_FRAGMENT_BIT, 16, 32, frag);
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            // Only the `add` vector and the x offset change.
            const float add[4] = {0.5f, 0, 0, 0.0f}, x = 0.6f;
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_FRAGMENT_BIT, 32, 16, add);
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, 4, &x);
            vkCmdDraw(c, 3, 1, 0, 0);
            // Another pipeline with the same layout, nothing pushed again; then one y offset pushed.
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, blended);
            const float y = 0.7f;
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT, 4, 4, &y);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_EQ(px(b, 0, 31)[2], 64);
        return b;
    });
}

// Specialization constants (float, int, bool, and an int sizing an array), three pipelines from one module with
// different map entries and data layouts, plus one with no specialization (the defaults).
TEST_F(ApiBreadth, SpecializationConstants) {
    both([](Kit& k) {
        Target t = target(k);
        struct Data {
            int32_t mode;
            float scale;
            VkBool32 invert;
            int32_t count;
        };
        const VkSpecializationMapEntry entries[4] = {{0, offsetof(Data, scale), 4},
                                                     {3, offsetof(Data, mode), 4},
                                                     {7, offsetof(Data, invert), 4},
                                                     {9, offsetof(Data, count), 4}};
        const Data data[3] = {{1, 0.75f, VK_FALSE, 3}, {2, 1.5f, VK_TRUE, 5}, {0, 0.5f, VK_TRUE, 1}};
        VkSpecializationInfo infos[3];
        for (int i = 0; i < 3; ++i) infos[i] = {4, entries, sizeof(Data), &data[i]};
        infos[2].mapEntryCount = 2;  // only scale and mode: invert and count keep their defaults
        std::vector<VkPipeline> pipes;
        for (int i = 0; i < 4; ++i) {
            Pipe p;
            p.fs = SPV(ab_spec_frag);
            p.rp = t.rp;
            p.blend = {alpha_over()};
            p.fs_spec = i < 3 ? &infos[i] : nullptr;
            pipes.push_back(k.pipeline(p));
        }
        std::vector<Vertex> verts = kBothTriangles;
        for (int i = 0; i < 3; ++i)
            verts.push_back(v(-1.0f + 0.9f * float(i), 1.0f - float(i == 1), 0.1f, 0.9f, 0.3f, 0.6f, 0.7f));
        verts.push_back(v(-0.3f, -1, 0, 0.1f, 0.8f, 0.2f, 0.9f));
        verts.push_back(v(1, 0.2f, 0, 0.6f, 0.1f, 0.9f, 0.4f));
        verts.push_back(v(0.5f, 1, 0, 0.3f, 0.3f, 0.3f, 0.6f));
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            bind_vertices(c, vb);
            for (uint32_t i = 0; i < 4; ++i) {
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes[i]);
                vkCmdDraw(c, 3, 1, 3 * i, 0);
            }
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(b, 10, 12)[2], 64);
        return b;
    });
}

// The limits tilevk reports are usable at their value: 16 vertex attributes from 16 bindings (mixed formats and
// rates), 56 varying components, 128 bytes of push constants visible to both stages, 8 descriptor sets, 8 colour
// attachments of 4 formats (lavapipe's 8 and 8).
TEST_F(ApiBreadth, ReportedLimitsAreUsable) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &props);
    const VkPhysicalDeviceLimits& lim = props.limits;
    ASSERT_GE(lim.maxVertexInputAttributes, 16u);
    ASSERT_GE(lim.maxVertexInputBindings, 16u);
    ASSERT_GE(lim.maxVertexOutputComponents, 56u);
    ASSERT_GE(lim.maxPushConstantsSize, 128u);
    ASSERT_GE(lim.maxBoundDescriptorSets, 8u);
    ASSERT_GE(lim.maxColorAttachments, 8u);
    VkPhysicalDeviceFeatures features{};
    features.independentBlend = VK_TRUE;
    Device tdev(tilevk_->physical(), &features), ldev(lavapipe_->physical(), &features);
    ASSERT_TRUE(tdev.ok() && ldev.ok());
    both_on(tdev, ldev, [](Kit& k) {
        const VkFormat fmts[4] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_B8G8R8A8_UNORM};
        const uint32_t texel[4] = {4, 16, 8, 4};
        std::vector<Device::Image> imgs;
        std::vector<VkImageView> views;
        std::vector<VkAttachmentDescription> atts;
        std::vector<VkAttachmentReference> refs;
        for (uint32_t i = 0; i < 8; ++i) {
            imgs.push_back(
                k.image(fmts[i % 4], 16, 16, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
            views.push_back(k.view(imgs.back().image, fmts[i % 4], VK_IMAGE_ASPECT_COLOR_BIT));
            atts.push_back(attachment(fmts[i % 4], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE));
            refs.push_back({i, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
        }
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 8;
        sub.pColorAttachments = refs.data();
        VkRenderPass rp = k.render_pass(atts, {sub});
        VkFramebuffer fb = k.framebuffer(rp, views, 16, 16);
        std::vector<VkDescriptorSetLayout> dsls;
        std::vector<VkDescriptorSet> sets;
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
        const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
        Device::Buffer ubo = k.buffer(8 * align, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        for (uint32_t i = 0; i < 8; ++i) {
            const float u[4] = {0.1f * float(i + 1), 0.5f, 1.0f - 0.2f * float(i), 0.25f};
            std::memcpy(static_cast<uint8_t*>(ubo.map) + i * align, u, 16);
            dsls.push_back(k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}}));
            sets.push_back(k.descriptor_set(dsls.back()));
            VkDescriptorBufferInfo bi{ubo.buffer, i * align, 16};
            k.write(sets.back(), 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bi, nullptr);
        }
        VkPipelineLayout layout =
            k.pipeline_layout(dsls, {{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 128}});
        // 16 bindings, one attribute each: formats cycle through float/norm/half, every fourth per instance.
        const VkFormat afmt[4] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM,
                                  VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_SNORM};
        const uint32_t asize[4] = {16, 4, 8, 4};
        Pipe p;
        p.vs = SPV(ab_limits_vert);
        p.fs = SPV(ab_limits_frag);
        p.rp = rp;
        p.layout = layout;
        p.width = p.height = 16;
        p.color_count = 8;
        p.bindings.clear();
        p.attrs.clear();
        std::vector<Device::Buffer> vbs;
        for (uint32_t i = 0; i < 16; ++i) {
            const uint32_t f = i == 0 ? 0 : i % 4;
            const bool inst = i % 4 == 3;
            p.bindings.push_back({i, asize[f], inst ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
            p.attrs.push_back({i, i, afmt[f], 0});
            std::vector<uint8_t> data = texel_data(f == 0   ? VK_FORMAT_R32G32B32A32_SFLOAT
                                                   : f == 2 ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                            : VK_FORMAT_R8G8B8A8_UNORM,
                                                   3, 40 + i);
            if (i == 0) {  // positions: a triangle covering most of the target
                const float pos[12] = {-0.9f, -0.9f, 0, 1, 0.95f, -0.6f, 0, 1, -0.5f, 0.9f, 0, 1};
                std::memcpy(data.data(), pos, sizeof pos);
            }
            vbs.push_back(k.buffer_of(data, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
        }
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 16, 16,
                       {clear_color(0, 0, 0.25f, 1), clear_color(-1, 0, 1, 0), clear_color(0.5f, 0, 0, 1),
                        clear_color(0, 1, 0, 1), clear_color(0.25f, 0.5f, 0, 1), clear_color(2, -3, 0.5f, 1),
                        clear_color(0, 0, 0, 0), clear_color(1, 1, 1, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            std::vector<VkBuffer> bufs;
            std::vector<VkDeviceSize> offs(16, 0);
            for (auto& b : vbs) bufs.push_back(b.buffer);
            vkCmdBindVertexBuffers(c, 0, 16, bufs.data(), offs.data());
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 8, sets.data(), 0, nullptr);
            float pc[32];
            for (int i = 0; i < 32; ++i) pc[i] = float((i * 7) % 11) / 10.0f - 0.2f;
            pc[0] = pc[1] = 0.0f;  // no position offset
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 128, pc);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes out;
        for (uint32_t i = 0; i < 8; ++i) out = concat({out, k.read(imgs[i].image, 16, 16, texel[i % 4])});
        EXPECT_NE(px(out, 8, 8, 16)[2], 64);  // attachment 0 drawn in the middle
        return out;
    });
}

// Two sets, several bindings each: a uniform buffer, a combined image sampler, a dynamic uniform buffer (two draws
// with different dynamic offsets), a separate sampled image + sampler.
TEST_F(ApiBreadth, DescriptorSetsDynamicOffsetsSeparateSamplers) {
    both([](Kit& k) {
        Target t = target(k);
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
        const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
        const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
        VkDescriptorSetLayout l0 = k.set_layout(
            {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, F}, {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, F}});
        VkDescriptorSetLayout l1 = k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, F},
                                                 {1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1, F},
                                                 {2, VK_DESCRIPTOR_TYPE_SAMPLER, 1, F}});
        VkPipelineLayout layout = k.pipeline_layout({l0, l1});
        VkDescriptorSet s0 = k.descriptor_set(l0), s1 = k.descriptor_set(l1);
        Device::Buffer ubo = k.buffer(align * 3, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        auto* u = static_cast<float*>(ubo.map);
        const float vals[3][4] = {{0.2f, 0.4f, 0.6f, 0.8f}, {1, 0, 0.5f, 1}, {0, 1, 0.25f, 0.5f}};
        for (int i = 0; i < 3; ++i) std::memcpy(u + i * align / 4, vals[i], 16);
        Device::Image t1 =
            k.image(VK_FORMAT_R8G8B8A8_UNORM, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        Device::Image t2 =
            k.image(VK_FORMAT_R8G8B8A8_UNORM, 8, 2, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        upload_rgba8(k, t1.image, 4, 4, 1);
        upload_rgba8(k, t2.image, 8, 2, 2);
        VkSampler smp = k.sampler(VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT);
        VkDescriptorBufferInfo b0{ubo.buffer, 0, 16}, bd{ubo.buffer, 0, 16};
        VkDescriptorImageInfo i1{smp, k.view(t1.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo i2{VK_NULL_HANDLE, k.view(t2.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo is{smp, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
        k.write(s0, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &b0, nullptr);
        k.write(s0, 3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &i1);
        k.write(s1, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, &bd, nullptr);
        k.write(s1, 1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, nullptr, &i2);
        k.write(s1, 2, VK_DESCRIPTOR_TYPE_SAMPLER, nullptr, &is);
        Pipe p;
        p.fs = SPV(ab_descriptors_frag);
        p.rp = t.rp;
        p.layout = layout;
        VkPipeline pipe = k.pipeline(p);
        std::vector<Vertex> verts = {v(-1, -1, 0, 0, 0, 0), v(1, -1, 0, 1.5f, 0, 0), v(-1, 1, 0, 0, 1.5f, 0),
                                     v(1, 1, 0, 1, 1, 0),   v(1, -1, 0, 1.5f, 0, 0), v(-1, 1, 0, 0, 1.5f, 0)};
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            VkDescriptorSet sets[2] = {s0, s1};
            uint32_t dyn = uint32_t(align);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 2, sets, 1, &dyn);
            vkCmdDraw(c, 3, 1, 0, 0);
            dyn = uint32_t(2 * align);  // rebinding set 1 only, with another offset
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &s1, 1, &dyn);
            vkCmdDraw(c, 3, 1, 3, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(b, 1, 1)[0], px(b, 30, 30)[0]);  // the two dynamic offsets differ
        return b;
    });
}

// Dynamic offsets are consumed in set order, then binding number (not declaration order), then array element:
// set 0 declares binding 2 (an array of two) before binding 0; set 1 has one; five offsets, rebound per draw.
TEST_F(ApiBreadth, DynamicOffsetOrderAcrossSetsBindingsAndArrays) {
    both([](Kit& k) {
        Target t = target(k);
        const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
        const VkDescriptorType DYN = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
        VkDescriptorSetLayout l0 = k.set_layout({{2, DYN, 2, F}, {0, DYN, 1, F}});
        VkDescriptorSetLayout l1 = k.set_layout({{1, DYN, 1, F}});
        VkPipelineLayout layout = k.pipeline_layout({l0, l1});
        VkDescriptorSet s0 = k.descriptor_set(l0), s1 = k.descriptor_set(l1);
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
        const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
        Device::Buffer ubo = k.buffer(8 * align, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        for (uint32_t i = 0; i < 8; ++i) {
            const float val[4] = {float(i) / 7.0f, float(7 - i) / 7.0f, float(i % 3) / 2.0f, 1.0f};
            std::memcpy(static_cast<uint8_t*>(ubo.map) + i * align, val, 16);
        }
        VkDescriptorBufferInfo bi[2] = {{ubo.buffer, 0, 16}, {ubo.buffer, 0, 16}};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = s0;
        w.dstBinding = 2;
        w.descriptorCount = 2;
        w.descriptorType = DYN;
        w.pBufferInfo = bi;
        vkUpdateDescriptorSets(k.d, 1, &w, 0, nullptr);
        k.write(s0, 0, DYN, bi, nullptr);
        k.write(s1, 1, DYN, bi, nullptr);
        Pipe p;
        p.fs = SPV(ab_dynamic_frag);
        p.rp = t.rp;
        p.layout = layout;
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            VkDescriptorSet sets[2] = {s0, s1};
            // Order: set 0 binding 0, set 0 binding 2 [0], [1], set 1 binding 1.
            uint32_t offs[4] = {uint32_t(1 * align), uint32_t(4 * align), uint32_t(6 * align), uint32_t(2 * align)};
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 2, sets, 4, offs);
            vkCmdDraw(c, 3, 1, 0, 0);
            uint32_t offs1[1] = {uint32_t(7 * align)};
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &s1, 1, offs1);
            vkCmdDraw(c, 3, 1, 3, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
}

// A 2D array texture with mips: layers selected by the third coordinate, through a view of levels 1..2 and
// layers 1..3 (so the view's base level and layer both matter).
TEST_F(ApiBreadth, ArrayTextureViewOfLevelsAndLayers) {
    both([](Kit& k) {
        Target t = target(k);
        Device::Image tex = k.image(VK_FORMAT_R8G8B8A8_UNORM, 16, 16,
                                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 3, 4);
        Device::Buffer src = k.buffer(16 * 16 * 4 * 4);
        auto* sp = static_cast<uint8_t*>(src.map);
        for (size_t i = 0; i < src.size; ++i) sp[i] = uint8_t((i * 53 + (i >> 7) * 29) & 255);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            transition(c, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy r[3] = {};
            for (uint32_t l = 0; l < 3; ++l) {
                r[l].bufferOffset = 1024 * l;
                r[l].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 4};
                r[l].imageExtent = {16u >> l, 16u >> l, 1};
            }
            vkCmdCopyBufferToImage(c, src.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 3, r);
            transition(c, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }),
                  VK_SUCCESS);
        const auto [dsl, layout, set] = sampler_set(k);
        VkDescriptorImageInfo ii{k.sampler(),
                                 k.view(tex.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT,
                                        VK_IMAGE_VIEW_TYPE_2D_ARRAY, 1, 2, 1, 3),
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        Pipe p;
        p.fs = SPV(ab_array_frag);
        p.rp = t.rp;
        p.layout = layout;
        VkPipeline pipe = k.pipeline(p);
        // z (times 4 in the shader) walks the layers across the triangle.
        std::vector<Vertex> verts = {v(-1, -1, 0, 0, 0, 0), v(3, -1, 0, 2, 0, 0.5f), v(-1, 3, 0, 0, 2, 0.5f)};
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
}

// Image views with component mappings (BGRA order, replicated red, constants ZERO/ONE) on RGBA8 and R8 textures:
// the sampled values are remapped as the view says.
TEST_F(ApiBreadth, ImageViewComponentSwizzle) {
    const VkComponentMapping mappings[] = {
        {VK_COMPONENT_SWIZZLE_B, VK_COMPONENT_SWIZZLE_G, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_A},
        {VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_ONE},
        {VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_A, VK_COMPONENT_SWIZZLE_IDENTITY, VK_COMPONENT_SWIZZLE_G},
    };
    for (VkFormat f : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8_UNORM, VK_FORMAT_R32G32B32A32_SFLOAT}) {
        for (const VkComponentMapping& m : mappings) {
            SCOPED_TRACE("format " + std::to_string(f) + " mapping " + std::to_string(m.r) + std::to_string(m.g) +
                         std::to_string(m.b) + std::to_string(m.a));
            const Bytes b = both([&](Kit& k) {
                // Integer views are read raw through usamplerBuffer / isamplerBuffer into an integer target.
                const bool uint_view = is_uint_format(f), sint_view = is_sint_format(f);
                Target tg = target(k,
                                   uint_view   ? VK_FORMAT_R32G32B32A32_UINT
                                   : sint_view ? VK_FORMAT_R32G32B32A32_SINT
                                               : VK_FORMAT_R32G32B32A32_SFLOAT,
                                   4, 4);
                Device::Image tex = k.image(f, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
                Device::Buffer src = k.buffer_of(texel_data(f, 16, 99), 0);
                upload(k, src, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, 4, 4);
                VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
                vci.image = tex.image;
                vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
                vci.format = f;
                vci.components = m;
                vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                VkImageView view = VK_NULL_HANDLE;
                EXPECT_EQ(vkCreateImageView(k.d, &vci, nullptr, &view), VK_SUCCESS);
                const auto [dsl, layout, set] = sampler_set(k);
                VkDescriptorImageInfo ii{k.sampler(), view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
                k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
                const Pipe p = fullscreen_pipe(SPV(ab_sample_frag), tg, layout);
                VkPipeline pipe = k.pipeline(p);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
                Bytes out = k.read(tg.image.image, 4, 4, 16);
                vkDestroyImageView(k.d, view, nullptr);
                return out;
            });
            // Independent check of the mapping on pixel 0: channel 3 of {R,R,R,ONE} is exactly 1.0, channel 0 of
            // {ZERO,...} exactly 0.
            float px0[4];
            std::memcpy(px0, b.data(), 16);
            if (m.a == VK_COMPONENT_SWIZZLE_ONE) {
                EXPECT_EQ(px0[3], 1.0f);
            }
            if (m.r == VK_COMPONENT_SWIZZLE_ZERO) {
                EXPECT_EQ(px0[0], 0.0f);
            }
            if (m.g == VK_COMPONENT_SWIZZLE_R) {
                EXPECT_EQ(px0[1], px0[0]);
            }
        }
    }
}

// Vertex pulling from a storage buffer in the vertex shader, an array of combined image samplers and an array of
// uniform blocks in the fragment shader (constant indices), one descriptor write covering several array elements.
TEST_F(ApiBreadth, DescriptorArraysAndVertexPulling) {
    both([](Kit& k) {
        Target t = target(k);
        const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
        VkDescriptorSetLayout dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3, F},
                                                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT},
                                                  {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2, F}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2}};
        VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pci.maxSets = 1;
        pci.poolSizeCount = 3;
        pci.pPoolSizes = sizes;
        VkDescriptorPool pool = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateDescriptorPool(k.d, &pci, nullptr, &pool), VK_SUCCESS);
        VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        ai.descriptorPool = pool;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &dsl;
        VkDescriptorSet set = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateDescriptorSets(k.d, &ai, &set), VK_SUCCESS);
        VkSampler smp = k.sampler(VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT);
        VkDescriptorImageInfo ii[3];
        for (uint32_t i = 0; i < 3; ++i) {
            Device::Image tex = k.image(VK_FORMAT_R8G8B8A8_UNORM, 4 + i, 4,
                                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
            upload_rgba8(k, tex.image, 4 + i, 4, 10 + i);
            ii[i] = {smp, k.view(tex.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT),
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        }
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
        const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
        Device::Buffer ubo = k.buffer(2 * align, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        const float scales[2][4] = {{0.5f, 0.25f, 1.0f, 1.0f}, {0.25f, 0.5f, 0.0f, 0.0f}};
        for (int i = 0; i < 2; ++i) std::memcpy(static_cast<uint8_t*>(ubo.map) + i * align, scales[i], 16);
        std::vector<Vertex> verts = {
            v(-1, -1, 0, 0, 0, 0),     v(1, -1, 0, 1.5f, 0, 0),          v(-1, 1, 0, 0, 1.5f, 0),
            v(0.9f, 0.8f, 0, 1, 1, 0), v(0.2f, -0.9f, 0, 0.3f, 0.7f, 0), v(-0.7f, 0.6f, 0, 0.9f, 0.2f, 0)};
        Device::Buffer ssbo = k.buffer_of(verts, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        VkDescriptorBufferInfo sb{ssbo.buffer, 0, VK_WHOLE_SIZE};
        VkDescriptorBufferInfo ub[2] = {{ubo.buffer, 0, 16}, {ubo.buffer, align, 16}};
        VkWriteDescriptorSet w[3] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                     {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                     {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
        w[0].dstSet = w[1].dstSet = w[2].dstSet = set;
        w[0].dstBinding = 0;
        w[0].descriptorCount = 3;
        w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        w[0].pImageInfo = ii;
        w[1].dstBinding = 1;
        w[1].descriptorCount = 1;
        w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w[1].pBufferInfo = &sb;
        w[2].dstBinding = 2;
        w[2].descriptorCount = 2;
        w[2].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        w[2].pBufferInfo = ub;
        vkUpdateDescriptorSets(k.d, 3, w, 0, nullptr);
        Pipe p;
        p.vs = SPV(ab_pull_vert);
        p.fs = SPV(ab_tex_array_frag);
        p.bindings = {};
        p.attrs = {};
        p.rp = t.rp;
        p.layout = layout;
        VkPipeline pipe = k.pipeline(p);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            // Bound before the render pass begins (binding state is not reset by it).
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            vkCmdDraw(c, 6, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        vkDestroyDescriptorPool(k.d, pool, nullptr);
        EXPECT_NE(px(b, 2, 2)[2], 64);
        return b;
    });
}

// 4x multisampled rendering into two colour attachments (RGBA8 and R32_SFLOAT) resolved at the end of the
// subpass, over a render area smaller than the framebuffer: the clear, the draw and the resolve stay inside it;
// the resolve targets keep their earlier contents outside.
TEST_F(ApiBreadth, MsaaTwoResolvesAndPartialRenderArea) {
    both([](Kit& k) {
        const VkFormat fmts[2] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT};
        Device::Image ms[2], rs[2];
        std::vector<VkImageView> views;
        for (int i = 0; i < 2; ++i) {
            ms[i] = k.dev().make_image(fmts[i], 32, 32, 1, 1, VK_SAMPLE_COUNT_4_BIT,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT);
            EXPECT_NE(ms[i].image, VK_NULL_HANDLE);
            views.push_back(k.view(ms[i].image, fmts[i], VK_IMAGE_ASPECT_COLOR_BIT));
        }
        for (int i = 0; i < 2; ++i) {
            rs[i] = k.image(fmts[i], 32, 32,
                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                VK_IMAGE_USAGE_TRANSFER_DST_BIT);
            views.push_back(k.view(rs[i].image, fmts[i], VK_IMAGE_ASPECT_COLOR_BIT));
        }
        std::vector<VkAttachmentDescription> atts;
        for (int i = 0; i < 2; ++i) {
            VkAttachmentDescription a =
                attachment(fmts[i], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                           VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
            a.samples = VK_SAMPLE_COUNT_4_BIT;
            atts.push_back(a);
        }
        for (int i = 0; i < 2; ++i)
            atts.push_back(attachment(fmts[i], VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_STORE));
        const VkImageLayout CA = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        VkAttachmentReference col[2] = {{0, CA}, {1, CA}}, res[2] = {{2, CA}, {3, CA}};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 2;
        sub.pColorAttachments = col;
        sub.pResolveAttachments = res;
        VkRenderPass rp = k.render_pass(atts, {sub});
        VkFramebuffer fb = k.framebuffer(rp, views, 32, 32);
        Pipe p;
        p.fs = SPV(ab_mrt_frag);
        p.rp = rp;
        p.color_count = 2;
        VkPipeline pipe = VK_NULL_HANDLE;
        {
            // The shared Pipe builder makes 1x pipelines; this one needs 4 samples.
            VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                         {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
            stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
            stages[0].module = k.shader(p.vs);
            stages[0].pName = "main";
            stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
            stages[1].module = k.shader(p.fs);
            stages[1].pName = "main";
            VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
            vi.vertexBindingDescriptionCount = 1;
            vi.pVertexBindingDescriptions = p.bindings.data();
            vi.vertexAttributeDescriptionCount = 2;
            vi.pVertexAttributeDescriptions = p.attrs.data();
            VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
            ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
            VkViewport vp{0, 0, 32, 32, 0, 1};
            VkRect2D sc{{6, 3}, {20, 22}};  // the render area: nothing is drawn outside it
            VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
            vps.viewportCount = vps.scissorCount = 1;
            vps.pViewports = &vp;
            vps.pScissors = &sc;
            VkPipelineRasterizationStateCreateInfo rs_state{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
            rs_state.lineWidth = 1.0f;
            VkPipelineMultisampleStateCreateInfo ms_state{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
            ms_state.rasterizationSamples = VK_SAMPLE_COUNT_4_BIT;
            VkPipelineColorBlendAttachmentState cba[2] = {opaque(), opaque()};
            VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
            cb.attachmentCount = 2;
            cb.pAttachments = cba;
            VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
            gci.stageCount = 2;
            gci.pStages = stages;
            gci.pVertexInputState = &vi;
            gci.pInputAssemblyState = &ia;
            gci.pViewportState = &vps;
            gci.pRasterizationState = &rs_state;
            gci.pMultisampleState = &ms_state;
            gci.pColorBlendState = &cb;
            gci.layout = k.empty_layout();
            gci.renderPass = rp;
            EXPECT_EQ(vkCreateGraphicsPipelines(k.d, VK_NULL_HANDLE, 1, &gci, nullptr, &pipe), VK_SUCCESS);
        }
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            // Earlier contents of the resolve targets, kept outside the render area.
            for (int i = 0; i < 2; ++i) {
                transition(c, rs[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
                VkClearColorValue cc{{0.75f, 0.5f, 0.25f, 1.0f}};
                VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                vkCmdClearColorImage(c, rs[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &cc, 1, &range);
                transition(c, rs[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            }
            VkClearValue clears[4] = {clear_color(0, 0, 0.25f, 1), clear_color(-1.5f, 0, 0, 0)};
            VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
            bi.renderPass = rp;
            bi.framebuffer = fb;
            bi.renderArea = {{6, 3}, {20, 22}};
            bi.clearValueCount = 2;
            bi.pClearValues = clears;
            vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes a = k.read(rs[0].image, 32, 32, 4), b = k.read(rs[1].image, 32, 32, 4);
        EXPECT_EQ(px(a, 0, 0)[0], 191);  // outside the render area: the earlier clear
        for (int i = 0; i < 2; ++i) k.dev().destroy(ms[i]);
        vkDestroyPipeline(k.d, pipe, nullptr);
        return concat({a, b});
    });
}

// Shadow lookups (sampler2DShadow, compare LESS_OR_EQUAL) on D16 and D32 textures with NEAREST and LINEAR
// (percentage-closer) filtering, into an RGBA32F target.
TEST_F(ApiBreadth, DepthCompareSampling) {
    for (VkFormat f : {VK_FORMAT_D16_UNORM, VK_FORMAT_D32_SFLOAT}) {
        for (VkFilter filter : {VK_FILTER_NEAREST, VK_FILTER_LINEAR}) {
            VkFormatProperties fp;
            vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &fp);
            if (filter == VK_FILTER_LINEAR &&
                !(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
                continue;  // not reported: not tested
            SCOPED_TRACE("format " + std::to_string(f) + " filter " + std::to_string(filter));
            both([&](Kit& k) {
                Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT);
                Device::Image tex = k.image(f, 8, 8, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
                Device::Buffer src = k.buffer_of(texel_data(f, 64, 7), 0);
                upload(k, src, tex.image, VK_IMAGE_ASPECT_DEPTH_BIT, 8, 8);
                VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
                sci.magFilter = sci.minFilter = filter;
                sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
                sci.compareEnable = VK_TRUE;
                sci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
                sci.maxLod = 0.25f;
                VkSampler smp = VK_NULL_HANDLE;
                EXPECT_EQ(vkCreateSampler(k.d, &sci, nullptr, &smp), VK_SUCCESS);
                const auto [dsl, layout, set] = sampler_set(k);
                VkDescriptorImageInfo ii{smp, k.view(tex.image, f, VK_IMAGE_ASPECT_DEPTH_BIT),
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
                k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
                Pipe p;
                p.fs = SPV(ab_shadow_frag);
                p.rp = tg.rp;
                p.layout = layout;
                VkPipeline pipe = k.pipeline(p);
                // uv over [0, 1.2] and the reference depth z over [0, 1] across the target.
                std::vector<Vertex> verts = {v(-1, -1, 0, 0, 0, 0), v(3, -1, 0, 2.4f, 0, 1.0f),
                                             v(-1, 3, 0, 0, 2.4f, 1.0f)};
                Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                    begin_pass(c, tg.rp, tg.fb, 32, 32, {clear_color(-1, -1, -1, -1)});
                    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                    bind_vertices(c, vb);
                    vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
                    vkCmdDraw(c, 3, 1, 0, 0);
                    vkCmdEndRenderPass(c);
                }),
                          VK_SUCCESS);
                Bytes out = k.read(tg.image.image, 32, 32, 16);
                vkDestroySampler(k.d, smp, nullptr);
                return out;
            });
        }
    }
}

// Shadow mapping as engines do it: a depth-only pass (no colour attachment, no fragment stage, depth bias) into a
// D16 image, then a pass sampling it with a comparison sampler; plus a rasterizer-discard pipeline that must draw
// nothing.
TEST_F(ApiBreadth, DepthOnlyPassWithoutFragmentStageThenShadowLookup) {
    both([](Kit& k) {
        const VkFormat D = VK_FORMAT_D16_UNORM;
        Device::Image shadow = k.image(
            D, 32, 32,
            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        VkImageView sv = k.view(shadow.image, D, VK_IMAGE_ASPECT_DEPTH_BIT);
        const VkAttachmentReference dref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkSubpassDependency dep{0,
                                VK_SUBPASS_EXTERNAL,
                                VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                                VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                VK_ACCESS_SHADER_READ_BIT,
                                0};
        VkRenderPass depth_rp = k.render_pass({attachment(D, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
                                                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)},
                                              {subpass(nullptr, &dref)}, {dep});
        VkFramebuffer depth_fb = k.framebuffer(depth_rp, {sv}, 32, 32);
        const VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
        Pipe dp;
        dp.rp = depth_rp;
        dp.ds = &ds;
        dp.no_fragment_stage = true;
        dp.color_count = 0;
        dp.depth_bias = true;
        dp.dynamic = {VK_DYNAMIC_STATE_DEPTH_BIAS};
        VkPipeline depth_pipe = k.pipeline(dp);
        dp.rasterizer_discard = true;
        VkPipeline discard_pipe = k.pipeline(dp);
        // Second pass: shadow lookups into RGBA32F.
        Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT);
        VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
        sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        sci.compareEnable = VK_TRUE;
        sci.compareOp = VK_COMPARE_OP_LESS;
        VkSampler smp = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateSampler(k.d, &sci, nullptr, &smp), VK_SUCCESS);
        const auto [dsl, layout, set] = sampler_set(k);
        VkDescriptorImageInfo ii{smp, sv, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        Pipe lp;
        lp.fs = SPV(ab_shadow_frag);
        lp.rp = tg.rp;
        lp.layout = layout;
        VkPipeline lookup = k.pipeline(lp);
        std::vector<Vertex> verts = kBothTriangles;
        verts.push_back(v(-1, -1, 0, 0, 0, 0));
        verts.push_back(v(3, -1, 0, 2.0f, 0, 1.0f));
        verts.push_back(v(-1, 3, 0, 0, 2.0f, 1.0f));
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, depth_rp, depth_fb, 32, 32, {clear_depth(1.0f)});
            bind_vertices(c, vb);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, discard_pipe);
            vkCmdSetDepthBias(c, 0.0f, 0.0f, 0.0f);
            vkCmdDraw(c, 3, 1, 6, 0);  // would cover everything at depth 0: discarded
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, depth_pipe);
            vkCmdSetDepthBias(c, 300.0f, 0.0f, 1.5f);
            vkCmdDraw(c, 6, 1, 0, 0);
            vkCmdEndRenderPass(c);
            begin_pass(c, tg.rp, tg.fb, 32, 32, {clear_color(-1, -1, -1, -1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, lookup);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
            vkCmdDraw(c, 3, 1, 6, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes out = k.read(tg.image.image, 32, 32, 16);
        vkDestroySampler(k.d, smp, nullptr);
        // The depth pass left shadowed and lit texels: the lookups see both (and the discarded draw none).
        int lit = 0, shadowed = 0;
        for (size_t i = 0; i < 32 * 32; ++i) {
            float a;
            std::memcpy(&a, out.data() + 16 * i, 4);
            lit += a == 1.0f;
            shadowed += a == 0.0f;
        }
        EXPECT_GT(lit, 0);
        EXPECT_GT(shadowed, 0);
        return out;
    });
}

// Rendering into one mip level and one array layer of an image (a single-layer view of level 1, layer 2 as the
// colour attachment, and of level 0 layer 1 as the depth attachment): only that subresource changes.
TEST_F(ApiBreadth, RenderIntoLevelAndLayer) {
    both([](Kit& k) {
        const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM, D = VK_FORMAT_D32_SFLOAT;
        Device::Image col = k.image(
            C, 64, 64,
            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 2,
            3);
        Device::Image dep =
            k.image(D, 32, 32, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, 1, 2);
        VkRenderPass rp = colour_depth_pass(k, C, D, VK_ATTACHMENT_LOAD_OP_LOAD);
        VkFramebuffer fb =
            k.framebuffer(rp,
                          {k.view(col.image, C, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_VIEW_TYPE_2D, 1, 1, 2, 1),
                           k.view(dep.image, D, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_VIEW_TYPE_2D, 0, 1, 1, 1)},
                          32, 32);
        const VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
        Pipe p;
        p.rp = rp;
        p.ds = &ds;
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            // Every subresource of the colour image starts grey; the pass loads level 1 layer 2.
            transition(c, col.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkClearColorValue grey{{0.5f, 0.5f, 0.5f, 1.0f}};
            VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 2, 0, 3};
            vkCmdClearColorImage(c, col.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &all);
            transition(c, col.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0, 0), clear_depth(1.0f)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            bind_vertices(c, vb);
            vkCmdDraw(c, 6, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes out;
        for (uint32_t level = 0; level < 2; ++level)
            for (uint32_t layer = 0; layer < 3; ++layer) {
                Bytes b = k.read(col.image, 64u >> level, 64u >> level, 4, VK_IMAGE_ASPECT_COLOR_BIT, level, layer);
                const bool target = level == 1 && layer == 2;
                EXPECT_EQ(px(b, 10, 12, 64u >> level)[0] == 128 && px(b, 10, 12, 64u >> level)[1] == 128, !target)
                    << "level " << level << " layer " << layer;
                out = concat({out, b});
            }
        // The depth attachment ends in TRANSFER_SRC_OPTIMAL (its finalLayout).
        return concat({out, k.read(dep.image, 32, 32, 4, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1)});
    });
}

// A LINEAR-tiled RGBA8 image written by the host through vkGetImageSubresourceLayout (PREINITIALIZED), then
// sampled; and a pipeline cache's data round trip.
TEST_F(ApiBreadth, LinearImageHostWritesAndPipelineCache) {
    both([](Kit& k) {
        Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
        VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ici.imageType = VK_IMAGE_TYPE_2D;
        ici.format = VK_FORMAT_R8G8B8A8_UNORM;
        ici.extent = {4, 4, 1};
        ici.mipLevels = ici.arrayLayers = 1;
        ici.samples = VK_SAMPLE_COUNT_1_BIT;
        ici.tiling = VK_IMAGE_TILING_LINEAR;
        ici.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
        ici.initialLayout = VK_IMAGE_LAYOUT_PREINITIALIZED;
        VkImage img = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImage(k.d, &ici, nullptr, &img), VK_SUCCESS);
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(k.d, img, &req);
        VkPhysicalDeviceMemoryProperties mp;
        vkGetPhysicalDeviceMemoryProperties(k.dev().physical(), &mp);
        uint32_t type = 0;
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        while (type < mp.memoryTypeCount &&
               !((req.memoryTypeBits >> type & 1) && (mp.memoryTypes[type].propertyFlags & host) == host))
            ++type;
        EXPECT_LT(type, mp.memoryTypeCount);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = type;
        VkDeviceMemory mem = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateMemory(k.d, &ai, nullptr, &mem), VK_SUCCESS);
        EXPECT_EQ(vkBindImageMemory(k.d, img, mem, 0), VK_SUCCESS);
        VkImageSubresource sr{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0};
        VkSubresourceLayout layout_info;
        vkGetImageSubresourceLayout(k.d, img, &sr, &layout_info);
        EXPECT_GE(layout_info.rowPitch, 16u);
        void* map = nullptr;
        EXPECT_EQ(vkMapMemory(k.d, mem, 0, VK_WHOLE_SIZE, 0, &map), VK_SUCCESS);
        const std::vector<uint8_t> texels = texel_data(VK_FORMAT_R8G8B8A8_UNORM, 16, 5);
        for (uint32_t y = 0; y < 4; ++y)
            std::memcpy(static_cast<uint8_t*>(map) + layout_info.offset + y * layout_info.rowPitch, &texels[y * 16],
                        16);
        vkUnmapMemory(k.d, mem);
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = img;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = VK_FORMAT_R8G8B8A8_UNORM;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;  // destroyed below, before its image
        EXPECT_EQ(vkCreateImageView(k.d, &vci, nullptr, &view), VK_SUCCESS);
        const auto [dsl, layout, set] = sampler_set(k);
        VkDescriptorImageInfo ii{k.sampler(), view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        // Pipeline cache: the header round-trips into a new cache, which then builds the pipeline.
        VkPipelineCacheCreateInfo pcci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
        VkPipelineCache cache = VK_NULL_HANDLE, cache2 = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreatePipelineCache(k.d, &pcci, nullptr, &cache), VK_SUCCESS);
        size_t size = 0;
        EXPECT_EQ(vkGetPipelineCacheData(k.d, cache, &size, nullptr), VK_SUCCESS);
        EXPECT_GE(size, 16u + VK_UUID_SIZE);
        std::vector<uint8_t> data(size);
        EXPECT_EQ(vkGetPipelineCacheData(k.d, cache, &size, data.data()), VK_SUCCESS);
        uint32_t header[4];
        std::memcpy(header, data.data(), 16);
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
        EXPECT_EQ(header[0], 16u + VK_UUID_SIZE);
        EXPECT_EQ(header[1], uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE));
        EXPECT_EQ(header[2], props.vendorID);
        EXPECT_EQ(header[3], props.deviceID);
        EXPECT_EQ(std::memcmp(data.data() + 16, props.pipelineCacheUUID, VK_UUID_SIZE), 0);
        pcci.initialDataSize = size;
        pcci.pInitialData = data.data();
        EXPECT_EQ(vkCreatePipelineCache(k.d, &pcci, nullptr, &cache2), VK_SUCCESS);
        EXPECT_EQ(vkMergePipelineCaches(k.d, cache2, 1, &cache), VK_SUCCESS);
        const Pipe p = fullscreen_pipe(SPV(ab_sample_frag), tg, layout);
        VkPipeline pipe = k.pipeline(p);  // (the builder passes no cache; the cache objects are checked above)
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
            b.srcAccessMask = VK_ACCESS_HOST_WRITE_BIT;
            b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
            b.oldLayout = VK_IMAGE_LAYOUT_PREINITIALIZED;
            b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = img;
            b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdPipelineBarrier(c, VK_PIPELINE_STAGE_HOST_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0,
                                 nullptr, 1, &b);
            draw_fullscreen(c, tg, pipe, layout, set);
        }),
                  VK_SUCCESS);
        Bytes out = k.read(tg.image.image, 4, 4, 16);
        float first;
        std::memcpy(&first, out.data(), 4);
        EXPECT_EQ(first, float(texels[0]) * float(1.0 / 255.0));  // texel (0,0) red, as written by the host
        vkDestroyPipelineCache(k.d, cache, nullptr);
        vkDestroyPipelineCache(k.d, cache2, nullptr);
        vkDestroyImageView(k.d, view, nullptr);
        vkDestroyImage(k.d, img, nullptr);
        vkFreeMemory(k.d, mem, nullptr);
        return out;
    });
}

// Uniform texel buffers: every format tilevk reports UNIFORM_TEXEL_BUFFER for (lavapipe must too) is read with
// texelFetch through a buffer view at a non-zero offset, and textureSize gives the view's texel count.
TEST_F(ApiBreadth, UniformTexelBuffers) {
    int tested = 0;
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties tp, lp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &tp);
        vkGetPhysicalDeviceFormatProperties(lavapipe_->physical(), f, &lp);
        if (!(tp.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT)) continue;
        ASSERT_TRUE(lp.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT) << "format " << fi;
        ++tested;
        SCOPED_TRACE("texel buffer format " + std::to_string(fi));
        both([f](Kit& k) {
            // Integer views are read raw through usamplerBuffer / isamplerBuffer into an integer target.
            const bool uint_view = is_uint_format(f), sint_view = is_sint_format(f);
            Target tg = target(k,
                               uint_view   ? VK_FORMAT_R32G32B32A32_UINT
                               : sint_view ? VK_FORMAT_R32G32B32A32_SINT
                                           : VK_FORMAT_R32G32B32A32_SFLOAT,
                               4, 4);
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
            const VkDeviceSize offset = std::max<VkDeviceSize>(props.limits.minTexelBufferOffsetAlignment, 16);
            const uint32_t n = texel_bytes(f, VK_IMAGE_ASPECT_COLOR_BIT);
            std::vector<uint8_t> data(offset, 0xEE);
            const std::vector<uint8_t> texels = texel_data(f, 20, 300 + uint32_t(f));
            data.insert(data.end(), texels.begin(), texels.end());
            Device::Buffer buf = k.buffer_of(data, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
            // 18 texels visible (2 more than the pixels)
            const TexelBufferSet tb = uniform_texel_buffer_set(k, buf, f, offset, VkDeviceSize(18) * n);
            const VkBufferView view = tb.view;
            const VkPipelineLayout layout = tb.layout;
            const VkDescriptorSet set = tb.set;
            const Pipe p = fullscreen_pipe(uint_view   ? SPV(ab_texel_buffer_uint_frag)
                                           : sint_view ? SPV(ab_texel_buffer_sint_frag)
                                                       : SPV(ab_texel_buffer_frag),
                                           tg, layout);
            VkPipeline pipe = k.pipeline(p);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
            Bytes out = k.read(tg.image.image, 4, 4, 16);
            if (uint_view || sint_view) {
                uint32_t size;
                std::memcpy(&size, out.data() + 12, 4);
                EXPECT_EQ(size, 18u);  // textureSize = range / texel size
            } else {
                float size;
                std::memcpy(&size, out.data() + 12, 4);
                EXPECT_EQ(size, 18.0f);
            }
            vkDestroyBufferView(k.d, view, nullptr);
            return out;
        });
    }
    EXPECT_GT(tested, 0);
}

}  // namespace
}  // namespace tilevk::test::breadth
