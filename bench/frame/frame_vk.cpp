#include "frame_vk.h"

#include <chrono>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <vector>

#include "frame_timing.h"
#include "glsl.hpp"

namespace tilevk::bench {
namespace {

using cts::vk_check;

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr uint32_t kPushBytes = 32;

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
};

struct Texture {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
};

// Texel (x, y) of mip `level` of a pattern: coloured checks with a gradient, so filtering and mips show.
void pattern(uint32_t seed, uint32_t size, uint32_t level, uint32_t x, uint32_t y, uint8_t out[4]) {
    const uint32_t cell = std::max(1u, (size >> level) / 8);
    const bool on = ((x / cell) + (y / cell) + seed) % 2 == 0;
    out[0] = uint8_t((x * 255) / std::max(1u, (size >> level) - 1));
    out[1] = uint8_t(on ? 230 : 40 + 20 * (level % 8));
    out[2] = uint8_t((y * 255) / std::max(1u, (size >> level) - 1));
    out[3] = 255;
    if (seed & 1) std::swap(out[0], out[2]);
}

}  // namespace

struct SceneOnDevice::Impl {
    const cts::DeviceContext* c = nullptr;
    const BenchScene* scene = nullptr;
    std::vector<std::function<void()>> cleanup;  // run in reverse
    Buffer vertices, readback;
    std::vector<Texture> textures;
    VkImage color = VK_NULL_HANDLE, resolved = VK_NULL_HANDLE;  // the image read back: resolved at 4x
    VkRenderPass render_pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::vector<VkPipeline> pipelines;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    double cold_ms = 0, record_ms = 0;

    ~Impl() {
        if (c) vkDeviceWaitIdle(c->device);
        for (auto it = cleanup.rbegin(); it != cleanup.rend(); ++it) (*it)();
    }
    VkDevice dev() const { return c->device; }

    Buffer make_buffer(VkDeviceSize size, VkBufferUsageFlags usage) {
        Buffer b;
        VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        ci.size = size;
        ci.usage = usage;
        vk_check(vkCreateBuffer(dev(), &ci, nullptr, &b.buffer), "vkCreateBuffer");
        cleanup.push_back([d = dev(), x = b.buffer] { vkDestroyBuffer(d, x, nullptr); });
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(dev(), b.buffer, &req);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = c->memory_type(req.memoryTypeBits,
                                            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        vk_check(vkAllocateMemory(dev(), &ai, nullptr, &b.memory), "vkAllocateMemory");
        // Cleanup runs in reverse: memory freed after the buffer is destroyed (registered before it).
        cleanup.insert(cleanup.end() - 1, [d = dev(), m = b.memory] { vkFreeMemory(d, m, nullptr); });
        vk_check(vkBindBufferMemory(dev(), b.buffer, b.memory, 0), "vkBindBufferMemory");
        vk_check(vkMapMemory(dev(), b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
        return b;
    }

    VkImage make_image(VkFormat f, uint32_t w, uint32_t h, uint32_t mips, VkSampleCountFlagBits samples,
                       VkImageUsageFlags usage) {
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = VK_IMAGE_TYPE_2D;
        ci.format = f;
        ci.extent = {w, h, 1};
        ci.mipLevels = mips;
        ci.arrayLayers = 1;
        ci.samples = samples;
        ci.tiling = VK_IMAGE_TILING_OPTIMAL;
        ci.usage = usage;
        VkImage img;
        vk_check(vkCreateImage(dev(), &ci, nullptr, &img), "vkCreateImage");
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(dev(), img, &req);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = c->memory_type(req.memoryTypeBits, 0);
        VkDeviceMemory mem;
        vk_check(vkAllocateMemory(dev(), &ai, nullptr, &mem), "vkAllocateMemory(image)");
        cleanup.push_back([d = dev(), mem] { vkFreeMemory(d, mem, nullptr); });
        cleanup.push_back([d = dev(), img] { vkDestroyImage(d, img, nullptr); });
        vk_check(vkBindImageMemory(dev(), img, mem, 0), "vkBindImageMemory");
        return img;
    }

    VkImageView make_view(VkImage img, VkFormat f, VkImageAspectFlags aspect, uint32_t mips) {
        VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        ci.image = img;
        ci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        ci.format = f;
        ci.subresourceRange = {aspect, 0, mips, 0, 1};
        VkImageView v;
        vk_check(vkCreateImageView(dev(), &ci, nullptr, &v), "vkCreateImageView");
        cleanup.push_back([d = dev(), v] { vkDestroyImageView(d, v, nullptr); });
        return v;
    }

    // Runs `record` in a one-time command buffer and waits for it.
    void one_time(const std::function<void(VkCommandBuffer)>& record) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = c->pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        VkCommandBuffer ocb;
        vk_check(vkAllocateCommandBuffers(dev(), &ai, &ocb), "vkAllocateCommandBuffers");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vk_check(vkBeginCommandBuffer(ocb, &bi), "vkBeginCommandBuffer");
        record(ocb);
        vk_check(vkEndCommandBuffer(ocb), "vkEndCommandBuffer");
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &ocb;
        vk_check(vkQueueSubmit(c->queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
        vk_check(vkQueueWaitIdle(c->queue), "vkQueueWaitIdle");
        vkFreeCommandBuffers(dev(), c->pool, 1, &ocb);
    }

    static void image_barrier(VkCommandBuffer cb, VkImage img, uint32_t mips, VkImageLayout from, VkImageLayout to,
                              VkAccessFlags src, VkAccessFlags dst, VkPipelineStageFlags src_stage,
                              VkPipelineStageFlags dst_stage) {
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = src;
        b.dstAccessMask = dst;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, mips, 0, 1};
        vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
    }

    Texture make_texture(const BenchTexture& t, VkDescriptorPool pool, VkDescriptorSetLayout set_layout) {
        Texture tex;
        uint32_t mips = 1;
        while ((t.size >> mips) > 0) ++mips;
        tex.image = make_image(kColorFormat, t.size, t.size, mips, VK_SAMPLE_COUNT_1_BIT,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        tex.view = make_view(tex.image, kColorFormat, VK_IMAGE_ASPECT_COLOR_BIT, mips);
        VkDeviceSize total = 0;
        for (uint32_t l = 0; l < mips; ++l) total += VkDeviceSize(t.size >> l) * (t.size >> l) * 4;
        Buffer staging = make_buffer(total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        std::vector<VkBufferImageCopy> copies;
        VkDeviceSize off = 0;
        for (uint32_t l = 0; l < mips; ++l) {
            const uint32_t n = t.size >> l;
            auto* bytes = static_cast<uint8_t*>(staging.mapped) + off;
            for (uint32_t y = 0; y < n; ++y)
                for (uint32_t x = 0; x < n; ++x) pattern(t.seed, t.size, l, x, y, bytes + (size_t(y) * n + x) * 4);
            VkBufferImageCopy r{};
            r.bufferOffset = off;
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
            r.imageExtent = {n, n, 1};
            copies.push_back(r);
            off += VkDeviceSize(n) * n * 4;
        }
        one_time([&](VkCommandBuffer ocb) {
            image_barrier(ocb, tex.image, mips, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                          VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT);
            vkCmdCopyBufferToImage(ocb, staging.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                   uint32_t(copies.size()), copies.data());
            image_barrier(ocb, tex.image, mips, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
        });
        VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        si.magFilter = si.minFilter = t.filter;
        si.mipmapMode = t.mip_mode;
        si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
        si.maxLod = float(mips);
        vk_check(vkCreateSampler(dev(), &si, nullptr, &tex.sampler), "vkCreateSampler");
        cleanup.push_back([d = dev(), s = tex.sampler] { vkDestroySampler(d, s, nullptr); });
        VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        dai.descriptorPool = pool;
        dai.descriptorSetCount = 1;
        dai.pSetLayouts = &set_layout;
        vk_check(vkAllocateDescriptorSets(dev(), &dai, &tex.set), "vkAllocateDescriptorSets");
        VkDescriptorImageInfo ii{tex.sampler, tex.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = tex.set;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        w.pImageInfo = &ii;
        vkUpdateDescriptorSets(dev(), 1, &w, 0, nullptr);
        return tex;
    }

    void make_render_pass() {
        const BenchScene& s = *scene;
        const bool msaa = s.samples != VK_SAMPLE_COUNT_1_BIT;
        std::vector<VkAttachmentDescription> att;
        att.push_back({0, kColorFormat, s.samples, VK_ATTACHMENT_LOAD_OP_CLEAR,
                       msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
                       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
        VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkAttachmentReference depth_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkAttachmentReference resolve_ref{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        if (s.depth != VK_FORMAT_UNDEFINED) {
            depth_ref.attachment = uint32_t(att.size());
            att.push_back({0, s.depth, s.samples, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                           VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                           VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL});
        }
        if (msaa) {
            resolve_ref.attachment = uint32_t(att.size());
            att.push_back({0, kColorFormat, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                           VK_ATTACHMENT_STORE_OP_STORE, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                           VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                           VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
        }
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &color_ref;
        sub.pResolveAttachments = msaa ? &resolve_ref : nullptr;
        sub.pDepthStencilAttachment = s.depth != VK_FORMAT_UNDEFINED ? &depth_ref : nullptr;
        // The next frame's pass (and the read-back copy) waits for this frame's attachment writes.
        VkSubpassDependency deps[2] = {
            {VK_SUBPASS_EXTERNAL, 0,
             VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
             VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
             VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
             VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 0},
            {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
             VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, 0}};
        VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        ci.attachmentCount = uint32_t(att.size());
        ci.pAttachments = att.data();
        ci.subpassCount = 1;
        ci.pSubpasses = &sub;
        ci.dependencyCount = 2;
        ci.pDependencies = deps;
        vk_check(vkCreateRenderPass(dev(), &ci, nullptr, &render_pass), "vkCreateRenderPass");
        cleanup.push_back([d = dev(), rp = render_pass] { vkDestroyRenderPass(d, rp, nullptr); });
    }

    VkPipeline make_pipeline(const BenchPipeline& p) {
        const BenchScene& s = *scene;
        const std::vector<uint32_t>& vs_spv = cts::compile_glsl(cts::Stage::kVertex, p.vertex_glsl);
        const std::vector<uint32_t>& fs_spv = cts::compile_glsl(cts::Stage::kFragment, p.fragment_glsl);
        const auto t0 = Clock::now();
        VkShaderModule modules[2];
        const std::vector<uint32_t>* code[2] = {&vs_spv, &fs_spv};
        for (int i = 0; i < 2; ++i) {
            VkShaderModuleCreateInfo mci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
            mci.codeSize = code[i]->size() * 4;
            mci.pCode = code[i]->data();
            vk_check(vkCreateShaderModule(dev(), &mci, nullptr, &modules[i]), "vkCreateShaderModule");
        }
        VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = modules[0];
        stages[0].pName = "main";
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = modules[1];
        stages[1].pName = "main";
        VkVertexInputBindingDescription binding{0, sizeof(BenchVertex), VK_VERTEX_INPUT_RATE_VERTEX};
        VkVertexInputAttributeDescription attrs[3] = {
            {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(BenchVertex, pos)},
            {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(BenchVertex, color)},
            {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BenchVertex, uv)}};
        VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        vi.vertexBindingDescriptionCount = 1;
        vi.pVertexBindingDescriptions = &binding;
        vi.vertexAttributeDescriptionCount = 3;
        vi.pVertexAttributeDescriptions = attrs;
        VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        vps.viewportCount = 1;
        vps.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        rs.polygonMode = VK_POLYGON_MODE_FILL;
        rs.cullMode = p.cull;
        rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        rs.lineWidth = 1.0f;
        VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        ms.rasterizationSamples = s.samples;
        VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
        ds.depthTestEnable = p.depth_test;
        ds.depthWriteEnable = p.depth_write;
        ds.depthCompareOp = VK_COMPARE_OP_LESS;
        ds.maxDepthBounds = 1.0f;
        VkPipelineColorBlendAttachmentState blend{};
        blend.colorWriteMask = 0xF;
        if (p.blend) {
            blend.blendEnable = VK_TRUE;
            blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
            blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
        }
        VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        cb.attachmentCount = 1;
        cb.pAttachments = &blend;
        const VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dy.dynamicStateCount = 2;
        dy.pDynamicStates = dyn;
        VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
        ci.stageCount = 2;
        ci.pStages = stages;
        ci.pVertexInputState = &vi;
        ci.pInputAssemblyState = &ia;
        ci.pViewportState = &vps;
        ci.pRasterizationState = &rs;
        ci.pMultisampleState = &ms;
        ci.pDepthStencilState = s.depth != VK_FORMAT_UNDEFINED ? &ds : nullptr;
        ci.pColorBlendState = &cb;
        ci.pDynamicState = &dy;
        ci.layout = layout;
        ci.renderPass = render_pass;
        VkPipeline pipe;
        vk_check(vkCreateGraphicsPipelines(dev(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipe), "vkCreateGraphicsPipelines");
        cold_ms += ms_since(t0);
        for (VkShaderModule m : modules) vkDestroyShaderModule(dev(), m, nullptr);
        cleanup.push_back([d = dev(), pipe] { vkDestroyPipeline(d, pipe, nullptr); });
        return pipe;
    }

    void record() {
        const BenchScene& s = *scene;
        vk_check(vkResetCommandBuffer(cb, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vk_check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
        VkClearValue clears[3];
        std::memcpy(clears[0].color.float32, s.clear_color, 16);
        clears[1].depthStencil = {1.0f, 0};
        clears[2] = clears[0];
        VkRenderPassBeginInfo rpbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rpbi.renderPass = render_pass;
        rpbi.framebuffer = framebuffer;
        rpbi.renderArea = {{0, 0}, {s.width, s.height}};
        rpbi.clearValueCount = 3;
        rpbi.pClearValues = clears;
        vkCmdBeginRenderPass(cb, &rpbi, VK_SUBPASS_CONTENTS_INLINE);
        const VkViewport vp{0, 0, float(s.width), float(s.height), 0, 1};
        vkCmdSetViewport(cb, 0, 1, &vp);
        const VkRect2D full{{0, 0}, {s.width, s.height}};
        VkRect2D scissor{{-1, -1}, {0, 0}};
        const VkDeviceSize zero = 0;
        vkCmdBindVertexBuffers(cb, 0, 1, &vertices.buffer, &zero);
        uint32_t bound_pipe = UINT32_MAX;
        int32_t bound_tex = -1;
        for (const BenchDraw& d : s.draws) {
            if (d.pipeline != bound_pipe) {
                vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines[d.pipeline]);
                bound_pipe = d.pipeline;
            }
            if (d.texture >= 0 && d.texture != bound_tex) {
                vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1,
                                        &textures[size_t(d.texture)].set, 0, nullptr);
                bound_tex = d.texture;
            }
            const VkRect2D want = d.scissor.extent.width ? d.scissor : full;
            if (std::memcmp(&want, &scissor, sizeof want) != 0) {
                vkCmdSetScissor(cb, 0, 1, &want);
                scissor = want;
            }
            vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, kPushBytes,
                               d.push);
            vkCmdDraw(cb, d.vertex_count, 1, d.first_vertex, 0);
        }
        vkCmdEndRenderPass(cb);
        vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    }
};

SceneOnDevice::SceneOnDevice(const cts::DeviceContext& c, const BenchScene& s) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.c = &c;
    m.scene = &s;
    VkDevice dev = c.device;
    m.vertices =
        m.make_buffer(std::max<size_t>(1, s.vertices.size()) * sizeof(BenchVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    std::memcpy(m.vertices.mapped, s.vertices.data(), s.vertices.size() * sizeof(BenchVertex));

    const bool msaa = s.samples != VK_SAMPLE_COUNT_1_BIT;
    std::vector<VkImageView> views;
    m.color = m.make_image(kColorFormat, s.width, s.height, 1, s.samples,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (msaa ? 0 : VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
    views.push_back(m.make_view(m.color, kColorFormat, VK_IMAGE_ASPECT_COLOR_BIT, 1));
    if (s.depth != VK_FORMAT_UNDEFINED) {
        VkImage depth =
            m.make_image(s.depth, s.width, s.height, 1, s.samples, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
        views.push_back(m.make_view(depth, s.depth, VK_IMAGE_ASPECT_DEPTH_BIT, 1));
    }
    m.resolved = m.color;
    if (msaa) {
        m.resolved = m.make_image(kColorFormat, s.width, s.height, 1, VK_SAMPLE_COUNT_1_BIT,
                                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        views.push_back(m.make_view(m.resolved, kColorFormat, VK_IMAGE_ASPECT_COLOR_BIT, 1));
    }
    m.readback = m.make_buffer(VkDeviceSize(s.width) * s.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    m.make_render_pass();
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = m.render_pass;
    fci.attachmentCount = uint32_t(views.size());
    fci.pAttachments = views.data();
    fci.width = s.width;
    fci.height = s.height;
    fci.layers = 1;
    vk_check(vkCreateFramebuffer(dev, &fci, nullptr, &m.framebuffer), "vkCreateFramebuffer");
    m.cleanup.push_back([dev, fb = m.framebuffer] { vkDestroyFramebuffer(dev, fb, nullptr); });

    // One layout for every pipeline: set 0 = a combined image sampler (fragment), 32 bytes of push constants.
    const VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
                                         nullptr};
    VkDescriptorSetLayoutCreateInfo dslci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dslci.bindingCount = 1;
    dslci.pBindings = &b;
    VkDescriptorSetLayout dsl;
    vk_check(vkCreateDescriptorSetLayout(dev, &dslci, nullptr, &dsl), "vkCreateDescriptorSetLayout");
    m.cleanup.push_back([dev, dsl] { vkDestroyDescriptorSetLayout(dev, dsl, nullptr); });
    const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, kPushBytes};
    VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &dsl;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &push;
    vk_check(vkCreatePipelineLayout(dev, &plci, nullptr, &m.layout), "vkCreatePipelineLayout");
    m.cleanup.push_back([dev, l = m.layout] { vkDestroyPipelineLayout(dev, l, nullptr); });

    if (!s.textures.empty()) {
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(s.textures.size())};
        VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpci.maxSets = uint32_t(s.textures.size());
        dpci.poolSizeCount = 1;
        dpci.pPoolSizes = &size;
        VkDescriptorPool pool;
        vk_check(vkCreateDescriptorPool(dev, &dpci, nullptr, &pool), "vkCreateDescriptorPool");
        m.cleanup.push_back([dev, pool] { vkDestroyDescriptorPool(dev, pool, nullptr); });
        for (const BenchTexture& t : s.textures) m.textures.push_back(m.make_texture(t, pool, dsl));
    }
    for (const BenchPipeline& p : s.pipelines) m.pipelines.push_back(m.make_pipeline(p));

    VkCommandBufferAllocateInfo cbai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cbai.commandPool = c.pool;
    cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cbai.commandBufferCount = 1;
    vk_check(vkAllocateCommandBuffers(dev, &cbai, &m.cb), "vkAllocateCommandBuffers");
    m.cleanup.push_back([dev, pool = c.pool, cb = m.cb] { vkFreeCommandBuffers(dev, pool, 1, &cb); });
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(dev, &fi, nullptr, &m.fence), "vkCreateFence");
    m.cleanup.push_back([dev, f = m.fence] { vkDestroyFence(dev, f, nullptr); });
}

SceneOnDevice::~SceneOnDevice() = default;

double SceneOnDevice::cold_pipeline_ms() const {
    return impl_->cold_ms;
}

double SceneOnDevice::last_record_ms() const {
    return impl_->record_ms;
}

double SceneOnDevice::frame() {
    Impl& m = *impl_;
    return timed_frame(
        m.dev(), m.c->queue, m.cb, m.fence, [&m] { m.record(); }, &m.record_ms);
}

const uint8_t* SceneOnDevice::image_bytes() const {
    return static_cast<const uint8_t*>(impl_->readback.mapped);
}

uint64_t SceneOnDevice::image_hash() {
    Impl& m = *impl_;
    const BenchScene& s = *m.scene;
    m.one_time([&](VkCommandBuffer ocb) {
        Impl::image_barrier(ocb, m.resolved, 1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                            VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {s.width, s.height, 1};
        vkCmdCopyImageToBuffer(ocb, m.resolved, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, m.readback.buffer, 1, &region);
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(ocb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                             nullptr, 0, nullptr);
    });
    const auto* bytes = static_cast<const uint8_t*>(m.readback.mapped);
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < size_t(s.width) * s.height * 4; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

}  // namespace tilevk::bench
