// API breadth: the Vulkan 1.0 graphics paths a demanding application or a conformance test exercises (secondary
// command buffers, several subpasses and attachments, dynamic state, push constants and descriptor variety,
// transfers over subresources, vertex input variety, indexed/indirect draws, format honesty, error paths). Each
// scenario runs the same commands on tilevk and lavapipe (validation on) and the read-back bytes must be equal;
// a coarse independent check makes sure something was drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "vk_harness.h"

namespace {

#include "ab_array_frag.h"
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
#include "ab_sample_frag.h"
#include "ab_shadow_frag.h"
#include "ab_spec_frag.h"
#include "ab_storage_texel_frag.h"
#include "ab_subpass_load_frag.h"
#include "ab_tex_array_frag.h"
#include "ab_texel_buffer_frag.h"
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
Vertex v(float x, float y, float z, float r, float g, float b, float a = 1.0f) {
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
};

VkPipelineColorBlendAttachmentState opaque() {
    VkPipelineColorBlendAttachmentState s{};
    s.colorWriteMask = 0xf;
    return s;
}
// Blending on, both ops ADD, all channels written.
VkPipelineColorBlendAttachmentState blend_add(VkBlendFactor src_color, VkBlendFactor dst_color, VkBlendFactor src_alpha,
                                              VkBlendFactor dst_alpha) {
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
VkPipelineColorBlendAttachmentState alpha_over() {
    return blend_add(VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_FACTOR_ONE,
                     VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA);
}

VkAttachmentDescription attachment(VkFormat f, VkAttachmentLoadOp load, VkAttachmentStoreOp store,
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

const VkAttachmentReference kColour0{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
const VkAttachmentReference kDepth1{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};

// A graphics subpass writing at most one colour and one depth/stencil attachment (null: none).
VkSubpassDescription subpass(const VkAttachmentReference* colour, const VkAttachmentReference* depth = nullptr) {
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
        for (auto it = undo_.rbegin(); it != undo_.rend(); ++it) (*it)();
        vkDestroyCommandPool(d, pool, nullptr);
    }
    Device& dev() { return dev_; }
    VkResult run(const std::function<void(VkCommandBuffer)>& record) { return dev_.run(record); }

    Device::Buffer buffer(VkDeviceSize n, VkBufferUsageFlags usage = 0) {
        Device::Buffer b = dev_.make_buffer(n, usage);
        std::memset(b.map, 0, n);
        undo_.push_back([this, b]() mutable { dev_.destroy(b); });
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
        undo_.push_back([this, i]() mutable {
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
        undo_.push_back([this, vw] { vkDestroyImageView(d, vw, nullptr); });
        return vw;
    }
    VkShaderModule shader(Spv s) {
        VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        ci.codeSize = s.bytes;
        ci.pCode = s.code;
        VkShaderModule m = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateShaderModule(d, &ci, nullptr, &m), VK_SUCCESS);
        undo_.push_back([this, m] { vkDestroyShaderModule(d, m, nullptr); });
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
        undo_.push_back([this, rp] { vkDestroyRenderPass(d, rp, nullptr); });
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
        undo_.push_back([this, fb] { vkDestroyFramebuffer(d, fb, nullptr); });
        return fb;
    }
    VkDescriptorSetLayout set_layout(const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
        VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        ci.bindingCount = uint32_t(bindings.size());
        ci.pBindings = bindings.data();
        VkDescriptorSetLayout l = VK_NULL_HANDLE;
        EXPECT_EQ(vkCreateDescriptorSetLayout(d, &ci, nullptr, &l), VK_SUCCESS);
        undo_.push_back([this, l] { vkDestroyDescriptorSetLayout(d, l, nullptr); });
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
        undo_.push_back([this, l] { vkDestroyPipelineLayout(d, l, nullptr); });
        return l;
    }
    VkDescriptorSet descriptor_set(VkDescriptorSetLayout layout) {
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 4},
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
        undo_.push_back([this, p] { vkDestroyDescriptorPool(d, p, nullptr); });
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
        undo_.push_back([this, s] { vkDestroySampler(d, s, nullptr); });
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
        VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        std::vector<VkPipelineColorBlendAttachmentState> blend = p.blend;
        if (blend.empty()) blend.assign(p.color_count, opaque());
        VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        cb.attachmentCount = uint32_t(blend.size());
        cb.pAttachments = blend.data();
        std::memcpy(cb.blendConstants, p.blend_constants, sizeof cb.blendConstants);
        VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dyn.dynamicStateCount = uint32_t(p.dynamic.size());
        dyn.pDynamicStates = p.dynamic.data();
        rs.rasterizerDiscardEnable = p.rasterizer_discard;
        VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
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
        const VkResult r = vkCreateGraphicsPipelines(d, VK_NULL_HANDLE, 1, &gci, nullptr, &pipe);
        if (result != nullptr)
            *result = r;
        else
            EXPECT_EQ(r, VK_SUCCESS);
        undo_.push_back([this, pipe] { vkDestroyPipeline(d, pipe, nullptr); });
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
    std::vector<std::function<void()>> undo_;
    VkPipelineLayout empty_layout_ = VK_NULL_HANDLE;
};

void begin_pass(VkCommandBuffer c, VkRenderPass rp, VkFramebuffer fb, uint32_t w, uint32_t h,
                const std::vector<VkClearValue>& clears, VkSubpassContents contents = VK_SUBPASS_CONTENTS_INLINE) {
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = rp;
    bi.framebuffer = fb;
    bi.renderArea = {{0, 0}, {w, h}};
    bi.clearValueCount = uint32_t(clears.size());
    bi.pClearValues = clears.data();
    vkCmdBeginRenderPass(c, &bi, contents);
}

VkClearValue clear_color(float r, float g, float b, float a) {
    VkClearValue c{};
    c.color = {{r, g, b, a}};
    return c;
}
VkClearValue clear_depth(float z, uint32_t s = 0) {
    VkClearValue c{};
    c.depthStencil = {z, s};
    return c;
}

// One RGBA8 colour attachment (32x32 by default) cleared at the start of a one-subpass render pass.
struct Target {
    Device::Image image;
    VkRenderPass rp;
    VkFramebuffer fb;
    uint32_t w, h;
};
Target target(Kit& k, VkFormat f = VK_FORMAT_R8G8B8A8_UNORM, uint32_t w = 32, uint32_t h = 32) {
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
VkRenderPass colour_depth_pass(Kit& k, VkFormat colour, VkFormat depth,
                               VkAttachmentLoadOp colour_load = VK_ATTACHMENT_LOAD_OP_CLEAR) {
    return k.render_pass({attachment(colour, colour_load, VK_ATTACHMENT_STORE_OP_STORE),
                          attachment(depth, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)},
                         {subpass(&kColour0, &kDepth1)});
}

bool has_stencil(VkFormat f) {
    return f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT;
}

// An RGBA8 colour attachment and a depth (and stencil, if the format has it) attachment, 32x32, both cleared at
// the start of a one-subpass render pass (colour_depth_pass).
struct DepthTarget {
    Device::Image col, dep;
    VkRenderPass rp;
    VkFramebuffer fb;
};
DepthTarget depth_target(Kit& k, VkFormat depth) {
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
    const VkImageAspectFlags aspects =
        VK_IMAGE_ASPECT_DEPTH_BIT | (has_stencil(depth) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    DepthTarget t{};
    t.col = k.image(C, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.dep = k.image(depth, 32, 32, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    t.rp = colour_depth_pass(k, C, depth);
    t.fb = k.framebuffer(t.rp, {k.view(t.col.image, C, VK_IMAGE_ASPECT_COLOR_BIT), k.view(t.dep.image, depth, aspects)},
                         32, 32);
    return t;
}

// Depth test and write with `compare`, stencil off (callers that test stencil set it up on the result).
VkPipelineDepthStencilStateCreateInfo depth_state(VkCompareOp compare) {
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = compare;
    return ds;
}

// A pipeline drawing ab_fullscreen.vert's one covering triangle (no vertex input) with fragment shader `fs` into
// all of `tg`.
Pipe fullscreen_pipe(Spv fs, const Target& tg, VkPipelineLayout layout) {
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
void draw_fullscreen(VkCommandBuffer c, const Target& tg, VkPipeline pipe, VkPipelineLayout layout,
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
SamplerSet sampler_set(Kit& k) {
    SamplerSet s{};
    s.dsl = k.set_layout({{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
    s.layout = k.pipeline_layout({s.dsl});
    s.set = k.descriptor_set(s.dsl);
    return s;
}

// Binds `vb` as vertex buffer 0 at offset 0.
void bind_vertices(VkCommandBuffer c, const Device::Buffer& vb) {
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(c, 0, 1, &vb.buffer, &zero);
}

const std::vector<Vertex> kTriangle = {v(-0.8f, -0.8f, 0.2f, 1, 0, 0), v(0.8f, -0.6f, 0.4f, 0, 1, 0),
                                       v(-0.2f, 0.9f, 0.6f, 0, 0, 1)};
const std::vector<Vertex> kTriangle2 = {v(0.9f, 0.9f, 0.5f, 1, 1, 0, 0.5f), v(-0.7f, 0.3f, 0.1f, 0, 1, 1, 0.8f),
                                        v(0.4f, -0.95f, 0.9f, 1, 0, 1, 0.3f)};
// kTriangle then kTriangle2 (six vertices).
const std::vector<Vertex> kBothTriangles = [] {
    std::vector<Vertex> both = kTriangle;
    both.insert(both.end(), kTriangle2.begin(), kTriangle2.end());
    return both;
}();

class ApiBreadth : public TwoDriverSuite {
  protected:
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
        EXPECT_EQ(diffs, 0u) << what << ": first difference at byte " << first << ": "
                             << (first < t.size() ? int(t[first]) : -1) << " vs "
                             << (first < l.size() ? int(l[first]) : -1);
    }
};

Bytes concat(std::initializer_list<Bytes> parts) {
    Bytes out;
    for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}
const uint8_t* px(const Bytes& b, uint32_t x, uint32_t y, uint32_t w = 32) {
    return b.data() + (y * w + x) * 4;
}

// ---- Texel data helpers ----------------------------------------------------------------------------------------

// Bytes of one texel of `aspect` in a buffer copy, for the formats tilevk reports; 0 if the test does not know it.
uint32_t texel_bytes(VkFormat f, VkImageAspectFlags aspect) {
    switch (f) {
        case VK_FORMAT_R8_UNORM:
            return 1;
        case VK_FORMAT_R8G8_UNORM:
            return 2;
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_SRGB:
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_D32_SFLOAT:
            return 4;
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
            return 8;
        case VK_FORMAT_R32G32B32A32_SFLOAT:
            return 16;
        case VK_FORMAT_D16_UNORM:
            return 2;
        case VK_FORMAT_D32_SFLOAT_S8_UINT:
        case VK_FORMAT_D24_UNORM_S8_UINT:
            return aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? 1 : 4;
        default:
            return 0;
    }
}
bool is_depth(VkFormat f) {
    return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D32_SFLOAT_S8_UINT ||
           f == VK_FORMAT_D24_UNORM_S8_UINT;
}

// Texel bytes with finite values for float formats (half exponents 10..20, floats in [-4,4]; depth floats [0,1]).
std::vector<uint8_t> texel_data(VkFormat f, size_t texels, uint32_t seed) {
    const uint32_t n = texel_bytes(f, VK_IMAGE_ASPECT_COLOR_BIT | VK_IMAGE_ASPECT_DEPTH_BIT);
    std::vector<uint8_t> data(texels * n);
    std::mt19937 rng(seed);
    for (auto& b : data) b = uint8_t(rng());
    if (f == VK_FORMAT_R16G16B16A16_SFLOAT) {
        for (size_t i = 0; i + 2 <= data.size(); i += 2) {
            const uint16_t bits = uint16_t(((rng() & 1) << 15) | ((10 + rng() % 11) << 10) | (rng() & 1023));
            std::memcpy(&data[i], &bits, 2);
        }
    } else if (f == VK_FORMAT_R32_SFLOAT || f == VK_FORMAT_R32G32_SFLOAT || f == VK_FORMAT_R32G32B32A32_SFLOAT ||
               f == VK_FORMAT_D32_SFLOAT) {
        for (size_t i = 0; i + 4 <= data.size(); i += 4) {
            const float x = f == VK_FORMAT_D32_SFLOAT ? float(rng() % 1000001) / 1000000.0f
                                                      : float(int32_t(rng() % 2000001) - 1000000) / 250000.0f;
            std::memcpy(&data[i], &x, 4);
        }
    }
    return data;
}

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
        const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM, D = VK_FORMAT_D32_SFLOAT, O = VK_FORMAT_R32G32B32A32_SFLOAT;
        Device::Image col = k.image(C, 32, 32,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT |
                                        VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        Device::Image dep =
            k.image(D, 32, 32, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT);
        Device::Image out = k.image(O, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        VkImageView cv = k.view(col.image, C, VK_IMAGE_ASPECT_COLOR_BIT),
                    dv = k.view(dep.image, D, VK_IMAGE_ASPECT_DEPTH_BIT),
                    ov = k.view(out.image, O, VK_IMAGE_ASPECT_COLOR_BIT);
        std::vector<VkAttachmentDescription> atts = {
            attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE),
            attachment(D, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                       VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL),
            attachment(O, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)};
        VkAttachmentReference c0{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
            d0{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkAttachmentReference in1[2] = {{0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                        {1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}};
        VkAttachmentReference o1{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        std::vector<VkSubpassDescription> subs(2);
        subs[0].pipelineBindPoint = subs[1].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subs[0].colorAttachmentCount = 1;
        subs[0].pColorAttachments = &c0;
        subs[0].pDepthStencilAttachment = &d0;
        subs[1].inputAttachmentCount = 2;
        subs[1].pInputAttachments = in1;
        subs[1].colorAttachmentCount = 1;
        subs[1].pColorAttachments = &o1;
        VkSubpassDependency dep01{
            0,
            1,
            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
            VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
            VK_ACCESS_INPUT_ATTACHMENT_READ_BIT,
            VK_DEPENDENCY_BY_REGION_BIT};
        VkRenderPass rp = k.render_pass(atts, subs, {dep01});
        VkFramebuffer fb = k.framebuffer(rp, {cv, dv, ov}, 32, 32);
        const VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
        Pipe p0;
        p0.rp = rp;
        p0.ds = &ds;
        VkPipeline pipe0 = k.pipeline(p0);
        const VkShaderStageFlags F = VK_SHADER_STAGE_FRAGMENT_BIT;
        VkDescriptorSetLayout dsl = k.set_layout(
            {{0, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1, F}, {1, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1, F}});
        VkPipelineLayout layout = k.pipeline_layout({dsl});
        VkDescriptorSet set = k.descriptor_set(dsl);
        VkDescriptorImageInfo ci{VK_NULL_HANDLE, cv, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            di{VK_NULL_HANDLE, dv, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, nullptr, &ci);
        k.write(set, 1, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, nullptr, &di);
        Pipe p1;
        p1.fs = SPV(ab_subpass_load_frag);
        p1.rp = rp;
        p1.subpass = 1;
        p1.layout = layout;
        VkPipeline pipe1 = k.pipeline(p1);
        std::vector<Vertex> verts = kBothTriangles;
        verts.push_back(v(-1, -1, 0, 0.2f, 0.4f, 0.6f, 1));
        verts.push_back(v(3, -1, 0, 0.2f, 0.4f, 0.6f, 1));
        verts.push_back(v(-1, 3, 0, 0.2f, 0.4f, 0.6f, 1));
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(0.75f), clear_color(0, 0, 0, 0)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe0);
            bind_vertices(c, vb);
            vkCmdDraw(c, 6, 1, 0, 0);
            vkCmdNextSubpass(c, VK_SUBPASS_CONTENTS_INLINE);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe1);
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
            vkCmdDraw(c, 3, 1, 6, 0);  // covers the whole target
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes o = k.read(out.image, 32, 32, 16);
        // Independent check at the corner (no triangle of subpass 0 there): colour (0, 0, 0.25, 1) read as
        // .bgra -> (0.25, 0, 0, 1); 0.5 of it + 0.5 of the vertex colour + 0.25 * depth 0.75.
        float corner[4];
        std::memcpy(corner, o.data() + (31 * 32 + 0) * 16, 16);
        EXPECT_NEAR(corner[0], 0.125f + 0.1f + 0.1875f, 1e-3f);
        EXPECT_NEAR(corner[3], 0.5f + 0.5f + 0.1875f, 1e-3f);
        return concat({o, k.read(col.image, 32, 32, 4)});
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
// rates), 56 varying components, 128 bytes of push constants visible to both stages, 4 descriptor sets, 4 colour
// attachments of 4 formats.
TEST_F(ApiBreadth, ReportedLimitsAreUsable) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(tilevk_->physical(), &props);
    const VkPhysicalDeviceLimits& lim = props.limits;
    ASSERT_GE(lim.maxVertexInputAttributes, 16u);
    ASSERT_GE(lim.maxVertexInputBindings, 16u);
    ASSERT_GE(lim.maxVertexOutputComponents, 56u);
    ASSERT_GE(lim.maxPushConstantsSize, 128u);
    ASSERT_GE(lim.maxBoundDescriptorSets, 4u);
    ASSERT_GE(lim.maxColorAttachments, 4u);
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
        for (uint32_t i = 0; i < 4; ++i) {
            imgs.push_back(
                k.image(fmts[i], 16, 16, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
            views.push_back(k.view(imgs.back().image, fmts[i], VK_IMAGE_ASPECT_COLOR_BIT));
            atts.push_back(attachment(fmts[i], VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE));
            refs.push_back({i, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
        }
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 4;
        sub.pColorAttachments = refs.data();
        VkRenderPass rp = k.render_pass(atts, {sub});
        VkFramebuffer fb = k.framebuffer(rp, views, 16, 16);
        std::vector<VkDescriptorSetLayout> dsls;
        std::vector<VkDescriptorSet> sets;
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
        const VkDeviceSize align = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
        Device::Buffer ubo = k.buffer(4 * align, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        for (uint32_t i = 0; i < 4; ++i) {
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
        p.color_count = 4;
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
                        clear_color(0, 1, 0, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            std::vector<VkBuffer> bufs;
            std::vector<VkDeviceSize> offs(16, 0);
            for (auto& b : vbs) bufs.push_back(b.buffer);
            vkCmdBindVertexBuffers(c, 0, 16, bufs.data(), offs.data());
            vkCmdBindDescriptorSets(c, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 4, sets.data(), 0, nullptr);
            float pc[32];
            for (int i = 0; i < 32; ++i) pc[i] = float((i * 7) % 11) / 10.0f - 0.2f;
            pc[0] = pc[1] = 0.0f;  // no position offset
            vkCmdPushConstants(c, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 128, pc);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes out;
        for (uint32_t i = 0; i < 4; ++i) out = concat({out, k.read(imgs[i].image, 16, 16, texel[i])});
        EXPECT_NE(px(out, 8, 8, 16)[2], 64);  // attachment 0 drawn in the middle
        return out;
    });
}

// Copies tight texels from `src` into level 0 (layers 0..layers-1, `aspect`) of a w x h image in UNDEFINED layout
// and leaves it SHADER_READ_ONLY.
void upload(Kit& k, const Device::Buffer& src, VkImage img, VkImageAspectFlags aspect, uint32_t w, uint32_t h,
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
void upload_rgba8(Kit& k, VkImage img, uint32_t w, uint32_t h, uint32_t seed, uint32_t layers = 1) {
    Device::Buffer src = k.buffer(VkDeviceSize(w) * h * 4 * layers);
    auto* p = static_cast<uint8_t*>(src.map);
    for (size_t i = 0; i < src.size; ++i) p[i] = uint8_t((i * 37 + seed * 101 + (i >> 5) * 11) & 255);
    upload(k, src, img, VK_IMAGE_ASPECT_COLOR_BIT, w, h, layers);
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
                Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
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
        EXPECT_FALSE(tp.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT) << "format " << fi;
        if (!(tp.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT)) continue;
        ASSERT_TRUE(lp.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT) << "format " << fi;
        ++tested;
        SCOPED_TRACE("texel buffer format " + std::to_string(fi));
        both([f](Kit& k) {
            Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(k.dev().physical(), &props);
            const VkDeviceSize offset = std::max<VkDeviceSize>(props.limits.minTexelBufferOffsetAlignment, 16);
            const uint32_t n = texel_bytes(f, VK_IMAGE_ASPECT_COLOR_BIT);
            std::vector<uint8_t> data(offset, 0xEE);
            const std::vector<uint8_t> texels = texel_data(f, 20, 300 + uint32_t(f));
            data.insert(data.end(), texels.begin(), texels.end());
            Device::Buffer buf = k.buffer_of(data, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
            VkBufferViewCreateInfo bvci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
            bvci.buffer = buf.buffer;
            bvci.format = f;
            bvci.offset = offset;
            bvci.range = VkDeviceSize(18) * n;  // 18 texels visible (2 more than the pixels)
            VkBufferView view = VK_NULL_HANDLE;
            EXPECT_EQ(vkCreateBufferView(k.d, &bvci, nullptr, &view), VK_SUCCESS);
            VkDescriptorSetLayout dsl =
                k.set_layout({{0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
            VkPipelineLayout layout = k.pipeline_layout({dsl});
            VkDescriptorSet set = k.descriptor_set(dsl);
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = set;
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
            w.pTexelBufferView = &view;
            vkUpdateDescriptorSets(k.d, 1, &w, 0, nullptr);
            const Pipe p = fullscreen_pipe(SPV(ab_texel_buffer_frag), tg, layout);
            VkPipeline pipe = k.pipeline(p);
            EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
            Bytes out = k.read(tg.image.image, 4, 4, 16);
            float size;
            std::memcpy(&size, out.data() + 12, 4);
            EXPECT_EQ(size, 18.0f);  // textureSize = range / texel size
            vkDestroyBufferView(k.d, view, nullptr);
            return out;
        });
    }
    EXPECT_GT(tested, 0);
}

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
                const bool is_uint = f == VK_FORMAT_R8_UINT || f == VK_FORMAT_R8G8_UINT || f == VK_FORMAT_R8G8B8_UINT ||
                                     f == VK_FORMAT_R8G8B8A8_UINT || f == VK_FORMAT_R16_UINT ||
                                     f == VK_FORMAT_R16G16_UINT || f == VK_FORMAT_R16G16B16_UINT ||
                                     f == VK_FORMAT_R16G16B16A16_UINT || f == VK_FORMAT_R32_UINT ||
                                     f == VK_FORMAT_R32G32_UINT || f == VK_FORMAT_R32G32B32_UINT ||
                                     f == VK_FORMAT_R32G32B32A32_UINT || f == VK_FORMAT_A2B10G10R10_UINT_PACK32;
                const bool is_sint = f == VK_FORMAT_R8_SINT || f == VK_FORMAT_R8G8_SINT || f == VK_FORMAT_R8G8B8_SINT ||
                                     f == VK_FORMAT_R8G8B8A8_SINT || f == VK_FORMAT_R16_SINT ||
                                     f == VK_FORMAT_R16G16_SINT || f == VK_FORMAT_R16G16B16_SINT ||
                                     f == VK_FORMAT_R16G16B16A16_SINT || f == VK_FORMAT_R32_SINT ||
                                     f == VK_FORMAT_R32G32_SINT || f == VK_FORMAT_R32G32B32_SINT ||
                                     f == VK_FORMAT_R32G32B32A32_SINT || f == VK_FORMAT_A2B10G10R10_SINT_PACK32;
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
                const bool half = f == VK_FORMAT_R16_SFLOAT || f == VK_FORMAT_R16G16_SFLOAT ||
                                  f == VK_FORMAT_R16G16B16_SFLOAT || f == VK_FORMAT_R16G16B16A16_SFLOAT;
                const bool single = f == VK_FORMAT_R32_SFLOAT || f == VK_FORMAT_R32G32_SFLOAT ||
                                    f == VK_FORMAT_R32G32B32_SFLOAT || f == VK_FORMAT_R32G32B32A32_SFLOAT;
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
                EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                    begin_pass(c, t.rp, t.fb, 4, 4, {clear_color(-1, -1, -1, -1)});
                    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                    bind_vertices(c, vb);
                    vkCmdDraw(c, 16, 1, 0, 0);
                    vkCmdEndRenderPass(c);
                }),
                          VK_SUCCESS);
                return k.read(t.image.image, 4, 4, 16);
            });
        }
    }
}

// ---- Format honesty --------------------------------------------------------------------------------------------

// Every format tilevk reports as COLOR_ATTACHMENT (+BLEND), DEPTH_STENCIL_ATTACHMENT or SAMPLED_IMAGE renders /
// samples exactly as on lavapipe; lavapipe must report the same feature (else the test could not compare).
TEST_F(ApiBreadth, EveryReportedImageFormatWorks) {
    int colour = 0, depth = 0, sampled = 0;
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties tp, lp;
        vkGetPhysicalDeviceFormatProperties(tilevk_->physical(), f, &tp);
        vkGetPhysicalDeviceFormatProperties(lavapipe_->physical(), f, &lp);
        const VkFormatFeatureFlags t = tp.optimalTilingFeatures;
        if (t == 0) continue;
        SCOPED_TRACE("format " + std::to_string(fi));
        EXPECT_EQ(t & ~lp.optimalTilingFeatures, 0u) << "tilevk reports features lavapipe lacks";
        ASSERT_NE(texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT), 0u) << "the test does not know this format";
        if (t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) {
            ++colour;
            const bool blend = t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
            both([&](Kit& k) {
                Target tg = target(k, f);
                Pipe p;
                p.rp = tg.rp;
                p.blend = {blend ? alpha_over() : opaque()};
                VkPipeline pipe = k.pipeline(p);
                Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                    begin_pass(c, tg.rp, tg.fb, 32, 32, {clear_color(0.1f, 0.2f, 0.3f, 0.4f)});
                    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                    bind_vertices(c, vb);
                    vkCmdDraw(c, 6, 1, 0, 0);
                    vkCmdEndRenderPass(c);
                }),
                          VK_SUCCESS);
                return k.read(tg.image.image, 32, 32, texel_bytes(f, VK_IMAGE_ASPECT_COLOR_BIT));
            });
        }
        if (t & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
            ++depth;
            both([&](Kit& k) {
                const auto [col, dep, rp, fb] = depth_target(k, f);
                VkPipelineDepthStencilStateCreateInfo ds = depth_state(VK_COMPARE_OP_LESS);
                ds.stencilTestEnable = has_stencil(f);
                ds.front = ds.back = {VK_STENCIL_OP_KEEP,
                                      VK_STENCIL_OP_REPLACE,
                                      VK_STENCIL_OP_INCREMENT_AND_CLAMP,
                                      VK_COMPARE_OP_ALWAYS,
                                      0xff,
                                      0xff,
                                      0x5a};
                Pipe p;
                p.rp = rp;
                p.ds = &ds;
                VkPipeline pipe = k.pipeline(p);
                Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                    begin_pass(c, rp, fb, 32, 32, {clear_color(0, 0, 0.25f, 1), clear_depth(0.7f, 3)});
                    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                    bind_vertices(c, vb);
                    vkCmdDraw(c, 6, 1, 0, 0);
                    vkCmdEndRenderPass(c);
                }),
                          VK_SUCCESS);
                Bytes out = concat(
                    {k.read(col.image, 32, 32, 4),
                     k.read(dep.image, 32, 32, texel_bytes(f, VK_IMAGE_ASPECT_DEPTH_BIT), VK_IMAGE_ASPECT_DEPTH_BIT)});
                if (has_stencil(f)) out = concat({out, k.read(dep.image, 32, 32, 1, VK_IMAGE_ASPECT_STENCIL_BIT)});
                return out;
            });
        }
        if (t & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) {
            ++sampled;
            both([&](Kit& k) {
                const VkImageAspectFlags aspect = is_depth(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
                Target tg = target(k, VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4);
                Device::Image tex = k.image(f, 4, 4, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
                Device::Buffer src = k.buffer_of(texel_data(f, 16, uint32_t(f)), 0);
                upload(k, src, tex.image, aspect, 4, 4);
                const auto [dsl, layout, set] = sampler_set(k);
                VkDescriptorImageInfo ii{k.sampler(), k.view(tex.image, f, aspect),
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
                k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
                const Pipe p = fullscreen_pipe(SPV(ab_sample_frag), tg, layout);
                VkPipeline pipe = k.pipeline(p);
                EXPECT_EQ(k.run([&](VkCommandBuffer c) { draw_fullscreen(c, tg, pipe, layout, set); }), VK_SUCCESS);
                return k.read(tg.image.image, 4, 4, 16);
            });
        }
    }
    EXPECT_GT(colour, 0);
    EXPECT_GT(depth, 0);
    EXPECT_GT(sampled, 0);
}

// vkGetPhysicalDeviceImageFormatProperties says VK_ERROR_FORMAT_NOT_SUPPORTED for every usage whose format feature
// is not reported (and for formats with no features at all), and what it accepts, vkCreateImage makes.
TEST_F(ApiBreadth, ImageFormatPropertiesMatchFeatures) {
    VkPhysicalDevice pd = tilevk_->physical();
    const std::pair<VkImageUsageFlags, VkFormatFeatureFlags> usages[] = {
        {VK_IMAGE_USAGE_SAMPLED_BIT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT},
        {VK_IMAGE_USAGE_STORAGE_BIT, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT},
        {VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT},
        {VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT},
        {VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_FORMAT_FEATURE_TRANSFER_SRC_BIT},
        {VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_FORMAT_FEATURE_TRANSFER_DST_BIT}};
    int accepted = 0;
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, f, &fp);
        for (auto [usage, feature] : usages) {
            VkImageFormatProperties ip;
            const VkResult r = vkGetPhysicalDeviceImageFormatProperties(pd, f, VK_IMAGE_TYPE_2D,
                                                                        VK_IMAGE_TILING_OPTIMAL, usage, 0, &ip);
            if (!(fp.optimalTilingFeatures & feature)) {
                EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << "format " << fi << " usage " << usage;
                continue;
            }
            EXPECT_EQ(r, VK_SUCCESS) << "format " << fi << " usage " << usage;
            if (r != VK_SUCCESS) continue;
            ++accepted;
            Device::Image img = tilevk_->make_image(f, 16, 8, 1, 1, VK_SAMPLE_COUNT_1_BIT, usage);
            EXPECT_NE(img.image, VK_NULL_HANDLE) << "format " << fi << " usage " << usage;
            if (img.image) tilevk_->destroy(img);
        }
    }
    EXPECT_GT(accepted, 20);
    // LINEAR tiling: what the linear features do not have is refused too.
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, VkFormat(fi), &fp);
        for (auto [usage, feature] : usages) {
            VkImageFormatProperties ip;
            const VkResult r = vkGetPhysicalDeviceImageFormatProperties(pd, VkFormat(fi), VK_IMAGE_TYPE_2D,
                                                                        VK_IMAGE_TILING_LINEAR, usage, 0, &ip);
            if (!(fp.linearTilingFeatures & feature))
                EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << "linear format " << fi << " usage " << usage;
            else
                EXPECT_EQ(r, VK_SUCCESS) << "linear format " << fi << " usage " << usage;
        }
    }
    // Input attachments: every colour-attachment format may be one (it is read by a texel fetch); a depth format
    // only when it is also sampled; never multisampled. What is accepted, vkCreateImage makes.
    for (int fi = 1; fi <= VK_FORMAT_ASTC_12x12_SRGB_BLOCK; ++fi) {
        const VkFormat f = VkFormat(fi);
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(pd, f, &fp);
        const VkFormatFeatureFlags t = fp.optimalTilingFeatures;
        const VkImageUsageFlags att = (t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)
                                          ? VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT
                                          : VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        const VkImageUsageFlags usage = att | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
        VkImageFormatProperties ip;
        const VkResult r =
            vkGetPhysicalDeviceImageFormatProperties(pd, f, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage, 0, &ip);
        const bool attachment =
            t & (VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT);
        if (!attachment) {
            EXPECT_EQ(r, VK_ERROR_FORMAT_NOT_SUPPORTED) << "format " << fi;
            continue;
        }
        if (t & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) {
            EXPECT_EQ(r, VK_SUCCESS) << "colour format " << fi;
        }
        if (r != VK_SUCCESS) continue;
        EXPECT_EQ(ip.sampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT)) << "format " << fi;
        Device::Image img = tilevk_->make_image(f, 16, 8, 1, 1, VK_SAMPLE_COUNT_1_BIT, usage);
        EXPECT_NE(img.image, VK_NULL_HANDLE) << "format " << fi;
        if (img.image) tilevk_->destroy(img);
    }
}

// ---- Synchronisation and error paths ---------------------------------------------------------------------------

// Fences (signalled at creation, reset, waited with and without timeout), a semaphore between two submissions,
// events set by the host and by a command buffer, vkCmdWaitEvents, queue/device idle: same results on both.
TEST_F(ApiBreadth, FencesSemaphoresEvents) {
    both([](Kit& k) {
        Bytes log;
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        VkFence fence;
        EXPECT_EQ(vkCreateFence(k.d, &fci, nullptr, &fence), VK_SUCCESS);
        log.push_back(uint8_t(vkGetFenceStatus(k.d, fence)));  // VK_SUCCESS
        EXPECT_EQ(vkResetFences(k.d, 1, &fence), VK_SUCCESS);
        log.push_back(uint8_t(vkGetFenceStatus(k.d, fence)));                 // VK_NOT_READY
        log.push_back(uint8_t(vkWaitForFences(k.d, 1, &fence, VK_TRUE, 0)));  // VK_TIMEOUT
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore sem;
        EXPECT_EQ(vkCreateSemaphore(k.d, &sci, nullptr, &sem), VK_SUCCESS);
        VkEventCreateInfo eci{VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
        VkEvent host_ev, dev_ev;
        EXPECT_EQ(vkCreateEvent(k.d, &eci, nullptr, &host_ev), VK_SUCCESS);
        EXPECT_EQ(vkCreateEvent(k.d, &eci, nullptr, &dev_ev), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, host_ev)));  // VK_EVENT_RESET
        EXPECT_EQ(vkSetEvent(k.d, host_ev), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, host_ev)));  // VK_EVENT_SET
        Device::Buffer buf = k.buffer(256);
        VkCommandBuffer a = k.command_buffer(), b = k.command_buffer();
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(a, &bi);
        vkCmdFillBuffer(a, buf.buffer, 0, 64, 0x01020304u);
        vkCmdSetEvent(a, dev_ev, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkEndCommandBuffer(a);
        vkBeginCommandBuffer(b, &bi);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_HOST_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        VkEvent evs[2] = {host_ev, dev_ev};
        vkCmdWaitEvents(b, 2, evs, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, 1, &mb, 0, nullptr, 0, nullptr);
        VkBufferCopy region{0, 128, 64};
        vkCmdCopyBuffer(b, buf.buffer, buf.buffer, 1, &region);
        vkCmdResetEvent(b, host_ev, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkEndCommandBuffer(b);
        VkSubmitInfo s1{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        s1.commandBufferCount = 1;
        s1.pCommandBuffers = &a;
        s1.signalSemaphoreCount = 1;
        s1.pSignalSemaphores = &sem;
        VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkSubmitInfo s2{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        s2.waitSemaphoreCount = 1;
        s2.pWaitSemaphores = &sem;
        s2.pWaitDstStageMask = &wait_stage;
        s2.commandBufferCount = 1;
        s2.pCommandBuffers = &b;
        EXPECT_EQ(vkQueueSubmit(k.queue, 1, &s1, VK_NULL_HANDLE), VK_SUCCESS);
        EXPECT_EQ(vkQueueSubmit(k.queue, 1, &s2, fence), VK_SUCCESS);
        log.push_back(uint8_t(vkWaitForFences(k.d, 1, &fence, VK_TRUE, UINT64_MAX)));
        log.push_back(uint8_t(vkGetFenceStatus(k.d, fence)));
        EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_SUCCESS);
        EXPECT_EQ(vkDeviceWaitIdle(k.d), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, dev_ev)));   // set by command buffer a
        log.push_back(uint8_t(vkGetEventStatus(k.d, host_ev)));  // reset by command buffer b
        EXPECT_EQ(vkResetEvent(k.d, dev_ev), VK_SUCCESS);
        log.push_back(uint8_t(vkGetEventStatus(k.d, dev_ev)));
        // An empty submission only signals its fence.
        EXPECT_EQ(vkResetFences(k.d, 1, &fence), VK_SUCCESS);
        EXPECT_EQ(vkQueueSubmit(k.queue, 0, nullptr, fence), VK_SUCCESS);
        log.push_back(uint8_t(vkWaitForFences(k.d, 1, &fence, VK_TRUE, UINT64_MAX)));
        vkDestroyEvent(k.d, host_ev, nullptr);
        vkDestroyEvent(k.d, dev_ev, nullptr);
        vkDestroySemaphore(k.d, sem, nullptr);
        vkDestroyFence(k.d, fence, nullptr);
        const Bytes data = Kit::bytes(buf);
        EXPECT_EQ(data[128], 4);  // the copy after the wait saw the fill
        EXPECT_EQ(log[1], uint8_t(VK_NOT_READY));
        EXPECT_EQ(log[2], uint8_t(VK_TIMEOUT));
        EXPECT_EQ(log[7], uint8_t(VK_EVENT_SET));
        EXPECT_EQ(log[8], uint8_t(VK_EVENT_RESET));
        return concat({log, data});
    });
}

// Error paths on tilevk without the validation layer (these calls are valid but must fail cleanly): an allocation
// larger than the heap, a pipeline whose shader reads a storage texel buffer (no imageLoad/imageStore), a geometry
// stage, a compute pipeline (no compute queue); each returns an error code and a null handle, and the device keeps
// working.
TEST_F(ApiBreadth, ErrorPathsFailCleanly) {
    Harness plain(false);
    ASSERT_NE(plain.instance(), VK_NULL_HANDLE);
    Device dev(plain.find_device("tilevk"));
    ASSERT_TRUE(dev.ok());
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(dev.physical(), &mp);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = mp.memoryHeaps[0].size + 4096;
    ai.memoryTypeIndex = 0;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateMemory(dev.device(), &ai, nullptr, &mem), VK_ERROR_OUT_OF_DEVICE_MEMORY);
    ai.allocationSize = uint64_t(1) << 62;
    EXPECT_EQ(vkAllocateMemory(dev.device(), &ai, nullptr, &mem), VK_ERROR_OUT_OF_DEVICE_MEMORY);
    {
        Kit k(dev);
        Target t = target(k);
        VkDescriptorSetLayout dsl =
            k.set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT}});
        Pipe p;
        p.fs = SPV(ab_storage_texel_frag);
        p.rp = t.rp;
        p.layout = k.pipeline_layout({dsl});
        VkResult r = VK_SUCCESS;
        VkPipeline pipe = k.pipeline(p, &r);
        EXPECT_NE(r, VK_SUCCESS);
        EXPECT_EQ(pipe, VK_NULL_HANDLE);
        // Compute pipeline: refused.
        VkComputePipelineCreateInfo cci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        cci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        cci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        cci.stage.module = k.shader(SPV(ab_compute_comp));
        cci.stage.pName = "main";
        cci.layout = k.empty_layout();
        VkPipeline cp = VK_NULL_HANDLE;
        EXPECT_NE(vkCreateComputePipelines(k.d, VK_NULL_HANDLE, 1, &cci, nullptr, &cp), VK_SUCCESS);
        EXPECT_EQ(cp, VK_NULL_HANDLE);
        // A geometry stage (the feature is not reported; without the layer nothing stops the call): refused.
        {
            VkPipelineShaderStageCreateInfo st[3] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
            const VkShaderStageFlagBits stages[3] = {VK_SHADER_STAGE_VERTEX_BIT, VK_SHADER_STAGE_GEOMETRY_BIT,
                                                     VK_SHADER_STAGE_FRAGMENT_BIT};
            const Spv code[3] = {SPV(draw_vert), SPV(ab_passthrough_geom), SPV(color_frag)};
            for (int i = 0; i < 3; ++i) {
                st[i].stage = stages[i];
                st[i].module = k.shader(code[i]);
                st[i].pName = "main";
            }
            VkVertexInputBindingDescription vb{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
            VkVertexInputAttributeDescription va[2] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                       {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 16}};
            VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
            vi.vertexBindingDescriptionCount = 1;
            vi.pVertexBindingDescriptions = &vb;
            vi.vertexAttributeDescriptionCount = 2;
            vi.pVertexAttributeDescriptions = va;
            VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
            ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
            VkViewport vp{0, 0, 32, 32, 0, 1};
            VkRect2D sc{{0, 0}, {32, 32}};
            VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
            vps.viewportCount = vps.scissorCount = 1;
            vps.pViewports = &vp;
            vps.pScissors = &sc;
            VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
            rs.lineWidth = 1.0f;
            VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
            ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
            VkPipelineColorBlendAttachmentState cba = opaque();
            VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
            cb.attachmentCount = 1;
            cb.pAttachments = &cba;
            VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
            gci.stageCount = 3;
            gci.pStages = st;
            gci.pVertexInputState = &vi;
            gci.pInputAssemblyState = &ia;
            gci.pViewportState = &vps;
            gci.pRasterizationState = &rs;
            gci.pMultisampleState = &ms;
            gci.pColorBlendState = &cb;
            gci.layout = k.empty_layout();
            gci.renderPass = t.rp;
            VkPipeline gp = VK_NULL_HANDLE;
            EXPECT_NE(vkCreateGraphicsPipelines(k.d, VK_NULL_HANDLE, 1, &gci, nullptr, &gp), VK_SUCCESS);
            EXPECT_EQ(gp, VK_NULL_HANDLE);
        }
        // The device still draws.
        Pipe ok;
        ok.rp = t.rp;
        VkPipeline good = k.pipeline(ok);
        Device::Buffer vb = k.buffer_of(kTriangle, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, good);
            bind_vertices(c, vb);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        Bytes b = k.read(t.image.image, 32, 32, 4);
        EXPECT_NE(px(b, 10, 12)[2], 64);
    }
    EXPECT_EQ(vkDeviceWaitIdle(dev.device()), VK_SUCCESS);
}

}  // namespace
