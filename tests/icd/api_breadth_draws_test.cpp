// API breadth (api_breadth.h): transfers over subresources and vertex input / indexed / indirect draws.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

// ---- Transfers -------------------------------------------------------------------------------------------------

// Buffer <-> image copies with bufferRowLength / bufferImageHeight / offsets into mip levels and array layers,
// image-to-image copies between levels and layers, update and fill; the whole image is read back per subresource.
TEST_F(ApiBreadth, TransfersOverLevelsLayersRowLengths) {
    both([](Kit& k) {
        const VkFormat F = VK_FORMAT_R8G8B8A8_UNORM;
        Device::Image a = k.image(F, 20, 12, VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 3, 3);
        Device::Image b = k.image(F, 20, 12, VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 3, 3);
        Device::Buffer src = k.buffer(64 * 1024), dst = k.buffer(32 * 1024);
        auto* sp = static_cast<uint8_t*>(src.map);
        for (size_t i = 0; i < src.size; ++i) sp[i] = uint8_t((i * 13 + (i >> 8)) & 255);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            transition(c, a.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            transition(c, b.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkClearColorValue zero{};
            VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 3, 0, 3};
            vkCmdClearColorImage(c, a.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
            vkCmdClearColorImage(c, b.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
            VkBufferImageCopy r[3] = {};
            r[0].bufferOffset = 12;  // rows of 24 texels, 14 rows per layer image, two layers
            r[0].bufferRowLength = 24;
            r[0].bufferImageHeight = 14;
            r[0].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 2};
            r[0].imageOffset = {3, 2, 0};
            r[0].imageExtent = {15, 9, 1};
            r[1].bufferOffset = 4000;
            r[1].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 1, 0, 3};
            r[1].imageExtent = {10, 6, 1};
            r[2].bufferOffset = 9000;
            r[2].bufferRowLength = 7;
            r[2].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 2, 2, 1};
            r[2].imageOffset = {1, 1, 0};
            r[2].imageExtent = {4, 2, 1};
            vkCmdCopyBufferToImage(c, src.buffer, a.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 3, r);
            transition(c, a.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            VkImageCopy ic[2] = {};
            ic[0].srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 2};
            ic[0].srcOffset = {4, 3, 0};
            ic[0].dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 2};
            ic[0].dstOffset = {1, 5, 0};
            ic[0].extent = {13, 6, 1};
            ic[1].srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 1, 2, 1};
            ic[1].dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 2, 1, 1};
            ic[1].extent = {5, 3, 1};
            vkCmdCopyImage(c, a.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, b.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 2, ic);
            transition(c, b.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            // Image to buffer with a row length and image height, then fill/update over part of it.
            VkBufferImageCopy o{};
            o.bufferOffset = 8;
            o.bufferRowLength = 22;
            o.bufferImageHeight = 13;
            o.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 3};
            o.imageExtent = {20, 12, 1};
            vkCmdCopyImageToBuffer(c, b.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.buffer, 1, &o);
            vkCmdFillBuffer(c, dst.buffer, 100, 36, 0x11223344u);
            const uint32_t upd[3] = {7, 8, 9};
            vkCmdUpdateBuffer(c, dst.buffer, 200, sizeof upd, upd);
            vkCmdFillBuffer(c, dst.buffer, 32 * 1024 - 12, VK_WHOLE_SIZE, 0xCAFEBABEu);
        }),
                  VK_SUCCESS);
        Bytes out = Kit::bytes(dst);
        for (uint32_t level = 0; level < 3; ++level)
            for (uint32_t layer = 0; layer < 3; ++layer) {
                Bytes s = k.read(a.image, 20u >> level, 12u >> level, 4, VK_IMAGE_ASPECT_COLOR_BIT, level, layer);
                Bytes t = k.read(b.image, 20u >> level, 12u >> level, 4, VK_IMAGE_ASPECT_COLOR_BIT, level, layer);
                out = concat({out, s, t});
            }
        return out;
    });
}

// ---- Vertex input and draws ------------------------------------------------------------------------------------

// Per-vertex and per-instance bindings, firstInstance, a stride-0 binding, instanced indexed draws with
// vertexOffset/firstIndex in UINT32 and UINT16 with primitive restart.
TEST_F(ApiBreadth, InstancedIndexedDrawsWithOffsetsAndRestart) {
    both([](Kit& k) {
        Target t = target(k);
        Pipe p;
        p.vs = SPV(ab_instanced_vert);
        p.rp = t.rp;
        p.bindings = {{0, 8, VK_VERTEX_INPUT_RATE_VERTEX},
                      {1, 32, VK_VERTEX_INPUT_RATE_INSTANCE},
                      {2, 0, VK_VERTEX_INPUT_RATE_VERTEX}};
        p.attrs = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0},
                   {1, 1, VK_FORMAT_R32G32_SFLOAT, 0},
                   {2, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 16},
                   {3, 2, VK_FORMAT_R8G8B8A8_UNORM, 3}};
        p.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        p.restart = true;
        VkPipeline strip = k.pipeline(p);
        std::vector<float> pos;  // a small quad (strip order) repeated at 4 base positions
        for (int i = 0; i < 16; ++i) {
            pos.push_back(-0.95f + 0.1f * float(i % 4) + ((i & 1) ? 0.3f : 0.0f));
            pos.push_back(-0.95f + ((i & 2) ? 0.35f : 0.0f) + 0.05f * float(i / 4));
        }
        std::vector<float> inst;
        for (int i = 0; i < 6; ++i) {
            const float row[8] = {0.3f * float(i % 3), 0.9f * float(i / 3),    0,    0,
                                  float(i) / 5.0f,     1.0f - float(i) / 6.0f, 0.5f, 1.0f};
            inst.insert(inst.end(), row, row + 8);
        }
        const std::vector<uint8_t> tint = {0, 0, 0, 255, 200, 255, 255, 255};
        const std::vector<uint32_t> idx32 = {9, 9, 0, 1, 2, 3, 0xFFFFFFFFu, 4, 5, 6, 7};
        const std::vector<uint16_t> idx16 = {0, 1, 2, 0xFFFF, 5, 6, 7, 8};
        Device::Buffer vb0 = k.buffer_of(pos, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb1 = k.buffer_of(inst, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb2 = k.buffer_of(tint, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer ib32 = k.buffer_of(idx32, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        Device::Buffer ib16 = k.buffer_of(idx16, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, strip);
            VkBuffer bufs[3] = {vb0.buffer, vb1.buffer, vb2.buffer};
            VkDeviceSize offs[3] = {0, 0, 1};
            vkCmdBindVertexBuffers(c, 0, 2, bufs, offs);
            vkCmdBindVertexBuffers(c, 2, 1, &bufs[2], &offs[2]);            // firstBinding 2 on its own
            vkCmdDraw(c, 4, 2, 0, 0);                                       // instances 0, 1
            vkCmdBindIndexBuffer(c, ib32.buffer, 4, VK_INDEX_TYPE_UINT32);  // offset one index
            vkCmdDrawIndexed(c, 9, 2, 1, 4, 2);  // firstIndex 1 (+1 from the offset), vertexOffset 4, instances 2, 3
            vkCmdBindIndexBuffer(c, ib16.buffer, 2, VK_INDEX_TYPE_UINT16);  // offset 2 bytes
            vkCmdDrawIndexed(c, 7, 1, 0, 7, 4);
            vkCmdDrawIndexed(c, 3, 1, 4, 4, 5);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_EQ(px(b, 31, 0)[2], 64);
        return b;
    });
}

// VK_EXT_vertex_attribute_divisor: ab_instanced.vert's instance binding with divisor 3, then 0, drawn with
// firstInstance 1 on tilevk and lavapipe (feature enabled, validation layer on), compared byte for byte. Checked
// against the rule too: 6 instances with divisor 3 read elements 1, 1, 1, 2, 2, 2 — the image of instances 1 and 2
// without a divisor (opaque quads drawn again in place); divisor 0 reads element 1 for every instance.
TEST_F(ApiBreadth, VertexAttributeDivisors) {
    VkPhysicalDeviceVertexAttributeDivisorFeaturesEXT feature{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_ATTRIBUTE_DIVISOR_FEATURES_EXT};
    feature.vertexAttributeInstanceRateDivisor = VK_TRUE;
    feature.vertexAttributeInstanceRateZeroDivisor = VK_TRUE;
    auto dev = device_pair({VK_EXT_VERTEX_ATTRIBUTE_DIVISOR_EXTENSION_NAME}, &feature);
    ASSERT_TRUE(dev->ok());
    // divisor: 1 means no VkPipelineVertexInputDivisorStateCreateInfoEXT at all.
    auto scene = [](Kit& k, uint32_t divisor, uint32_t instances) {
        Target t = target(k);
        VkVertexInputBindingDivisorDescriptionEXT d{1, divisor};
        VkPipelineVertexInputDivisorStateCreateInfoEXT dci{
            VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_DIVISOR_STATE_CREATE_INFO_EXT};
        dci.vertexBindingDivisorCount = 1;
        dci.pVertexBindingDivisors = &d;
        Pipe p;
        p.vs = SPV(ab_instanced_vert);
        p.rp = t.rp;
        p.vertex_input_pnext = divisor == 1 ? nullptr : &dci;
        p.bindings = {{0, 8, VK_VERTEX_INPUT_RATE_VERTEX},
                      {1, 32, VK_VERTEX_INPUT_RATE_INSTANCE},
                      {2, 0, VK_VERTEX_INPUT_RATE_VERTEX}};
        p.attrs = {{0, 0, VK_FORMAT_R32G32_SFLOAT, 0},
                   {1, 1, VK_FORMAT_R32G32_SFLOAT, 0},
                   {2, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 16},
                   {3, 2, VK_FORMAT_R8G8B8A8_UNORM, 0}};
        p.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        VkPipeline pipe = k.pipeline(p);
        const std::vector<float> pos = {-0.9f, -0.9f, -0.5f, -0.9f, -0.9f, -0.5f, -0.5f, -0.5f};
        std::vector<float> inst;
        for (int i = 0; i < 4; ++i) {
            const float row[8] = {0.45f * float(i), 0.3f * float(i),        0,    0,
                                  float(i) / 3.0f,  1.0f - float(i) / 4.0f, 0.5f, 1.0f};
            inst.insert(inst.end(), row, row + 8);
        }
        const std::vector<uint8_t> tint = {255, 255, 255, 255};
        Device::Buffer vb0 = k.buffer_of(pos, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb1 = k.buffer_of(inst, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Device::Buffer vb2 = k.buffer_of(tint, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            VkBuffer bufs[3] = {vb0.buffer, vb1.buffer, vb2.buffer};
            VkDeviceSize offs[3] = {0, 0, 0};
            vkCmdBindVertexBuffers(c, 0, 3, bufs, offs);
            vkCmdDraw(c, 4, instances, 0, 1);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    };
    const Bytes by3 = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return scene(k, 3, 6); });
    const Bytes by0 = both_on(dev->tilevk, dev->lavapipe, [&](Kit& k) { return scene(k, 0, 5); });
    Kit k(dev->tilevk);
    expect_same(by3, scene(k, 1, 2), "divisor 3, 6 instances vs instances 1 and 2");
    expect_same(by0, scene(k, 1, 1), "divisor 0, 5 instances vs instance 1");
    EXPECT_NE(by3, by0);
}

// vkCmdDrawIndirect / vkCmdDrawIndexedIndirect at offsets and strides (drawCount > 1 only where the driver
// reports multiDrawIndirect; otherwise one call per record).
TEST_F(ApiBreadth, IndirectDrawsWithStride) {
    VkPhysicalDeviceFeatures tf, lf, feats{};
    vkGetPhysicalDeviceFeatures(tilevk_->physical(), &tf);
    vkGetPhysicalDeviceFeatures(lavapipe_->physical(), &lf);
    feats.multiDrawIndirect = tf.multiDrawIndirect && lf.multiDrawIndirect;
    feats.drawIndirectFirstInstance = tf.drawIndirectFirstInstance && lf.drawIndirectFirstInstance;
    feats.fullDrawIndexUint32 = tf.fullDrawIndexUint32 && lf.fullDrawIndexUint32;
    // tilevk reports all three (execute_draw.cpp reads every record; indices are 32-bit throughout).
    EXPECT_TRUE(tf.multiDrawIndirect && tf.drawIndirectFirstInstance && tf.fullDrawIndexUint32);
    Device tdev(tilevk_->physical(), &feats), ldev(lavapipe_->physical(), &feats);
    ASSERT_TRUE(tdev.ok() && ldev.ok());
    both_on(tdev, ldev, [&](Kit& k) {
        Target t = target(k);
        // Positions per vertex (binding 0), colours per instance (binding 1): firstInstance picks the colour.
        Pipe p;
        p.rp = t.rp;
        p.bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}, {1, 16, VK_VERTEX_INPUT_RATE_INSTANCE}};
        p.attrs = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 0}};
        p.blend = {alpha_over()};
        VkPipeline pipe = k.pipeline(p);
        std::vector<Vertex> verts = kBothTriangles;
        for (int i = 0; i < 3; ++i) verts.push_back(v(-1.0f + 0.4f * float(i), 1.0f - float(i == 1), 0, 0, 0, 0));
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        const std::vector<float> colours = {1, 0, 0, 0.5f, 0, 1, 0, 0.5f, 0, 0, 1, 0.5f, 1, 1, 0, 0.5f, 0, 1, 1, 0.5f};
        Device::Buffer cb = k.buffer_of(colours, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        const std::vector<uint16_t> idx = {0, 1, 2, 0, 2, 8, 7, 3};
        Device::Buffer ib = k.buffer_of(idx, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        // 32-bit index values past 2^24, brought back into the buffer by vertexOffset (fullDrawIndexUint32).
        const std::vector<uint32_t> big = {0x01000006u, 0x01000007u, 0x01000008u};
        Device::Buffer ib32 = k.buffer_of(big, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        // Records 24 bytes apart (stride 24) after a 12-byte header.
        std::vector<uint32_t> ind(64, 0xEEEEEEEEu);
        const uint32_t first_instance = feats.drawIndirectFirstInstance ? 2 : 0;
        const uint32_t plain[2][4] = {{3, 1, 0, first_instance}, {3, 2, 3, 0}};
        for (int i = 0; i < 2; ++i) std::memcpy(&ind[3 + 6 * i], plain[i], 16);
        const uint32_t indexed[2][5] = {{3, 2, 3, 0, first_instance + 1},
                                        {3, 1, 5, uint32_t(-3), 0}};  // vertexOffset -3
        for (int i = 0; i < 2; ++i) std::memcpy(&ind[20 + 6 * i], indexed[i], 20);
        Device::Buffer indirect = k.buffer_of(ind, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            VkBuffer bufs[2] = {vb.buffer, cb.buffer};
            VkDeviceSize offs[2] = {0, 0};
            vkCmdBindVertexBuffers(c, 0, 2, bufs, offs);
            vkCmdBindIndexBuffer(c, ib.buffer, 0, VK_INDEX_TYPE_UINT16);
            if (feats.multiDrawIndirect) {
                vkCmdDrawIndirect(c, indirect.buffer, 12, 2, 24);
                vkCmdDrawIndexedIndirect(c, indirect.buffer, 80, 2, 24);
            } else {
                for (uint32_t i = 0; i < 2; ++i) {
                    vkCmdDrawIndirect(c, indirect.buffer, 12 + 24 * i, 1, 0);
                    vkCmdDrawIndexedIndirect(c, indirect.buffer, 80 + 24 * i, 1, 0);
                }
            }
            if (feats.fullDrawIndexUint32) {
                vkCmdBindIndexBuffer(c, ib32.buffer, 0, VK_INDEX_TYPE_UINT32);
                vkCmdDrawIndexed(c, 3, 1, 0, -0x01000000, 4);
            }
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(b, 10, 12)[2], 64);
        return b;
    });
}

// The vertex formats every application uses must be reported (Vulkan's mandatory VERTEX_BUFFER formats that
// tilevk's fetch implements), and each reported one fetches what lavapipe fetches: 16 points, one per pixel of a
// 4x4 RGBA32F target, each with its own element at an odd stride and a non-zero attribute offset.
TEST_F(ApiBreadth, VertexFormatsFetchLikeLavapipe) {
    const VkFormat mandatory[] = {VK_FORMAT_R8_UNORM,          VK_FORMAT_R8G8_UNORM,
                                  VK_FORMAT_R8G8B8A8_UNORM,    VK_FORMAT_B8G8R8A8_UNORM,
                                  VK_FORMAT_R8G8B8A8_SNORM,    VK_FORMAT_R8G8B8A8_UINT,
                                  VK_FORMAT_R8G8B8A8_SINT,     VK_FORMAT_R16_SFLOAT,
                                  VK_FORMAT_R16G16_SFLOAT,     VK_FORMAT_R16G16B16A16_SFLOAT,
                                  VK_FORMAT_R16G16_UNORM,      VK_FORMAT_R16G16B16A16_SNORM,
                                  VK_FORMAT_R32_SFLOAT,        VK_FORMAT_R32G32B32_SFLOAT,
                                  VK_FORMAT_R32G32B32A32_UINT, VK_FORMAT_A2B10G10R10_UNORM_PACK32};
    std::vector<VkFormat> tested;
    for (int f = 1; f <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++f) {
        VkFormatProperties tp, lp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), VkFormat(f), &tp);
        vkGetPhysicalDeviceFormatProperties(lavapipe_->physical(), VkFormat(f), &lp);
        if (!(tp.bufferFeatures & VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT)) continue;
        EXPECT_TRUE(lp.bufferFeatures & VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT) << "format " << f;
        tested.push_back(VkFormat(f));
    }
    for (VkFormat f : mandatory) {
        VkFormatProperties tp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &tp);
        EXPECT_TRUE(tp.bufferFeatures & VK_FORMAT_FEATURE_VERTEX_BUFFER_BIT) << "mandatory vertex format " << f;
    }
    for (VkFormat f : tested) {
        for (bool unaligned : {false, true}) {
            SCOPED_TRACE("vertex format " + std::to_string(f) + (unaligned ? " unaligned" : ""));
            both([f, unaligned](Kit& k) {
                Target t = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
                // The largest element is 16 bytes. Aligned: stride 20, offset 4; unaligned (legal in Vulkan 1.0, no
                // alignment rule for vertex input): stride 21, offset 3, so most elements start at odd addresses.
                const uint32_t stride = unaligned ? 21 : 20, offset = unaligned ? 3 : 4;
                Pipe p;
                const bool is_uint = is_uint_format(f), is_sint = is_sint_format(f);
                p.vs = is_uint ? SPV(ab_point_uint_vert) : is_sint ? SPV(ab_point_sint_vert) : SPV(ab_point_float_vert);
                p.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
                p.width = p.height = 4;
                p.rp = t.rp;
                p.bindings = {{0, stride, VK_VERTEX_INPUT_RATE_VERTEX}};
                p.attrs = {{0, 0, f, offset}};
                VkPipeline pipe = k.pipeline(p);
                // Bytes: integers and norms take anything; float formats get finite values (no NaN/Inf/denormal
                // questions): half floats with exponents 10..20, floats in [-4, 4].
                std::vector<uint8_t> data(16 * stride + 16);
                std::mt19937 rng(uint32_t(f) * 7919u);
                for (auto& b : data) b = uint8_t(rng());
                const bool half = is_half_format(f), single = is_float32_format(f);
                for (uint32_t e = 0; e < 16; ++e) {  // components of each element, wherever it starts
                    const size_t base = size_t(offset) + size_t(e) * stride;
                    for (int c = 0; c < 4; ++c) {
                        if (half) {
                            const uint16_t bits =
                                uint16_t(((rng() & 1) << 15) | ((10 + rng() % 11) << 10) | (rng() & 1023));
                            std::memcpy(&data[base + 2 * c], &bits, 2);
                        } else if (single) {
                            const float x = float(int32_t(rng() % 2000001) - 1000000) / 250000.0f;
                            std::memcpy(&data[base + 4 * c], &x, 4);
                        }
                    }
                }
                Device::Buffer vb = k.buffer_of(data, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
                EXPECT_EQ(
                    k.run([&](VkCommandBuffer c) { draw_vertices(c, t, pipe, vb, 16, clear_color(-1, -1, -1, -1)); }),
                    VK_SUCCESS);
                return k.read(t.image.image, 4, 4, 16);
            });
        }
    }
}

// Half-float vertex attributes that are NaN (signalling and quiet, with payloads), infinite or denormal reach the
// shader as VCVTPH2PS converts them (lavapipe's SoA fetch: lp_build_half_to_float on F16C hosts): signalling NaNs
// quieted, payloads kept. The RGBA32F target carries the bits; 16 points, one per pixel. (Whether the fetch itself
// quiets a signalling NaN is not observable here: the first arithmetic on the value quiets it in both drivers; a
// canonical NaN instead of the payload fails.)
TEST_F(ApiBreadth, HalfVertexSpecialsFetchLikeLavapipe) {
    const uint16_t specials[] = {0x7c01, 0x7d55, 0xfc01, 0xfdff, 0x7e00, 0x7e01, 0x7fff, 0xffff,
                                 0x7c00, 0xfc00, 0x0001, 0x03ff, 0x83ff, 0x7bff, 0x3c00, 0xbc00};
    const Bytes data = half_specials(specials);
    const Bytes out = both([&](Kit& k) {
        Target t = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
        Pipe p;
        p.vs = SPV(ab_point_float_vert);
        p.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
        p.width = p.height = 4;
        p.rp = t.rp;
        p.bindings = {{0, 8, VK_VERTEX_INPUT_RATE_VERTEX}};
        p.attrs = {{0, 0, VK_FORMAT_R16G16B16A16_SFLOAT, 0}};
        VkPipeline pipe = k.pipeline(p);
        Device::Buffer vb = k.buffer_of(data, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_vertices(c, t, pipe, vb, 16, clear_color(-1, -1, -1, -1)); }),
                  VK_SUCCESS);
        return k.read(t.image.image, 4, 4, 16);
    });
    expect_signalling_half_nan_quieted(data, out);
}

}  // namespace
}  // namespace tilevk::test::breadth
