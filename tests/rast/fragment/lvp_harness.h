// Vulkan harness for the lavapipe cross-checks: device setup, buffers, images and the render passes the tests
// run on lavapipe. Included by lavapipe_crosscheck_test.cpp only.
#pragma once

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "buffer_color_frag.h"
#include "buffer_depth_frag.h"
#include "fullscreen_vert.h"
#include "interp_frag.h"
#include "interp_vert.h"
#include "rast/fragment/blend.h"
#include "rast/fragment/depth_stencil.h"
#include "rast/fragment/interp.h"
#include "rast/fragment/msaa.h"
#include "sample_color_frag.h"
#include "vk_harness.h"
#include "vk_pipeline.h"

using namespace tilevk::rast::fragment;

namespace {

constexpr uint32_t kW = 64, kH = 64;

#define VKC(x)                                                                               \
    do {                                                                                     \
        VkResult r_ = (x);                                                                   \
        if (r_ != VK_SUCCESS) throw std::runtime_error(#x " failed: " + std::to_string(r_)); \
    } while (0)

VkFormat to_vk(ColorFormat f) {
    switch (f) {
        case ColorFormat::R8G8B8A8_UNORM:
            return VK_FORMAT_R8G8B8A8_UNORM;
        case ColorFormat::B8G8R8A8_UNORM:
            return VK_FORMAT_B8G8R8A8_UNORM;
        case ColorFormat::R8G8B8A8_SRGB:
            return VK_FORMAT_R8G8B8A8_SRGB;
        case ColorFormat::B8G8R8A8_SRGB:
            return VK_FORMAT_B8G8R8A8_SRGB;
        case ColorFormat::R8_UNORM:
            return VK_FORMAT_R8_UNORM;
        case ColorFormat::R8G8_UNORM:
            return VK_FORMAT_R8G8_UNORM;
        case ColorFormat::R16G16B16A16_SFLOAT:
            return VK_FORMAT_R16G16B16A16_SFLOAT;
        case ColorFormat::R32_SFLOAT:
            return VK_FORMAT_R32_SFLOAT;
        case ColorFormat::R32G32_SFLOAT:
            return VK_FORMAT_R32G32_SFLOAT;
        case ColorFormat::R32G32B32A32_SFLOAT:
            return VK_FORMAT_R32G32B32A32_SFLOAT;
        default:  // the colour formats the fragment stage writes are the ones above
            break;
    }
    return VK_FORMAT_UNDEFINED;
}

// lavapipe through the shared test harness (tests/harness/vk_harness.h): no validation layer (these tests judge
// lavapipe's bytes, not the API usage), depthClamp and sampleRateShading enabled.
struct Lvp {
    std::unique_ptr<tilevk::test::Harness> harness;
    std::unique_ptr<tilevk::test::Device> device;
    VkDevice dev = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;

    bool init() {
        harness = std::make_unique<tilevk::test::Harness>(/*validation=*/false);
        if (harness->instance() == VK_NULL_HANDLE) return false;
        const VkPhysicalDevice phys = harness->find_device("llvmpipe");
        if (!phys) return false;
        VkPhysicalDeviceFeatures feats{};
        feats.depthClamp = VK_TRUE;
        feats.sampleRateShading = VK_TRUE;
        device = std::make_unique<tilevk::test::Device>(phys, &feats);
        if (!device->ok() || device->pool() == VK_NULL_HANDLE) return false;
        dev = device->device();
        queue = device->queue();
        pool = device->pool();
        return true;
    }
    uint32_t mem_type(uint32_t bits, VkMemoryPropertyFlags want) const {
        const uint32_t t = device->memory_type(bits, want);
        if (t == ~0u) throw std::runtime_error("no memory type");
        return t;
    }
};

struct Buffer {
    VkBuffer buf = VK_NULL_HANDLE;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    void* map = nullptr;
};

// Host-visible, coherent and mapped, with TRANSFER_SRC|DST besides `usage` (the shared harness's buffers).
Buffer make_buffer(const Lvp& v, VkDeviceSize size, VkBufferUsageFlags usage) {
    const tilevk::test::Device::Buffer b = v.device->make_buffer(size, usage);
    if (b.map == nullptr) throw std::runtime_error("make_buffer failed");
    return {b.buffer, b.memory, b.map};
}
void free_buffer(const Lvp& v, Buffer& b) {
    tilevk::test::Device::Buffer d{b.buf, b.mem, b.map, 0};
    v.device->destroy(d);
    b = {};
}

VkShaderModule make_shader(const Lvp& v, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule m;
    VKC(vkCreateShaderModule(v.dev, &ci, nullptr, &m));
    return m;
}

struct Img {
    VkImage img = VK_NULL_HANDLE;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
};

Img make_image(const Lvp& v, VkFormat f, VkSampleCountFlagBits samples, VkImageUsageFlags usage,
               VkImageAspectFlags aspect) {
    Img r;
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = f;
    ii.extent = {kW, kH, 1};
    ii.mipLevels = ii.arrayLayers = 1;
    ii.samples = samples;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage;
    VKC(vkCreateImage(v.dev, &ii, nullptr, &r.img));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(v.dev, r.img, &req);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = v.mem_type(req.memoryTypeBits, 0);
    VKC(vkAllocateMemory(v.dev, &mai, nullptr, &r.mem));
    VKC(vkBindImageMemory(v.dev, r.img, r.mem, 0));
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = r.img;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = f;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    VKC(vkCreateImageView(v.dev, &vi, nullptr, &r.view));
    return r;
}
void free_image(const Lvp& v, Img& i) {
    vkDestroyImageView(v.dev, i.view, nullptr);
    vkDestroyImage(v.dev, i.img, nullptr);
    vkFreeMemory(v.dev, i.mem, nullptr);
}

// A one-subpass render pass over `atts` (the subpass as `sub` describes it) and its kW x kH framebuffer.
struct Pass {
    const Lvp& v;
    VkRenderPass rp = VK_NULL_HANDLE;
    VkFramebuffer fb = VK_NULL_HANDLE;
    Pass(const Lvp& lvp, const VkAttachmentDescription* atts, uint32_t count, const VkSubpassDescription& sub,
         const VkImageView* views)
        : v(lvp) {
        VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        rpi.attachmentCount = count;
        rpi.pAttachments = atts;
        rpi.subpassCount = 1;
        rpi.pSubpasses = &sub;
        VKC(vkCreateRenderPass(v.dev, &rpi, nullptr, &rp));
        VkFramebufferCreateInfo fbi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fbi.renderPass = rp;
        fbi.attachmentCount = count;
        fbi.pAttachments = views;
        fbi.width = kW;
        fbi.height = kH;
        fbi.layers = 1;
        VKC(vkCreateFramebuffer(v.dev, &fbi, nullptr, &fb));
    }
    ~Pass() {
        vkDestroyFramebuffer(v.dev, fb, nullptr);
        vkDestroyRenderPass(v.dev, rp, nullptr);
    }
    Pass(const Pass&) = delete;
    Pass& operator=(const Pass&) = delete;
};

// What the passes below share: a storage buffer holding `data` at binding 0 of set 0 (visible to `stages`), the
// fragment stage's 4-byte push constant (the target width), and a pipeline of `states` with the vertex and fragment
// shaders `vert` and `frag` in `pass`; record() draws the full-screen triangle in one instance of the pass.
struct BufferDraw {
    const Lvp& v;
    VkDescriptorSetLayout dsl = VK_NULL_HANDLE;
    VkPipelineLayout pl = VK_NULL_HANDLE;
    VkDescriptorPool dp = VK_NULL_HANDLE;
    VkDescriptorSet ds = VK_NULL_HANDLE;
    VkPipeline pipe = VK_NULL_HANDLE;
    Buffer ssbo;

    BufferDraw(const Lvp& lvp, VkShaderStageFlags stages, const void* data, size_t bytes, const Pass& pass,
               const uint32_t* vert, size_t vert_bytes, const uint32_t* frag, size_t frag_bytes,
               tilevk::test::PipelineStates& states)
        : v(lvp) {
        VkDescriptorSetLayoutBinding b0{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr};
        VkDescriptorSetLayoutCreateInfo dli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        dli.bindingCount = 1;
        dli.pBindings = &b0;
        VKC(vkCreateDescriptorSetLayout(v.dev, &dli, nullptr, &dsl));
        VkPushConstantRange pcr{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};
        VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        pli.setLayoutCount = 1;
        pli.pSetLayouts = &dsl;
        pli.pushConstantRangeCount = 1;
        pli.pPushConstantRanges = &pcr;
        VKC(vkCreatePipelineLayout(v.dev, &pli, nullptr, &pl));
        VkShaderModule vs = make_shader(v, vert, vert_bytes);
        VkShaderModule fs = make_shader(v, frag, frag_bytes);
        const VkPipelineShaderStageCreateInfo st[2] = {tilevk::test::shader_stage(VK_SHADER_STAGE_VERTEX_BIT, vs),
                                                       tilevk::test::shader_stage(VK_SHADER_STAGE_FRAGMENT_BIT, fs)};
        const VkResult made = states.create(v.dev, pass.rp, pl, st, 2, &pipe);
        vkDestroyShaderModule(v.dev, vs, nullptr);
        vkDestroyShaderModule(v.dev, fs, nullptr);
        VKC(made);

        VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
        VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpi.maxSets = 1;
        dpi.poolSizeCount = 1;
        dpi.pPoolSizes = &ps;
        VKC(vkCreateDescriptorPool(v.dev, &dpi, nullptr, &dp));
        VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        dai.descriptorPool = dp;
        dai.descriptorSetCount = 1;
        dai.pSetLayouts = &dsl;
        VKC(vkAllocateDescriptorSets(v.dev, &dai, &ds));
        ssbo = make_buffer(v, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        std::memcpy(ssbo.map, data, bytes);
        VkDescriptorBufferInfo dbi{ssbo.buf, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = ds;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w.pBufferInfo = &dbi;
        vkUpdateDescriptorSets(v.dev, 1, &w, 0, nullptr);
    }
    ~BufferDraw() {
        free_buffer(v, ssbo);
        vkDestroyDescriptorPool(v.dev, dp, nullptr);
        vkDestroyPipeline(v.dev, pipe, nullptr);
        vkDestroyPipelineLayout(v.dev, pl, nullptr);
        vkDestroyDescriptorSetLayout(v.dev, dsl, nullptr);
    }
    BufferDraw(const BufferDraw&) = delete;
    BufferDraw& operator=(const BufferDraw&) = delete;

    // One instance of `pass` over the whole target (`clear`: its first attachment's clear value, or null), the
    // full-screen triangle drawn unless `draw` is false.
    void record(VkCommandBuffer cmd, const Pass& pass, const VkClearValue* clear, bool draw = true) const {
        VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rbi.renderPass = pass.rp;
        rbi.framebuffer = pass.fb;
        rbi.renderArea = {{0, 0}, {kW, kH}};
        rbi.clearValueCount = clear != nullptr ? 1 : 0;
        rbi.pClearValues = clear;
        vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pl, 0, 1, &ds, 0, nullptr);
        const uint32_t width = kW;
        vkCmdPushConstants(cmd, pl, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4, &width);
        if (draw) vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRenderPass(cmd);
    }
};

// Uploads the bytes at `xfer` (regions `bic`) into `img`, taking it from UNDEFINED through TRANSFER_DST to
// `attachment_layout` for the pass (reached at `stage` with `access`).
void upload(VkCommandBuffer cmd, VkImage img, VkImageAspectFlags aspects, const Buffer& xfer,
            const VkBufferImageCopy* bic, uint32_t regions, VkImageLayout attachment_layout, VkPipelineStageFlags stage,
            VkAccessFlags access) {
    VkImageMemoryBarrier bar{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    bar.srcQueueFamilyIndex = bar.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    bar.image = img;
    bar.subresourceRange = {aspects, 0, 1, 0, 1};
    bar.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    bar.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    bar.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &bar);
    vkCmdCopyBufferToImage(cmd, xfer.buf, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, regions, bic);
    bar.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    bar.newLayout = attachment_layout;
    bar.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    bar.dstAccessMask = access;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, stage, 0, 0, nullptr, 0, nullptr, 1, &bar);
}

// Records with `record` on lavapipe and waits for it (the shared harness's one-shot command buffer).
void run(const Lvp& v, const std::function<void(VkCommandBuffer)>& record) {
    VKC(v.device->run(record));
}

// Renders src colours over dst bytes with the blend state; returns the image bytes.
std::vector<uint8_t> render(const Lvp& v, ColorFormat f, const BlendAttachment& a, const float consts[4],
                            const std::vector<float>& src, const std::vector<uint8_t>& dst) {
    const uint32_t bpp = format_info(f).bytes;
    const VkFormat vf = to_vk(f);
    Img img = make_image(
        v, vf, VK_SAMPLE_COUNT_1_BIT,
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        VK_IMAGE_ASPECT_COLOR_BIT);
    VkAttachmentDescription att{};
    att.format = vf;
    att.samples = VK_SAMPLE_COUNT_1_BIT;
    att.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    att.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    const Pass pass(v, &att, 1, sub, &img.view);

    tilevk::test::PipelineStates states(kW, kH);
    VkPipelineColorBlendAttachmentState& cba = states.blend;
    cba.blendEnable = a.blend_enable;
    cba.srcColorBlendFactor = VkBlendFactor(a.src_color);
    cba.dstColorBlendFactor = VkBlendFactor(a.dst_color);
    cba.colorBlendOp = VkBlendOp(a.color_op);
    cba.srcAlphaBlendFactor = VkBlendFactor(a.src_alpha);
    cba.dstAlphaBlendFactor = VkBlendFactor(a.dst_alpha);
    cba.alphaBlendOp = VkBlendOp(a.alpha_op);
    cba.colorWriteMask = a.write_mask;
    std::memcpy(states.color_blend.blendConstants, consts, 16);
    const BufferDraw draw(v, VK_SHADER_STAGE_FRAGMENT_BIT, src.data(), src.size() * 4, pass, kFullscreenVert,
                          sizeof kFullscreenVert, kBufferColorFrag, sizeof kBufferColorFrag, states);

    Buffer xfer = make_buffer(v, VkDeviceSize(kW) * kH * bpp,
                              VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    std::memcpy(xfer.map, dst.data(), dst.size());
    VkBufferImageCopy bic{};
    bic.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    bic.imageExtent = {kW, kH, 1};
    run(v, [&](VkCommandBuffer cmd) {
        upload(cmd, img.img, VK_IMAGE_ASPECT_COLOR_BIT, xfer, &bic, 1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
        draw.record(cmd, pass, nullptr);
        vkCmdCopyImageToBuffer(cmd, img.img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, xfer.buf, 1, &bic);
    });
    std::vector<uint8_t> out(size_t(kW) * kH * bpp);
    std::memcpy(out.data(), xfer.map, out.size());
    free_buffer(v, xfer);
    free_image(v, img);
    return out;
}

float random_src(std::mt19937& rng, ChannelKind kind) {
    const uint32_t r = rng() % 1000;
    if (kind == ChannelKind::Float32 || kind == ChannelKind::Half) return float(int(rng() % 40001) - 20000) / 7919.0f;
    if (r < 5) return INFINITY;  // the 8-wide conversion clamps +Inf to 1 (the 4-wide one would give 0)
    if (r < 8) return NAN;
    if (r < 10) return 3e9f;
    if (r < 30) return -0.25f;
    if (r < 60) return 1.5f;
    return float(rng() % 1000001) / 1000000.0f;
}

void random_dst(std::mt19937& rng, ColorFormat f, uint8_t* px) {
    const FormatInfo fi = format_info(f);
    if (fi.kind == ChannelKind::Float32) {
        for (int c = 0; c < fi.channels; ++c) {
            const float v = float(int(rng() % 20001) - 10000) / 4999.0f;
            std::memcpy(px + 4 * c, &v, 4);
        }
    } else if (fi.kind == ChannelKind::Half) {
        for (int c = 0; c < fi.channels; ++c) {
            const uint16_t h = uint16_t(rng() % 0x4400u) | uint16_t((rng() & 1) << 15);  // finite, |x| < 4
            std::memcpy(px + 2 * c, &h, 2);
        }
    } else {
        for (int i = 0; i < fi.bytes; ++i) px[i] = uint8_t(rng());
    }
}

struct Case {
    const char* name;
    ColorFormat format;
    BlendAttachment a;
};

BlendAttachment ba(BlendFactor sc, BlendFactor dc, BlendOp co, BlendFactor sa, BlendFactor da, BlendOp ao,
                   uint8_t mask = 0xf) {
    BlendAttachment a;
    a.blend_enable = true;
    a.src_color = sc;
    a.dst_color = dc;
    a.color_op = co;
    a.src_alpha = sa;
    a.dst_alpha = da;
    a.alpha_op = ao;
    a.write_mask = mask;
    return a;
}

struct PassSpec {
    bool depth = false;  // depth-only pass writing gl_FragDepth, else colour (4x, per-sample) + resolve
    VkFormat format = VK_FORMAT_UNDEFINED;
    bool depth_clamp = false;
    float min_depth = 0.0f, max_depth = 1.0f;
    bool per_pixel_color = false;  // colour pass: one colour per pixel (no sample shading) instead of per sample
    bool alpha_to_coverage = false;
    uint32_t sample_mask = 0xf;
    bool interp = false;  // interp.vert/interp.frag with vertex data in the buffer, `samples` samples
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;
    bool no_draw = false;  // only the render pass clear
    float clear[4] = {};   // colour clear value
};

// Runs one pass and returns the readback (depth aspect, or the resolved colour image).
std::vector<uint8_t> run_pass(const Lvp& v, const PassSpec& spec, const std::vector<float>& data, uint32_t bpp) {
    const VkSampleCountFlagBits samples = spec.depth ? VK_SAMPLE_COUNT_1_BIT : spec.samples;
    const bool resolve = !spec.depth && samples != VK_SAMPLE_COUNT_1_BIT;
    const VkImageAspectFlags aspect = spec.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    Img target =
        make_image(v, spec.format, samples,
                   (spec.depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                   aspect);
    Img resolved;
    if (resolve)
        resolved = make_image(v, spec.format, VK_SAMPLE_COUNT_1_BIT,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, aspect);

    VkAttachmentDescription att[2]{};
    att[0].format = spec.format;
    att[0].samples = samples;
    att[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    att[1] = att[0];
    att[1].samples = VK_SAMPLE_COUNT_1_BIT;
    att[1].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    VkAttachmentReference r0{
        0, spec.depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference r1{1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    if (spec.depth) {
        sub.pDepthStencilAttachment = &r0;
    } else {
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &r0;
        if (resolve) sub.pResolveAttachments = &r1;
    }
    const VkImageView views[2] = {target.view, resolved.view};
    const Pass pass(v, att, resolve ? 2 : 1, sub, views);

    tilevk::test::PipelineStates states(kW, kH);
    states.viewport.minDepth = spec.min_depth;
    states.viewport.maxDepth = spec.max_depth;
    states.raster.depthClampEnable = spec.depth_clamp;
    VkPipelineMultisampleStateCreateInfo& ms = states.multisample;
    ms.rasterizationSamples = samples;
    ms.sampleShadingEnable = !spec.depth && !spec.per_pixel_color && !spec.interp;
    ms.minSampleShading = 1.0f;
    const VkSampleMask smask = spec.sample_mask;
    ms.pSampleMask = &smask;
    ms.alphaToCoverageEnable = spec.alpha_to_coverage;
    states.depth_stencil_enabled = spec.depth;
    states.depth_stencil.depthTestEnable = VK_TRUE;
    states.depth_stencil.depthWriteEnable = VK_TRUE;
    states.depth_stencil.depthCompareOp = VK_COMPARE_OP_ALWAYS;
    states.color_blend.attachmentCount = spec.depth ? 0 : 1;
    const uint32_t* vert = spec.interp ? kInterpVert : kFullscreenVert;
    const size_t vert_bytes = spec.interp ? sizeof kInterpVert : sizeof kFullscreenVert;
    const uint32_t* frag = spec.interp            ? kInterpFrag
                           : spec.depth           ? kBufferDepthFrag
                           : spec.per_pixel_color ? kBufferColorFrag
                                                  : kSampleColorFrag;
    const size_t frag_bytes = spec.interp            ? sizeof kInterpFrag
                              : spec.depth           ? sizeof kBufferDepthFrag
                              : spec.per_pixel_color ? sizeof kBufferColorFrag
                                                     : sizeof kSampleColorFrag;
    const BufferDraw draw(v, VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_VERTEX_BIT, data.data(), data.size() * 4,
                          pass, vert, vert_bytes, frag, frag_bytes, states);

    Buffer xfer = make_buffer(v, VkDeviceSize(kW) * kH * bpp, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    run(v, [&](VkCommandBuffer cmd) {
        VkClearValue clear{};
        std::memcpy(clear.color.float32, spec.clear, 16);
        draw.record(cmd, pass, &clear, !spec.no_draw);
        VkBufferImageCopy bic{};
        bic.imageSubresource = {aspect, 0, 0, 1};
        bic.imageExtent = {kW, kH, 1};
        vkCmdCopyImageToBuffer(cmd, resolve ? resolved.img : target.img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, xfer.buf,
                               1, &bic);
    });
    std::vector<uint8_t> out(size_t(kW) * kH * bpp);
    std::memcpy(out.data(), xfer.map, out.size());
    free_buffer(v, xfer);
    free_image(v, target);
    if (resolve) free_image(v, resolved);
    return out;
}

float bits_f(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

}  // namespace

namespace {

VkStencilOpState to_vk(const StencilFace& f) {
    VkStencilOpState s{};
    s.failOp = VkStencilOp(f.fail_op);
    s.passOp = VkStencilOp(f.pass_op);
    s.depthFailOp = VkStencilOp(f.depth_fail_op);
    s.compareOp = VkCompareOp(f.compare_op);
    s.compareMask = f.compare_mask;
    s.writeMask = f.write_mask;
    s.reference = f.reference;
    return s;
}

// D24S8 pass: initial depth/stencil from buffers, gl_FragDepth from `z`, returns (depth words, stencil bytes).
void run_stencil_pass(const Lvp& v, const DepthStencilState& st, bool front, const std::vector<uint32_t>& d0,
                      const std::vector<uint8_t>& s0, const std::vector<float>& z, std::vector<uint32_t>& d1,
                      std::vector<uint8_t>& s1) {
    const VkFormat vf = VK_FORMAT_D24_UNORM_S8_UINT;
    const VkImageAspectFlags both = VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    Img img = make_image(
        v, vf, VK_SAMPLE_COUNT_1_BIT,
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        both);
    VkAttachmentDescription att{};
    att.format = vf;
    att.samples = VK_SAMPLE_COUNT_1_BIT;
    att.loadOp = att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    att.storeOp = att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.initialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    att.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference r0{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.pDepthStencilAttachment = &r0;
    const Pass pass(v, &att, 1, sub, &img.view);

    tilevk::test::PipelineStates states(kW, kH);
    // The full-screen triangle has negative Vulkan area: it is front-facing with CLOCKWISE.
    states.raster.frontFace = front ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
    states.depth_stencil_enabled = true;
    VkPipelineDepthStencilStateCreateInfo& dss = states.depth_stencil;
    dss.depthTestEnable = st.depth_test;
    dss.depthWriteEnable = st.depth_write;
    dss.depthCompareOp = VkCompareOp(st.depth_compare);
    dss.stencilTestEnable = st.stencil_test;
    dss.front = to_vk(st.front);
    dss.back = to_vk(st.back);
    states.color_blend.attachmentCount = 0;
    const size_t n = size_t(kW) * kH;
    const BufferDraw draw(v, VK_SHADER_STAGE_FRAGMENT_BIT, z.data(), n * 4, pass, kFullscreenVert,
                          sizeof kFullscreenVert, kBufferDepthFrag, sizeof kBufferDepthFrag, states);

    Buffer xfer = make_buffer(v, n * 5, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    std::memcpy(xfer.map, d0.data(), n * 4);
    std::memcpy(static_cast<uint8_t*>(xfer.map) + n * 4, s0.data(), n);
    VkBufferImageCopy bic[2]{};
    bic[0].imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    bic[0].imageExtent = {kW, kH, 1};
    bic[1] = bic[0];
    bic[1].imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
    bic[1].bufferOffset = n * 4;
    run(v, [&](VkCommandBuffer cmd) {
        upload(cmd, img.img, both, xfer, bic, 2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
        draw.record(cmd, pass, nullptr);
        vkCmdCopyImageToBuffer(cmd, img.img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, xfer.buf, 2, bic);
    });
    d1.resize(n);
    s1.resize(n);
    std::memcpy(d1.data(), xfer.map, n * 4);
    std::memcpy(s1.data(), static_cast<uint8_t*>(xfer.map) + n * 4, n);
    free_buffer(v, xfer);
    free_image(v, img);
}

}  // namespace

namespace {

struct SetupPlane {
    // lp_state_setup.c emit_tri_coef with unfused float ops; v are the re-ordered window positions.
    static Plane make(const float vx[3], const float vy[3], const float a[3], float pc) {
        volatile float x0c = vx[0] - pc, y0c = vy[0] - pc;
        volatile float dx01 = vx[0] - vx[1], dy01 = vy[0] - vy[1];
        volatile float dx20 = vx[2] - vx[0], dy20 = vy[2] - vy[0];
        volatile float m1 = dx01 * dy20, m2 = dy01 * dx20;
        volatile float area = m1 - m2;
        volatile float ooa = 1.0f / area;
        volatile float dx20o = dx20 * ooa, dy20o = dy20 * ooa, dx01o = dx01 * ooa, dy01o = dy01 * ooa;
        volatile float da01 = a[0] - a[1], da20 = a[2] - a[0];
        volatile float t1 = da01 * dy20o, t2 = da20 * dy01o;
        volatile float dadx = t1 - t2;
        volatile float t3 = da20 * dx01o, t4 = da01 * dx20o;
        volatile float dady = t3 - t4;
        volatile float u1 = dadx * x0c, u2 = dady * y0c;
        volatile float s = u1 + u2;
        volatile float a0 = a[0] - s;
        return Plane{dadx, dady, a0};
    }
};

}  // namespace
