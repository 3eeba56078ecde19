// Shared by the API-breadth tests (tests/icd/api_breadth_*_test.cpp): the shaders, the Kit that builds objects
// on one device, the ApiBreadth fixture that runs a scenario on tilevk and lavapipe and compares the bytes, and the
// small set-up helpers the scenarios share. One test binary links all the files (meson: icd_api_breadth).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>

#include "vk_harness.h"

namespace tilevk::test::breadth {

#include "ab_array_frag.h"
#include "ab_color_sint_frag.h"
#include "ab_color_uint_frag.h"
#include "ab_compute_comp.h"
#include "ab_descriptors_frag.h"
#include "ab_dynamic_frag.h"
#include "ab_fullscreen_vert.h"
#include "ab_instanced_vert.h"
#include "ab_limits_frag.h"
#include "ab_limits_vert.h"
#include "ab_mrt_frag.h"
#include "ab_passthrough_geom.h"
#include "ab_point_float_vert.h"
#include "ab_point_sint_vert.h"
#include "ab_point_uint_vert.h"
#include "ab_pull_vert.h"
#include "ab_push_frag.h"
#include "ab_push_vert.h"
#include "ab_sample_edges_frag.h"
#include "ab_sample_frag.h"
#include "ab_sample_sint_frag.h"
#include "ab_sample_uint_frag.h"
#include "ab_shadow_frag.h"
#include "ab_spec_frag.h"
#include "ab_subpass_load_frag.h"
#include "ab_tex_array_frag.h"
#include "ab_texel_buffer_frag.h"
#include "ab_texel_buffer_sint_frag.h"
#include "ab_texel_buffer_uint_frag.h"
#include "color_frag.h"
#include "draw_vert.h"

using tilevk::test::Device;
using tilevk::test::Harness;
using tilevk::test::transition;
using tilevk::test::TwoDriverSuite;
using Bytes = std::vector<uint8_t>;
struct Spv {
    const uint32_t* code;
    size_t bytes;
};
#define SPV(name)         \
    Spv {                 \
        name, sizeof name \
    }

struct Vertex {
    float pos[4];
    float color[4];
};
inline Vertex v(float x, float y, float z, float r, float g, float b, float a = 1.0f) {
    return {{x, y, z, 1.0f}, {r, g, b, a}};
}

// What a pipeline is made of; defaults: draw.vert/color.frag with `Vertex` input, one opaque colour attachment.
struct Pipe {
    Spv vs = SPV(draw_vert), fs = SPV(color_frag);
    std::vector<VkVertexInputBindingDescription> bindings{{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    std::vector<VkVertexInputAttributeDescription> attrs{{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                         {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    bool restart = false;
    uint32_t width = 32, height = 32;
    std::vector<VkDynamicState> dynamic;
    uint32_t color_count = 1;
    std::vector<VkPipelineColorBlendAttachmentState> blend;  // empty: color_count opaque attachments
    float blend_constants[4] = {0, 0, 0, 0};
    const VkPipelineDepthStencilStateCreateInfo* ds = nullptr;
    bool depth_bias = false;
    float line_width = 1.0f;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkRenderPass rp = VK_NULL_HANDLE;
    uint32_t subpass = 0;
    const VkSpecializationInfo* fs_spec = nullptr;  // fragment stage specialization
    bool no_fragment_stage = false;                 // vertex stage only (depth-only passes)
    bool rasterizer_discard = false;
    const void* pnext = nullptr;               // VkGraphicsPipelineCreateInfo::pNext
    const void* vertex_input_pnext = nullptr;  // VkPipelineVertexInputStateCreateInfo::pNext
    const void* color_blend_pnext = nullptr;   // VkPipelineColorBlendStateCreateInfo::pNext
    const void* rasterization_pnext = nullptr;  // VkPipelineRasterizationStateCreateInfo::pNext
    bool depth_clamp = false;                   // depthClampEnable
    VkPipelineCache cache = VK_NULL_HANDLE;
    VkPipelineCreateFlags flags = 0;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  // rasterizationSamples
    const VkSampleMask* sample_mask = nullptr;              // pSampleMask (null: all samples)
};

inline VkPipelineColorBlendAttachmentState opaque() {
    VkPipelineColorBlendAttachmentState s{};
    s.colorWriteMask = 0xf;
    return s;
}
// Blending on, both ops ADD, all channels written.
inline VkPipelineColorBlendAttachmentState blend_add(VkBlendFactor src_color, VkBlendFactor dst_color,
                                                     VkBlendFactor src_alpha, VkBlendFactor dst_alpha) {
    VkPipelineColorBlendAttachmentState s{};
    s.blendEnable = VK_TRUE;
    s.srcColorBlendFactor = src_color;
    s.dstColorBlendFactor = dst_color;
    s.colorBlendOp = VK_BLEND_OP_ADD;
    s.srcAlphaBlendFactor = src_alpha;
    s.dstAlphaBlendFactor = dst_alpha;
    s.alphaBlendOp = VK_BLEND_OP_ADD;
    s.colorWriteMask = 0xf;
    return s;
}
inline VkPipelineColorBlendAttachmentState alpha_over() {
    return blend_add(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_FACTOR_ONE,
                     VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
}

inline VkAttachmentDescription attachment(VkFormat f, VkAttachmentLoadOp load, VkAttachmentStoreOp store,
                                          VkImageLayout final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) {
    VkAttachmentDescription a{};
    a.format = f;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = load;
    a.storeOp = store;
    a.stencilLoadOp = load;
    a.stencilStoreOp = store;
    a.initialLayout = load == VK_ATTACHMENT_LOAD_OP_LOAD ? final_layout : VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = final_layout;
    return a;
}

inline const VkAttachmentReference kColour0{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
inline const VkAttachmentReference kDepth1{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};

// A graphics subpass writing at most one colour and one depth/stencil attachment (null: none).
inline VkSubpassDescription subpass(const VkAttachmentReference* colour, const VkAttachmentReference* depth = nullptr) {
    VkSubpassDescription s{};
    s.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    s.colorAttachmentCount = colour != nullptr ? 1 : 0;
    s.pColorAttachments = colour;
    s.pDepthStencilAttachment = depth;
    return s;
}

// Objects on one device, destroyed in reverse order of creation.
class Kit {
  public:
    explicit Kit(Device& dev) : d(dev.device()), dev_(dev) {
        vkGetDeviceQueue(d, 0, 0, &queue);
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        vkCreateCommandPool(d, &pci, nullptr, &pool);
    }
    ~Kit() {
        for (auto it = undo_.rbegin(); it != undo_.rend(); ++it) it->destroy();
        vkDestroyCommandPool(d, pool, nullptr);
    }
    Device& dev() { return dev_; }
    // Registers how to destroy an object made outside the Kit (run at the end, or by destroy_now).
    template <class H>
    void undo(VkObjectType type, H handle, std::function<void()> destroy) {
        undo_.push_back({type, uint64_t(handle), std::move(destroy)});
    }
    // Drops an object from the Kit's list without destroying it (the test destroyed it itself).
    template <class H>
    void forget(VkObjectType type, H handle) {
        std::erase_if(undo_, [&](const Undo& u) { return u.type == type && u.handle == uint64_t(handle); });
    }
    // Destroys an object made here now instead of at the end (all objects of `type` when `handle` is null):
    // lifetime tests destroy objects while others made from them live on.
    template <class H>
    void destroy_now(VkObjectType type, H handle) {
        for (auto it = undo_.begin(); it != undo_.end();) {
            if (it->type == type && (handle == VK_NULL_HANDLE || it->handle == uint64_t(handle))) {
                it->destroy();
                it = undo_.erase(it);
            } else {
                ++it;
            }
        }
    }
    VkResult run(const std::function<void(VkCommandBuffer)>& record) { return dev_.run(record); }

    Device::Buffer buffer(VkDeviceSize n, VkBufferUsageFlags usage = 0) {
        Device::Buffer b = dev_.make_buffer(n, usage);
        std::memset(b.map, 0, n);
        undo(VK_OBJECT_TYPE_BUFFER, b.buffer, [this, b]() mutable { dev_.destroy(b); });
        return b;
    }
    template <class T>
    Device::Buffer buffer_of(const std::vector<T>& data, VkBufferUsageFlags usage) {
        Device::Buffer b = buffer(data.size() * sizeof(T), usage);
        std::memcpy(b.map, data.data(), b.size);
        return b;
    }
    Device::Image image(VkFormat f, uint32_t w, uint32_t h, VkImageUsageFlags usage, uint32_t levels = 1,
                        uint32_t layers = 1) {
        Device::Image i = dev_.make_image(f, w, h, levels, layers, VK_SAMPLE_COUNT_1_BIT, usage);
        EXPECT_NE(i.image, VK_NULL_HANDLE) << "format " << f;
        undo(VK_OBJECT_TYPE_IMAGE, i.image, [this, i]() mutable {
            if (i.image) dev_.destroy(i);
        });
        return i;
    }
    VkImageView view(VkImage img, VkFormat f, VkImageAspectFlags aspect, VkImageViewType type = VK_IMAGE_VIEW_TYPE_2D,
                     uint32_t base_level = 0, uint32_t levels = 1, uint32_t base_layer = 0, uint32_t layers = 1) {
        VkImageViewCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        ci.image = img;
        ci.viewType = type;
        ci.format = f;
        ci.subresourceRange = {aspect, base_level, levels, base_layer, layers};
        VkImageView vw = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateImageView(d, &ci, nullptr, &vw), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_IMAGE_VIEW, vw, [this, vw] { vkDestroyImageView(d, vw, nullptr); });
        return vw;
    }
    VkShaderModule shader(Spv s) {
        VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        ci.codeSize = s.bytes;
        ci.pCode = s.code;
        VkShaderModule m = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateShaderModule(d, &ci, nullptr, &m), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_SHADER_MODULE, m, [this, m] { vkDestroyShaderModule(d, m, nullptr); });
        return m;
    }
    VkRenderPass render_pass(const std::vector<VkAttachmentDescription>& atts,
                             const std::vector<VkSubpassDescription>& subs,
                             const std::vector<VkSubpassDependency>& deps = {}) {
        VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        ci.attachmentCount = uint32_t(atts.size());
        ci.pAttachments = atts.data();
        ci.subpassCount = uint32_t(subs.size());
        ci.pSubpasses = subs.data();
        ci.dependencyCount = uint32_t(deps.size());
        ci.pDependencies = deps.data();
        VkRenderPass rp = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateRenderPass(d, &ci, nullptr, &rp), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_RENDER_PASS, rp, [this, rp] { vkDestroyRenderPass(d, rp, nullptr); });
        return rp;
    }
    VkFramebuffer framebuffer(VkRenderPass rp, const std::vector<VkImageView>& views, uint32_t w, uint32_t h,
                              uint32_t layers = 1) {
        VkFramebufferCreateInfo ci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        ci.renderPass = rp;
        ci.attachmentCount = uint32_t(views.size());
        ci.pAttachments = views.data();
        ci.width = w;
        ci.height = h;
        ci.layers = layers;
        VkFramebuffer fb = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateFramebuffer(d, &ci, nullptr, &fb), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_FRAMEBUFFER, fb, [this, fb] { vkDestroyFramebuffer(d, fb, nullptr); });
        return fb;
    }
    VkDescriptorSetLayout set_layout(const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
        VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        ci.bindingCount = uint32_t(bindings.size());
        ci.pBindings = bindings.data();
        VkDescriptorSetLayout l = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateDescriptorSetLayout(d, &ci, nullptr, &l), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, l, [this, l] { vkDestroyDescriptorSetLayout(d, l, nullptr); });
        return l;
    }
    VkPipelineLayout pipeline_layout(const std::vector<VkDescriptorSetLayout>& sets,
                                     const std::vector<VkPushConstantRange>& push = {}) {
        VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        ci.setLayoutCount = uint32_t(sets.size());
        ci.pSetLayouts = sets.data();
        ci.pushConstantRangeCount = uint32_t(push.size());
        ci.pPushConstantRanges = push.data();
        VkPipelineLayout l = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreatePipelineLayout(d, &ci, nullptr, &l), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_PIPELINE_LAYOUT, l, [this, l] { vkDestroyPipelineLayout(d, l, nullptr); });
        return l;
    }
    VkDescriptorSet descriptor_set(VkDescriptorSetLayout layout) {
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 4},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 4},
                                              {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 4},
                                              {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4},
                                              {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 4},
                                              {VK_DESCRIPTOR_TYPE_SAMPLER, 4},
                                              {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 4},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 4},
                                              {VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 4}};
        VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        pci.maxSets = 1;
        pci.poolSizeCount = uint32_t(std::size(sizes));
        pci.pPoolSizes = sizes;
        VkDescriptorPool p = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateDescriptorPool(d, &pci, nullptr, &p), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_DESCRIPTOR_POOL, p, [this, p] { vkDestroyDescriptorPool(d, p, nullptr); });
        VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        ai.descriptorPool = p;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &layout;
        VkDescriptorSet s = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateDescriptorSets(d, &ai, &s), VK_SUCCESS);
        return s;
    }
    void write(VkDescriptorSet s, uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* b,
               const VkDescriptorImageInfo* i) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = s;
        w.dstBinding = binding;
        w.descriptorCount = 1;
        w.descriptorType = type;
        w.pBufferInfo = b;
        w.pImageInfo = i;
        vkUpdateDescriptorSets(d, 1, &w, 0, nullptr);
    }
    VkSampler sampler(VkFilter filter = VK_FILTER_NEAREST,
                      VkSamplerAddressMode mode = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
        VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        ci.magFilter = ci.minFilter = filter;
        ci.addressModeU = ci.addressModeV = ci.addressModeW = mode;
        ci.maxLod = 0.25f;
        VkSampler s = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateSampler(d, &ci, nullptr, &s), VK_SUCCESS);
        undo(VK_OBJECT_TYPE_SAMPLER, s, [this, s] { vkDestroySampler(d, s, nullptr); });
        return s;
    }
    VkPipeline pipeline(const Pipe& p, VkResult* result = nullptr) {
        VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = shader(p.vs);
        stages[0].pName = "main";
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = shader(p.fs);
        stages[1].pName = "main";
        stages[1].pSpecializationInfo = p.fs_spec;
        VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        vi.pNext = p.vertex_input_pnext;
        vi.vertexBindingDescriptionCount = uint32_t(p.bindings.size());
        vi.pVertexBindingDescriptions = p.bindings.data();
        vi.vertexAttributeDescriptionCount = uint32_t(p.attrs.size());
        vi.pVertexAttributeDescriptions = p.attrs.data();
        VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        ia.topology = p.topology;
        ia.primitiveRestartEnable = p.restart;
        VkViewport vp{0, 0, float(p.width), float(p.height), 0, 1};
        VkRect2D sc{{0, 0}, {p.width, p.height}};
        VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        vps.viewportCount = 1;
        vps.pViewports = &vp;
        vps.scissorCount = 1;
        vps.pScissors = &sc;
        VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        rs.polygonMode = VK_POLYGON_MODE_FILL;
        rs.cullMode = VK_CULL_MODE_NONE;
        rs.lineWidth = p.line_width;
        rs.depthBiasEnable = p.depth_bias;
        rs.pNext = p.rasterization_pnext;
        rs.depthClampEnable = p.depth_clamp;
        VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        ms.rasterizationSamples = p.samples;
        ms.pSampleMask = p.sample_mask;
        std::vector<VkPipelineColorBlendAttachmentState> blend = p.blend;
        if (blend.empty()) blend.assign(p.color_count, opaque());
        VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        cb.pNext = p.color_blend_pnext;
        cb.attachmentCount = uint32_t(blend.size());
        cb.pAttachments = blend.data();
        std::memcpy(cb.blendConstants, p.blend_constants, sizeof cb.blendConstants);
        VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dyn.dynamicStateCount = uint32_t(p.dynamic.size());
        dyn.pDynamicStates = p.dynamic.data();
        rs.rasterizerDiscardEnable = p.rasterizer_discard;
        VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
        gci.pNext = p.pnext;
        gci.flags = p.flags;
        gci.stageCount = p.no_fragment_stage ? 1 : 2;
        gci.pStages = stages;
        gci.pVertexInputState = &vi;
        gci.pInputAssemblyState = &ia;
        gci.pViewportState = &vps;
        gci.pRasterizationState = &rs;
        gci.pMultisampleState = &ms;
        gci.pDepthStencilState = p.ds;
        gci.pColorBlendState = blend.empty() ? nullptr : &cb;
        gci.pDynamicState = p.dynamic.empty() ? nullptr : &dyn;
        gci.layout = p.layout != VK_NULL_HANDLE ? p.layout : empty_layout();
        gci.renderPass = p.rp;
        gci.subpass = p.subpass;
        VkPipeline pipe = VK_NULL_HANDLE;
        const VkResult r = vkCreateGraphicsPipelines(d, p.cache, 1, &gci, nullptr, &pipe);
        if (result != nullptr)
            *result = r;
        else
            EXPECT_EQ(r, VK_SUCCESS);
        undo(VK_OBJECT_TYPE_PIPELINE, pipe, [this, pipe] { vkDestroyPipeline(d, pipe, nullptr); });
        return pipe;
    }
    VkPipelineLayout empty_layout() {
        if (empty_layout_ == VK_NULL_HANDLE) empty_layout_ = pipeline_layout({});
        return empty_layout_;
    }
    VkCommandBuffer command_buffer(VkCommandBufferLevel level = VK_COMMAND_BUFFER_LEVEL_PRIMARY) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool;
        ai.level = level;
        ai.commandBufferCount = 1;
        VkCommandBuffer cb = VK_NULL_HANDLE;
        EXPECT_EQ(vkAllocateCommandBuffers(d, &ai, &cb), VK_SUCCESS);
        return cb;
    }
    VkResult submit(VkCommandBuffer cb) {
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cb;
        VkResult r = vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE);
        return r == VK_SUCCESS ? vkQueueWaitIdle(queue) : r;
    }
    // Bytes of one subresource (tight rows), read through a buffer; the image must be in TRANSFER_SRC_OPTIMAL.
    Bytes read(VkImage img, uint32_t w, uint32_t h, uint32_t texel_bytes,
               VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT, uint32_t level = 0, uint32_t layer = 0) {
        Device::Buffer b = buffer(VkDeviceSize(w) * h * texel_bytes);
        EXPECT_EQ(run([&](VkCommandBuffer c) {
                      VkBufferImageCopy r{};
                      r.imageSubresource = {aspect, level, layer, 1};
                      r.imageExtent = {w, h, 1};
                      vkCmdCopyImageToBuffer(c, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, b.buffer, 1, &r);
                  }),
                  VK_SUCCESS);
        return bytes(b);
    }
    static Bytes bytes(const Device::Buffer& b) {
        const auto* p = static_cast<const uint8_t*>(b.map);
        return Bytes(p, p + b.size);
    }

    VkDevice d;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;

  private:
    Device& dev_;
    struct Undo {
        VkObjectType type;
        uint64_t handle;
        std::function<void()> destroy;
    };
    std::vector<Undo> undo_;
    VkPipelineLayout empty_layout_ = VK_NULL_HANDLE;
};

// A device-level command by name; the test fails, naming it, when the device does not offer it.
template <class F>
F device_proc(VkDevice d, const char* name) {
    auto f = reinterpret_cast<F>(vkGetDeviceProcAddr(d, name));
    EXPECT_NE(f, nullptr) << name;
    return f;
}
template <class F>
F device_proc(Kit& k, const char* name) {
    return device_proc<F>(k.d, name);
}

inline void begin_pass(VkCommandBuffer c, VkRenderPass rp, VkFramebuffer fb, uint32_t w, uint32_t h,
                       const std::vector<VkClearValue>& clears,
                       VkSubpassContents contents = VK_SUBPASS_CONTENTS_INLINE) {
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = rp;
    bi.framebuffer = fb;
    bi.renderArea = {{0, 0}, {w, h}};
    bi.clearValueCount = uint32_t(clears.size());
    bi.pClearValues = clears.data();
    vkCmdBeginRenderPass(c, &bi, contents);
}

inline VkClearValue clear_color(float r, float g, float b, float a) {
    VkClearValue c{};
    c.color = {{r, g, b, a}};
    return c;
}
inline VkClearValue clear_depth(float z, uint32_t s = 0) {
    VkClearValue c{};
    c.depthStencil = {z, s};
    return c;
}

// One RGBA8 colour attachment (32x32 by default) cleared at the start of a one-subpass render pass.
// A compute pipeline of `code` (entry `entry`, specialization `spec`) with `layout`; the result in *result when
// given, else expected to be VK_SUCCESS.
inline VkPipeline compute_pipeline(Kit& k, Spv code, VkPipelineLayout layout,
                                   const VkSpecializationInfo* spec = nullptr, VkResult* result = nullptr,
                                   const char* entry = "main") {
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = k.shader(code);
    ci.stage.pName = entry;
    ci.stage.pSpecializationInfo = spec;
    ci.layout = layout;
    VkPipeline p = VK_NULL_HANDLE;
    const VkResult r = vkCreateComputePipelines(k.d, VK_NULL_HANDLE, 1, &ci, nullptr, &p);
    if (result != nullptr)
        *result = r;
    else
        EXPECT_EQ(r, VK_SUCCESS);
    if (p != VK_NULL_HANDLE) k.undo(VK_OBJECT_TYPE_PIPELINE, p, [&k, p] { vkDestroyPipeline(k.d, p, nullptr); });
    return p;
}

struct Target {
    Device::Image image;
    VkRenderPass rp;
    VkFramebuffer fb;
    uint32_t w, h;
};
inline Target target(Kit& k, VkFormat f = VK_FORMAT_R8G8B8A8_UNORM, uint32_t w = 32, uint32_t h = 32) {
    Target t{};
    t.w = w;
    t.h = h;
    t.image = k.image(f, w, h, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.rp =
        k.render_pass({attachment(f, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)}, {subpass(&kColour0)});
    t.fb = k.framebuffer(t.rp, {k.view(t.image.image, f, VK_IMAGE_ASPECT_COLOR_BIT)}, w, h);
    return t;
}

// A one-subpass render pass: colour attachment 0 (loaded or cleared) and depth/stencil attachment 1 (cleared),
// both stored and left in TRANSFER_SRC_OPTIMAL.
inline VkRenderPass colour_depth_pass(Kit& k, VkFormat colour, VkFormat depth,
                                      VkAttachmentLoadOp colour_load = VK_ATTACHMENT_LOAD_OP_CLEAR) {
    return k.render_pass({attachment(colour, colour_load, VK_ATTACHMENT_STORE_OP_STORE),
                          attachment(depth, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)},
                         {subpass(&kColour0, &kDepth1)});
}

inline bool has_stencil(VkFormat f) {
    return f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_S8_UINT;
}

// An RGBA8 colour attachment and a depth (and stencil, if the format has it) attachment, 32x32, both cleared at
// the start of a one-subpass render pass (colour_depth_pass).
struct DepthTarget {
    Device::Image col, dep;
    VkRenderPass rp;
    VkFramebuffer fb;
};
inline DepthTarget depth_target(Kit& k, VkFormat depth) {
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageAspectFlags aspects = (depth == VK_FORMAT_S8_UINT ? 0 : VK_IMAGE_ASPECT_DEPTH_BIT) |
                                       (has_stencil(depth) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    DepthTarget t{};
    t.col = k.image(C, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.dep = k.image(depth, 32, 32, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.rp = colour_depth_pass(k, C, depth);
    t.fb = k.framebuffer(t.rp, {k.view(t.col.image, C, VK_IMAGE_ASPECT_COLOR_BIT), k.view(t.dep.image, depth, aspects)},
                         32, 32);
    return t;
}

// Depth test and write with `compare`, stencil off (callers that test stencil set it up on the result).
inline VkPipelineDepthStencilStateCreateInfo depth_state(VkCompareOp compare) {
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = compare;
    return ds;
}

// A pipeline drawing ab_fullscreen.vert's one covering triangle (no vertex input) with fragment shader `fs` into
// all of `tg`.
inline Pipe fullscreen_pipe(Spv fs, const Target& tg, VkPipelineLayout layout) {
    Pipe p;
    p.vs = SPV(ab_fullscreen_vert);
    p.fs = fs;
    p.bindings = {};
    p.attrs = {};
    p.width = tg.w;
    p.height = tg.h;
    p.rp = tg.rp;
    p.layout = layout;
    return p;
}

// One pass over all of `tg` (cleared to -1, so unwritten texels show) drawing the fullscreen triangle of `pipe`
// with descriptor set 0 = `set`.
inline void draw_fullscreen(VkCommandBuffer c, const Target& tg, VkPipeline pipe, VkPipelineLayout layout,
                            VkDescriptorSet set) {
    begin_pass(c, tg.rp, tg.fb, tg.w, tg.h, {clear_color(-1, -1, -1, -1)});
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
    vkCmdDraw(c, 3, 1, 0, 0);
    vkCmdEndRenderPass(c);
}

// A set layout with one combined image sampler (binding 0, fragment stage), a pipeline layout of it and a set.
struct SamplerSet {
    VkDescriptorSetLayout dsl;
    VkPipelineLayout layout;
    VkDescriptorSet set;
};
inline SamplerSet sampler_set(Kit& k) {
    SamplerSet s{};
    s.dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
    s.layout = k.pipeline_layout({s.dsl});
    s.set = k.descriptor_set(s.dsl);
    return s;
}

// A uniform texel buffer view of `buf` (`format`, `offset`, `range`) written to binding 0 (fragment stage) of a
// set of its own, with its layouts; the caller destroys the view.
struct TexelBufferSet {
    VkBufferView view;
    VkDescriptorSetLayout dsl;
    VkPipelineLayout layout;
    VkDescriptorSet set;
};
inline TexelBufferSet uniform_texel_buffer_set(Kit& k, const Device::Buffer& buf, VkFormat format, VkDeviceSize offset,
                                               VkDeviceSize range) {
    TexelBufferSet t{};
    VkBufferViewCreateInfo bvci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    bvci.buffer = buf.buffer;
    bvci.format = format;
    bvci.offset = offset;
    bvci.range = range;
    EXPECT_EQ(vkCreateBufferView(k.d, &bvci, nullptr, &t.view), VK_SUCCESS);
    t.dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
    t.layout = k.pipeline_layout({t.dsl});
    t.set = k.descriptor_set(t.dsl);
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = t.set;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    w.pTexelBufferView = &t.view;
    vkUpdateDescriptorSets(k.d, 1, &w, 0, nullptr);
    return t;
}

// Binds `vb` as vertex buffer 0 at offset 0.
inline void bind_vertices(VkCommandBuffer c, const Device::Buffer& vb) {
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(c, 0, 1, &vb.buffer, &zero);
}

// One pass over all of `tg` (its colour cleared to `clear`) drawing `vertex_count` vertices of `vb` with `pipe`.
inline void draw_vertices(VkCommandBuffer c, const Target& tg, VkPipeline pipe, const Device::Buffer& vb,
                          uint32_t vertex_count, VkClearValue clear) {
    begin_pass(c, tg.rp, tg.fb, tg.w, tg.h, {clear});
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    bind_vertices(c, vb);
    vkCmdDraw(c, vertex_count, 1, 0, 0);
    vkCmdEndRenderPass(c);
}

inline const std::vector<Vertex> kTriangle = {v(-0.8f, -0.8f, 0.2f, 1, 0, 0), v(0.8f, -0.6f, 0.4f, 0, 1, 0),
                                              v(-0.2f, 0.9f, 0.6f, 0, 0, 1)};
inline const std::vector<Vertex> kTriangle2 = {v(0.9f, 0.9f, 0.5f, 1, 1, 0, 0.5f), v(-0.7f, 0.3f, 0.1f, 0, 1, 1, 0.8f),
                                               v(0.4f, -0.95f, 0.9f, 1, 0, 1, 0.3f)};
// kTriangle then kTriangle2 (six vertices).
inline const std::vector<Vertex> kBothTriangles = [] {
    std::vector<Vertex> both = kTriangle;
    both.insert(both.end(), kTriangle2.begin(), kTriangle2.end());
    return both;
}();

// A device on each driver with `extensions` enabled and `chain` as VkDeviceCreateInfo::pNext (the tests of
// optional extensions and features).
struct DevicePair {
    DevicePair(VkPhysicalDevice t, VkPhysicalDevice l, const std::vector<const char*>& extensions,
               const void* chain = nullptr)
        : tilevk(t, nullptr, extensions, chain), lavapipe(l, nullptr, extensions, chain) {}
    bool ok() const { return tilevk.ok() && lavapipe.ok(); }
    Device tilevk, lavapipe;
};

class ApiBreadth : public TwoDriverSuite {
  protected:
    // A DevicePair on the suite's physical devices, expected to be made on both drivers.
    std::unique_ptr<DevicePair> device_pair(const std::vector<const char*>& extensions, const void* chain = nullptr) {
        auto d = std::make_unique<DevicePair>(tilevk_->physical(), lavapipe_->physical(), extensions, chain);
        EXPECT_TRUE(d->ok());
        return d;
    }
    // Runs `scene` on both drivers; returns tilevk's bytes after checking they equal lavapipe's.
    Bytes both(const std::function<Bytes(Kit&)>& scene) { return both_on(*tilevk_, *lavapipe_, scene); }
    // The same on devices of the caller's (e.g. made with features enabled).
    Bytes both_on(Device& tilevk, Device& lavapipe, const std::function<Bytes(Kit&)>& scene) {
        Bytes t, l;
        {
            Kit k(tilevk);
            t = scene(k);
        }
        {
            Kit k(lavapipe);
            l = scene(k);
        }
        expect_same(t, l);
        return t;
    }
    static void expect_same(const Bytes& t, const Bytes& l, const std::string& what = "") {
        EXPECT_EQ(t.size(), l.size()) << what;
        size_t diffs = 0, first = 0;
        for (size_t i = 0; i < std::min(t.size(), l.size()); ++i)
            if (t[i] != l[i] && diffs++ == 0) first = i;
        if (std::getenv("TILEVK_TEST_DUMP_DIFFS"))
            for (size_t i = 0, shown = 0;
                 i + 4 <= std::min(t.size(), l.size()) && shown < (std::getenv("TILEVK_TEST_DUMP_ALL") ? 100000u : 12u);
                 i += 4)
                if ((std::getenv("TILEVK_TEST_DUMP_ALL") || std::memcmp(&t[i], &l[i], 4) != 0) && ++shown)
                    std::fprintf(stderr, "word %zu: tilevk %02x%02x%02x%02x lavapipe %02x%02x%02x%02x\n", i / 4,
                                 t[i + 3], t[i + 2], t[i + 1], t[i], l[i + 3], l[i + 2], l[i + 1], l[i]);
        EXPECT_EQ(diffs, 0u) << what << ": first difference at byte " << first << ": "
                             << (first < t.size() ? int(t[first]) : -1) << " vs "
                             << (first < l.size() ? int(l[first]) : -1);
    }
};

inline Bytes concat(std::initializer_list<Bytes> parts) {
    Bytes out;
    for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}
inline const uint8_t* px(const Bytes& b, uint32_t x, uint32_t y, uint32_t w = 32) {
    return b.data() + (y * w + x) * 4;
}

// ---- Texel data helpers ----------------------------------------------------------------------------------------

// Bytes of one texel of `aspect` in a buffer copy (the spec's texel block sizes, by VkFormat ranges of the core
// uncompressed formats); 0 for formats the test does not know (compressed, planar, 64-bit channels).
inline uint32_t texel_bytes(VkFormat f, VkImageAspectFlags aspect) {
    const int v = int(f);
    if (f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D16_UNORM_S8_UINT)
        return aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? 1 : f == VK_FORMAT_D16_UNORM_S8_UINT ? 2 : 4;
    if (v == 1 || (v >= 9 && v <= 15) || f == VK_FORMAT_S8_UINT) return 1;
    if ((v >= 2 && v <= 8) || (v >= 16 && v <= 22) || (v >= 70 && v <= 76) || f == VK_FORMAT_D16_UNORM) return 2;
    if (f == VK_FORMAT_A4R4G4B4_UNORM_PACK16 || f == VK_FORMAT_A4B4G4R4_UNORM_PACK16) return 2;
    if (v >= 23 && v <= 36) return 3;
    if ((v >= 37 && v <= 69) || (v >= 77 && v <= 83) || (v >= 98 && v <= 100) || (v >= 122 && v <= 123) ||
        f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D32_SFLOAT)
        return 4;
    if (v >= 84 && v <= 90) return 6;
    if ((v >= 91 && v <= 97) || (v >= 101 && v <= 103)) return 8;
    if (v >= 104 && v <= 106) return 12;
    if (v >= 107 && v <= 109) return 16;
    return 0;
}
inline bool is_depth(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D32_SFLOAT_S8_UINT ||
           f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D16_UNORM_S8_UINT;
}
// Pure-integer colour formats (their shaders read and write uvec4 / ivec4): the core UINT formats, each followed by
// its SINT twin.
inline bool is_uint_format(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R8_UINT:
        case VK_FORMAT_R8G8_UINT:
        case VK_FORMAT_R8G8B8_UINT:
        case VK_FORMAT_B8G8R8_UINT:
        case VK_FORMAT_R8G8B8A8_UINT:
        case VK_FORMAT_B8G8R8A8_UINT:
        case VK_FORMAT_A8B8G8R8_UINT_PACK32:
        case VK_FORMAT_A2R10G10B10_UINT_PACK32:
        case VK_FORMAT_A2B10G10R10_UINT_PACK32:
        case VK_FORMAT_R16_UINT:
        case VK_FORMAT_R16G16_UINT:
        case VK_FORMAT_R16G16B16_UINT:
        case VK_FORMAT_R16G16B16A16_UINT:
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R32G32_UINT:
        case VK_FORMAT_R32G32B32_UINT:
        case VK_FORMAT_R32G32B32A32_UINT:
            return true;
        default:
            return false;
    }
}
inline bool is_sint_format(VkFormat f) {
    return f != VK_FORMAT_R8_UINT && is_uint_format(VkFormat(int(f) - 1));
}
inline bool is_half_format(VkFormat f) {
    return f == VK_FORMAT_R16_SFLOAT || f == VK_FORMAT_R16G16_SFLOAT || f == VK_FORMAT_R16G16B16_SFLOAT ||
           f == VK_FORMAT_R16G16B16A16_SFLOAT;
}
inline bool is_float32_format(VkFormat f) {
    return f == VK_FORMAT_R32_SFLOAT || f == VK_FORMAT_R32G32_SFLOAT || f == VK_FORMAT_R32G32B32_SFLOAT ||
           f == VK_FORMAT_R32G32B32A32_SFLOAT || f == VK_FORMAT_D32_SFLOAT;
}

// Texel bytes with finite values for float formats (half exponents 10..20, floats in [-4,4]; depth floats [0,1]);
// every other format (normalized, integer, packed, the small floats B10G11R11 and E5B9G9R9) takes any bytes.
inline std::vector<uint8_t> texel_data(VkFormat f, size_t texels, uint32_t seed) {
    const uint32_t n = texel_bytes(f, VK_IMAGE_ASPECT_COLOR_BIT | VK_IMAGE_ASPECT_DEPTH_BIT);
    std::vector<uint8_t> data(texels * n);
    std::mt19937 rng(seed);
    for (auto& b : data) b = uint8_t(rng());
    if (is_half_format(f)) {
        for (size_t i = 0; i + 2 <= data.size(); i += 2) {
            const uint16_t bits = uint16_t(((rng() & 1) << 15) | ((10 + rng() % 11) << 10) | (rng() & 1023));
            std::memcpy(&data[i], &bits, 2);
        }
    } else if (is_float32_format(f)) {
        for (size_t i = 0; i + 4 <= data.size(); i += 4) {
            const float x = f == VK_FORMAT_D32_SFLOAT ? float(rng() % 1000001) / 1000000.0f
                                                      : float(int32_t(rng() % 2000001) - 1000000) / 250000.0f;
            std::memcpy(&data[i], &x, 4);
        }
    }
    return data;
}

// 64 halves (16 RGBA16F texels or vertices) drawn from the 16 `specials` in a fixed scatter, each in several
// channels.
inline Bytes half_specials(const uint16_t (&specials)[16]) {
    Bytes data(64 * 2);
    for (size_t i = 0; i < 64; ++i) {
        const uint16_t h = specials[(i * 5 + i / 16) % 16];
        std::memcpy(&data[2 * i], &h, 2);
    }
    return data;
}

// Independent spot check beside the comparison with lavapipe: each signalling NaN 0x7c01 among the 64 halves of
// `halves` arrives in `out` (one float per half) as the quiet float NaN 0x7fc02000 (quiet bit set, payload moved up
// 13 bits), and there is at least one.
inline void expect_signalling_half_nan_quieted(const Bytes& halves, const Bytes& out) {
    int found = 0;
    for (size_t i = 0; i < 64; ++i) {
        uint16_t h;
        std::memcpy(&h, &halves[2 * i], 2);
        if (h != 0x7c01) continue;
        uint32_t got;
        std::memcpy(&got, &out[4 * i], 4);
        EXPECT_EQ(got, 0x7fc02000u) << i;
        ++found;
    }
    EXPECT_GT(found, 0);
}

// Copies tight texels from `src` into level 0 (layers 0..layers-1, `aspect`) of a w x h image in UNDEFINED layout
// and leaves it SHADER_READ_ONLY.
inline void upload(Kit& k, const Device::Buffer& src, VkImage img, VkImageAspectFlags aspect, uint32_t w, uint32_t h,
                   uint32_t layers = 1) {
    EXPECT_EQ(k.run([&](VkCommandBuffer c) {
        transition(c, img, aspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy r{};
        r.imageSubresource = {aspect, 0, 0, layers};
        r.imageExtent = {w, h, 1};
        vkCmdCopyBufferToImage(c, src.buffer, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
        transition(c, img, aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }),
              VK_SUCCESS);
}

// Fills a w x h RGBA8 image (level 0, layer 0) with distinct texels and leaves it SHADER_READ_ONLY.
inline void upload_rgba8(Kit& k, VkImage img, uint32_t w, uint32_t h, uint32_t seed, uint32_t layers = 1) {
    Device::Buffer src = k.buffer(VkDeviceSize(w) * h * 4 * layers);
    auto* p = static_cast<uint8_t*>(src.map);
    for (size_t i = 0; i < src.size; ++i) p[i] = uint8_t((i * 37 + seed * 101 + (i >> 5) * 11) & 255);
    upload(k, src, img, VK_IMAGE_ASPECT_COLOR_BIT, w, h, layers);
}

// A 4x4 texture of `f` (texel_data seeded by the format; depth formats through their depth aspect) sampled by `fs`
// at the pixel centres of a 4x4 target: R32G32B32A32_UINT for integer formats (their bits, NaN patterns untouched),
// else R32G32B32A32_SFLOAT. Returns the target's bytes.
inline Bytes sample_4x4(Kit& k, VkFormat f, Spv fs) {
    const VkImageAspectFlags aspect = is_depth(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    const bool integer = is_uint_format(f) || is_sint_format(f);
    Target tg = target(k, integer ? VK_FORMAT_R32G32B32A32_UINT : VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
    Device::Image tex = k.image(f, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    Device::Buffer src = k.buffer_of(texel_data(f, 16, uint32_t(f)), 0);
    upload(k, src, tex.image, aspect, 4, 4);
    const auto [dsl, layout, set] = sampler_set(k);
    VkDescriptorImageInfo ii{k.sampler(), k.view(tex.image, f, aspect), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
    VkPipeline pipe = k.pipeline(fullscreen_pipe(fs, tg, layout));
    EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
    return k.read(tg.image.image, 4, 4, 16);
}

}  // namespace tilevk::test::breadth
