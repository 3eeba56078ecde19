// Test harness: a minimal Vulkan renderer on lavapipe (64x64 R8G8B8A8_UNORM target, 1x, one interleaved vertex
// buffer with a vec4 position and a vec4 colour attribute), pipelines cached per state.
#pragma once

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "kXcheck_frag.spv.h"
#include "kXcheck_noflat_frag.spv.h"
#include "kXcheck_vert.spv.h"
#include "rast/geometry/planes.h"
#include "vk_harness.h"
#include "vk_pipeline.h"

namespace xcheck {

using tilevk::rast::geometry::DepthBias;

constexpr int kSize = 64;
constexpr size_t kIndexOffset = 1 << 19;  // index data lives in the upper half of the vertex buffer

struct InVertex {
    float pos[4];
    float col[4];
};

// Less common state for a draw (pipeline key, plus an optional 32-bit index buffer).
struct Extra {
    bool depth_clamp = false;
    VkCullModeFlags cull = VK_CULL_MODE_NONE;
    VkFrontFace front = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool restart = false;
    const std::vector<uint32_t>* indices = nullptr;
    float vp[4] = {0, 0, kSize, kSize};  // x, y, width, height
    bool no_flat = false;                // fragment shader without a flat input (smooth colour only)
    int samples = 1;                     // 1, or 4 (rendered at 4x and resolved by the render pass)
};

#define VK_OK(x)                                      \
    do {                                              \
        VkResult r_ = (x);                            \
        if (r_ != VK_SUCCESS) {                       \
            ADD_FAILURE() << #x << " failed: " << r_; \
            return {};                                \
        }                                             \
    } while (0)

// Minimal Vulkan renderer on lavapipe: one pipeline, one 64x64 RGBA8 target, draws a triangle list.
class Lavapipe {
  public:
    Lavapipe() = default;
    Lavapipe(const Lavapipe&) = delete;  // owns its Vulkan objects
    Lavapipe& operator=(const Lavapipe&) = delete;
    // lavapipe through the shared test harness (tests/harness/vk_harness.h), no validation layer: wide lines, large
    // points, depth bias clamp and depth clamp, plus VK_EXT_line_rasterization's Bresenham lines where offered.
    bool init() {
        harness_ = std::make_unique<tilevk::test::Harness>(/*validation=*/false);
        if (harness_->instance() == VK_NULL_HANDLE) return false;
        pd_ = harness_->find_device("llvmpipe");
        if (!pd_) return false;
        VkPhysicalDeviceFeatures feats{};
        feats.wideLines = VK_TRUE;
        feats.largePoints = VK_TRUE;
        feats.depthBiasClamp = VK_TRUE;
        feats.depthClamp = VK_TRUE;
        VkPhysicalDeviceLineRasterizationFeaturesEXT line_feats{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
        line_feats.bresenhamLines = VK_TRUE;
        const char* ext = VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME;
        uint32_t next = 0;
        vkEnumerateDeviceExtensionProperties(pd_, nullptr, &next, nullptr);
        std::vector<VkExtensionProperties> exts(next);
        vkEnumerateDeviceExtensionProperties(pd_, nullptr, &next, exts.data());
        for (const auto& e : exts)
            if (std::strcmp(e.extensionName, ext) == 0) has_line_ext_ = true;
        std::vector<const char*> enabled;
        if (has_line_ext_) enabled.push_back(ext);
        device_ = std::make_unique<tilevk::test::Device>(pd_, &feats, enabled, has_line_ext_ ? &line_feats : nullptr);
        if (!device_->ok()) return false;
        dev_ = device_->device();
        queue_ = device_->queue();
        return setup();
    }
    // Every object is destroyed explicitly (vkDestroy* of VK_NULL_HANDLE is a no-op, so a half-done init() is fine):
    // a device destroyed with live children is invalid usage, and the leak check under ASan would see them.
    ~Lavapipe() {
        if (dev_) {
            vkDeviceWaitIdle(dev_);
            for (const auto& p : pipes_) vkDestroyPipeline(dev_, p.pipe, nullptr);
            vkDestroyPipelineLayout(dev_, layout_, nullptr);
            for (VkShaderModule m : {vs_, fs_, fs_noflat_}) vkDestroyShaderModule(dev_, m, nullptr);
            vkDestroyFramebuffer(dev_, fb_ms_, nullptr);
            vkDestroyFramebuffer(dev_, fb_, nullptr);
            vkDestroyRenderPass(dev_, pass_ms_, nullptr);
            vkDestroyRenderPass(dev_, pass_, nullptr);
            vkDestroyImageView(dev_, ms_view_, nullptr);
            vkDestroyImageView(dev_, view_, nullptr);
            vkDestroyImage(dev_, ms_image_, nullptr);
            vkDestroyImage(dev_, image_, nullptr);
            vkDestroyBuffer(dev_, rb_, nullptr);
            vkDestroyBuffer(dev_, vb_, nullptr);
            for (VkDeviceMemory m : {ms_mem_, image_mem_, rb_mem_, vb_mem_}) vkFreeMemory(dev_, m, nullptr);
        }  // device_ and then harness_ destroy the device and the instance
    }

    bool has_line_ext() const { return has_line_ext_; }

    // Renders `verts` as a triangle list with the given fragment mode; returns RGBA8 pixels.
    std::vector<uint8_t> render(const std::vector<InVertex>& verts, int mode,
                                VkPrimitiveTopology topo = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, float line_width = 1,
                                bool bresenham = false, VkFormat col_format = VK_FORMAT_R32G32B32A32_SFLOAT,
                                const DepthBias* bias = nullptr, const Extra& extra = Extra{}) {
        const VkPipeline pipe = pipeline(topo, line_width, bresenham, col_format, bias, extra);
        if (pipe == VK_NULL_HANDLE) return {};
        std::memcpy(vb_map_, verts.data(), verts.size() * sizeof(InVertex));
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        VK_OK(vkResetCommandBuffer(cmd_, 0));
        VK_OK(vkBeginCommandBuffer(cmd_, &bi));
        VkClearValue clear[2] = {};
        VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rp.renderPass = extra.samples == 4 ? pass_ms_ : pass_;
        rp.framebuffer = extra.samples == 4 ? fb_ms_ : fb_;
        rp.renderArea.extent = {kSize, kSize};
        rp.clearValueCount = extra.samples == 4 ? 2 : 1;
        rp.pClearValues = clear;
        vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        VkDeviceSize off = 0;
        vkCmdBindVertexBuffers(cmd_, 0, 1, &vb_, &off);
        vkCmdPushConstants(cmd_, layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &mode);
        if (extra.indices) {
            std::memcpy(static_cast<char*>(vb_map_) + kIndexOffset, extra.indices->data(), extra.indices->size() * 4);
            vkCmdBindIndexBuffer(cmd_, vb_, kIndexOffset, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd_, static_cast<uint32_t>(extra.indices->size()), 1, 0, 0, 0);
        } else {
            vkCmdDraw(cmd_, static_cast<uint32_t>(verts.size()), 1, 0, 0);
        }
        vkCmdEndRenderPass(cmd_);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {kSize, kSize, 1};
        vkCmdCopyImageToBuffer(cmd_, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, rb_, 1, &copy);
        VK_OK(vkEndCommandBuffer(cmd_));
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd_;
        VK_OK(vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE));
        VK_OK(vkQueueWaitIdle(queue_));
        std::vector<uint8_t> px(kSize * kSize * 4);
        std::memcpy(px.data(), rb_map_, px.size());
        return px;
    }

  private:
    uint32_t host_memory_type(uint32_t bits) { return device_->memory_type(bits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT); }
    // A mapped host-visible buffer of the shared harness (TRANSFER_SRC|DST besides `usage`), freed by ~Lavapipe.
    bool buffer(VkDeviceSize size, VkBufferUsageFlags usage, VkBuffer* b, VkDeviceMemory* m, void** map) {
        const tilevk::test::Device::Buffer made = device_->make_buffer(size, usage);
        *b = made.buffer, *m = made.memory, *map = made.map;
        return made.map != nullptr;
    }
    VkPipeline pipeline(VkPrimitiveTopology topo, float line_width, bool bresenham, VkFormat col_format,
                        const DepthBias* bias, const Extra& x) {
        const DepthBias b = bias ? *bias : DepthBias{};
        for (const auto& p : pipes_)
            if (p.topo == topo && p.width == line_width && p.bresenham == bresenham && p.format == col_format &&
                p.bias.constant_factor == b.constant_factor && p.bias.slope_factor == b.slope_factor &&
                p.bias.clamp == b.clamp && p.x.depth_clamp == x.depth_clamp && p.x.cull == x.cull &&
                p.x.front == x.front && p.x.restart == x.restart && std::memcmp(p.x.vp, x.vp, sizeof(x.vp)) == 0 &&
                p.x.no_flat == x.no_flat)
                return p.pipe;
        const VkPipelineShaderStageCreateInfo st[2] = {
            tilevk::test::shader_stage(VK_SHADER_STAGE_VERTEX_BIT, vs_),
            tilevk::test::shader_stage(VK_SHADER_STAGE_FRAGMENT_BIT, x.no_flat ? fs_noflat_ : fs_)};
        VkVertexInputBindingDescription bind{0, sizeof(InVertex), VK_VERTEX_INPUT_RATE_VERTEX};
        VkVertexInputAttributeDescription attrs[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {1, 0, col_format, 16}};
        tilevk::test::PipelineStates states(kSize, kSize);
        states.vertex_input.vertexBindingDescriptionCount = 1;
        states.vertex_input.pVertexBindingDescriptions = &bind;
        states.vertex_input.vertexAttributeDescriptionCount = 2;
        states.vertex_input.pVertexAttributeDescriptions = attrs;
        states.assembly.topology = topo;
        states.assembly.primitiveRestartEnable = x.restart;
        states.viewport = {x.vp[0], x.vp[1], x.vp[2], x.vp[3], 0, 1};
        VkPipelineRasterizationStateCreateInfo& rs = states.raster;
        rs.cullMode = x.cull;
        rs.frontFace = x.front;
        rs.depthClampEnable = x.depth_clamp;
        rs.lineWidth = line_width;
        rs.depthBiasEnable = bias != nullptr;
        rs.depthBiasConstantFactor = b.constant_factor;
        rs.depthBiasSlopeFactor = b.slope_factor;
        rs.depthBiasClamp = b.clamp;
        VkPipelineRasterizationLineStateCreateInfoEXT ls{
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
        ls.lineRasterizationMode = VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
        if (bresenham) rs.pNext = &ls;
        states.multisample.rasterizationSamples = x.samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
        VkPipeline pipe = VK_NULL_HANDLE;
        if (states.create(dev_, x.samples == 4 ? pass_ms_ : pass_, layout_, st, 2, &pipe) != VK_SUCCESS) return pipe;
        pipes_.push_back({topo, line_width, bresenham, col_format, b, x, pipe});
        return pipe;
    }
    bool setup() {
        if (!buffer(1 << 20, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &vb_, &vb_mem_,
                    &vb_map_))
            return false;
        if (!buffer(kSize * kSize * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &rb_, &rb_mem_, &rb_map_)) return false;
        VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ii.imageType = VK_IMAGE_TYPE_2D;
        ii.format = VK_FORMAT_R8G8B8A8_UNORM;
        ii.extent = {kSize, kSize, 1};
        ii.mipLevels = ii.arrayLayers = 1;
        ii.samples = VK_SAMPLE_COUNT_1_BIT;
        ii.tiling = VK_IMAGE_TILING_OPTIMAL;
        ii.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        if (vkCreateImage(dev_, &ii, nullptr, &image_) != VK_SUCCESS) return false;
        VkMemoryRequirements mr;
        vkGetImageMemoryRequirements(dev_, image_, &mr);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = mr.size;
        ai.memoryTypeIndex = host_memory_type(mr.memoryTypeBits);
        if (vkAllocateMemory(dev_, &ai, nullptr, &image_mem_) != VK_SUCCESS) return false;
        vkBindImageMemory(dev_, image_, image_mem_, 0);
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = image_;
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.format = ii.format;
        vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        if (vkCreateImageView(dev_, &vi, nullptr, &view_) != VK_SUCCESS) return false;
        VkAttachmentDescription att{};
        att.format = ii.format;
        att.samples = VK_SAMPLE_COUNT_1_BIT;
        att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        att.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &ref;
        VkSubpassDependency dep{};
        dep.srcSubpass = 0;
        dep.dstSubpass = VK_SUBPASS_EXTERNAL;
        dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        dep.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
        dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        dep.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        rpi.attachmentCount = 1;
        rpi.pAttachments = &att;
        rpi.subpassCount = 1;
        rpi.pSubpasses = &sub;
        rpi.dependencyCount = 1;
        rpi.pDependencies = &dep;
        if (vkCreateRenderPass(dev_, &rpi, nullptr, &pass_) != VK_SUCCESS) return false;
        VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fi.renderPass = pass_;
        fi.attachmentCount = 1;
        fi.pAttachments = &view_;
        fi.width = fi.height = kSize;
        fi.layers = 1;
        if (vkCreateFramebuffer(dev_, &fi, nullptr, &fb_) != VK_SUCCESS) return false;
        // 4x: a multisampled colour attachment resolved into image_ at the end of the subpass
        ii.samples = VK_SAMPLE_COUNT_4_BIT;
        ii.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        if (vkCreateImage(dev_, &ii, nullptr, &ms_image_) != VK_SUCCESS) return false;
        vkGetImageMemoryRequirements(dev_, ms_image_, &mr);
        ai.allocationSize = mr.size;
        ai.memoryTypeIndex = host_memory_type(mr.memoryTypeBits);
        if (vkAllocateMemory(dev_, &ai, nullptr, &ms_mem_) != VK_SUCCESS) return false;
        vkBindImageMemory(dev_, ms_image_, ms_mem_, 0);
        vi.image = ms_image_;
        if (vkCreateImageView(dev_, &vi, nullptr, &ms_view_) != VK_SUCCESS) return false;
        VkAttachmentDescription atts[2] = {att, att};
        atts[0].samples = VK_SAMPLE_COUNT_4_BIT;
        atts[0].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        atts[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        atts[1].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        VkAttachmentReference resolve_ref{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        sub.pResolveAttachments = &resolve_ref;
        rpi.attachmentCount = 2;
        rpi.pAttachments = atts;
        if (vkCreateRenderPass(dev_, &rpi, nullptr, &pass_ms_) != VK_SUCCESS) return false;
        VkImageView ms_views[2] = {ms_view_, view_};
        fi.renderPass = pass_ms_;
        fi.attachmentCount = 2;
        fi.pAttachments = ms_views;
        if (vkCreateFramebuffer(dev_, &fi, nullptr, &fb_ms_) != VK_SUCCESS) return false;
        VkShaderModuleCreateInfo smi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        smi.codeSize = sizeof(kXcheck_vert);
        smi.pCode = kXcheck_vert;
        if (vkCreateShaderModule(dev_, &smi, nullptr, &vs_) != VK_SUCCESS) return false;
        smi.codeSize = sizeof(kXcheck_frag);
        smi.pCode = kXcheck_frag;
        if (vkCreateShaderModule(dev_, &smi, nullptr, &fs_) != VK_SUCCESS) return false;
        smi.codeSize = sizeof(kXcheck_noflat_frag);
        smi.pCode = kXcheck_noflat_frag;
        if (vkCreateShaderModule(dev_, &smi, nullptr, &fs_noflat_) != VK_SUCCESS) return false;
        VkPushConstantRange pcr{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
        VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        li.pushConstantRangeCount = 1;
        li.pPushConstantRanges = &pcr;
        if (vkCreatePipelineLayout(dev_, &li, nullptr, &layout_) != VK_SUCCESS) return false;
        pool_ = device_->pool();  // resettable command buffers; destroyed (with cmd_) by device_
        if (pool_ == VK_NULL_HANDLE) return false;
        VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cai.commandPool = pool_;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        return vkAllocateCommandBuffers(dev_, &cai, &cmd_) == VK_SUCCESS;
    }

    std::unique_ptr<tilevk::test::Harness> harness_;
    std::unique_ptr<tilevk::test::Device> device_;  // after harness_: destroyed first
    VkPhysicalDevice pd_ = VK_NULL_HANDLE;
    VkDevice dev_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkBuffer vb_ = VK_NULL_HANDLE, rb_ = VK_NULL_HANDLE;
    VkDeviceMemory vb_mem_ = VK_NULL_HANDLE, rb_mem_ = VK_NULL_HANDLE;
    void* vb_map_ = nullptr;
    void* rb_map_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE, ms_image_ = VK_NULL_HANDLE;
    VkDeviceMemory image_mem_ = VK_NULL_HANDLE, ms_mem_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE, ms_view_ = VK_NULL_HANDLE;
    VkRenderPass pass_ = VK_NULL_HANDLE;
    VkFramebuffer fb_ = VK_NULL_HANDLE;
    VkRenderPass pass_ms_ = VK_NULL_HANDLE;
    VkFramebuffer fb_ms_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkShaderModule vs_ = VK_NULL_HANDLE, fs_ = VK_NULL_HANDLE, fs_noflat_ = VK_NULL_HANDLE;
    struct Pipe {
        VkPrimitiveTopology topo;
        float width;
        bool bresenham;
        VkFormat format;
        DepthBias bias;
        Extra x;
        VkPipeline pipe;
    };
    std::vector<Pipe> pipes_;
    bool has_line_ext_ = false;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

}  // namespace xcheck
