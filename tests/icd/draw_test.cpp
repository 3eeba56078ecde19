// Draws on both drivers (tilevk and lavapipe, through the loader with validation on): each scenario renders the
// same scene on both and the read-back bytes must be equal; a coarse independent check (a pixel known to be
// covered / uncovered) makes sure the scene really drew something.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "vk_harness.h"
#include "vk_pipeline.h"

namespace {

#include "color_frag.h"
#include "draw_vert.h"
#include "endless_vert.h"
#include "texture_frag.h"

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::PipelineStates;
using tilevk::test::shader_stage;
using tilevk::test::transition;
using tilevk::test::TwoDriverSuite;
using Bytes = std::vector<uint8_t>;

constexpr uint32_t kSize = 32;

struct Vertex {
    float pos[4];
    float color[4];
};

struct Scene {
    std::vector<Vertex> vertices;
    std::vector<uint16_t> indices;  // indexed draw when not empty
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    bool restart = false;
    bool depth = false;                                     // D32_SFLOAT attachment, test LESS, write on, cleared to 1
    bool blend = false;                                     // src alpha over
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  // 4: resolved into the 1x read-back image
    bool texture = false;                                   // 4x4 RGBA8 texture sampled (nearest) at v_color.xy
    bool endless_vertex_loop = false;                       // a vertex shader whose loop never terminates
    VkResult* draw_result = nullptr;                        // receives the draw submission's result if set
};

VkShaderModule module(VkDevice d, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateShaderModule(d, &ci, nullptr, &m), VK_SUCCESS);
    return m;
}

// Renders `s` into a kSize x kSize RGBA8 image cleared to opaque dark blue; returns its bytes.
Bytes render(Device& dev, const Scene& s) {
    VkDevice d = dev.device();
    const bool msaa = s.samples != VK_SAMPLE_COUNT_1_BIT;
    const VkFormat kColor = VK_FORMAT_R8G8B8A8_UNORM;
    Device::Image out = dev.make_image(kColor, kSize, kSize, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    Device::Image ms{}, depth{}, tex{};
    if (msaa) ms = dev.make_image(kColor, kSize, kSize, 1, 1, s.samples, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    if (s.depth)
        depth = dev.make_image(VK_FORMAT_D32_SFLOAT, kSize, kSize, 1, 1, s.samples,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    if (s.texture)
        tex = dev.make_image(kColor, 4, 4, 1, 1, VK_SAMPLE_COUNT_1_BIT,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);

    auto view_of = [&](VkImage img, VkFormat f, VkImageAspectFlags aspect) {
        VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        ci.image = img;
        ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        ci.format = f;
        ci.subresourceRange = {aspect, 0, 1, 0, 1};
        VkImageView v = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(d, &ci, nullptr, &v), VK_SUCCESS);
        return v;
    };
    std::vector<VkImageView> views;
    std::vector<VkAttachmentDescription> att;
    VkAttachmentDescription a{};
    a.format = kColor;
    a.samples = s.samples;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = msaa ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    att.push_back(a);
    views.push_back(view_of(msaa ? ms.image : out.image, kColor, VK_IMAGE_ASPECT_COLOR_BIT));
    VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference resolve_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    if (msaa) {
        a.samples = VK_SAMPLE_COUNT_1_BIT;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        a.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        resolve_ref.attachment = uint32_t(att.size());
        att.push_back(a);
        views.push_back(view_of(out.image, kColor, VK_IMAGE_ASPECT_COLOR_BIT));
    }
    if (s.depth) {
        a.format = VK_FORMAT_D32_SFLOAT;
        a.samples = s.samples;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        depth_ref.attachment = uint32_t(att.size());
        att.push_back(a);
        views.push_back(view_of(depth.image, VK_FORMAT_D32_SFLOAT, VK_IMAGE_ASPECT_DEPTH_BIT));
    }
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &color_ref;
    sub.pResolveAttachments = msaa ? &resolve_ref : nullptr;
    sub.pDepthStencilAttachment = s.depth ? &depth_ref : nullptr;
    VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpci.attachmentCount = uint32_t(att.size());
    rpci.pAttachments = att.data();
    rpci.subpassCount = 1;
    rpci.pSubpasses = &sub;
    VkRenderPass rp = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateRenderPass(d, &rpci, nullptr, &rp), VK_SUCCESS);
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = rp;
    fci.attachmentCount = uint32_t(views.size());
    fci.pAttachments = views.data();
    fci.width = fci.height = kSize;
    fci.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateFramebuffer(d, &fci, nullptr, &fb), VK_SUCCESS);

    // Descriptors (texture scenario).
    VkDescriptorSetLayout dsl = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    VkImageView tex_view = VK_NULL_HANDLE;
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    if (s.texture) {
        VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT};
        VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        lci.bindingCount = 1;
        lci.pBindings = &b;
        EXPECT_EQ(vkCreateDescriptorSetLayout(d, &lci, nullptr, &dsl), VK_SUCCESS);
        VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
        VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pci.maxSets = 1;
        pci.poolSizeCount = 1;
        pci.pPoolSizes = &ps;
        EXPECT_EQ(vkCreateDescriptorPool(d, &pci, nullptr, &pool), VK_SUCCESS);
        VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        ai.descriptorPool = pool;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &dsl;
        EXPECT_EQ(vkAllocateDescriptorSets(d, &ai, &set), VK_SUCCESS);
        VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
        sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
        sci.maxLod = 0.25f;
        EXPECT_EQ(vkCreateSampler(d, &sci, nullptr, &sampler), VK_SUCCESS);
        tex_view = view_of(tex.image, kColor, VK_IMAGE_ASPECT_COLOR_BIT);
        VkDescriptorImageInfo ii{sampler, tex_view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        w.pImageInfo = &ii;
        vkUpdateDescriptorSets(d, 1, &w, 0, nullptr);
        plci.setLayoutCount = 1;
        plci.pSetLayouts = &dsl;
    }
    VkPipelineLayout layout = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreatePipelineLayout(d, &plci, nullptr, &layout), VK_SUCCESS);

    // Pipeline.
    VkShaderModule vs =
        s.endless_vertex_loop ? module(d, endless_vert, sizeof endless_vert) : module(d, draw_vert, sizeof draw_vert);
    VkShaderModule fs =
        s.texture ? module(d, texture_frag, sizeof texture_frag) : module(d, color_frag, sizeof color_frag);
    const VkPipelineShaderStageCreateInfo stages[2] = {shader_stage(VK_SHADER_STAGE_VERTEX_BIT, vs),
                                                       shader_stage(VK_SHADER_STAGE_FRAGMENT_BIT, fs)};
    VkVertexInputBindingDescription vb{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription va[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                               {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
    PipelineStates states(kSize, kSize);
    states.vertex_input.vertexBindingDescriptionCount = 1;
    states.vertex_input.pVertexBindingDescriptions = &vb;
    states.vertex_input.vertexAttributeDescriptionCount = 2;
    states.vertex_input.pVertexAttributeDescriptions = va;
    states.assembly.topology = s.topology;
    states.assembly.primitiveRestartEnable = s.restart;
    states.multisample.rasterizationSamples = s.samples;
    states.depth_stencil_enabled = s.depth;
    states.depth_stencil.depthTestEnable = states.depth_stencil.depthWriteEnable = s.depth;
    states.depth_stencil.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState& cba = states.blend;
    cba.blendEnable = s.blend;
    cba.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    cba.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    cba.colorBlendOp = VK_BLEND_OP_ADD;
    cba.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    cba.dstAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    cba.alphaBlendOp = VK_BLEND_OP_ADD;
    VkPipeline pipe = VK_NULL_HANDLE;
    EXPECT_EQ(states.create(d, rp, layout, stages, 2, &pipe), VK_SUCCESS);

    Device::Buffer vbuf = dev.make_buffer(sizeof(Vertex) * s.vertices.size(), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    std::memcpy(vbuf.map, s.vertices.data(), vbuf.size);
    Device::Buffer ibuf{};
    if (!s.indices.empty()) {
        ibuf = dev.make_buffer(2 * s.indices.size(), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        std::memcpy(ibuf.map, s.indices.data(), ibuf.size);
    }
    Device::Buffer staging = dev.make_buffer(kSize * kSize * 4);
    if (s.texture) {
        // 4x4 texels, each a distinct colour.
        Device::Buffer texels = dev.make_buffer(64);
        auto* p = static_cast<uint8_t*>(texels.map);
        for (int i = 0; i < 16; ++i) {
            p[4 * i + 0] = uint8_t(i * 16);
            p[4 * i + 1] = uint8_t(255 - i * 13);
            p[4 * i + 2] = uint8_t((i * 77) & 255);
            p[4 * i + 3] = 255;
        }
        dev.run([&](VkCommandBuffer c) {
            transition(c, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy r{};
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            r.imageExtent = {4, 4, 1};
            vkCmdCopyBufferToImage(c, texels.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
            transition(c, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        });
        dev.destroy(texels);
    }

    const VkResult drawn = dev.run([&](VkCommandBuffer c) {
        VkClearValue clears[3] = {};
        clears[0].color = {{0.0f, 0.0f, 0.25f, 1.0f}};
        if (s.depth) clears[depth_ref.attachment].depthStencil = {1.0f, 0};
        VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        bi.renderPass = rp;
        bi.framebuffer = fb;
        bi.renderArea = states.scissor;
        bi.clearValueCount = uint32_t(att.size());
        bi.pClearValues = clears;
        vkCmdBeginRenderPass(c, &bi, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        VkDeviceSize zero = 0;
        vkCmdBindVertexBuffers(c, 0, 1, &vbuf.buffer, &zero);
        if (s.texture) vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
        if (s.indices.empty()) {
            vkCmdDraw(c, uint32_t(s.vertices.size()), 1, 0, 0);
        } else {
            vkCmdBindIndexBuffer(c, ibuf.buffer, 0, VK_INDEX_TYPE_UINT16);
            vkCmdDrawIndexed(c, uint32_t(s.indices.size()), 1, 0, 0, 0);
        }
        vkCmdEndRenderPass(c);
        VkBufferImageCopy r{};
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        r.imageExtent = {kSize, kSize, 1};
        vkCmdCopyImageToBuffer(c, out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &r);
    });
    if (s.draw_result != nullptr)
        *s.draw_result = drawn;
    else
        EXPECT_EQ(drawn, VK_SUCCESS);
    Bytes bytes(static_cast<uint8_t*>(staging.map), static_cast<uint8_t*>(staging.map) + staging.size);

    dev.destroy(staging);
    dev.destroy(vbuf);
    if (ibuf.buffer) dev.destroy(ibuf);
    vkDestroyPipeline(d, pipe, nullptr);
    vkDestroyShaderModule(d, vs, nullptr);
    vkDestroyShaderModule(d, fs, nullptr);
    vkDestroyPipelineLayout(d, layout, nullptr);
    if (s.texture) {
        vkDestroyImageView(d, tex_view, nullptr);
        vkDestroySampler(d, sampler, nullptr);
        vkDestroyDescriptorPool(d, pool, nullptr);
        vkDestroyDescriptorSetLayout(d, dsl, nullptr);
        dev.destroy(tex);
    }
    vkDestroyFramebuffer(d, fb, nullptr);
    vkDestroyRenderPass(d, rp, nullptr);
    for (VkImageView v : views) vkDestroyImageView(d, v, nullptr);
    dev.destroy(out);
    if (msaa) dev.destroy(ms);
    if (s.depth) dev.destroy(depth);
    return bytes;
}

class Draw : public TwoDriverSuite {
  protected:
    // Renders on both drivers; returns tilevk's bytes after checking they equal lavapipe's.
    Bytes both(const Scene& s) {
        Bytes t = render(*tilevk_, s), l = render(*lavapipe_, s);
        EXPECT_EQ(t.size(), l.size());
        size_t diffs = 0, first = 0;
        for (size_t i = 0; i < std::min(t.size(), l.size()); ++i)
            if (t[i] != l[i] && diffs++ == 0) first = i;
        EXPECT_EQ(diffs, 0u) << "first difference at pixel " << first / 4 << " byte " << first % 4 << ": "
                             << int(t[first]) << " vs " << int(l[first]);
        return t;
    }
};

const uint8_t* pixel(const Bytes& b, uint32_t x, uint32_t y) {
    return b.data() + (y * kSize + x) * 4;
}
constexpr uint8_t kClearBlue = 64;  // 0.25 * 255 rounded

Vertex v(float x, float y, float z, float r, float g, float b, float a = 1.0f) {
    return {{x, y, z, 1.0f}, {r, g, b, a}};
}

TEST_F(Draw, Triangle) {
    Scene s;
    s.vertices = {v(-0.8f, -0.8f, 0, 1, 0, 0), v(0.8f, -0.6f, 0, 0, 1, 0), v(-0.2f, 0.9f, 0, 0, 0, 1)};
    const Bytes b = both(s);
    EXPECT_EQ(pixel(b, 31, 31)[2], kClearBlue);  // corner: untouched
    EXPECT_NE(pixel(b, 10, 12)[2], kClearBlue);  // inside
}

TEST_F(Draw, IndexedStripWithRestart) {
    Scene s;
    s.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    s.restart = true;
    s.vertices = {v(-1, -1, 0, 1, 0, 0), v(-1, 0, 0, 0, 1, 0), v(0, -1, 0, 0, 0, 1), v(0, 0, 0, 1, 1, 0),
                  v(0, 0, 0, 1, 0, 1),   v(0, 1, 0, 0, 1, 1),  v(1, 0, 0, 1, 1, 1),  v(1, 1, 0, 0.5f, 0.5f, 0.5f)};
    s.indices = {0, 1, 2, 3, 0xFFFF, 4, 5, 6, 7};
    const Bytes b = both(s);
    EXPECT_NE(pixel(b, 4, 4)[3], 0);
    EXPECT_EQ(pixel(b, 28, 4)[2], kClearBlue);  // between the two strips: the restart cut it
    EXPECT_NE(pixel(b, 28, 28)[0], 0);
}

TEST_F(Draw, DepthTest) {
    Scene s;
    s.depth = true;
    // Far red quad first, then a near green triangle, then a farther blue one that must lose.
    s.vertices = {v(-1, -1, 0.5f, 1, 0, 0),       v(1, -1, 0.5f, 1, 0, 0),       v(-1, 1, 0.5f, 1, 0, 0),
                  v(-0.9f, -0.9f, 0.2f, 0, 1, 0), v(0.9f, -0.9f, 0.3f, 0, 1, 0), v(0, 0.9f, 0.4f, 0, 1, 0),
                  v(-1, -1, 0.9f, 0, 0, 1),       v(1, 1, 0.1f, 0, 0, 1),        v(-1, 1, 0.6f, 0, 0, 1)};
    const Bytes b = both(s);
    EXPECT_EQ(pixel(b, 16, 10)[1], 255);  // green wins
}

TEST_F(Draw, Blend) {
    Scene s;
    s.blend = true;
    s.vertices = {v(-1, -1, 0, 1, 0, 0, 0.5f),       v(1, -1, 0, 1, 0, 0, 0.5f),    v(-1, 1, 0, 1, 0, 0, 0.5f),
                  v(-0.5f, -0.5f, 0, 0, 1, 0, 0.3f), v(1, -0.5f, 0, 0, 1, 0, 0.7f), v(-0.5f, 1, 0, 0, 1, 0, 0.1f)};
    const Bytes b = both(s);
    const uint8_t* p = pixel(b, 2, 2);
    EXPECT_NEAR(p[0], 128, 1);  // 0.5 red over the clear
    EXPECT_NEAR(p[2], 32, 1);
}

TEST_F(Draw, Msaa4xResolve) {
    Scene s;
    s.samples = VK_SAMPLE_COUNT_4_BIT;
    s.vertices = {v(-0.83f, -0.71f, 0, 1, 1, 1), v(0.77f, -0.9f, 0, 1, 1, 1), v(0.1f, 0.93f, 0, 1, 1, 1)};
    const Bytes b = both(s);
    // Some edge pixel is partly covered: neither clear nor white.
    bool partial = false;
    for (uint32_t i = 0; i < kSize * kSize; ++i) partial |= b[4 * i] != 0 && b[4 * i] != 255;
    EXPECT_TRUE(partial);
}

TEST_F(Draw, TextureSample) {
    Scene s;
    s.texture = true;
    s.vertices = {v(-1, -1, 0, 0, 0, 0), v(3, -1, 0, 2, 0, 0), v(-1, 3, 0, 0, 2, 0)};
    const Bytes b = both(s);
    EXPECT_EQ(pixel(b, 0, 0)[0], 0);             // texel 0
    EXPECT_EQ(pixel(b, 9, 0)[0], 16);            // texel 1 (x 9.5/32*4 = 1.19)
    EXPECT_EQ(pixel(b, 0, 9)[1], 255 - 4 * 13);  // texel 4
}

// A shader that never terminates is cut short by the loop watchdog (shader/README.md). tilevk must not present the
// incomplete image as valid: the submission reports VK_ERROR_DEVICE_LOST, as a hung GPU would, and the device stays
// lost. Another device of the same driver is unaffected. (lavapipe would hang, so this runs on tilevk only.)
TEST_F(Draw, EndlessShaderLosesTheDevice) {
    Device lost(harness_->find_device("tilevk"));
    ASSERT_TRUE(lost.ok());
    VkResult result = VK_SUCCESS;
    Scene s;
    s.endless_vertex_loop = true;
    s.draw_result = &result;
    s.vertices = {v(-0.8f, -0.8f, 0, 1, 0, 0), v(0.8f, -0.6f, 0, 0, 1, 0), v(-0.2f, 0.9f, 0, 0, 0, 1)};
    render(lost, s);
    EXPECT_EQ(result, VK_ERROR_DEVICE_LOST);
    // Lost for good: the next (harmless) submission and the idle waits report it too.
    Scene plain;
    plain.draw_result = &result;
    plain.vertices = s.vertices;
    result = VK_SUCCESS;
    render(lost, plain);
    EXPECT_EQ(result, VK_ERROR_DEVICE_LOST);
    EXPECT_EQ(vkDeviceWaitIdle(lost.device()), VK_ERROR_DEVICE_LOST);
    // The shared tilevk device still renders, equal to lavapipe.
    Scene fine;
    fine.vertices = s.vertices;
    const Bytes b = both(fine);
    EXPECT_NE(pixel(b, 10, 12)[2], kClearBlue);
}

}  // namespace
